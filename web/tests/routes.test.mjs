// Which screen each page address shows (routes.js), the players' pages included.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { routeOf } from '../js/routes.js';

test('the players pages are routed', () => {
  assert.deepEqual(routeOf('/profile'), { screen: 'profile', playerId: null });
  assert.deepEqual(routeOf('/p/abc_DEF-12'), { screen: 'profile', playerId: 'abc_DEF-12' });
  assert.deepEqual(routeOf('/leaderboard'), { screen: 'leaderboard' });
  assert.deepEqual(routeOf('/login'), { screen: 'login' });
  assert.deepEqual(routeOf('/login/'), { screen: 'login' });
  assert.deepEqual(routeOf('/p/<script>'), { screen: 'lobby' });
});

test('tables, replays and the lobby are as before', () => {
  assert.deepEqual(routeOf('/r/room1'), { screen: 'table', roomId: 'room1' });
  assert.deepEqual(routeOf('/m/7'), { screen: 'replay', matchId: '7' });
  assert.deepEqual(routeOf('/'), { screen: 'lobby' });
});
