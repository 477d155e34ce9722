import { test } from 'node:test';
import assert from 'node:assert/strict';
import { aimWords } from '../js/screens/table/words.js';
import { AimController } from '../js/input.js';

const noNote = { text: '', kind: '', until: 0 };
/** @param {Record<string, any>} over */
const sit = (over = {}) => ({ table: null, balls: [], cue: null, myTurn: true,
  ballInHand: null, requiresCall: false, limits: /** @type {any} */ ({}), ...over });

test('a fresh note is said first, even to a player who is not at the table', () => {
  const feedback = { text: 'Shot cancelled.', kind: 'cancelled', until: 10 };
  const words = aimWords({ feedback, aim: new AimController(), sit: sit({ myTurn: false }),
    called: null, time: 9 });
  assert.deepEqual(words, { text: 'Shot cancelled.', kind: 'cancelled' });
  assert.equal(aimWords({ feedback, aim: new AimController(), sit: sit({ myTurn: false }),
    called: null, time: 11 }), null);
});

test('the pull-back, the dragged cue ball, the call and ball in hand each have their words', () => {
  const aim = new AimController();
  aim.mode = 'pulling';
  const at = { feedback: noNote, called: null, time: 0 };
  assert.equal(aimWords({ ...at, aim, sit: sit() })?.kind, 'pull');
  aim.power = 0.5;
  assert.deepEqual(aimWords({ ...at, aim, sit: sit() }),
    { text: 'Release to shoot · 50 %', kind: 'release' });
  aim.mode = 'placing';
  aim.placing = { x: 0, y: 0, free: false };
  assert.equal(aimWords({ ...at, aim, sit: sit() })?.kind, 'refused');
  aim.placing = { x: 0, y: 0, free: true, clamped: true };
  assert.equal(aimWords({ ...at, aim, sit: sit({ ballInHand: 'behind_head_string' }) })?.text,
    'Behind the head string only');
  aim.reset();
  assert.equal(aimWords({ ...at, aim, sit: sit({ requiresCall: true }) })?.kind, 'call');
  assert.equal(aimWords({ ...at, called: 3, aim, sit: sit({ requiresCall: true }) }), null);
  assert.equal(aimWords({ ...at, aim, sit: sit({ ballInHand: 'anywhere' }) })?.kind, 'hand');
});
