"""The lobby (name remembered, open tables listed with join and watch) and ball in hand
(dragging the cue ball with the mouse), in real Chromium against a real server."""

from __future__ import annotations

import re

import pytest
from playwright.sync_api import expect

from .helpers import create_table, lobby_row, table_point, wait_for, wait_ready

pytestmark = pytest.mark.browser


def test_lobby_lists_tables_to_join_or_watch_and_remembers_the_name(base_url, new_page):
    ana = new_page()
    ana.goto(base_url + "/")
    expect(ana.get_by_test_id("name")).to_have_value(re.compile(r"^Player "))  # the profile's
    ana.get_by_test_id("name").fill("")
    ana.get_by_test_id("create-room").click()
    expect(ana.get_by_test_id("lobby-error")).to_contain_text("name")  # no name, no table
    ana.get_by_test_id("name").fill("Ana")
    ana.get_by_test_id("game-select").select_option("nine_ball")
    room_id = create_table(ana)

    ben = new_page()
    ben.goto(base_url + "/")
    row = lobby_row(ben, room_id)
    expect(row).to_contain_text("9-ball")
    expect(row).to_contain_text("Ana vs free seat")
    ben.get_by_test_id("name").fill("Ben")
    ben.reload()
    expect(ben.get_by_test_id("name")).to_have_value("Ben")  # remembered
    lobby_row(ben, room_id).get_by_test_id("join").click()
    ben.wait_for_url(re.compile(f"/r/{room_id}$"))
    wait_ready(ben, "aiming")
    expect(ben.get_by_test_id("role")).to_have_text("seat 2")
    expect(ben.get_by_test_id("player-0")).to_contain_text("Ana")
    expect(ben.get_by_test_id("player-1")).to_contain_text("Ben (you)")

    # The table is full now: the lobby offers only to watch it.
    carl = new_page()
    carl.goto(base_url + "/")
    full = lobby_row(carl, room_id)
    expect(full).to_contain_text("Ana vs Ben")
    expect(full.get_by_test_id("join")).to_have_count(0)
    full.get_by_test_id("watch").click()
    carl.wait_for_url(re.compile(f"/r/{room_id}"))
    wait_ready(carl, "aiming")
    expect(carl.get_by_test_id("role")).to_have_text("spectator")
    expect(carl.get_by_test_id("turn")).to_contain_text("Ana's turn")


def test_ball_in_hand_drag_places_the_cue_ball(base_url, new_page):
    page = new_page()
    page.goto(base_url + "/")
    page.get_by_test_id("name").fill("Solo")
    page.get_by_test_id("game-select").select_option("practice")
    page.get_by_test_id("create-room").click()
    wait_ready(page, "aiming")
    expect(page.get_by_test_id("turn")).to_contain_text("Your turn")
    cue = page.evaluate("window.__pool.balls.find((b) => b.id === 0)")
    start = table_point(page, cue["x"], cue["y"])
    target = table_point(page, 0.4, 0.3)
    page.mouse.move(*start)
    page.mouse.down()
    page.mouse.move(*target, steps=8)
    page.mouse.up()
    wait_for(
        page,
        "(() => { const c = window.__pool.state.balls.find((b) => b.id === 0);"
        " return c && Math.abs(c.x - 0.4) < 0.01 && Math.abs(c.y - 0.3) < 0.01; })()",
        timeout=5000,
    )
    assert page.evaluate("window.__pool.shotsSeen") == 0, "placing is not a shot"


CATCH_VIOLATIONS = """
window.__csp = [];
document.addEventListener('securitypolicyviolation',
  (e) => window.__csp.push(e.violatedDirective + ' ' + e.blockedURI));
"""


def test_a_private_table_plays_under_the_security_policy(base_url, new_page):
    """The page runs under its Content-Security-Policy (no inline script, no eval) without
    a single violation, and a private table is reached by its link, not the lobby."""
    ana = new_page()
    ana.add_init_script(CATCH_VIOLATIONS)
    response = ana.goto(base_url + "/")
    assert response is not None
    assert "script-src 'self'" in response.headers["content-security-policy"]
    ana.get_by_test_id("name").fill("Ana")
    ana.get_by_test_id("private-table").check()
    room_id = create_table(ana)

    ben = new_page()
    ben.add_init_script(CATCH_VIOLATIONS)
    ben.goto(base_url + "/")
    ben.get_by_test_id("name").fill("Ben")
    expect(ben.get_by_test_id("rooms")).not_to_contain_text("Ana vs free seat")
    assert lobby_row(ben, room_id).count() == 0
    ben.goto(f"{base_url}/r/{room_id}")  # the link Ana sent
    ben.get_by_test_id("join-name").fill("Ben")
    ben.get_by_test_id("join").click()
    wait_ready(ben, "aiming")
    wait_ready(ana, "aiming")
    assert ana.evaluate("window.__csp") == [] and ben.evaluate("window.__csp") == []
