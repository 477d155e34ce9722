"""Accounts in real Chromium, on `localhost` (a secure context whose host can be a
WebAuthn relying party): two guests play a rated Play now match; one keeps its player with
a passkey made by Chromium's virtual authenticator, and a second, empty browser that holds
a copy of that passkey signs in and sees the same name, rating and history; the other
keeps its player with a password and signs in on a browser where another guest practised,
answering the merge question. Wrong passwords are refused with 401, then 429."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from playwright.sync_api import Page, expect

from .helpers import wait_ready
from .test_second_look import concede_match, seated_by_play_now, until_both_have_shot

pytestmark = pytest.mark.browser

AUTHENTICATOR = {
    "protocol": "ctap2",
    "transport": "internal",
    "hasResidentKey": True,
    "hasUserVerification": True,
    "isUserVerified": True,
}
PASSWORD = "a long pool passphrase"


def on_localhost(base_url: str) -> str:
    return base_url.replace("127.0.0.1", "localhost")


def authenticator(page: Page) -> tuple[Any, str]:
    """A virtual platform authenticator in the page's browser (CDP), and its id."""
    cdp = page.context.new_cdp_session(page)
    cdp.send("WebAuthn.enable", {"enableUI": False})
    added = cdp.send("WebAuthn.addVirtualAuthenticator", {"options": AUTHENTICATOR})
    return cdp, added["authenticatorId"]


def shown(page: Page) -> dict[str, Any]:
    """What the profile page shows of the player: name, 8-ball rating, ranked matches."""
    expect(page.get_by_test_id("account-panel")).to_be_visible()
    return {
        "name": page.get_by_test_id("profile-name").inner_text(),
        "rating": page.get_by_test_id("rating-eight_ball").get_by_test_id("rating").inner_text(),
        "recent": page.get_by_test_id("recent-match").all_inner_texts(),
    }


@pytest.fixture
def rated_pair(base_url, new_page) -> tuple[Page, Page]:
    """Two guests after a rated 8-ball Play now match (each struck, then Ana conceded)."""
    ana, ben = seated_by_play_now(on_localhost(base_url), new_page)
    until_both_have_shot(ana, ben)
    wait_ready(ana)
    concede_match(ana)
    return ana, ben


def test_a_passkey_and_a_password_keep_the_player_on_another_browser(
    base_url, new_page, rated_pair, artifacts: Path
):
    ana, ben = rated_pair
    local = on_localhost(base_url)
    for page in (ana, ben):
        page.goto(local + "/profile")
        expect(page.get_by_test_id("recent-match")).to_have_count(1)
    before = {"ana": shown(ana), "ben": shown(ben)}

    # Ana adds a passkey: her guest is an account now.
    expect(ana.get_by_test_id("account-panel")).to_contain_text("Keep this player")
    ana.get_by_test_id("account-panel").screenshot(path=str(artifacts / "accounts-keep.png"))
    cdp, first = authenticator(ana)
    ana.get_by_test_id("add-passkey").click()
    expect(ana.get_by_test_id("passkey")).to_have_count(1)
    expect(ana.get_by_test_id("session")).to_have_count(1)
    expect(ana.get_by_test_id("new-password")).to_be_visible()
    expect(ana.get_by_test_id("old-password")).to_have_count(0)  # no password yet
    ana.screenshot(path=str(artifacts / "accounts-profile.png"), full_page=True)
    (credential,) = cdp.send("WebAuthn.getCredentials", {"authenticatorId": first})["credentials"]
    assert credential["isResidentCredential"] and credential["rpId"] == "localhost"

    # An empty browser holding a copy of the passkey signs in without typing anything.
    laptop = new_page()
    other, second = authenticator(laptop)
    other.send("WebAuthn.addCredential", {"authenticatorId": second, "credential": credential})
    laptop.goto(local + "/login")
    expect(laptop.get_by_test_id("login-passkey")).to_be_enabled()
    laptop.screenshot(path=str(artifacts / "accounts-login.png"), full_page=True)
    laptop.get_by_test_id("login-passkey").click()
    laptop.wait_for_url(local + "/profile")
    assert shown(laptop) == before["ana"]
    expect(laptop.get_by_test_id("session")).to_have_count(2)

    # Ben sets a password; a browser where another guest practised signs in with it.
    ben.get_by_test_id("new-password").fill(PASSWORD)
    ben.get_by_test_id("set-password").click()
    expect(ben.get_by_test_id("sign-out-everywhere")).to_be_visible()
    expect(ben.get_by_test_id("old-password")).to_be_visible()  # changing asks for it
    phone = new_page()
    phone.goto(local + "/")
    phone.get_by_test_id("practice").click()
    wait_ready(phone)
    phone.goto(local + "/login")
    phone.get_by_test_id("login-name").fill(before["ben"]["name"])
    phone.get_by_test_id("login-password").fill(PASSWORD)
    phone.get_by_test_id("login-submit").click()
    expect(phone.get_by_test_id("merge-question")).to_contain_text("a match")
    phone.screenshot(path=str(artifacts / "accounts-merge.png"), full_page=True)
    phone.get_by_test_id("merge-yes").click()
    phone.wait_for_url(local + "/profile")
    assert shown(phone) == before["ben"]
    expect(phone.get_by_test_id("played-match")).to_have_count(2)  # the practice came along


def test_wrong_passwords_are_refused_then_limited(base_url, new_page):
    local = on_localhost(base_url)
    owner = new_page()
    owner.goto(local + "/profile")
    owner.get_by_test_id("profile-name-input").fill("Limited Lou")
    owner.get_by_test_id("profile-save").click()
    expect(owner.get_by_test_id("profile-name")).to_have_text("Limited Lou")
    owner.get_by_test_id("new-password").fill(PASSWORD)
    owner.get_by_test_id("set-password").click()
    expect(owner.get_by_test_id("sign-out-everywhere")).to_be_visible()

    guesser = new_page()
    guesser.goto(local + "/login")
    statuses = []
    for n in range(6):
        guesser.get_by_test_id("login-name").fill("limited lou")
        guesser.get_by_test_id("login-password").fill(f"wrong guess {n}")
        with guesser.expect_response("**/api/login") as answer:
            guesser.get_by_test_id("login-submit").click()
        statuses.append(answer.value.status)
    assert statuses == [401, 401, 401, 401, 401, 429]
    expect(guesser.get_by_test_id("login-error")).to_contain_text("Too many attempts")
