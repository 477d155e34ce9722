"""What a spectator's page draws of a real break, read through `window.pool.track(t)`.

The break is played by a player's socket; the pages only watch. The engine, run here on the
same rack and shot, says when each contact happens; at each of those instants the page must
draw the two balls touching (centres 2R apart) or the ball touching the rail, within 1 mm.
A second spectator comes in while the break is rolling and is shown the rest of it.
"""

from __future__ import annotations

import json
import math

import httpx
import pytest
from websockets.sync.client import connect as ws_connect

from server.engine import BALL_RADIUS, Table, rack, simulate
from tests.support.games import BREAK, BREAK_MESSAGE, EIGHT_BALL

from .helpers import READY, wait_for, wait_ready

pytestmark = pytest.mark.browser

MM = 0.001


def test_a_spectator_draws_every_contact_of_a_break_within_a_millimetre(base_url, new_page):
    table = Table.pool("9ft")
    balls = rack("eight_ball", table, seed=EIGHT_BALL)  # every room of the server racks so
    result = simulate(table, balls, BREAK)
    with httpx.Client(base_url=base_url) as http:
        room_id = http.post("/api/rooms", json={"game": "eight_ball"}).json()["room_id"]
        ana = http.post(f"/api/rooms/{room_id}/join", json={"name": "Ana"}).json()
        http.post(f"/api/rooms/{room_id}/join", json={"name": "Ben"})

    watcher = new_page()
    watcher.goto(f"{base_url}/r/{room_id}?watch")
    wait_ready(watcher, "aiming")
    rest = watcher.evaluate("window.__pool.state.match.balls")
    assert [(b["id"], b["x"], b["y"]) for b in rest] == [
        (int(i), x, y) for i, (x, y) in zip(balls.ids, balls.positions.tolist(), strict=True)
    ], "the page's rack is the one simulated here"

    ws_url = base_url.replace("http://", "ws://") + f"/ws/rooms/{room_id}?token={ana['token']}"
    with ws_connect(ws_url) as player:
        player.send(json.dumps(BREAK_MESSAGE))
        wait_for(watcher, "window.__pool.playing", timeout=10_000)
        late = new_page()  # comes in while the balls roll
        late.goto(f"{base_url}/r/{room_id}?watch")
        wait_for(late, READY + " && window.__pool.playing", timeout=10_000)
        joined_at = late.evaluate("window.__pool.shotTime")
        wait_for(watcher, "!window.__pool.playing", timeout=30_000)
        wait_for(late, "!window.__pool.playing", timeout=30_000)

    contacts = [e for e in result.events if e.kind in ("ball", "cushion")]
    assert len(contacts) > 20
    drawn = watcher.evaluate(
        "(ts) => ts.map((t) => window.pool.track(t))", [e.time for e in contacts]
    )
    cushions = table.cushion_array()
    for event, balls_at in zip(contacts, drawn, strict=True):
        at = {b["id"]: (b["x"], b["y"]) for b in balls_at}
        if event.kind == "ball":
            a, b = (at[i] for i in event.ids)
            gap = math.dist(a, b) - 2 * BALL_RADIUS
            assert abs(gap) <= MM, f"{event}: drawn {gap / MM:.2f} mm off touching"
        else:
            x, y = at[event.ids[0]]
            c = cushions[event.target]
            off = (x - c[0]) * c[4] + (y - c[1]) * c[5] - BALL_RADIUS
            assert abs(off) <= MM, f"{event}: drawn {off / MM:.2f} mm off the rail"

    # The latecomer started where the break was, and was shown the rest of it: the same
    # track from there on, ending where the balls rest.
    duration = len(result.frames) / 120
    assert 0.2 < joined_at < duration
    later = [joined_at + (duration - joined_at) * k / 10 for k in range(11)]
    mine = late.evaluate("(ts) => ts.map((t) => window.pool.track(t))", later)
    theirs = watcher.evaluate("(ts) => ts.map((t) => window.pool.track(t))", later)
    assert mine == theirs
    final = result.final
    drawn_rest = {b["id"]: (b["x"], b["y"]) for b in late.evaluate("window.__pool.balls")}
    assert sorted(drawn_rest) == final.ids[final.on_table].tolist()
    for i, (x, y) in zip(final.ids.tolist(), final.positions.tolist(), strict=True):
        if i in drawn_rest:
            assert math.dist(drawn_rest[i], (x, y)) <= MM
