/**
 * The display loop (javascript-tetris's `frame()`): `step(dt, now)` on every animation
 * frame, dt clamped to 0.1 s, times in seconds. Hidden tabs get no animation frames, so a
 * timer keeps the stream and the HUD moving there (at least every 250 ms).
 * @param {(dt: number, now: number) => void} step
 */
export function startLoop(step) {
  let last = performance.now();
  let lastLoopAt = 0;
  const tick = () => {
    const t = performance.now();
    const dt = Math.min(0.1, Math.max(0, (t - last) / 1000));
    last = t;
    lastLoopAt = t;
    step(dt, t / 1000);
  };
  const frame = () => { tick(); requestAnimationFrame(frame); };
  requestAnimationFrame(frame);
  setInterval(() => { if (performance.now() - lastLoopAt > 300) tick(); }, 250);
}
