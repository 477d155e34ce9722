"""The web client in a cluster: a page served by one server watches a table played by
another (it connects where `ws_url` says, which the page's CSP allows), and when that server
dies the page asks again and follows the room to the server that took it over."""

from __future__ import annotations

import pytest
from playwright.sync_api import sync_playwright

from tests.e2e.conftest import CHROMIUM_ARGS
from tests.e2e.helpers import wait_ready
from tests.support.games import EIGHT_BALL
from tests.support.waiting import until

from .servers import Server, ServerSet

pytestmark = [
    pytest.mark.timeout(360),
    pytest.mark.redis,
    pytest.mark.postgres,
    pytest.mark.slow,
    pytest.mark.browser,
]


def spectators(server: Server, room: str) -> int:
    with server.http() as client:
        reply = client.get(f"/api/rooms/{room}")
    return reply.json()["spectators"] if reply.status_code == 200 else -1


def test_a_page_follows_its_table_to_another_server(servers) -> None:
    group: ServerSet = servers(2, store="sqlite", rack_seed=EIGHT_BALL, lease_ttl=2.0)
    page_server, other = group.all
    with page_server.http() as client:
        rooms = [client.post("/api/rooms", json={"game": "eight_ball"}).json() for _ in range(2)]
    room = next(r for r in rooms if other.address in r["ws_url"])["room_id"]

    errors: list[str] = []
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=CHROMIUM_ARGS)
        try:
            page = browser.new_page()
            page.on("pageerror", lambda e: errors.append(str(e)))
            page.on(
                "console", lambda m: errors.append(m.text) if "Content-Security" in m.text else None
            )
            page.goto(f"{page_server.url}/r/{room}")
            wait_ready(page, "waiting")  # watching, over a socket to the other server
            until(lambda: spectators(page_server, room) == 1)

            other.kill()
            until(lambda: spectators(page_server, room) == 1, within=60.0)  # back, here now
            with page_server.http() as client:
                assert page_server.address in client.get(f"/api/rooms/{room}").json()["ws_url"]
            wait_ready(page, "waiting")
        finally:
            browser.close()
    assert errors == []
