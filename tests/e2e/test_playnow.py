"""Players in real Chromium: two browsers press Play now and meet at one table as
opponents; a profile (its cookie) survives a reload, its name shown as text; the
leaderboard and profile pages load."""

from __future__ import annotations

import re

import pytest
from playwright.sync_api import expect

from .helpers import wait_for, wait_ready

pytestmark = pytest.mark.browser


def test_two_browsers_press_play_now_and_land_at_the_same_table(base_url, new_page):
    ana, ben = new_page(), new_page()
    for page, game in ((ana, "nine_ball"), (ben, "nine_ball")):
        page.goto(base_url + "/")
        expect(page.get_by_test_id("play-now")).to_be_visible()
        page.get_by_test_id("playnow-game").select_option(game)
    ana.get_by_test_id("play-now").click()
    expect(ana.get_by_test_id("playnow-status")).to_contain_text("Looking for a 9-ball")
    expect(ana.get_by_test_id("playnow-cancel")).to_be_visible()
    ben.get_by_test_id("play-now").click()
    ben.wait_for_url(re.compile(r"/r/[A-Za-z0-9_-]+$"))
    ana.wait_for_url(re.compile(r"/r/[A-Za-z0-9_-]+$"))  # the long-poll told Ana too
    assert ana.url == ben.url
    wait_ready(ana, "aiming")
    wait_ready(ben, "aiming")
    seats = [p.evaluate("window.__pool.state.me") for p in (ana, ben)]
    assert sorted(me["seat"] for me in seats) == [0, 1]
    assert {me["role"] for me in seats} == {"player"}
    expect(ana.get_by_test_id("player-0")).to_contain_text("(you)")
    expect(ben.get_by_test_id("player-1")).to_contain_text("(you)")
    # The match is on Ana's profile, in play.
    ana.goto(base_url + "/profile")
    expect(ana.get_by_test_id("played-match")).to_have_count(1)
    expect(ana.get_by_test_id("played-match")).to_contain_text("In play")
    expect(ana.get_by_test_id("played-match")).to_contain_text("9-ball")


def test_the_profile_survives_a_reload_and_shows_names_as_text(base_url, new_page):
    page = new_page()
    page.goto(base_url + "/profile")
    name = page.get_by_test_id("profile-name")
    expect(name).to_contain_text("Player ")
    page.get_by_test_id("profile-name-input").fill("Ana <i>x</i>")
    page.get_by_test_id("profile-save").click()
    expect(name).to_have_text("Ana <i>x</i>")
    page.reload()
    expect(page.get_by_test_id("profile-name")).to_have_text("Ana <i>x</i>")
    assert page.locator("[data-testid=profile-name] i").count() == 0  # text, not markup
    expect(page.get_by_test_id("rating-eight_ball")).to_contain_text("1500?")  # provisional
    cookies = page.context.cookies()
    (player,) = [c for c in cookies if c["name"] == "pool_player"]
    assert player["httpOnly"] and player["sameSite"] == "Lax"
    assert page.evaluate("document.cookie") == ""  # the page never sees the secret
    # The lobby knows the same player.
    page.goto(base_url + "/")
    expect(page.get_by_test_id("playnow-name")).to_have_text("Playing as Ana <i>x</i> · ")


def test_the_leaderboard_page_lists_both_games(base_url, new_page):
    page = new_page()
    page.goto(base_url + "/")
    page.get_by_test_id("leaderboard-link").click()
    page.wait_for_url(re.compile(r"/leaderboard$"))
    expect(page.get_by_test_id("leaderboard-ranked")).to_be_visible()
    page.get_by_test_id("leaderboard-nine_ball").click()
    page.wait_for_url(re.compile(r"/leaderboard\?game=nine_ball$"))
    expect(page.locator("#leaderboard h1")).to_have_text("9-ball leaderboard")
    wait_for(page, "document.querySelector('[data-testid=leaderboard-provisional]') !== null")
