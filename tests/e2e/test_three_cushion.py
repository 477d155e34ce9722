"""A newcomer plays three-cushion against the computer through the page, in real Chromium:
the lobby's computer card, the carom table (no pockets, its sights numbered), the opening
stroke on the red, the computer's inning with its own (yellow) ball, the scoreboard
(points, innings, average, high run) and the cushions counted, then the game conceded so
the match ends.

Everything is driven through the page (lobby fields, the mouse on the canvas, buttons);
`window.__pool` is only read, to wait and to find where things are drawn.
"""

from __future__ import annotations

import re

import pytest
from playwright.sync_api import expect

from .helpers import aim_and_shoot, wait_for, wait_ready

pytestmark = pytest.mark.browser

ANA_AT_THE_TABLE = "window.__pool.state.phase === 'aiming' && window.__pool.state.match.turn === 0"


def test_a_newcomer_plays_three_cushion_against_the_computer(base_url, new_page, artifacts):
    ana = new_page()
    ana.goto(base_url + "/")
    ana.get_by_test_id("name").fill("Ana")
    ana.get_by_test_id("computer-game").select_option("three_cushion")
    ana.get_by_test_id("computer-level").select_option("beginner")
    ana.get_by_test_id("play-computer").click()
    ana.wait_for_url(re.compile(r"/r/[A-Za-z0-9_-]+$"))
    wait_ready(ana, "aiming")
    table = ana.evaluate("window.__pool.state.table")
    assert table["style"] == "carom" and table["pockets"] == []
    assert (table["length"], table["width"]) == (2.84, 1.42)
    assert sorted(b["id"] for b in ana.evaluate("window.__pool.balls")) == [0, 1, 2]
    expect(ana.get_by_test_id("carom-box")).to_be_visible()
    expect(ana.get_by_test_id("carom")).to_contain_text("opening: hit the red first")
    expect(ana.get_by_test_id("turn")).to_contain_text("Your turn")
    # Ana opens on the red with her white, softly, until her inning ends.
    for _ in range(4):
        red = ana.evaluate("window.__pool.balls.find((b) => b.id === 2)")
        aim_and_shoot(ana, (red["x"], red["y"]), pull_px=60)
        wait_for(ana, "window.__pool.state.lastResult?.outcome?.shooter === 0", timeout=60_000)
        if ana.evaluate("window.__pool.state.match.turn") == 1:
            break
        wait_for(ana, ANA_AT_THE_TABLE, timeout=60_000)
    computer_shot = "window.__pool.state.lastResult?.outcome?.shooter === 1"
    wait_for(ana, computer_shot, timeout=120_000)  # the computer played with the yellow
    ana.get_by_test_id("table").screenshot(path=str(artifacts / "three_cushion.png"))
    board = ana.get_by_test_id("carom").inner_text()
    assert "Ana (white)" in board and "(yellow)" in board
    assert "innings" in board and "average" in board and "high run" in board
    expect(ana.get_by_test_id("cushions")).to_contain_text("Cushions:")
    carom = ana.evaluate("window.__pool.state.match.carom")
    assert carom["innings"][1] >= 1 and carom["cue_balls"] == [0, 1]
    assert ana.evaluate("window.__pool.state.match.points") == carom["points"]
    # Ana concedes at her next stroke.
    wait_for(ana, ANA_AT_THE_TABLE, timeout=180_000)
    ana.once("dialog", lambda d: d.accept())
    ana.get_by_test_id("concede").click()
    wait_for(ana, "window.__pool.state.phase === 'over'", timeout=30_000)
    expect(ana.get_by_test_id("turn")).to_contain_text("wins the match")


def test_show_me_a_shot_on_the_three_cushion_practice_table(base_url, new_page):
    """Practice on the carom table: "Show me a shot" is the computer's point off the red
    (the opening), "Try it" sets it up and Shoot plays it; the scoreboard counts it."""
    pia = new_page()
    pia.goto(base_url + "/")
    pia.get_by_test_id("name").fill("Pia")
    pia.get_by_test_id("game-select").select_option("three_cushion_practice")
    pia.get_by_test_id("create-room").click()
    pia.wait_for_url(re.compile(r"/r/[A-Za-z0-9_-]+$"))
    wait_ready(pia, "aiming")
    assert pia.evaluate("window.__pool.state.table.style") == "carom"
    with pia.expect_response(lambda r: r.url.endswith("/hint")) as answer:
        pia.get_by_test_id("hint").click()
    plan = answer.value.json()
    assert plan["kind"] == "point" and plan["target"] == 2 and plan["chance"] > 0
    caption = pia.get_by_test_id("hint-text")
    expect(caption).to_have_text(re.compile(r"^Score the point \(\d+ % of the computer's trials"))
    pia.get_by_test_id("hint-try").click()
    pia.get_by_test_id("hint-shoot").click()
    wait_for(pia, "window.__pool.shotsSeen === 1")
    wait_for(pia, "window.__pool.state.lastResult?.outcome?.shooter === 0", timeout=60_000)
    carom = pia.evaluate("window.__pool.state.match.carom")
    assert carom["points"][0] + carom["innings"][0] >= 2 and not carom["opening"]
    expect(pia.get_by_test_id("carom")).to_contain_text("Pia (white)")
