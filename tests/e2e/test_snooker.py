"""A newcomer plays snooker against the computer through the page, in real Chromium: the
lobby's computer card, the table drawn with the D, the break-off from the D, the
computer's visit, the frame's scoreboard, then the frame conceded (WPBSA 2.1 Frame: a
player may concede during their turn) so the match ends.

Everything is driven through the page (lobby fields, the mouse on the canvas, buttons);
`window.__pool` is only read, to wait and to find where things are drawn.
"""

from __future__ import annotations

import re

import pytest
from playwright.sync_api import expect

from .helpers import aim_and_shoot, table_point, wait_for, wait_ready

pytestmark = pytest.mark.browser


def test_a_newcomer_plays_a_snooker_frame_against_the_computer(base_url, new_page, artifacts):
    ana = new_page()
    ana.goto(base_url + "/")
    ana.get_by_test_id("name").fill("Ana")
    ana.get_by_test_id("computer-game").select_option("snooker")
    ana.get_by_test_id("computer-level").select_option("beginner")
    ana.get_by_test_id("play-computer").click()
    ana.wait_for_url(re.compile(r"/r/[A-Za-z0-9_-]+$"))
    wait_ready(ana, "aiming")
    table = ana.evaluate("window.__pool.state.table")
    assert table["style"] == "snooker" and table["ball_radius"] == 0.02625
    assert [a["radius"] for a in table["arcs"]] == [0.292]
    assert len(ana.evaluate("window.__pool.balls")) == 22
    expect(ana.get_by_test_id("frame-box")).to_be_visible()
    expect(ana.get_by_test_id("frame")).to_contain_text("Remaining 147")
    expect(ana.get_by_test_id("turn")).to_contain_text("Your turn")
    # Ball in hand in the D: drag the cue ball to the brown's side, then break off at the
    # back red of the pack's near corner.
    cue = ana.evaluate("window.__pool.balls.find((b) => b.id === 0)")
    brown = table["spots"]["brown"]
    start = table_point(ana, cue["x"], cue["y"])
    end = table_point(ana, brown[0] - 0.05, brown[1] + 0.1)
    ana.mouse.move(*start)
    ana.mouse.down()
    ana.mouse.move(*end, steps=8)
    ana.mouse.up()
    wait_for(
        ana,
        "([x]) => Math.abs(window.__pool.balls.find((b) => b.id === 0).x - x) < 0.01",
        [brown[0] - 0.05],
    )
    placed = ana.evaluate("window.__pool.balls.find((b) => b.id === 0)")
    assert abs(placed["x"] - (brown[0] - 0.05)) < 0.01, placed
    reds = ana.evaluate("window.__pool.balls.filter((b) => b.id >= 1 && b.id <= 15)")
    corner = max(reds, key=lambda b: (b["x"], b["y"]))
    aim_and_shoot(ana, (corner["x"], corner["y"]), pull_px=120)
    wait_for(ana, "window.__pool.state.lastResult?.outcome?.shooter === 0", timeout=60_000)
    computer_shot = "window.__pool.state.lastResult?.outcome?.shooter === 1"
    wait_for(ana, computer_shot, timeout=120_000)  # the computer played its own visit
    ana.get_by_test_id("table").screenshot(path=str(artifacts / "snooker.png"))
    frame = ana.get_by_test_id("frame").inner_text()
    assert "Ana" in frame and "Remaining" in frame
    points = ana.evaluate("window.__pool.state.match.points")
    assert len(points) == 2 and sum(points) >= 0
    # Ana concedes the frame between two strokes.
    wait_for(ana, "window.__pool.state.phase === 'aiming'", timeout=60_000)
    ana.once("dialog", lambda d: d.accept())
    ana.get_by_test_id("concede").click()
    wait_for(ana, "window.__pool.state.phase === 'over'", timeout=30_000)
    expect(ana.get_by_test_id("turn")).to_contain_text("wins the match")
