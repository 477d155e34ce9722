import { test } from 'node:test';
import assert from 'node:assert/strict';
import { FramePlayer, celStep, interpolateCel } from '../js/interpolation.js';

const R = 0.028575;
const frame = (t, balls, last = false) => ({ t, last,
  balls: balls.map(([id, x, y, cel]) => ({ id, x, y, cel })) });

test('cel steps follow the distance rolled, across the wrap', () => {
  assert.equal(celStep(14, 2, 16, 4), 4); // wrapped forward
  assert.equal(celStep(3, 3, 16, 16), 16); // one whole turn in one frame
  assert.equal(celStep(3, 3, 16, 0), 0); // at rest
  assert.equal(celStep(5, 4, 16, 15), 15);
  const turnPerCel = (2 * Math.PI * R) / 16;
  assert.equal(interpolateCel(14, 2, 0.5, 16, 4 * turnPerCel, R), 0);
});

test('playback interpolates positions between frames, behind the newest one', () => {
  const p = new FramePlayer({ delay: 0.1 });
  p.reset([{ id: 0, x: 0.5, y: 0.5 }, { id: 1, x: 1.5, y: 0.5 }]);
  p.startShot();
  p.push(frame(0.05, [[0, 0.55, 0.5, 1], [1, 1.5, 0.5, 0]]));
  p.push(frame(0.1, [[0, 0.6, 0.5, 3], [1, 1.5, 0.5, 0]]));
  p.push(frame(0.15, [[0, 0.65, 0.5, 5], [1, 1.5, 0.5, 0]]));
  let balls = p.advance(0); // starts `delay` behind the first frame received: t = 0
  assert.ok(Math.abs(balls.get(0).x - 0.5) < 1e-12);
  balls = p.advance(0.075);
  assert.ok(balls.get(0).x > 0.55 && balls.get(0).x < 0.65, `x=${balls.get(0).x}`);
  assert.equal(balls.get(1).x, 1.5);
  assert.ok(Math.abs(balls.get(0).heading) < 1e-9, 'rolling along +x');
});

test('playback holds on the newest frame when the stream stalls, then resumes', () => {
  const p = new FramePlayer({ delay: 0.1 });
  p.reset([{ id: 0, x: 0, y: 0 }]);
  p.startShot();
  p.push(frame(0.05, [[0, 0.1, 0, 0]]));
  for (let i = 0; i < 30; i++) p.advance(1 / 60);
  assert.equal(p.current.get(0).x, 0.1);
  p.push(frame(0.1, [[0, 0.2, 0, 0]]));
  const before = p.current.get(0).x;
  const after = p.advance(1 / 60).get(0).x;
  assert.ok(after >= before);
});

test('playback far behind jumps to hold only `delay` behind the newest frame', () => {
  const p = new FramePlayer({ delay: 0.1 });
  p.reset([{ id: 0, x: 0, y: 0 }]);
  p.startShot();
  for (let k = 1; k <= 60; k++) p.push(frame(k * 0.05, [[0, k * 0.01, 0, 0]]));
  p.advance(1 / 60);
  assert.ok(p.lag <= 0.1 + 1e-9, `lag ${p.lag}`);
});

test('a ball missing from the next frame was pocketed: shown until then, gone after', () => {
  const p = new FramePlayer({ delay: 0 });
  p.reset([{ id: 0, x: 0, y: 0 }, { id: 3, x: 1, y: 1 }]);
  p.startShot();
  p.push(frame(0.05, [[0, 0.1, 0, 0], [3, 1.02, 1.0, 0]]));
  p.push(frame(0.1, [[0, 0.2, 0, 0]], true));
  let balls = p.advance(0.01);
  assert.ok(balls.has(3));
  for (let i = 0; i < 10; i++) balls = p.advance(0.02);
  assert.ok(!balls.has(3));
  assert.ok(p.done, 'reached the last frame');
});

test('a stopped ball keeps its cel and its heading', () => {
  const p = new FramePlayer({ delay: 0 });
  p.reset([{ id: 0, x: 0, y: 0 }]);
  p.startShot();
  p.push(frame(0.05, [[0, 0, 0.1, 7]]));
  p.push(frame(0.1, [[0, 0, 0.1, 7]], true));
  const balls = p.advance(0.2);
  assert.equal(balls.get(0).cel, 7);
  assert.ok(Math.abs(balls.get(0).heading - Math.PI / 2) < 1e-9, 'last moved along +y');
  p.reset([{ id: 0, x: 0, y: 0.1, cel: 7 }]);
  assert.equal(p.current.get(0).cel, 7);
  assert.ok(Math.abs(p.current.get(0).heading - Math.PI / 2) < 1e-9);
});

test('joining a shot mid-stream starts from the state`s tick', () => {
  const p = new FramePlayer({ delay: 0.1 });
  p.startShot([{ id: 0, x: 1, y: 0.5, cel: 2 }], 1.0);
  p.push(frame(1.05, [[0, 1.1, 0.5, 4]]));
  const balls = p.advance(0.05);
  assert.ok(balls.get(0).x >= 1 && balls.get(0).x <= 1.1);
});

test('frames sent ahead (four a message) play at real-time speed, `delay` behind', () => {
  // The server's stream: a frame every 0.05 s, sent four to a message (one on time, three
  // ahead) every 0.2 s. Playback must run at speed 1 and never run dry between messages.
  const p = new FramePlayer({ delay: 0.1 });
  p.reset([{ id: 0, x: 0, y: 0 }]);
  p.startShot();
  const step = 1 / 60;
  let wall = 0;
  let next = 1; // index of the next frame to send
  const behind = [];
  for (let i = 0; i < 180; i++) { // 3 s of display
    while (next * 0.05 <= wall + 1e-9 && next <= 60) {
      for (let k = 0; k < 4 && next + k <= 60; k++) {
        const t = (next + k) * 0.05;
        p.push({ t, ahead: k > 0, last: next + k === 60, balls: [{ id: 0, x: t, y: 0, cel: 0 }] });
      }
      next += 4;
    }
    const x = p.advance(step).get(0).x;
    wall += step;
    if (wall > 0.5) behind.push(wall - x); // playback time = x in this stream
  }
  const mean = behind.reduce((a, b) => a + b, 0) / behind.length;
  assert.ok(Math.abs(mean - 0.1) < 0.03, `mean delay ${mean}`);
  assert.ok(Math.max(...behind) - Math.min(...behind) < 0.05, 'no stutter or sawtooth');
});
