"""'Show me a shot' in practice, in real Chromium against a real server: the button asks the
server for the strongest computer level's plan and draws it on the table without playing
it."""

from __future__ import annotations

import json
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
    expect(caption).to_have_text(re.compile(r"power \d+ %, "), timeout=60_000)
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


def test_a_racked_table_is_shown_the_break_and_try_it_sets_it_up_to_shoot(base_url, new_page):
    """On a fresh practice rack the hint is the computer's tuned break, its power in % as
    the aim shows it; "Try it" places the cue ball and sets the aim, spin and power, and
    one press of Shoot plays it."""
    ana = new_page()
    sent: list[dict] = []
    ana.on(
        "websocket",
        lambda ws: ws.on(
            "framesent", lambda f: sent.append(json.loads(f)) if isinstance(f, str) else None
        ),
    )
    ana.goto(base_url + "/")
    ana.get_by_test_id("practice").click()
    ana.wait_for_url(re.compile(r"/r/[A-Za-z0-9_-]+$"))
    wait_ready(ana, "aiming")
    with ana.expect_response(lambda r: r.url.endswith("/hint")) as answer:
        ana.get_by_test_id("hint").click()
    plan = answer.value.json()
    assert plan["kind"] == "break" and plan["place"] is not None
    caption = ana.get_by_test_id("hint-text")
    expect(caption).to_have_text(re.compile(r"^Break: power \d+ %, centre ball\.$"))
    percent = int(re.search(r"power (\d+) %", caption.inner_text())[1])
    expect(ana.get_by_test_id("hint-shoot")).to_be_hidden()
    ana.get_by_test_id("hint-try").click()
    shoot = ana.get_by_test_id("hint-shoot")
    expect(shoot).to_have_text(f"Shoot · {percent} %")
    aim = ana.evaluate("window.__pool.aim")
    assert abs(aim["angle"] - plan["angle"]) < 1e-9 and aim["tip"] == plan["tip"]
    assert round(aim["power"] * 100) == percent
    wait_for(
        ana,
        """([x, y]) => { const c = window.__pool.balls.find((b) => b.id === 0);
           return Math.hypot(c.x - x, c.y - y) < 1e-4; }""",
        plan["place"],
    )
    assert ana.evaluate("window.__pool.shotsSeen") == 0
    shoot.click()
    wait_for(ana, "window.__pool.shotsSeen === 1")
    (shot,) = [m for m in sent if m.get("type") == "shoot"]
    assert abs(shot["speed"] - plan["speed"]) < 1e-3 and abs(shot["angle"] - plan["angle"]) < 1e-5
    assert shot["tip"] == plan["tip"]
