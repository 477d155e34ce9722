"""A finished match's analysis on its replay page: "Analyse" asks for it, the strip shows
each shot coloured by its verdict, the players' accuracy is shown, and the pro's best shot
is drawn over the table beside the shot played; a newcomer's mistake played again as a
drill; the standard solo drills from the lobby (ghost 9-ball, the line-up). Real
Chromium, real server (the analysis in its idle-class planner process, as in production)."""

from __future__ import annotations

import re

import httpx
import pytest
from playwright.sync_api import expect

from .helpers import aim_and_shoot, apex, create, sit, table_point, wait_for, wait_ready
from .test_history import REPLAY_READY, play_a_short_match

pytestmark = pytest.mark.browser

ANALYSED = 120_000  # ms: the planner process starts, then two shots are judged
# A checksum of the replay canvas' pixels: what is drawn changes it.
REPLAY_PIXELS = """() => {
  const c = document.querySelector('[data-testid=replay-table]');
  const px = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
  let a = 0, b = 0;
  for (let i = 0; i < px.length; i++) { a = (a + px[i]) % 65521; b = (b + a) % 65521; }
  return `${a}:${b}`;
}"""


def test_a_replay_shows_the_verdict_strip_and_the_best_shot(base_url, new_page, artifacts):
    match_id = play_a_short_match(base_url)
    page = new_page()
    page.goto(f"{base_url}/m/{match_id}")
    wait_for(page, REPLAY_READY)
    before = page.evaluate(REPLAY_PIXELS)
    page.get_by_test_id("replay-analyse").click()
    wait_for(page, "window.__replay.analysis.ready", timeout=ANALYSED)

    cells = page.get_by_test_id("verdict")
    expect(cells).to_have_count(2)
    verdicts = page.evaluate("window.__replay.analysis.verdicts")
    assert all(v in ("best", "good", "mistake", "blunder") for v in verdicts)
    for k, verdict in enumerate(verdicts):
        expect(cells.nth(k)).to_have_attribute("data-verdict", verdict)
        expect(cells.nth(k)).to_have_class(
            f"verdict verdict-{verdict}" + (" current" if k == 0 else "")
        )
    expect(page.get_by_test_id("accuracy")).to_have_count(2)
    expect(page.get_by_test_id("accuracy").first).to_contain_text("Ana: accuracy")
    expect(page.get_by_test_id("analysis-shot")).to_contain_text("The pro:")

    # The break on the table: the pro's best shot is drawn over it.
    wait_for(page, "window.__replay.analysis.bestDrawn")
    assert page.evaluate(REPLAY_PIXELS) != before
    page.get_by_test_id("replay-view").screenshot(path=str(artifacts / "analysis-replay.png"))

    # A cell of the strip shows its shot, judged.
    cells.nth(1).click()
    expect(page.get_by_test_id("replay-shot")).to_have_text("shot 2 / 2")
    expect(page.get_by_test_id("analysis-shot")).to_have_attribute("data-verdict", verdicts[1])
    wait_for(page, "window.__replay.analysis.bestDrawn")


def test_a_newcomer_analyses_their_game_and_plays_a_mistake_as_a_drill(
    base_url, new_page, artifacts
):
    room_id = create(base_url, race_to=1, shot_clock=0)
    ana, ben = new_page(), new_page()
    sit(ana, base_url, room_id, "Ana")
    sit(ben, base_url, room_id, "Ben")
    wait_ready(ana, "aiming")
    # Ana's soft break is illegal (a mistake to learn from); Ben plays on, then concedes.
    aim_and_shoot(ana, apex(ana), pull_px=40)
    decision = ben.get_by_test_id("decision")
    decision.get_by_role("button", name="Play from here").click(timeout=30_000)
    wait_for(ana, "!window.__pool.state.match.decision")
    ben.on("dialog", lambda d: d.accept())
    ben.get_by_test_id("concede").click()

    # After the game: Analyse opens the replay with the analysis.
    ana.get_by_test_id("analyse").click(timeout=30_000)
    ana.wait_for_url(re.compile(r"/m/\d+\?analyse=1$"))
    wait_for(ana, "window.__replay && window.__replay.analysis.ready", timeout=ANALYSED)
    first = ana.get_by_test_id("verdict").first
    expect(first).to_have_attribute("data-verdict", re.compile("^(mistake|blunder)$"))
    expect(ana.get_by_test_id("analysis-shot")).to_contain_text("The pro:")
    match_id = int(ana.url.split("/m/")[1].split("?")[0])
    stored = httpx.get(f"{base_url}/api/matches/{match_id}", timeout=20).json()["shots"][0]["b"]

    # Play it again: a practice table with the stored table, the pro's chance as par.
    ana.get_by_test_id("analysis-drill").click()
    ana.wait_for_url(re.compile(r"/r/[^/?]+$"))
    ana.get_by_test_id("join").click()
    wait_ready(ana, "aiming")
    expect(ana.get_by_test_id("drill-text")).to_contain_text("Par: the strongest computer level")
    drill_room = ana.url.split("/r/")[1]
    state = httpx.get(f"{base_url}/api/rooms/{drill_room}", timeout=20).json()["state"]
    assert sorted(map(tuple, state["balls"])) == sorted(map(tuple, stored))
    ana.screenshot(path=str(artifacts / "analysis-drill.png"))
    aim_and_shoot(ana, apex(ana))
    expect(ana.get_by_test_id("drill-text")).to_have_attribute(
        "data-made", re.compile("^(true|false)$"), timeout=30_000
    )
    expect(ana.get_by_test_id("drill-back")).to_have_attribute("href", f"/m/{match_id}?analyse=1")

    # The profile keeps the drill among the personal bests, and charts the accuracy.
    ana.goto(f"{base_url}/profile")
    expect(ana.get_by_test_id("profile-drills")).to_contain_text("of 1;")
    expect(ana.get_by_test_id("accuracy-chart")).to_be_visible()
    expect(ana.get_by_test_id("accuracy-last")).to_contain_text("Last analysed match:")


def test_ghost_nine_ball_from_the_lobby_keeps_a_personal_best(base_url, new_page):
    page = new_page()
    page.goto(base_url + "/")
    page.get_by_test_id("ghost-drill").click()
    page.wait_for_url(re.compile(r"/r/[^/?]+$"))
    page.get_by_test_id("join").click()
    wait_ready(page, "aiming")
    words = page.get_by_test_id("drill-text")
    expect(words).to_contain_text("Ghost 9-ball: hit the lowest ball first")
    expect(page.get_by_test_id("drill-back")).to_be_hidden()
    balls = page.evaluate("window.__pool.balls")
    assert sorted(b["id"] for b in balls if b["id"] != 0) == list(range(1, 10))
    aim_and_shoot(page, apex(page))  # the break, at the 1
    # Scored: the ghost took the rack, or the break pocketed a ball in order.
    wait_for(page, "(d => d.done || d.score > 0)(window.__pool.state.room.drill)")
    expect(words).to_contain_text(re.compile(r"of 9 pocketed|Pocketed: [1-9] of 9"))
    page.goto(f"{base_url}/profile")
    expect(page.get_by_test_id("profile-ghost")).to_contain_text("of 1 racks")


def test_the_lineup_drill_from_the_lobby_plays_its_first_shot_and_keeps_a_best(base_url, new_page):
    page = new_page()
    page.goto(base_url + "/")
    page.get_by_test_id("lineup-drill").click()
    page.wait_for_url(re.compile(r"/r/[^/?]+$"))
    page.get_by_test_id("join").click()
    wait_ready(page, "aiming")
    words = page.get_by_test_id("drill-text")
    expect(words).to_contain_text("Line-up: clear the 3 balls in any order")
    table = page.evaluate("window.__pool.state.table")
    length, width = table["length"], table["width"]
    balls = page.evaluate("window.__pool.balls")
    line = sorted(b["id"] for b in balls if b["id"] != 0 and abs(b["y"] - width / 2) < 0.005)
    assert line == [1, 2, 3]
    # Ball in hand: drag the cue ball above the middle ball, then pot it in the side pocket.
    cue = page.evaluate("window.__pool.balls.find((b) => b.id === 0)")
    page.mouse.move(*table_point(page, cue["x"], cue["y"]))
    page.mouse.down()
    page.mouse.move(*table_point(page, length / 2, width / 2 + 0.3), steps=8)
    page.mouse.up()
    wait_for(
        page,
        "([x, y]) => { const c = window.__pool.state.balls.find((b) => b.id === 0);"
        " return c && Math.abs(c.x - x) < 0.01 && Math.abs(c.y - y) < 0.01; }",
        [length / 2, width / 2 + 0.3],
        timeout=5000,
    )
    aim_and_shoot(page, (length / 2, width / 2), pull_px=100)
    wait_for(page, "(d => d.done || d.score > 0)(window.__pool.state.room.drill)")
    expect(words).to_contain_text(re.compile(r"Pocketed: [1-9]|Run over"))
    page.get_by_test_id("rerack").click()  # another run
    wait_for(page, "(d => d.tries === 2 && d.score === 0)(window.__pool.state.room.drill)")
    page.goto(f"{base_url}/profile")
    expect(page.get_by_test_id("profile-lineup")).to_contain_text("of 1 runs")
