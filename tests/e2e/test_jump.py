"""A jump shot in real Chromium: a player jumps the cue ball over a ball in its way, and a
page watching shows the hop, read through `window.pool.track(t)` (its `z`, the height a
ball flies above the bed, from the `motion` message's version 2).

The engine, run here on the same table and stroke, says where the ball flies; the page must
draw it over the blocker, higher than the blocker's top, within a millimetre of the
engine's height.
"""

from __future__ import annotations

import json
import math

import httpx
import numpy as np
import pytest
from websockets.sync.client import connect as ws_connect

from server.engine import BALL_RADIUS, BallSet, Shot, ShotInMotion, Table, tip_seen_level
from server.protocol.motion import TRACE

from .helpers import wait_for, wait_ready

pytestmark = pytest.mark.browser

MM = 0.001
ELEVATION = math.radians(45)
JUMP = Shot(-math.pi / 2, 4.0, tip_seen_level((0.0, 0.0), ELEVATION), ELEVATION)
CUE_AT = "window.__pool.state.match.balls.find((b) => b.id === 0)"


def test_a_player_jumps_over_a_blocker_and_the_page_shows_the_hop(base_url, new_page):
    table = Table.pool("9ft")
    with httpx.Client(base_url=base_url) as http:
        room_id = http.post("/api/rooms", json={"game": "practice"}).json()["room_id"]
        ana = http.post(f"/api/rooms/{room_id}/join", json={"name": "Ana"}).json()
    watcher = new_page()
    watcher.goto(f"{base_url}/r/{room_id}?watch")
    wait_ready(watcher, "aiming")
    apex_x, apex_y = table.foot_spot  # the rack's apex ball: the blocker, 25 cm ahead
    ws_url = base_url.replace("http://", "ws://") + f"/ws/rooms/{room_id}?token={ana['token']}"
    with ws_connect(ws_url) as player:
        player.send(json.dumps({"type": "place_cue", "x": apex_x, "y": apex_y + 0.25}))
        wait_for(watcher, f"Math.abs({CUE_AT}.y - {apex_y + 0.25}) < 1e-9", timeout=10_000)
        rest = watcher.evaluate("window.__pool.state.match.balls")
        blocker = next(b["id"] for b in rest if math.dist((b["x"], b["y"]), (apex_x, apex_y)) < MM)
        balls = BallSet.place({b["id"]: (b["x"], b["y"]) for b in rest})
        message = {"type": "shoot", "angle": JUMP.angle, "speed": JUMP.speed,
                   "tip": list(JUMP.tip), "elevation": JUMP.elevation}  # fmt: skip
        player.send(json.dumps(message))
        wait_for(watcher, "window.__pool.playing", timeout=10_000)
        wait_for(watcher, "!window.__pool.playing", timeout=30_000)

    # The engine: the instant the cue ball is over the blocker, and its height then.
    engine = ShotInMotion(table, balls, JUMP)
    engine.run(trace=TRACE)
    samples = engine.trace
    assert samples.heights is not None
    cue, row = (
        int(np.flatnonzero(samples.ids == 0)[0]),
        int(np.flatnonzero(samples.ids == blocker)[0]),
    )
    # The first sample past the blocker's line (the cue ball flies -y at it).
    over = int(np.flatnonzero(samples.positions[:, cue, 1] <= samples.positions[:, row, 1])[0])
    t_over, z_over = float(samples.times[over]), float(samples.heights[over, cue])
    assert z_over > 2 * BALL_RADIUS * math.sqrt(0.75)

    drawn = watcher.evaluate("(t) => window.pool.track(t)", t_over)
    at = {b["id"]: b for b in drawn}
    assert at[0]["z"] > 2 * BALL_RADIUS * math.sqrt(0.75), "drawn in the air over the blocker"
    assert abs(at[0]["z"] - z_over) <= MM
    assert at[blocker]["z"] == 0
    assert math.dist((at[blocker]["x"], at[blocker]["y"]), (apex_x, apex_y)) < MM, "not touched"
    # Before the strike and at rest the ball is on the bed.
    assert watcher.evaluate("window.pool.track(0)")[0]["z"] == 0
