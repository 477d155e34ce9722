"""A ranked friends' table in real Chromium: the creator ticks "Ranked" in the lobby, the
friend's join dialog says the rating will change and its button is the agreement."""

from __future__ import annotations

import re

import pytest
from playwright.sync_api import expect

from .helpers import create_table, lobby_row, wait_ready

pytestmark = pytest.mark.browser


def test_a_ranked_table_asks_the_friend_to_agree_before_seating_them(base_url, new_page):
    ana = new_page()
    ana.goto(base_url + "/")
    ranked = ana.get_by_test_id("ranked-table")
    ana.get_by_test_id("game-select").select_option("practice")
    expect(ranked).to_be_disabled()  # practice is never ranked
    ana.get_by_test_id("game-select").select_option("nine_ball")
    expect(ranked).to_be_enabled()
    ana.get_by_test_id("name").fill("Ana")
    ranked.check()
    room_id = create_table(ana)

    ben = new_page()
    ben.goto(base_url + "/")
    row = lobby_row(ben, room_id)
    expect(row).to_contain_text("9-ball · race to 3 · ranked")
    ben.get_by_test_id("name").fill("Ben")
    row.get_by_test_id("join").click()  # a ranked table: its page asks first
    ben.wait_for_url(re.compile(f"/r/{room_id}$"))
    expect(ben.locator("#join-info")).to_contain_text(
        "This table is ranked: your rating will change."
    )
    join = ben.locator("#join-seat")
    expect(join).to_have_text("Join the ranked game")
    join.click()
    wait_ready(ben, "aiming")
    expect(ben.get_by_test_id("player-0")).to_contain_text("Ana")
    expect(ben.get_by_test_id("player-1")).to_contain_text("Ben (you)")
