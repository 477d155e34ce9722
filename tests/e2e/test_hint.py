"""'Show me a shot' in practice, in real Chromium against a real server: the button asks the
server for the strongest computer level's plan and draws it on the table without playing
it."""

from __future__ import annotations

import re

import pytest
from playwright.sync_api import expect

from .helpers import canvas_digest, wait_for, wait_ready

pytestmark = pytest.mark.browser


def test_show_me_a_shot_draws_the_plan_without_playing_it(base_url, new_page, artifacts):
    ana = new_page()
    ana.goto(base_url + "/")
    ana.get_by_test_id("name").fill("Ana")
    ana.get_by_test_id("game-select").select_option("practice")
    ana.get_by_test_id("create-room").click()
    ana.wait_for_url(re.compile(r"/r/[A-Za-z0-9_-]+$"))
    wait_ready(ana, "aiming")
    button = ana.get_by_test_id("hint")
    expect(button).to_be_visible()
    expect(button).to_have_text("Show me a shot")
    balls = ana.evaluate("window.__pool.balls")
    before = canvas_digest(ana)
    ana.wait_for_timeout(300)
    assert canvas_digest(ana) == before  # the table at rest draws the same picture
    button.click()
    caption = ana.get_by_test_id("hint-text")
    expect(caption).to_have_text(re.compile(r"m/s, "), timeout=60_000)
    wait_for(ana, "window.__pool.ready")
    # The plan is drawn over the table on the next animation frame after the caption.
    for _ in range(50):
        if canvas_digest(ana) != before:
            break
        ana.wait_for_timeout(100)
    assert canvas_digest(ana) != before
    ana.get_by_test_id("table").screenshot(path=str(artifacts / "hint.png"))
    # Nothing was played: no shot, the balls where they were, still the player's turn.
    assert ana.evaluate("window.__pool.shotsSeen") == 0
    assert ana.evaluate("window.__pool.balls") == balls
    assert ana.evaluate("window.__pool.state.phase") == "aiming"
