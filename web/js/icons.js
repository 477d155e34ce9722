/**
 * Small icons drawn as inline SVG: they look the same everywhere, unlike emoji, which
 * show as an empty box on a system without an emoji font.
 */

const NS = 'http://www.w3.org/2000/svg';

/** @type {Record<string, string[]>} path data of each icon, on a 24 x 24 grid */
const PATHS = {
  trophy: [
    'M7 3h10v2h3v3a4 4 0 0 1-4 4h-.3A5 5 0 0 1 13 14.9V18h3v3H8v-3h3v-3.1A5 5 0 0 1 8.3 12H8'
      + 'a4 4 0 0 1-4-4V5h3V3zm0 4H6v1a2 2 0 0 0 1 1.7V7zm10 0v2.7A2 2 0 0 0 18 8V7h-1z',
  ],
  flag: ['M5 3h2v18H5V3zm3 1h10l-2 4 2 4H8V4z'],
  hand: [
    'M12 2a1.5 1.5 0 0 1 1.5 1.5V11h1V4.5a1.5 1.5 0 0 1 3 0V12h1V7.5a1.5 1.5 0 0 1 3 0V15'
      + 'a7 7 0 0 1-7 7h-1a7 7 0 0 1-5.6-2.8L3 14.6a1.5 1.5 0 0 1 2.3-1.9L8 15V5.5a1.5 1.5 0 0 1'
      + ' 3 0V11h-.5V3.5A1.5 1.5 0 0 1 12 2z',
  ],
  check: ['M9 16.2 4.8 12l-1.4 1.4L9 19 21 7l-1.4-1.4z'],
  clock: [
    'M12 2a10 10 0 1 0 0 20 10 10 0 0 0 0-20zm0 2a8 8 0 1 1 0 16 8 8 0 0 1 0-16zm-1 3v6l5 3'
      + ' 1-1.7-4-2.3V7h-2z',
  ],
};

/**
 * An icon element (`aria-hidden`: the text next to it says what it means).
 * @param {keyof typeof PATHS} name
 * @param {number} [size] CSS pixels
 * @returns {SVGSVGElement}
 */
export function icon(name, size = 20) {
  const svg = /** @type {SVGSVGElement} */ (document.createElementNS(NS, 'svg'));
  svg.setAttribute('viewBox', '0 0 24 24');
  svg.setAttribute('width', String(size));
  svg.setAttribute('height', String(size));
  svg.setAttribute('aria-hidden', 'true');
  svg.setAttribute('class', `icon icon-${name}`);
  svg.dataset.icon = name;
  for (const d of PATHS[name] ?? []) {
    const path = document.createElementNS(NS, 'path');
    path.setAttribute('d', d);
    path.setAttribute('fill', 'currentColor');
    svg.append(path);
  }
  return svg;
}

export const ICONS = Object.keys(PATHS);
