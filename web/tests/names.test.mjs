import { test } from 'node:test';
import assert from 'node:assert/strict';
import { nameNote, nameProblem } from '../js/names.js';

test('a fine name has no problem, stripped', () => {
  assert.equal(nameProblem('  Ana ', 24), null);
});

test('each refusal is one plain sentence', () => {
  for (const [name, words] of [['', 'empty'], ['   ', 'empty'], ['x'.repeat(25), 'at most 24'],
    ['a\tb', 'control']]) {
    const problem = nameProblem(name, 24);
    assert.ok(problem?.includes(words), `${JSON.stringify(name)}: ${problem}`);
    assert.ok(!/String should|pydantic|character\(s\)/.test(problem ?? ''));
    assert.equal(problem?.split('. ').length, 1);
  }
});

test('the field says its limit, and when a paste was cut', () => {
  assert.equal(nameNote('Ana', 24), '3/24 characters');
  assert.equal(nameNote('x'.repeat(24), 24, 300), '24/24 characters · cut to 24: the paste had 300.');
});
