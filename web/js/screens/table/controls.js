/**
 * The live table's controls other than the pointer on the cloth: fine aim (arrow keys, the
 * mouse wheel, the ↺ ↻ buttons), Escape, the sound switch, rematch / concede / re-rack /
 * push-out, the chat line and the room link's copy button. Each turns into a call on the
 * table (`LiveTable`) or a message it sends.
 */

import { memory, request } from '../../net.js';
import { $, $input, bindMute } from '../../ui.js';
import { icon } from '../../icons.js';

const FINE_STEP = 0.002; // radians per fine-aim step (x10 with Shift)

/** @typedef {import('./live.js').LiveTable} LiveTable */

/** @param {LiveTable} live */
export function bindControls(live) {
  bindKeys(live);
  bindFineAim(live);
  bindButtons(live);
}

/** @param {LiveTable} live */
function bindKeys(live) {
  const unlockAudio = () => live.audio.unlock();
  window.addEventListener('pointerdown', unlockAudio);
  window.addEventListener('keydown', (ev) => {
    unlockAudio();
    if (ev.key === 'Escape') live.inputQueue.push({ type: 'cancel' });
    const typing = ev.target instanceof HTMLInputElement || ev.target instanceof HTMLSelectElement;
    if (typing) return;
    const step = FINE_STEP * (ev.shiftKey ? 10 : 1);
    if (ev.key === 'ArrowLeft' || ev.key === 'ArrowDown') { live.nudge(step); ev.preventDefault(); }
    if (ev.key === 'ArrowRight' || ev.key === 'ArrowUp') { live.nudge(-step); ev.preventDefault(); }
  });
  live.view.canvas.addEventListener('wheel', (ev) => {
    if (!live.situation().myTurn) return;
    ev.preventDefault();
    live.nudge((ev.deltaY > 0 ? -1 : 1) * FINE_STEP * (ev.shiftKey ? 10 : 1));
  }, { passive: false });
}

/**
 * The ↺ ↻ buttons: a step per press, repeating (faster after a while) while held.
 * @param {LiveTable} live
 */
function bindFineAim(live) {
  for (const [id, sign] of /** @type {[string, number][]} */ ([['aim-left', 1], ['aim-right', -1]])) {
    const button = $(id);
    /** @type {ReturnType<typeof setInterval> | undefined} */
    let repeat;
    const stop = () => { clearInterval(repeat); repeat = undefined; };
    button.addEventListener('pointerdown', (ev) => {
      ev.preventDefault();
      live.nudge(sign * FINE_STEP);
      stop();
      let n = 0;
      repeat = setInterval(() => {
        n += 1;
        if (n > 4) live.nudge(sign * FINE_STEP * (n > 20 ? 4 : 1));
      }, 60);
    });
    for (const end of ['pointerup', 'pointerleave', 'pointercancel']) {
      button.addEventListener(end, stop);
    }
    button.addEventListener('keydown', (ev) => {
      if (ev.key === 'Enter' || ev.key === ' ') { ev.preventDefault(); live.nudge(sign * FINE_STEP); }
    });
  }
}

/**
 * The replay of the room's newest match, its analysis asked for at once.
 * @param {string} roomId
 */
async function openAnalysis(roomId) {
  try {
    const { matches } = await request('GET',
      `/api/matches?room=${encodeURIComponent(roomId)}&limit=1`);
    if (matches.length) location.assign(`/m/${matches[0].id}?analyse=1`);
  } catch { /* the button stays; pressing it again asks again */ }
}

/** @param {LiveTable} live */
function bindButtons(live) {
  bindMute($('mute'), live.audio, (muted) => memory.setMuted(muted));
  $('rematch').addEventListener('click', () => live.send({ type: 'rematch' }));
  $('analyse').addEventListener('click', () => { openAnalysis(live.roomId); });
  $('concede').addEventListener('click', () => {
    // Naming the game makes a concession sent just as the frame ended harmless.
    if (confirm('Concede this frame?')) live.send({ type: 'concede', game: live.currentGame() });
  });
  $('rerack').addEventListener('click', () => live.send({ type: 'rerack' }));
  $('push-out').addEventListener('click', () => live.send({ type: 'push_out' }));
  $('chat-form').addEventListener('submit', (ev) => {
    ev.preventDefault();
    const input = $input('chat-input');
    const text = input.value.trim();
    if (text && live.send({ type: 'chat', text: text.slice(0, live.limits.max_chat) })) {
      input.value = '';
    }
  });
}

/**
 * The room link and its copy button (the clipboard, else the old `execCommand`, else the
 * link left selected for the player to copy).
 * @param {string} link
 */
export function bindRoomLink(link) {
  $input('room-link').value = link;
  const copyButton = $('copy-link');
  copyButton.addEventListener('click', async () => {
    $input('room-link').select();
    let copied = false;
    try { await navigator.clipboard.writeText(link); copied = true; } catch { /* below */ }
    if (!copied) {
      try { copied = document.execCommand('copy'); } catch { copied = false; }
    }
    copyButton.replaceChildren(...(copied ? [icon('check', 16), ' Copied'] : ['Select + copy']));
    copyButton.dataset.copied = String(copied);
    setTimeout(() => { copyButton.textContent = 'Copy'; delete copyButton.dataset.copied; }, 2000);
  });
}
