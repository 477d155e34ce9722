"""Watching a finished match again: the lobby lists it, `/m/{id}` replays its shots from the
stored start states through the live table's renderer (frames, sprites, sounds), with play,
pause, previous/next and speed; an unknown match says so. Real Chromium, real server."""

from __future__ import annotations

import json
from urllib.parse import urlparse
from urllib.request import Request, urlopen

from playwright.sync_api import expect
from websockets.sync.client import connect

SHOTS = [{"type": "shoot", "angle": 0.0, "speed": 9.0},
         {"type": "shoot", "angle": 2.2, "speed": 2.5}]
REPLAY_READY = "window.__replay && window.__replay.ready && window.__replay.match"


def _http(base_url: str, method: str, path: str, body: dict | None = None) -> dict:
    data = None if body is None else json.dumps(body).encode()
    req = Request(base_url + path, data=data, method=method,
                  headers={"content-type": "application/json"})
    with urlopen(req, timeout=10) as reply:
        return json.loads(reply.read())


def _until(ws, kind: str) -> list[dict]:
    seen = []
    while True:
        seen.append(json.loads(ws.recv(timeout=30)))
        if seen[-1]["type"] == kind:
            return seen


def play_a_short_match(base_url: str) -> int:
    """Two players over the real API: the break, one more shot, then a concession (race to
    1): a finished match of two shots. Returns its id."""
    room = _http(base_url, "POST", "/api/rooms", {"game": "eight_ball", "race_to": 1})
    room_id = room["room_id"]
    tokens = [_http(base_url, "POST", f"/api/rooms/{room_id}/join", {"name": n})["token"]
              for n in ("Ana", "Ben")]
    ws_base = f"ws://{urlparse(base_url).netloc}/ws/rooms/{room_id}"
    with connect(f"{ws_base}?token={tokens[0]}") as a, \
            connect(f"{ws_base}?token={tokens[1]}") as b:
        players = (a, b)
        state = _until(a, "state")[-1]
        for shot in SHOTS:
            match = state["match"]
            if match["decision"] is not None:
                decision = match["decision"]
                players[decision["seat"]].send(json.dumps(
                    {"type": "decide", "option": decision["options"][0]}))
                state = _until(a, "state")[-1]
                match = state["match"]
            shooter = players[match["turn"]]
            if not any(row[0] == 0 for row in state["balls"]):  # ball in hand
                shooter.send(json.dumps({"type": "place_cue", "x": 0.4, "y": 0.3}))
                state = _until(a, "state")[-1]
            if state["match"]["requires_call"]:
                shooter.send(json.dumps({"type": "call", "pocket": 0}))
                state = _until(a, "state")[-1]
            shooter.send(json.dumps(shot))
            seen = _until(a, "shot_result")
            assert not any(m["type"] == "error" for m in seen), seen
            state = _until(a, "state")[-1]
        players[state["match"]["turn"]].send(json.dumps({"type": "concede"}))
        assert _until(a, "state")[-1]["phase"] == "over"
    matches = _http(base_url, "GET", "/api/matches?status=finished&limit=100")["matches"]
    return next(m["id"] for m in matches if m["room_id"] == room_id)


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
    page.wait_for_function(REPLAY_READY)
    expect(page.get_by_test_id("replay-title")).to_contain_text("Ana vs Ben")
    expect(page.get_by_test_id("replay-shot")).to_have_text("shot 1 / 2")

    # Before playing: the rack, at rest, drawn where the stored table had it.
    rack = page.evaluate("window.__replay.balls")
    assert len(rack) == 16
    page.get_by_test_id("replay-speed").select_option("4")
    page.get_by_test_id("replay-play").click()
    expect(page.get_by_test_id("replay-play")).to_have_text("Stop")
    page.wait_for_function("window.__replay.framesSeen > 5")
    cue_start = next(b for b in rack if b["id"] == 0)
    page.wait_for_function(
        "([x, y]) => { const c = window.__replay.balls.find((b) => b.id === 0);"
        " return !c || Math.hypot(c.x - x, c.y - y) > 0.2; }",
        arg=[cue_start["x"], cue_start["y"]])
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
    shown = sorted((b["id"], round(b["x"], 3), round(b["y"], 3))
                   for b in page.evaluate("window.__replay.balls"))
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
