"""A jump shot in real Chromium, played the way a person plays it: the player drags the
cue ball into place, raises the cue with the elevation control (its side view, by the
keyboard), aims and pulls back on the table, and lets go; a page watching shows the hop,
read through `window.pool.track(t)` (its `z`, the height a ball flies above the bed, from
the `motion` message's version 2).

The engine, run here on the same table and the stroke the page sent, says where the ball
flies; the page must draw it over the blocker, higher than the blocker's top, within a
millimetre of the engine's height.
"""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest
from playwright.sync_api import expect

from server.engine import BALL_RADIUS, BallSet, Shot, ShotInMotion, Table
from server.protocol.motion import TRACE

from .helpers import table_point, wait_for, wait_ready

pytestmark = pytest.mark.browser

MM = 0.001
DEGREES = 45
PULL = 0.2  # metres pulled back: half the full pull, about 4 m/s (speedFromPower)
CUE_AT = "window.__pool.state.match.balls.find((b) => b.id === 0)"
OVER = 2 * BALL_RADIUS * math.sqrt(0.75)  # a ball's centre this high clears a ball's top


def test_a_player_jumps_over_a_blocker_and_the_page_shows_the_hop(base_url, new_page):
    table = Table.pool("9ft")
    ana = new_page()
    sent: list[dict] = []
    ana.on(
        "websocket",
        lambda ws: ws.on(
            "framesent", lambda f: sent.append(json.loads(f)) if isinstance(f, str) else None
        ),
    )
    ana.goto(base_url + "/")
    ana.get_by_test_id("name").fill("Ana")
    ana.get_by_test_id("game-select").select_option("practice")
    ana.get_by_test_id("create-room").click()
    ana.wait_for_url(re.compile(r"/r/[A-Za-z0-9_-]+$"))
    room_id = ana.url.rsplit("/", 1)[1]
    wait_ready(ana, "aiming")
    watcher = new_page()
    watcher.goto(f"{base_url}/r/{room_id}?watch")
    wait_ready(watcher, "aiming")

    # Ball in hand: drag the cue ball 25 cm short of the rack's apex ball (the blocker).
    apex_x, apex_y = table.foot_spot
    start = (apex_x, apex_y + 0.25)
    cue = ana.evaluate(CUE_AT)
    ana.mouse.move(*table_point(ana, cue["x"], cue["y"]))
    ana.mouse.down()
    ana.mouse.move(*table_point(ana, *start), steps=12)
    ana.mouse.up()
    wait_for(ana, f"Math.hypot({CUE_AT}.x - {start[0]}, {CUE_AT}.y - {start[1]}) < 0.003")
    placed = ana.evaluate(CUE_AT)
    rest = ana.evaluate("window.__pool.state.match.balls")

    # Level, the guide meets the blocker.
    target = (placed["x"], placed["y"] - 0.1)
    ana.mouse.move(*table_point(ana, *target), steps=5)
    wait_for(ana, "window.__pool.objectGuide !== null")

    # Raise the cue with the side view: focus it, level (Home), then up 45 degrees.
    view = ana.get_by_test_id("elevation-view")
    view.focus()
    view.press("Home")
    for _ in range(DEGREES // 10):
        view.press("Shift+ArrowUp")
    for _ in range(DEGREES % 10):
        view.press("ArrowUp")
    expect(ana.get_by_test_id("elevation-out")).to_have_text(f"{DEGREES}°")
    assert abs(ana.evaluate("window.__pool.aim.elevation") - math.radians(DEGREES)) < 1e-12
    assert ana.get_by_test_id("elevation").input_value() == str(DEGREES)

    # Aim at the blocker, press, pull back: the raised guide passes over it; let go.
    ana.mouse.move(*table_point(ana, *target), steps=5)
    ana.mouse.down()
    ana.mouse.move(*table_point(ana, target[0], target[1] + PULL), steps=10)
    wait_for(ana, "window.__pool.aim.mode === 'pulling' && window.__pool.objectGuide === null")
    # The watcher is sent the raised aim and draws its guide over the blocker too.
    relayed = "window.__pool.state.aim && window.__pool.state.aim.power > 0.4"
    wait_for(watcher, f"{relayed} && window.__pool.objectGuide === null")
    assert watcher.evaluate("window.__pool.state.aim.elevation") == pytest.approx(
        math.radians(DEGREES), abs=1e-6
    )
    ana.mouse.up()
    wait_for(watcher, "window.__pool.playing", timeout=10_000)
    wait_for(watcher, "!window.__pool.playing", timeout=30_000)

    shots = [m for m in sent if m.get("type") == "shoot"]
    assert len(shots) == 1 and shots[0]["elevation"] == pytest.approx(math.radians(DEGREES))
    shoot = shots[0]
    stroke = Shot(shoot["angle"], shoot["speed"], tuple(shoot["tip"]), shoot["elevation"])

    # The engine, on the table as it was: when the cue ball is over the blocker, how high.
    blocker = next(b["id"] for b in rest if math.dist((b["x"], b["y"]), (apex_x, apex_y)) < MM)
    balls = BallSet.place({b["id"]: (b["x"], b["y"]) for b in rest})
    engine = ShotInMotion(table, balls, stroke)
    engine.run(trace=TRACE)
    samples = engine.trace
    assert samples.heights is not None
    cue_row = int(np.flatnonzero(samples.ids == 0)[0])
    row = int(np.flatnonzero(samples.ids == blocker)[0])
    # The first sample past the blocker's line (the cue ball flies -y at it).
    past = samples.positions[:, cue_row, 1] <= samples.positions[:, row, 1]
    over = int(np.flatnonzero(past)[0])
    t_over, z_over = float(samples.times[over]), float(samples.heights[over, cue_row])
    assert z_over > OVER

    drawn = watcher.evaluate("(t) => window.pool.track(t)", t_over)
    at = {b["id"]: b for b in drawn}
    assert at[0]["z"] > OVER, "drawn in the air over the blocker"
    assert abs(at[0]["z"] - z_over) <= MM
    assert at[blocker]["z"] == 0
    assert math.dist((at[blocker]["x"], at[blocker]["y"]), (apex_x, apex_y)) < MM, "not touched"
    # Before the strike and at rest the ball is on the bed.
    assert watcher.evaluate("window.pool.track(0)")[0]["z"] == 0
