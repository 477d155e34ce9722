import { test } from 'node:test';
import assert from 'node:assert/strict';
import { tidyOutcome, decisionLabel, countdown } from '../js/words.js';

test('an outcome says each thing once, the detailed sentence kept', () => {
  assert.equal(
    tidyOutcome('Ana pocketed the 8. Ana pocketed the 8 in the called bottom side pocket.'
      + ' Ana wins the game.'),
    'Ana pocketed the 8 in the called bottom side pocket. Ana wins the game.');
  assert.equal(tidyOutcome('Time ran out. Ben passes. Ben passes.'), 'Time ran out. Ben passes.');
  assert.equal(tidyOutcome('Foul: scratch. Ball in hand for Ben.'),
    'Foul: scratch. Ball in hand for Ben.');
  // A sentence that merely starts with the same letters is another sentence.
  assert.equal(tidyOutcome('Ana wins. Ana winsome.'), 'Ana wins. Ana winsome.');
  assert.equal(tidyOutcome(''), '');
});

test('decision options read as what they do', () => {
  assert.equal(decisionLabel('accept'), 'Play from here');
  assert.equal(decisionLabel('rerack'), 'Re-rack and break');
  assert.equal(decisionLabel('rerack_opponent_breaks'), 'Re-rack, opponent breaks');
  assert.equal(decisionLabel('pass'), 'Pass it back');
  assert.equal(decisionLabel('some_new_option'), 'Some new option');
});

test('countdowns read as seconds, minutes past a minute', () => {
  assert.equal(countdown(9.2), '10 s');
  assert.equal(countdown(0), '0 s');
  assert.equal(countdown(-3), '0 s');
  assert.equal(countdown(239.5), '4:00');
  assert.equal(countdown(65), '1:05');
});
