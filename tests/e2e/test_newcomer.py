"""A newcomer's first game, and the table's words, clocks and signals, in real Chromium
against a real server (its own, with a short grace period and shot clock so waiting for
them takes seconds).

Everything is driven through the page (lobby fields, the join dialog, the mouse on the
canvas, buttons); `window.__pool` is only read, to wait and to find where things are drawn.
"""

from __future__ import annotations

import math
import re
import time
from collections.abc import Iterator
from urllib.parse import urlparse

import httpx
import pytest
from playwright.sync_api import Page, expect
from websockets.sync.client import connect

from tests.support.games import (
    BREAK,
    EIGHT_BALL,
    EIGHT_BALL_BREAK_BALL,
    EIGHT_BALL_GROUP_BALL,
    EIGHT_BALL_GROUP_SHOT,
    EIGHT_BALL_PLACE,
    EIGHT_BALL_SCRATCH,
)
from tests.support.live import http, live_server, ws_url
from tests.support.messages import JsonSocket, receive_until
from tests.support.rooms import play_shot, seated_room

from .conftest import E2E_SETTINGS
from .helpers import aim_and_shoot, apex, create, sit, table_point, wait_for, wait_ready
from .test_history import REPLAY_READY, play_a_short_match

pytestmark = pytest.mark.browser

GRACE = 3.0  # seconds a dropped player keeps the seat here
CLOCK = 3.0  # the shot clock of the rooms that test it


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    settings = E2E_SETTINGS.replace(
        db_path=tmp_path_factory.mktemp("newcomer") / "billiards.db",
        grace=GRACE,
        min_shot_clock=1.0,
    )
    with live_server(settings, EIGHT_BALL) as address:
        yield f"http://{address}"


def two_players(new_page, server: str, **room: object) -> tuple[Page, Page, str]:
    room_id = create(server, **room)
    ana, ben = new_page(), new_page()
    sit(ana, server, room_id, "Ana")
    sit(ben, server, room_id, "Ben")
    wait_ready(ana, "aiming")
    wait_ready(ben, "aiming")
    return ana, ben, room_id


def test_a_newcomer_is_shown_the_gesture_and_the_clock_does_not_take_the_break(
    server, new_page, artifacts
):
    room_id = create(server, race_to=2, shot_clock=CLOCK)
    ana = new_page()
    ana.goto(f"{server}/r/{room_id}")
    # The join dialog says which game and race this is.
    expect(ana.locator("#join-info")).to_contain_text("8-ball · race to 2")
    ana.get_by_test_id("join-name").fill("Ana")
    ana.get_by_test_id("join").click()
    ben = new_page()
    sit(ben, server, room_id, "Ben")
    wait_ready(ana, "aiming")
    hint = ana.get_by_test_id("first-shot-hint")
    expect(hint).to_be_visible()
    expect(hint).to_contain_text("pull back")
    expect(ben.get_by_test_id("first-shot-hint")).to_be_hidden()  # not Ben's turn

    # The room's clock is 3 s, but the first break gets four of them: no timeout after 3.5 s.
    clock = ana.get_by_test_id("shot-clock")
    expect(clock).to_be_visible()
    ana.wait_for_timeout(3_500)
    assert ana.evaluate("window.__pool.state.lastResult") is None, "the clock took the break"
    expect(ana.get_by_test_id("turn")).to_contain_text("Your turn")

    # A plain click does not shoot, and says why.
    x, y = apex(ana)
    px, py = table_point(ana, x, y)
    ana.mouse.click(px, py)
    state = ana.get_by_test_id("aim-state")
    expect(state).to_contain_text("Shot cancelled")
    assert ana.evaluate("window.__pool.shotsSeen") == 0

    # Following the hint: press on the ball, pull back (the chip says so), let go.
    cue = ana.evaluate("window.__pool.balls.find((b) => b.id === 0)")
    cx, cy = table_point(ana, cue["x"], cue["y"])
    dx, dy = px - cx, py - cy
    n = (dx * dx + dy * dy) ** 0.5
    ana.mouse.move(px, py)
    ana.mouse.down()
    expect(state).to_contain_text("Pull back")
    ana.mouse.move(px - 160 * dx / n, py - 160 * dy / n, steps=10)
    expect(state).to_contain_text("Release to shoot")
    expect(state).to_have_attribute("data-state", "release")
    ana.mouse.up()
    wait_for(ana, "window.__pool.shotsSeen >= 1", timeout=10_000)
    expect(hint).to_be_hidden()
    wait_for(ana, "window.__pool.state.phase === 'aiming' && !window.__pool.playing")
    # After the first break the clock is the room's own 3 s: urgent (red, ticking) at once.
    expect(clock).to_have_attribute("data-urgent", "true", timeout=5_000)
    expect(clock).to_have_class(re.compile(r"\burgent\b"))
    assert ana.evaluate("window.__pool.ticks") > 0, "the last seconds tick"
    ana.screenshot(path=str(artifacts / "table-desktop.png"))

    # Remembered: at her next table, on her turn, the hint stays away.
    again = ana.context.new_page()
    sit(again, server, create(server, shot_clock=0), "Ana")
    sit(new_page(), server, again.url.rsplit("/", 1)[1], "Cleo")
    wait_ready(again, "aiming")
    expect(again.get_by_test_id("turn")).to_contain_text("Your turn")
    again.wait_for_timeout(300)
    expect(again.get_by_test_id("first-shot-hint")).to_be_hidden()


def test_a_dropped_opponent_is_shown_with_a_countdown_and_a_left_room_is_abandoned(
    server, new_page
):
    ana, ben, room_id = two_players(new_page, server, race_to=3)
    ben.close()
    away = ana.get_by_test_id("opponent-away")
    expect(away).to_be_visible()
    expect(away).to_contain_text("Ben left the table")
    first = int(re.search(r"(\d+) s", away.inner_text()).group(1))
    assert 0 < first <= GRACE
    expect(ana.get_by_test_id("player-1")).to_have_class(re.compile(r"\babsent\b"))
    ana.close()  # both gone: when Ben's grace runs out, nobody forfeits

    def abandoned() -> list[dict]:
        reply = httpx.get(f"{server}/api/matches?status=abandoned", timeout=20).json()
        return [m for m in reply["matches"] if m["room_id"] == room_id]

    deadline = time.monotonic() + GRACE + 15
    while not abandoned() and time.monotonic() < deadline:
        time.sleep(0.1)  # polling the history, as `wait_for` polls a page
    (match,) = abandoned()
    assert match["winner"] is None and match["score"] == [0, 0]
    lobby = new_page()
    lobby.goto(server + "/")
    entry = lobby.locator(f"[data-testid=history-match][data-match='{match['id']}']")
    expect(entry).to_have_count(1, timeout=10_000)
    expect(entry).to_have_attribute("data-status", "abandoned")
    expect(entry).to_contain_text("abandoned")
    expect(entry).not_to_contain_text("won")
    expect(entry.get_by_test_id("watch-match")).to_have_count(0)  # nothing to watch
    finished = httpx.get(f"{server}/api/matches?status=finished", timeout=20).json()["matches"]
    assert all(m["room_id"] != room_id for m in finished)
    # The room is over: not among the open tables.
    expect(lobby.locator(f"[data-room='{room_id}']")).to_have_count(0)


def test_decisions_frames_rematch_and_chat_history(server, new_page):
    ana, ben, room_id = two_players(new_page, server, race_to=2, shot_clock=0)
    # A soft break is illegal: Ben chooses, with buttons worded for people.
    aim_and_shoot(ana, apex(ana), pull_px=40)
    decision = ben.get_by_test_id("decision")
    expect(decision.get_by_role("button", name="Play from here")).to_be_visible(timeout=30_000)
    expect(decision.get_by_role("button", name="Re-rack and break")).to_be_visible()
    expect(decision).not_to_contain_text("rerack_opponent_breaks")
    decision.get_by_role("button", name="Play from here").click()
    wait_for(ana, "!window.__pool.state.match.decision")

    # Chat survives a reload.
    ana.get_by_test_id("chat-input").fill("nice table")
    ana.get_by_test_id("chat-input").press("Enter")
    expect(ben.get_by_test_id("chat-log")).to_contain_text("nice table")
    ben.reload()
    wait_ready(ben, "aiming")
    expect(ben.get_by_test_id("chat-log")).to_contain_text("Ana: nice table")

    # Ana concedes the frame: both see a frame-won banner for Ben, with the score.
    ana.on("dialog", lambda d: d.accept())
    ana.get_by_test_id("concede").click()
    for page in (ana, ben):
        expect(page.get_by_test_id("frame-won")).to_contain_text("Ben wins the frame · 0 – 1")
    wait_ready(ana, "aiming")
    ana.get_by_test_id("concede").click()
    # The match is over: a trophy drawn in SVG (no emoji font needed).
    for page in (ana, ben):
        banner = page.get_by_test_id("winner")
        expect(banner).to_contain_text("Ben wins the match!")
        expect(banner.locator("svg[data-icon=trophy]")).to_have_count(1)
    # A rematch request is seen by the other player, who accepts it.
    ana.get_by_test_id("rematch").click()
    expect(ana.get_by_test_id("rematch")).to_have_text("Rematch asked")
    expect(ana.get_by_test_id("rematch-state")).to_contain_text("Waiting for Ben")
    expect(ben.get_by_test_id("rematch-state")).to_contain_text("Ana asks you for a rematch")
    expect(ben.get_by_test_id("rematch")).to_have_text("Accept rematch")
    ben.get_by_test_id("rematch").click()
    for page in (ana, ben):
        wait_ready(page, "aiming")
        expect(page.get_by_test_id("winner")).to_be_hidden()
        expect(page.get_by_test_id("score")).to_have_text("Ana 0 – 0 Ben (race to 2)")
        expect(page.get_by_test_id("outcome")).to_have_text("")  # no stale words

    # The finished match's replay says who plays each shot and the score, and draws the cue.
    matches = httpx.get(f"{server}/api/matches?status=finished", timeout=20).json()["matches"]
    (match,) = [m for m in matches if m["room_id"] == room_id]
    assert match["winner_name"] == "Ben" and match["shots"] == 1
    ben.goto(f"{server}/m/{match['id']}")
    wait_for(ben, "window.__replay && window.__replay.ready")
    expect(ben.get_by_test_id("replay-shooter")).to_have_text("Ana to play")
    expect(ben.get_by_test_id("replay-at-score")).to_have_text("game 1 · Ana 0 – 0 Ben")
    assert ben.evaluate("window.__replay.cueDrawn")


def test_the_object_balls_guide_line_stops_at_the_rail(server, new_page):
    ana, _, _ = two_players(new_page, server, shot_clock=0)
    aim_and_shoot(ana, apex(ana))  # the known break: Ana plays again, balls spread
    wait_for(ana, "window.__pool.shotsSeen >= 1 && !window.__pool.playing", timeout=30_000)
    wait_ready(ana, "aiming")
    # Find an aim whose object ball runs into a cushion, then aim there with the mouse.
    aim = ana.evaluate(
        """async () => {
          const g = await import('/js/geometry.js');
          const { table } = window.__pool.state;
          const cue = window.__pool.balls.find((b) => b.id === 0);
          const on = window.__pool.balls;
          for (let k = 0; k < 3600; k++) {
            const angle = -Math.PI + (k * 2 * Math.PI) / 3600;
            const guide = g.castGuide(table, on, [cue.x, cue.y], angle);
            if (guide.kind !== 'ball') continue;
            const hit = on.find((b) => b.id === guide.hitId);
            const path = g.objectPath(table, on, [hit.x, hit.y], guide.objectDir, [0, hit.id]);
            if (path.kind === 'cushion' && path.t > 0.08 && path.t < 0.18 && guide.t > 0.15) {
              return { angle, end: path.end, dir: guide.objectDir, hit: [hit.x, hit.y] };
            }
          }
          return null;
        }"""
    )
    assert aim is not None, "no shot on this table sends a ball into a cushion"
    cue = ana.evaluate("window.__pool.balls.find((b) => b.id === 0)")
    far = (cue["x"] + 0.15 * math.cos(aim["angle"]), cue["y"] + 0.15 * math.sin(aim["angle"]))
    ana.mouse.move(*table_point(ana, *far))
    wait_for(ana, "window.__pool.objectGuide && window.__pool.objectGuide.kind === 'cushion'")
    end = ana.evaluate("window.__pool.objectGuide.end")
    table = ana.evaluate("window.__pool.state.table")
    r = table["ball_radius"]
    slack = 1e-6  # the ball's centre stays one radius inside the cushion noses
    assert r - slack <= end[0] <= table["length"] - r + slack
    assert r - slack <= end[1] <= table["width"] - r + slack

    def yellow(points: list[tuple[float, float]]) -> int:
        """How many of these table points are drawn in the guide's yellow (3x3 px each)."""
        box = ana.get_by_test_id("table").bounding_box()
        screen = [
            [p - q for p, q in zip(table_point(ana, *pt), (box["x"], box["y"]), strict=True)]
            for pt in points
        ]
        return ana.evaluate(
            """(pts) => {
              const c = document.querySelector('[data-testid=table]');
              const k = c.width / c.clientWidth;
              const ctx = c.getContext('2d');
              let n = 0;
              for (const [x, y] of pts) {
                const d = ctx.getImageData(Math.round(x * k) - 1, Math.round(y * k) - 1, 3, 3).data;
                for (let i = 0; i < d.length; i += 4) {
                  const [r, g, b] = [d[i], d[i + 1], d[i + 2]];
                  if (r > 130 && g > 140 && b > 50 && b < 190 && r - b > 30 && g - b > 30) {
                    n++;
                    break;
                  }
                }
              }
              return n;
            }""",
            screen,
        )

    dx, dy = aim["dir"]
    hx, hy = aim["hit"]
    length = math.hypot(end[0] - hx, end[1] - hy)
    inside = [(hx + dx * t, hy + dy * t) for t in [length * f for f in (0.45, 0.55, 0.65, 0.75)]]
    beyond = [(end[0] + dx * (r + t), end[1] + dy * (r + t)) for t in (0.02, 0.05, 0.08, 0.11)]
    assert yellow(inside) >= 3, "the guide line is drawn up to the rail"
    assert yellow(beyond) == 0, "the guide line runs on across the rail"

    # Fine aim from the keyboard: an arrow key turns the cue by a small step.
    before = ana.evaluate("window.__pool.aim.angle")
    ana.keyboard.press("ArrowLeft")
    wait_for(ana, "(a) => window.__pool.aim.angle !== a", before)
    assert 0 < ana.evaluate("window.__pool.aim.angle") - before < 0.01


def test_a_link_to_a_table_that_does_not_exist(server, new_page):
    page = new_page()
    sockets: list[str] = []
    page.on("websocket", lambda ws: sockets.append(ws.url))
    page.goto(server + "/r/NoSuchTable00")
    expect(page.get_by_test_id("no-room")).to_be_visible()
    expect(page.get_by_test_id("no-room")).to_contain_text("No such table")
    expect(page.locator("#room")).to_be_hidden()
    page.wait_for_timeout(1500)
    assert sockets == [], "no socket is opened (and retried) for a table that does not exist"


def test_lobby_options_follow_the_game_and_copy_says_so(server, new_page):
    page = new_page(permissions=["clipboard-read", "clipboard-write"])
    page.goto(server + "/")
    page.get_by_test_id("game-select").select_option("practice")
    expect(page.get_by_test_id("race-to")).to_be_disabled()
    expect(page.get_by_test_id("shot-clock-select")).to_be_disabled()
    page.get_by_test_id("game-select").select_option("nine_ball")
    expect(page.get_by_test_id("race-to")).to_be_enabled()
    page.get_by_test_id("name").fill("Ana")
    page.get_by_test_id("shot-clock-select").select_option("30")
    page.get_by_test_id("create-room").click()
    page.wait_for_url(re.compile(r"/r/[A-Za-z0-9_-]+$"))
    wait_ready(page, "waiting")
    assert page.evaluate("window.__pool.state.room.shot_clock") == 30
    page.get_by_test_id("copy-link").click()
    expect(page.get_by_test_id("copy-link")).to_contain_text("Copied")
    assert page.evaluate("navigator.clipboard.readText()") == page.url


def test_every_ball_is_readable_from_above_at_every_cel(server, new_page):
    """The real sprites, drawn by the browser: at every cel each object ball shows its own
    colour and the dark ink of its number, and a striped ball is never as white as the cue
    ball."""
    page = new_page()
    page.goto(server + "/")
    seen = page.evaluate(
        """async () => {
          const { buildSprites, CELS, hexToRgb } = await import('/js/sprites.js');
          const { ballColor } = await import('/js/balls.js');
          const s = buildSprites(24);
          const out = {};
          for (let id = 0; id < 16; id++) {
            const [cr, cg, cb] = hexToRgb(ballColor(id));
            out[id] = [];
            for (let k = 0; k < CELS; k++) {
              const c = document.createElement('canvas');
              c.width = c.height = s.side;
              const ctx = c.getContext('2d');
              ctx.drawImage(s.cels[id][k], 0, 0);
              const d = ctx.getImageData(0, 0, s.side, s.side).data;
              let disc = 0, own = 0, ink = 0, white = 0;
              for (let i = 0; i < d.length; i += 4) {
                if (d[i + 3] < 250) continue;
                disc++;
                const [r, g, b] = [d[i], d[i + 1], d[i + 2]];
                const near = Math.abs(r - cr) + Math.abs(g - cg) + Math.abs(b - cb) < 40;
                if (near) own++;
                if (r > 235 && g > 230 && b > 215) white++;
                else if (r + g + b < 120 && !near) ink++;
              }
              out[id].push({ own: own / disc, ink: ink / disc, white: white / disc });
            }
          }
          return out;
        }"""
    )
    for k, cue in enumerate(seen["0"]):
        assert cue["white"] > 0.85, f"the cue ball is white (cel {k})"
    for ball in range(1, 16):
        for k, cel in enumerate(seen[str(ball)]):
            assert cel["own"] > 0.2, f"ball {ball} cel {k}: its colour hardly shows ({cel})"
            if ball != 8:  # the 8's ink is black on black around its disc
                assert cel["ink"] > 0.01, f"ball {ball} cel {k}: no number shows ({cel})"
            assert cel["white"] < seen["0"][k]["white"] - 0.3, f"ball {ball} cel {k} reads white"


def test_previous_while_playing_at_four_times_goes_back_one_shot(base_url, new_page):
    match_id = play_a_short_match(base_url)
    page = new_page()
    page.goto(f"{base_url}/m/{match_id}")
    wait_for(page, REPLAY_READY)
    expect(page.get_by_test_id("replay-shooter")).to_have_text("Ana to play")
    page.get_by_test_id("replay-speed").select_option("4")
    page.get_by_test_id("replay-play").click()
    wait_for(page, "window.__replay.index === 1 && window.__replay.framesSeen >= 2")
    page.get_by_test_id("replay-prev").click()
    # Back to the first shot, from its start, still playing: the break again, then shot 2.
    expect(page.get_by_test_id("replay-shot")).to_have_text("shot 1 / 2")
    assert page.evaluate("[window.__replay.playing, window.__replay.index]") == [True, 0]
    wait_for(page, "window.__replay.framesSeen >= 3")  # shot 1's motion plays again
    expect(page.get_by_test_id("replay-shot")).to_have_text("shot 2 / 2", timeout=20_000)
    wait_for(page, "!window.__replay.playing", timeout=20_000)


def test_the_pocketed_tray_is_split_per_player_once_groups_are_taken(base_url, new_page):
    """The known game (`games.EIGHT_BALL`) played over the API while a spectator watches:
    after Ben takes the stripes with the 10, the tray shows Ana's solids (the 6 from the
    break) and Ben's stripes on rows of their own."""
    address = urlparse(base_url).netloc
    with http(address) as client:
        room_id, ta, tb = seated_room(client, race_to=1)
    watcher = new_page()
    watcher.goto(f"{base_url}/r/{room_id}?watch=1")
    wait_ready(watcher, "aiming")
    with connect(ws_url(address, room_id, ta)) as ca, connect(ws_url(address, room_id, tb)) as cb:
        a, b = JsonSocket(ca), JsonSocket(cb)
        state = receive_until(a, "state")[-1]
        _, _, state = play_shot((a, b), a, state, BREAK)
        _, _, state = play_shot((a, b), a, state, EIGHT_BALL_SCRATCH)
        _, _, state = play_shot((a, b), a, state, EIGHT_BALL_GROUP_SHOT, EIGHT_BALL_PLACE)
        assert state["match"]["groups"] is not None
    assert state["match"]["groups"] == ["solids", "stripes"]
    tray = watcher.get_by_test_id("pocketed")
    expect(tray.locator(".tray-row[data-seat='1'] [data-ball]")).to_have_count(1, timeout=30_000)
    assert tray.locator(".tray-row[data-seat='1'] [data-ball]").get_attribute("data-ball") == str(
        EIGHT_BALL_GROUP_BALL
    )
    expect(tray.locator(".tray-row[data-seat='1']")).to_contain_text("Ben · stripes")
    expect(tray.locator(".tray-row[data-seat='0'] [data-ball]")).to_have_count(1)
    assert tray.locator(".tray-row[data-seat='0'] [data-ball]").get_attribute("data-ball") == str(
        EIGHT_BALL_BREAK_BALL
    )
