"""Watching a finished match again: the lobby lists it, `/m/{id}` replays its shots from the
stored start states through the live table's renderer (frames, sprites, sounds), with play,
pause, previous/next and speed; an unknown match says so. Real Chromium, real server."""

from __future__ import annotations

from urllib.parse import urlparse

import pytest
from playwright.sync_api import expect
from websockets.sync.client import connect

from tests.support.games import BREAK, EIGHT_BALL_BREAK_BALL, EIGHT_BALL_SCRATCH
from tests.support.live import http, ws_url
from tests.support.messages import JsonSocket, receive_until
from tests.support.rooms import play_shot, seated_room

from .helpers import wait_for

pytestmark = pytest.mark.browser

SHOTS = [BREAK, EIGHT_BALL_SCRATCH]
REPLAY_READY = "window.__replay && window.__replay.ready && window.__replay.match"


def play_a_short_match(base_url: str) -> int:
    """Two players over the real API, the rack of `games.EIGHT_BALL` (conftest), race to 1:
    the break pockets a ball, Ana's second shot scratches, Ben concedes. A finished match of
    two shots; returns its id."""
    address = urlparse(base_url).netloc
    with http(address) as client:
        room_id, ta, tb = seated_room(client, race_to=1)
    with connect(ws_url(address, room_id, ta)) as ca, connect(ws_url(address, room_id, tb)) as cb:
        a, b = JsonSocket(ca), JsonSocket(cb)
        state = receive_until(a, "state")[-1]
        pocketed = []
        for shot in SHOTS:
            _, seen, state = play_shot((a, b), a, state, shot)
            pocketed += [m["outcome"]["pocketed"] for m in seen if m["type"] == "shot_result"]
        assert pocketed == [[EIGHT_BALL_BREAK_BALL], [0]]  # a ball, then the cue ball
        assert state["match"]["turn"] == 1  # Ben's, with ball in hand
        b.send_json({"type": "concede"})
        assert receive_until(a, "state")[-1]["phase"] == "over"
    with http(address) as client:
        matches = client.get("/api/matches", params={"status": "finished", "limit": 100})
    return next(m["id"] for m in matches.json()["matches"] if m["room_id"] == room_id)


def test_a_finished_match_is_listed_and_replayed_shot_by_shot(base_url, new_page, artifacts):
    match_id = play_a_short_match(base_url)

    page = new_page()
    page.goto(base_url + "/")
    entry = page.locator(f"[data-testid=history-match][data-match='{match_id}']")
    expect(entry).to_contain_text("Ana")
    expect(entry).to_contain_text("Ben")
    expect(entry).to_contain_text("won")
    expect(page.locator("#no-history")).to_be_hidden()
    entry.get_by_test_id("watch-match").click()
    page.wait_for_url(f"{base_url}/m/{match_id}")
    expect(page.get_by_test_id("replay-view")).to_be_visible()
    wait_for(page, REPLAY_READY)
    expect(page.get_by_test_id("replay-title")).to_contain_text("Ana vs Ben")
    expect(page.get_by_test_id("replay-shot")).to_have_text("shot 1 / 2")

    # Before playing: the rack, at rest, drawn where the stored table had it.
    rack = page.evaluate("window.__replay.balls")
    assert len(rack) == 16
    page.get_by_test_id("replay-speed").select_option("4")
    page.get_by_test_id("replay-play").click()
    expect(page.get_by_test_id("replay-play")).to_have_text("Stop")
    wait_for(page, "window.__replay.framesSeen >= 1")  # the first shot's motion came
    cue_start = next(b for b in rack if b["id"] == 0)
    wait_for(
        page,
        "([x, y]) => { const c = window.__replay.balls.find((b) => b.id === 0);"
        " return !c || Math.hypot(c.x - x, c.y - y) > 0.2; }",
        arg=[cue_start["x"], cue_start["y"]],
    )
    page.get_by_test_id("replay-table").screenshot(path=str(artifacts / "replay.png"))

    # The break ends, its outcome shows, and the next shot follows on its own.
    expect(page.get_by_test_id("replay-shot")).to_have_text("shot 2 / 2", timeout=30_000)
    second = page.evaluate("window.__replay.match.shots[1].b")
    assert len(second) >= 1
    # At the end of the match playback stops.
    expect(page.get_by_test_id("replay-play")).to_have_text("Play", timeout=30_000)

    # Previous / next move by one shot and put that shot's starting table down.
    page.get_by_test_id("replay-prev").click()
    expect(page.get_by_test_id("replay-shot")).to_have_text("shot 1 / 2")
    assert len(page.evaluate("window.__replay.balls")) == 16
    page.get_by_test_id("replay-next").click()
    expect(page.get_by_test_id("replay-shot")).to_have_text("shot 2 / 2")
    shown = sorted(
        (b["id"], round(b["x"], 3), round(b["y"], 3))
        for b in page.evaluate("window.__replay.balls")
    )
    assert shown == sorted((i, round(x / 1000, 3), round(y / 1000, 3)) for i, x, y, _ in second)

    page.get_by_test_id("replay-back").click()
    page.wait_for_url(f"{base_url}/")
    expect(page.get_by_test_id("history-list")).to_be_visible()


def test_an_unknown_match_says_so(base_url, new_page):
    page = new_page()
    page.goto(base_url + "/m/999999")
    expect(page.get_by_test_id("replay-error")).to_contain_text("no such match")
    page.goto(base_url + "/m/not-a-number")
    expect(page.get_by_test_id("replay-error")).to_contain_text("no such match")
