"""Two players, a spectator and a reload, in real Chromium against a real server.

Everything is driven through the page: the lobby's fields and buttons, the room link, and
the mouse on the canvas (aim, pull back, release). `window.__pool` is only read, to wait
for the stream and to find where the balls are drawn.
"""

from __future__ import annotations

import re
import time

import pytest
from playwright.sync_api import expect

from tests.support.games import EIGHT_BALL_BREAK_SAYS

from .helpers import aim_and_shoot, canvas_digest, table_point, wait_for, wait_ready

pytestmark = pytest.mark.browser


def test_break_seen_by_both_players_and_a_spectator_then_reload_rejoins(
    base_url, new_page, artifacts
):
    ana = new_page(device_scale_factor=2)  # a high-DPI screen
    ana.goto(base_url + "/")
    ana.get_by_test_id("name").fill("Ana")
    ana.get_by_test_id("game-select").select_option("eight_ball")
    ana.get_by_test_id("race-to").fill("2")
    ana.get_by_test_id("create-room").click()
    ana.wait_for_url(re.compile(r"/r/[A-Za-z0-9_-]+$"))
    # The link is filled in once the room has been read over HTTP, after the page loads.
    expect(ana.get_by_test_id("room-link")).to_have_value(ana.url)
    link = ana.get_by_test_id("room-link").input_value()
    wait_ready(ana, "waiting")
    expect(ana.get_by_test_id("turn")).to_contain_text("Waiting for an opponent")
    dpr_backing = ana.evaluate(
        "(() => { const c = document.querySelector('[data-testid=table]');"
        " return c.width / c.clientWidth; })()"
    )
    assert dpr_backing == 2, "the canvas backing store follows devicePixelRatio"

    ben = new_page()
    ben.goto(link)
    ben.get_by_test_id("join-name").fill("Ben")
    ben.get_by_test_id("join").click()
    wait_ready(ben, "aiming")
    wait_ready(ana, "aiming")
    expect(ben.get_by_test_id("role")).to_have_text("seat 2")
    expect(ana.get_by_test_id("turn")).to_contain_text("Your turn")
    expect(ben.get_by_test_id("turn")).to_contain_text("Ana's turn")
    expect(ana.get_by_test_id("score")).to_have_text("Ana 0 – 0 Ben (race to 2)")

    watcher = new_page()
    watcher.goto(link)  # both seats taken: a third person watches
    wait_ready(watcher, "aiming")
    expect(watcher.get_by_test_id("role")).to_have_text("spectator")
    expect(watcher.get_by_test_id("join")).to_be_hidden()
    expect(watcher.get_by_test_id("turn")).to_contain_text("Ana's turn")

    # Where the rack is drawn on each page, and its pixels before the break.
    foot = ana.evaluate("window.__pool.state.table.foot_spot")
    apex = ana.evaluate(
        "(fx) => window.__pool.balls.find((b) => b.id !== 0 && Math.abs(b.x - fx) < 0.01)", foot[0]
    )
    assert apex is not None, "a ball sits on the foot spot"

    def rack_region(page):
        (x0, y0), (x1, y1) = (
            table_point(page, foot[0] - 0.04, foot[1] + 0.04),
            table_point(page, foot[0] + 0.04, foot[1] - 0.04),
        )
        box = page.get_by_test_id("table").bounding_box()
        return (x0 - box["x"], y0 - box["y"], x1 - x0, y1 - y0)

    pages = {"ana": ana, "ben": ben, "watcher": watcher}
    before = {name: canvas_digest(p, rack_region(p)) for name, p in pages.items()}

    # Ana aims at the apex ball: Ben sees her cue through the relayed `aim`.
    tx, ty = table_point(ana, apex["x"], apex["y"])
    ana.mouse.move(tx, ty - 40)
    ana.mouse.move(tx, ty, steps=5)
    wait_for(ben, "window.__pool.state.aim && window.__pool.state.aim.seat === 0", timeout=5000)
    aim_and_shoot(ana, (apex["x"], apex["y"]))

    # The balls roll on every page: the canvas keeps changing while the stream plays.
    for page in pages.values():
        wait_for(page, "window.__pool.playing", timeout=10_000)
    changes = {name: set() for name in pages}
    for _ in range(4):
        for name, page in pages.items():
            changes[name].add(canvas_digest(page))
        time.sleep(0.15)
    for name in pages:
        assert len(changes[name]) >= 3, f"{name}'s canvas did not animate"

    # The shot ends: the outcome is written and the turn indicator names who plays next.
    for page in pages.values():
        wait_for(
            page,
            "window.__pool.state.phase === 'aiming' && !window.__pool.playing"
            " && window.__pool.shotsSeen >= 1",
            timeout=30_000,
        )
        expect(page.get_by_test_id("outcome")).to_contain_text("break")
    # The rack is fixed (conftest): this break pockets one ball and Ana plays again.
    outcome = ana.get_by_test_id("outcome").inner_text()
    assert outcome == EIGHT_BALL_BREAK_SAYS
    assert (
        outcome
        == ben.get_by_test_id("outcome").inner_text()
        == watcher.get_by_test_id("outcome").inner_text()
    )
    assert ana.evaluate("window.__pool.state.match.turn") == 0
    expect(ana.get_by_test_id("turn")).to_contain_text("Your turn")
    expect(ben.get_by_test_id("turn")).to_contain_text("Ana's turn")
    expect(watcher.get_by_test_id("turn")).to_contain_text("Ana's turn")
    for name, page in pages.items():
        assert canvas_digest(page, rack_region(page)) != before[name], (
            f"the rack still looks the same on {name}'s page"
        )
    # All three pages show the same table at rest.
    rest = [
        sorted(
            (b["id"], round(b["x"], 3), round(b["y"], 3)) for b in p.evaluate("window.__pool.balls")
        )
        for p in pages.values()
    ]
    assert rest[0] == rest[1] == rest[2]
    ana.get_by_test_id("table").screenshot(path=str(artifacts / "after-break.png"))
    assert ana.evaluate("window.__pool.state.error") is None, "the server refused nothing"

    # Chat reaches everyone.
    watcher.get_by_test_id("chat-input").fill("great break")
    watcher.get_by_test_id("chat-input").press("Enter")
    expect(ben.get_by_test_id("chat-log")).to_contain_text("great break")

    # A reload keeps Ben's seat (the token is remembered for this room).
    ben.reload()
    wait_ready(ben, "aiming")
    expect(ben.get_by_test_id("role")).to_have_text("seat 2")
    expect(ben.get_by_test_id("join")).to_be_hidden()
    expect(ben.get_by_test_id("connection")).to_have_text("open")
    expect(ben.get_by_test_id("outcome")).to_have_text(outcome)
    assert ben.evaluate("window.__pool.state.me.seat") == 1


def test_a_game_against_the_computer_from_the_lobby(base_url, new_page, artifacts):
    """Alone in the lobby: play the computer (its own card); it takes the second seat, and
    after Ana's break it is seen playing its own turn."""
    ana = new_page()
    ana.goto(base_url + "/")
    ana.get_by_test_id("name").fill("Ana")
    ana.get_by_test_id("computer-game").select_option("eight_ball")
    expect(ana.get_by_test_id("computer-level")).to_contain_text("Beginner")
    ana.get_by_test_id("computer-level").select_option("beginner")
    ana.get_by_test_id("play-computer").click()
    ana.wait_for_url(re.compile(r"/r/[A-Za-z0-9_-]+$"))
    wait_ready(ana, "aiming")
    expect(ana.get_by_test_id("player-1")).to_contain_text("Computer (beginner)")
    expect(ana.get_by_test_id("turn")).to_contain_text("Your turn")
    foot = ana.evaluate("window.__pool.state.table.foot_spot")
    aim_and_shoot(ana, (foot[0], foot[1]), pull_px=40)  # a soft break: not a legal one
    computer_shot = "window.__pool.state.lastResult?.outcome?.shooter === 1"
    wait_for(ana, computer_shot, timeout=90_000)  # the computer played its own shot
    wait_for(ana, "window.__pool.shotsSeen >= 2", timeout=30_000)  # and it was shown
    ana.get_by_test_id("table").screenshot(path=str(artifacts / "computer.png"))
