"""A newcomer's second look, through the page only: the computer played from the lobby
without a name prompt, race to 1 and no clock unless changed; every finished game offers
Rematch, a new opponent and the lobby, and the lobby stays the lobby after a Play now game;
one name (the profile's) at every table; names refused in one sentence, their limit shown."""

from __future__ import annotations

import re

import pytest
from playwright.sync_api import Page, Route, expect

from .helpers import TABLE_PAGE, aim_and_shoot, table_point, wait_for, wait_ready

pytestmark = pytest.mark.browser


def profile_name(page: Page) -> str:
    return page.evaluate("fetch('/api/players/me').then((r) => r.json()).then((p) => p.name)")


def concede_match(page: Page) -> None:
    """Concede frame after frame until the match is over (race to 1: once)."""
    page.on("dialog", lambda d: d.accept())
    page.get_by_test_id("concede").click()
    wait_ready(page, "over")


def test_the_computer_from_the_lobby_without_a_name_then_back_to_the_lobby(base_url, new_page):
    ana = new_page()
    ana.goto(base_url + "/")
    for card in ("playnow-panel", "computer-panel", "friend-panel"):
        expect(ana.get_by_test_id(card)).to_be_visible()
    expect(ana.get_by_test_id("practice")).to_be_visible()
    # The name is the profile's, already there: nothing to type.
    expect(ana.get_by_test_id("name")).to_have_value(re.compile(r"^Player "))
    mine = profile_name(ana)
    expect(ana.get_by_test_id("computer-race-to")).to_have_value("1")
    expect(ana.get_by_test_id("computer-clock")).to_have_value("0")
    expect(ana.get_by_test_id("computer-level")).to_contain_text("Beginner")
    ana.get_by_test_id("play-computer").click()
    ana.wait_for_url(TABLE_PAGE)
    wait_ready(ana, "aiming")
    room = ana.evaluate("window.__pool.state.room")
    assert room["race_to"] == 1 and not room["shot_clock"]
    expect(ana.get_by_test_id("player-0")).to_contain_text(f"{mine} (you)")
    expect(ana.get_by_test_id("shot-clock")).to_be_hidden()
    concede_match(ana)
    expect(ana.get_by_test_id("rematch")).to_be_visible()
    expect(ana.get_by_test_id("new-opponent")).to_be_visible()
    ana.get_by_test_id("end-lobby").click()
    ana.wait_for_url(base_url + "/")
    ana.wait_for_timeout(1500)
    assert ana.url == base_url + "/"
    expect(ana.get_by_test_id("play-now")).to_be_visible()


def test_the_computer_can_be_given_a_longer_race_and_a_clock(base_url, new_page):
    ana = new_page()
    ana.goto(base_url + "/")
    ana.get_by_test_id("computer-game").select_option("nine_ball")
    ana.get_by_test_id("computer-race-to").select_option("3")
    ana.get_by_test_id("computer-clock").select_option("30")
    ana.get_by_test_id("play-computer").click()
    ana.wait_for_url(TABLE_PAGE)
    wait_ready(ana, "aiming")
    room = ana.evaluate("window.__pool.state.room")
    assert (room["game"], room["race_to"], room["shot_clock"]) == ("nine_ball", 3, 30)


class HeldRequests:
    """A route handler that holds the requests it sees until `release()`, then lets every
    later one through."""

    def __init__(self) -> None:
        self.routes: list[Route] = []
        self.released = False

    def __call__(self, route: Route) -> None:
        if self.released:
            route.continue_()
        else:
            self.routes.append(route)

    def release(self) -> None:
        self.released = True
        for route in self.routes:
            route.continue_()


def test_play_the_computer_pressed_before_the_profile_came_waits_for_its_name(base_url, new_page):
    """A quick press, while the profile (and so the name) is still on its way: the table
    opens under the profile's name once it comes, with no "enter your name"."""
    ana = new_page()
    profile = HeldRequests()
    ana.route("**/api/players/me", profile)
    ana.goto(base_url + "/")
    assert profile.routes, "the page asks for its profile"
    ana.get_by_test_id("play-computer").click()
    expect(ana.get_by_test_id("lobby-error")).to_have_text("")
    profile.release()
    ana.wait_for_url(TABLE_PAGE)
    wait_ready(ana, "aiming")
    assert profile_name(ana) in ana.get_by_test_id("player-0").inner_text()


def seated_by_play_now(base_url: str, new_page) -> tuple[Page, Page]:
    """Two strangers press Play now for 8-ball, one after the other, and are seated at one
    table, aiming."""
    ana, ben = new_page(), new_page()
    for page in (ana, ben):
        page.goto(base_url + "/")
        expect(page.get_by_test_id("play-now")).to_be_visible()
        page.get_by_test_id("playnow-game").select_option("eight_ball")
    ana.get_by_test_id("play-now").click()
    expect(ana.get_by_test_id("playnow-status")).to_contain_text("Looking for")
    ben.get_by_test_id("play-now").click()
    for page in (ana, ben):
        page.wait_for_url(TABLE_PAGE)
        wait_ready(page, "aiming")
    return ana, ben


def test_two_strangers_play_now_and_both_get_back_to_the_lobby(base_url, new_page):
    ana, ben = seated_by_play_now(base_url, new_page)
    names = {profile_name(ana), profile_name(ben)}
    hud = {ana.get_by_test_id(f"player-{s}").inner_text() for s in (0, 1)}
    assert all(any(n in h for h in hud) for n in names)  # the profiles' names seated
    concede_match(ana)
    wait_ready(ben, "over")
    for page in (ana, ben):
        expect(page.get_by_test_id("rematch")).to_be_visible()
        expect(page.get_by_test_id("new-opponent")).to_be_visible()
        expect(page.get_by_test_id("end-lobby")).to_be_visible()
    # Ana types the lobby's address; Ben presses the button: both stay in the lobby.
    ana.goto(base_url + "/")
    ben.get_by_test_id("end-lobby").click()
    ben.wait_for_url(base_url + "/")
    for page in (ana, ben):
        expect(page.get_by_test_id("playnow-name")).to_contain_text("Playing as")
    ana.wait_for_timeout(2000)
    assert ana.url == base_url + "/" and ben.url == base_url + "/"
    # A new opponent: straight back into the queue.
    ben.go_back()
    ben.wait_for_url(TABLE_PAGE)
    ben.get_by_test_id("new-opponent").click()
    expect(ben.get_by_test_id("playnow-status")).to_contain_text("Looking for an 8-ball")
    assert ben.url == base_url + "/"
    ben.get_by_test_id("playnow-cancel").click()
    expect(ben.get_by_test_id("play-now")).to_be_visible()


def test_a_new_name_typed_at_a_table_is_the_profiles_from_then_on(base_url, new_page):
    ana = new_page()
    ana.goto(base_url + "/")
    expect(ana.get_by_test_id("name")).to_have_value(re.compile(r"^Player "))
    ana.get_by_test_id("name").fill("Ana")
    ana.get_by_test_id("play-computer").click()
    ana.wait_for_url(TABLE_PAGE)
    wait_ready(ana, "aiming")
    expect(ana.get_by_test_id("player-0")).to_contain_text("Ana (you)")
    assert profile_name(ana) == "Ana"
    ana.goto(base_url + "/")
    expect(ana.get_by_test_id("name")).to_have_value("Ana")
    expect(ana.get_by_test_id("playnow-name")).to_have_text("Playing as Ana · ")


def test_names_are_refused_in_one_sentence_and_the_field_shows_its_limit(base_url, new_page):
    ana = new_page()
    ana.goto(base_url + "/")
    name = ana.get_by_test_id("name")
    expect(name).to_have_value(re.compile(r"^Player "))
    name.fill("")
    expect(ana.get_by_test_id("name-note")).to_have_text("0/24 characters")
    ana.get_by_test_id("play-computer").click()
    error = ana.get_by_test_id("lobby-error")
    expect(error).to_have_text("Type a name: it cannot be empty.")
    assert "String should" not in error.inner_text()
    name.fill("Ana")
    expect(ana.get_by_test_id("name-note")).to_have_text("3/24 characters")
    # A 300-character paste is cut to the limit, and the field says so.
    name.fill("")
    name.focus()
    ana.evaluate(
        """() => {
          const input = document.querySelector('[data-testid=name]');
          const data = new DataTransfer();
          data.setData('text/plain', 'x'.repeat(300));
          input.dispatchEvent(new ClipboardEvent('paste', {clipboardData: data,
            bubbles: true, cancelable: true}));
        }"""
    )
    ana.keyboard.insert_text("x" * 300)
    expect(name).to_have_value("x" * 24)
    expect(ana.get_by_test_id("name-note")).to_contain_text("cut to 24: the paste had 300")


def until_both_have_shot(ana: Page, ben: Page, limit: int = 8) -> None:
    """Whoever is to play strikes softly at the nearest object ball, until each seat has
    struck a shot (a match is rated only then)."""
    struck: set[int] = set()
    for _ in range(limit):
        if len(struck) == 2:
            return
        wait_ready(ana, "aiming")
        turn = ana.evaluate("window.__pool.state.match.turn")
        page = ana if turn == ana.evaluate("window.__pool.state.me.seat") else ben
        seen = page.evaluate("window.__pool.shotsSeen")
        cue = page.evaluate("window.__pool.balls.find((b) => b.id === 0)")
        others = page.evaluate("window.__pool.balls.filter((b) => b.id !== 0)")
        near = min(others, key=lambda b: (b["x"] - cue["x"]) ** 2 + (b["y"] - cue["y"]) ** 2)
        aim_and_shoot(page, (near["x"], near["y"]), pull_px=80)
        wait_for(page, f"window.__pool.shotsSeen > {seen} && !window.__pool.playing")
        struck.add(turn)
    raise AssertionError(f"only seats {struck} struck in {limit} shots")


def test_the_leaderboard_marks_and_explains_provisional_players(base_url, new_page):
    """A rated Play now match (each seat strikes, then a concession) puts both players on
    the 8-ball leaderboard, provisional: their ratings marked "?", the mark explained, and
    no "Nobody ranked yet" over them."""
    ana, ben = seated_by_play_now(base_url, new_page)
    until_both_have_shot(ana, ben)
    wait_ready(ana)
    concede_match(ana)
    names = [profile_name(p) for p in (ana, ben)]
    board = new_page()
    board.goto(base_url + "/leaderboard")
    provisional = board.get_by_test_id("leaderboard-provisional")
    for name in names:
        row = provisional.locator("tr", has_text=name)
        expect(row.get_by_test_id("standing-rating")).to_have_text(re.compile(r"^\d+\?$"))
    expect(board.get_by_test_id("provisional-why")).to_contain_text("marked ? is provisional")
    expect(board.locator("#leaderboard")).not_to_contain_text("Nobody ranked yet")


def table_box(page: Page, margin: float) -> dict:
    """The table's bed `margin` metres beyond the cushions (the pockets and the rails), in
    page CSS pixels."""
    size = page.evaluate("[window.__pool.state.table.length, window.__pool.state.table.width]")
    corners = [
        table_point(page, x, y)
        for x in (-margin, size[0] + margin)
        for y in (-margin, size[1] + margin)
    ]
    xs, ys = [c[0] for c in corners], [c[1] for c in corners]
    return {"x": min(xs), "y": min(ys), "width": max(xs) - min(xs), "height": max(ys) - min(ys)}


def overlaps(a: dict, b: dict) -> bool:
    return (
        a["x"] < b["x"] + b["width"]
        and b["x"] < a["x"] + a["width"]
        and a["y"] < b["y"] + b["height"]
        and b["y"] < a["y"] + a["height"]
    )


@pytest.mark.parametrize("viewport", [(390, 844), (844, 390)], ids=["upright", "landscape"])
def test_on_a_phone_nothing_covers_the_cloth_or_a_pocket(base_url, browser, viewport):
    width, height = viewport
    ctx = browser.new_context(
        viewport={"width": width, "height": height}, is_mobile=True, has_touch=True
    )
    try:
        page = ctx.new_page()
        page.goto(base_url + "/")
        page.get_by_test_id("play-computer").tap()
        page.wait_for_url(TABLE_PAGE)
        wait_ready(page, "aiming")
        bed = table_box(page, 0.1)  # the pockets' mouths and the rails round the cloth
        coach = page.get_by_test_id("first-shot-hint")
        expect(coach).to_be_visible()
        assert not overlaps(coach.bounding_box(), bed), "the first-shot coach"
        page.get_by_test_id("first-shot-hint-ok").tap()
        expect(page.get_by_test_id("aim-state")).to_be_visible()  # "Ball in hand…"
        shown = ["aim-state", "aim-left", "aim-right"]
        for testid in shown:
            box = page.get_by_test_id(testid).bounding_box()
            assert box is not None and not overlaps(box, bed), testid
            assert box["y"] + box["height"] <= height, testid
        page.on("dialog", lambda d: d.accept())
        page.get_by_test_id("concede").tap()
        wait_ready(page, "over")
        banner = page.get_by_test_id("winner")
        expect(banner).to_be_visible()
        assert not overlaps(banner.bounding_box(), bed)
    finally:
        ctx.close()
