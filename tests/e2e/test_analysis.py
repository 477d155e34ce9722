"""A finished match's analysis on its replay page: "Analyse" asks for it, the strip shows
each shot coloured by its verdict, the players' accuracy is shown, and the pro's best shot
is drawn over the table beside the shot played. Real Chromium, real server (the analysis
in its idle-class planner process, as in production)."""

from __future__ import annotations

import pytest
from playwright.sync_api import expect

from .helpers import wait_for
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
