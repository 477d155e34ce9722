/**
 * The words over the live table for what the pointer is doing now: a short-lived note (a
 * cancelled shot, a refused drop), the pull-back, the cue ball being dragged, the pocket to
 * call, ball in hand. Pure: the table screen shows them in its `aim-state` chip.
 */

/** @typedef {{text: string, kind: string}} AimWords */

/**
 * @param {object} moment what is true now
 * @param {{text: string, kind: string, until: number}} moment.feedback the last note
 * @param {import('../../input.js').AimController} moment.aim
 * @param {import('../../input.js').Situation} moment.sit
 * @param {number | null | undefined} moment.called the pocket called for the 8
 * @param {number} moment.time local time, seconds
 * @returns {AimWords | null}
 */
export function aimWords({ feedback, aim, sit, called, time }) {
  if (time < feedback.until) return { text: feedback.text, kind: feedback.kind };
  if (!sit.myTurn) return null;
  if (aim.mode === 'pulling') {
    return aim.tooShort
      ? { text: 'Pull back to set the power…', kind: 'pull' }
      : { text: `Release to shoot · ${Math.round(aim.power * 100)} %`, kind: 'release' };
  }
  if (aim.mode === 'placing' && aim.placing) return placingWords(aim.placing, sit.ballInHand);
  if (sit.requiresCall && called == null) {
    return { text: 'Tap the pocket you call for the 8', kind: 'call' };
  }
  if (sit.ballInHand) {
    const where = {
      behind_head_string: 'Ball in hand behind the line: drag the white ball, or aim and shoot',
      in_d: 'Ball in hand in the D: drag the white ball, or aim and shoot',
    }[sit.ballInHand];
    return { text: where ?? 'Ball in hand: drag the white ball anywhere, or aim and shoot',
      kind: 'hand' };
  }
  return null;
}

/**
 * @param {{free: boolean, clamped?: boolean}} placing where the dragged cue ball would go
 * @param {string | null} ballInHand
 * @returns {AimWords}
 */
function placingWords(placing, ballInHand) {
  if (!placing.free) return { text: 'Not on another ball', kind: 'refused' };
  if (placing.clamped && ballInHand === 'behind_head_string') {
    return { text: 'Behind the head string only', kind: 'placing' };
  }
  if (placing.clamped && ballInHand === 'in_d') {
    return { text: 'In the D only', kind: 'placing' };
  }
  return { text: 'Let go to put the cue ball here', kind: 'placing' };
}
