"""A newcomer plays snooker against the computer through the page, in real Chromium: the
lobby's computer card, the table drawn with the D, the break-off from the D, then the whole
frame to its end on the table (the black potted, or the frame otherwise won or lost by the
rules, never conceded), with the scoreboard's final points. A second, shorter game ends by
concession (WPBSA 2.1 Frame: a player may concede during their turn).

Everything is driven through the page as a person does it: lobby fields, the mouse on the
canvas (drag the cue ball in the D, tap a colour to nominate it, press on the line of aim,
pull back, let go), the arrow keys for fine aim, and the decision buttons.
`window.__pool` is only read, to wait and to find where things are drawn; the strokes are
chosen from what is drawn (`snooker_stroke`).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

import httpx
import pytest
from playwright.sync_api import Page, expect

from server.engine.rack import COLOURS

from .helpers import aim_and_shoot, table_point, wait_for, wait_ready
from .snooker_stroke import Layout, Point, Stroke, choose, place_in_d

pytestmark = pytest.mark.browser

PERSON = "Ana"
# The pro level ends the frame in the fewest of the newcomer's turns: it pots most of what
# it is left (docs/ai.md) and fouls least. Measured: against pro the newcomer played 35
# strokes (313 s), against beginner 44 (331 s, with three choices after its fouls).
LEVEL = "pro"
BLACK = COLOURS["black"]
MAX_STROKES = 150  # the newcomer's strokes before the test calls the frame stuck
FRAME_TIMEOUT = 1200  # s for the whole frame (docs/testing.md has how long it takes)
VISIT_WAIT = 300_000  # ms: the computer's longest visit (planning and the shots shown)
FINE_STEP = 0.002  # rad per arrow key (x10 with Shift): web/js/screens/table/controls.js
MAX_PULL = 0.4  # m of pull-back for full power: web/js/input.js
MIN_SPEED = 0.25  # m/s at the bottom of the power scale: web/js/geometry.js

# The newcomer's turn (or a choice to make), with the table drawn at rest where the
# server has it; or the match is over.
MY_MOVE = """() => {
  const p = window.__pool;
  if (!p || !p.ready) return false;
  const s = p.state, m = s.match;
  if (s.phase === 'over') return true;
  if (!m || s.phase !== 'aiming' || p.playing) return false;
  const mine = m.decision ? m.decision.seat === s.me.seat : m.turn === s.me.seat;
  if (!mine) return false;
  const drawn = new Map(p.balls.map((b) => [b.id, b]));
  return m.balls.every((b) => !b.on_table || (drawn.has(b.id)
    && Math.abs(drawn.get(b.id).x - b.x) < 1e-3 && Math.abs(drawn.get(b.id).y - b.y) < 1e-3));
}"""
# What the newcomer reads off the page: the balls drawn on the cloth, the scoreboard's
# ball on, and what the turn holds.
LOOK = """() => {
  const p = window.__pool, s = p.state, m = s.match;
  const here = new Set(m.balls.filter((b) => b.on_table).map((b) => b.id));
  return {phase: s.phase, seat: s.me.seat, turn: m.turn, decision: m.decision,
          inHand: m.ball_in_hand, on: m.legal_targets, nominations: m.nominations,
          frame: m.frame, reason: m.reason, winner: m.winner,
          balls: p.balls.filter((b) => here.has(b.id)).map((b) => [b.id, b.x, b.y])};
}"""


@dataclass
class Newcomer:
    """The person at the table: their page, the table's layout, and what they did."""

    page: Page
    layout: Layout
    max_speed: float
    strokes: list[str] = field(default_factory=list)
    tried: dict[tuple, int] = field(default_factory=dict)

    def look(self) -> dict:
        return self.page.evaluate(LOOK)

    def decide(self, view: dict) -> None:
        """After the computer's foul: play from where the balls lie."""
        options = view["decision"]["options"]
        option = "play" if "play" in options else options[0]
        self.page.get_by_test_id("decision").locator(f"button[data-option='{option}']").click()
        wait_for(self.page, "!window.__pool.state.match.decision", timeout=30_000)
        self.strokes.append(f"chose {option}")

    def place(self, view: dict) -> None:
        """Ball in hand in the D: drag the cue ball (or put it down) where a pot is easiest."""
        balls = {b: (x, y) for b, x, y in view["balls"] if b != 0}
        x, y = place_in_d(self.layout, balls, view["on"])
        cue = next(((bx, by) for b, bx, by in view["balls"] if b == 0), None)
        page = self.page
        self.press(cue or (x, y), "placing")
        page.mouse.move(*table_point(page, x, y), steps=8)
        page.mouse.up()
        wait_for(
            page,
            """([x, y]) => { const c = window.__pool.state.match.balls.find((b) => b.id === 0);
               return c.on_table && Math.hypot(c.x - x, c.y - y) < 0.005; }""",
            [x, y],
            timeout=30_000,
        )
        self.strokes.append(f"placed in the D at ({x:.3f}, {y:.3f})")

    def nominate(self, ball: int) -> None:
        """On a colour: tap the colour to be played to nominate it."""
        page = self.page
        drawn = page.evaluate("(id) => window.__pool.balls.find((b) => b.id === id)", ball)
        page.mouse.click(*table_point(page, drawn["x"], drawn["y"]))
        wait_for(
            page, "(id) => window.__pool.state.match.frame.nominated === id", ball, timeout=30_000
        )
        self.strokes.append(f"nominated {ball}")

    def play(self, view: dict) -> None:
        """One stroke: choose it from what is drawn, nominate if a colour is on, shoot."""
        if view["inHand"]:
            self.place(view)
            view = self.look()
        balls = {b: (x, y) for b, x, y in view["balls"] if b != 0}
        cue = next((x, y) for b, x, y in view["balls"] if b == 0)
        key = tuple(sorted((b, round(x, 3), round(y, 3)) for b, x, y in view["balls"]))
        attempt = self.tried.get(key, 0)
        self.tried[key] = attempt + 1
        stroke = choose(self.layout, cue, balls, view["on"], attempt)
        if stroke.ball in view["nominations"] and view["frame"]["nominated"] != stroke.ball:
            self.nominate(stroke.ball)
        self.shoot(stroke, cue, balls, view["nominations"])
        self.strokes.append(f"{stroke.kind} at {stroke.ball}")

    def shoot(
        self, stroke: Stroke, cue: Point, balls: dict[int, Point], nominations: list[int]
    ) -> None:
        """Press on the line of aim, set the aim exactly with the arrow keys, pull back
        for the stroke's speed and let go; then wait until the page shows the shot."""
        page = self.page
        press = self.press_point(stroke, cue, balls, nominations)
        before = page.evaluate("window.__pool.shotsSeen")
        self.press(press, "pulling")
        self.fine_aim(stroke.angle)
        power = ((stroke.speed - MIN_SPEED) / (self.max_speed - MIN_SPEED)) ** (1 / 1.6)
        pull = power * MAX_PULL
        back = (press[0] - pull * math.cos(stroke.angle), press[1] - pull * math.sin(stroke.angle))
        page.mouse.move(*table_point(page, *back), steps=10)
        page.mouse.up()
        wait_for(
            page,
            "(n) => window.__pool.shotsSeen > n || window.__pool.state.phase !== 'aiming'",
            before,
            timeout=60_000,
        )

    def press_point(
        self, stroke: Stroke, cue: Point, balls: dict[int, Point], nominations: list[int]
    ) -> Point:
        """A point on the line of aim to press on: on the cloth, not on a colour that a
        tap would nominate, and away from the cue ball (which a press there would pick up
        with ball in hand)."""
        r = self.layout.radius
        c, s = math.cos(stroke.angle), math.sin(stroke.angle)
        base = math.hypot(stroke.press[0] - cue[0], stroke.press[1] - cue[1])
        for reach in (base, 0.2, 0.3, 0.4, 0.15, 0.5, 0.1):
            p = (cue[0] + c * reach, cue[1] + s * reach)
            on_cloth = r < p[0] < self.layout.length - r and r < p[1] < self.layout.width - r
            taps = any(math.dist(p, balls[b]) < 1.6 * r for b in nominations if b in balls)
            if on_cloth and not taps and reach > 3 * r:
                return p
        return stroke.press

    def press(self, at: Point, mode: str) -> None:
        """Press on the cloth and hold until the page answers: the cue pulling back, or
        the cue ball picked up (`mode`). The page ignores the cue for a moment after a
        shot was sent, until the server has answered it: then press again."""
        page = self.page
        x, y = table_point(page, *at)
        for _ in range(40):
            page.mouse.move(x - 20, y - 20)
            page.mouse.move(x, y, steps=4)
            page.mouse.down()
            try:
                wait_for(page, "(mode) => window.__pool.aim.mode === mode", mode, timeout=500)
                return
            except TimeoutError:
                page.mouse.up()
        raise AssertionError(f"a press on the cloth at {at} never started {mode}")

    def fine_aim(self, angle: float) -> None:
        """The arrow keys turn the cue by FINE_STEP (Shift: 10 steps) until it points at
        `angle` within a step."""
        page = self.page
        delta = angle - page.evaluate("window.__pool.aim.angle")
        delta = math.atan2(math.sin(delta), math.cos(delta))
        coarse = int(delta / (10 * FINE_STEP))
        fine = round((delta - coarse * 10 * FINE_STEP) / FINE_STEP)
        for steps, key in ((coarse, "Shift+Arrow"), (fine, "Arrow")):
            for _ in range(abs(steps)):
                page.keyboard.press(key + ("Left" if steps > 0 else "Right"))
        left = page.evaluate("window.__pool.aim.angle") - angle
        assert abs(math.atan2(math.sin(left), math.cos(left))) <= FINE_STEP, left


def open_snooker(page: Page, base_url: str) -> dict:
    """From the lobby: the name, snooker against the computer at LEVEL; the table's state."""
    page.goto(base_url + "/")
    page.get_by_test_id("name").fill(PERSON)
    page.get_by_test_id("computer-game").select_option("snooker")
    expect(page.get_by_test_id("computer-level")).to_contain_text("Pro")
    page.get_by_test_id("computer-level").select_option(LEVEL)
    page.get_by_test_id("play-computer").click()
    page.wait_for_url(re.compile(r"/r/[A-Za-z0-9_-]+$"))
    wait_ready(page, "aiming")
    return page.evaluate("window.__pool.state.table")


def break_off(page: Page, table: dict) -> None:
    """Ball in hand in the D: drag the cue ball to the brown's side, then break off at the
    back red of the pack's near corner."""
    cue = page.evaluate("window.__pool.balls.find((b) => b.id === 0)")
    brown = table["spots"]["brown"]
    start = table_point(page, cue["x"], cue["y"])
    end = table_point(page, brown[0] - 0.05, brown[1] + 0.1)
    page.mouse.move(*start)
    page.mouse.down()
    page.mouse.move(*end, steps=8)
    page.mouse.up()
    wait_for(
        page,
        "([x]) => Math.abs(window.__pool.balls.find((b) => b.id === 0).x - x) < 0.01",
        [brown[0] - 0.05],
    )
    placed = page.evaluate("window.__pool.balls.find((b) => b.id === 0)")
    assert abs(placed["x"] - (brown[0] - 0.05)) < 0.01, placed
    reds = page.evaluate("window.__pool.balls.filter((b) => b.id >= 1 && b.id <= 15)")
    corner = max(reds, key=lambda b: (b["x"], b["y"]))
    aim_and_shoot(page, (corner["x"], corner["y"]), pull_px=120)
    wait_for(page, "window.__pool.state.lastResult?.outcome?.shooter === 0", timeout=60_000)


@pytest.mark.slow
@pytest.mark.timeout(FRAME_TIMEOUT)
def test_a_newcomer_plays_a_whole_snooker_frame_against_the_computer(base_url, new_page, artifacts):
    ana = new_page()
    table = open_snooker(ana, base_url)
    assert table["style"] == "snooker" and table["ball_radius"] == 0.02625
    assert [a["radius"] for a in table["arcs"]] == [0.292]
    assert len(ana.evaluate("window.__pool.balls")) == 22
    expect(ana.get_by_test_id("frame-box")).to_be_visible()
    expect(ana.get_by_test_id("frame")).to_contain_text("Remaining 147")
    expect(ana.get_by_test_id("turn")).to_contain_text("Your turn")
    break_off(ana, table)
    ana.get_by_test_id("table").screenshot(path=str(artifacts / "snooker.png"))

    max_speed = httpx.get(f"{base_url}/api/limits", timeout=20).json()["max_speed"]
    person = Newcomer(ana, Layout.of(table), max_speed)
    while True:
        wait_for(ana, MY_MOVE, timeout=VISIT_WAIT)
        view = person.look()
        if view["phase"] == "over":
            break
        assert len(person.strokes) < MAX_STROKES, f"the frame did not end: {person.strokes}"
        if view["decision"]:
            person.decide(view)
        else:
            person.play(view)

    ana.get_by_test_id("table").screenshot(path=str(artifacts / "snooker-frame.png"))
    assert_ended_on_the_table(ana, view, person.strokes)
    print(f"{view['reason']} The newcomer's strokes ({len(person.strokes)}): {person.strokes}")


def assert_ended_on_the_table(page: Page, view: dict, strokes: list[str]) -> None:
    """The frame ended by the rules (WPBSA 3.3: the black potted, or fouled, as the last
    ball), not by a concession: the winner named with the final points, which the
    scoreboard shows, and nothing left on the table but a black fouled back on its spot."""
    points, winner = view["frame"]["points"], view["winner"]
    names = [PERSON, f"Computer ({LEVEL})"]
    said = re.fullmatch(r"(.+) wins the frame (\d+)-(\d+)\.", view["reason"] or "")
    assert said, f"the frame did not end on the table: {view['reason']!r} after {strokes}"
    assert said[1] == names[winner]
    assert (int(said[2]), int(said[3])) == (points[winner], points[1 - winner])
    assert points[winner] > points[1 - winner]
    frame = page.get_by_test_id("frame").inner_text()
    for seat, name in enumerate(names):
        won = 1 if seat == winner else 0
        assert f"{name} ({won}): {points[seat]}" in frame, frame
    left = [b for b, _, _ in view["balls"] if b != 0]
    assert left in ([], [BLACK]), f"balls left on the table: {left}"
    remaining = 7 if left else 0
    assert view["frame"]["remaining"] == remaining and f"Remaining {remaining}" in frame, frame
    expect(page.get_by_test_id("turn")).to_contain_text(f"{names[winner]} wins the match")


def test_a_snooker_frame_can_be_conceded_by_the_striker(base_url, new_page):
    """WPBSA 2.1 Frame: a player may concede during their turn; the frame, and with it a
    one-frame match, goes to the opponent."""
    ana = new_page()
    table = open_snooker(ana, base_url)
    break_off(ana, table)
    computer_shot = "window.__pool.state.lastResult?.outcome?.shooter === 1"
    wait_for(ana, computer_shot, timeout=VISIT_WAIT)  # the computer played its own visit
    frame = ana.get_by_test_id("frame").inner_text()
    assert PERSON in frame and "Remaining" in frame
    points = ana.evaluate("window.__pool.state.match.points")
    assert len(points) == 2 and sum(points) >= 0
    wait_for(ana, MY_MOVE, timeout=VISIT_WAIT)  # Ana is the striker again
    ana.once("dialog", lambda d: d.accept())
    ana.get_by_test_id("concede").click()
    wait_for(ana, "window.__pool.state.phase === 'over'", timeout=30_000)
    expect(ana.get_by_test_id("turn")).to_contain_text("wins the match")
