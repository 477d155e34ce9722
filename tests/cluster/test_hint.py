"""The hint ("Show me a shot") in a cluster: the page asks whichever server the load
balancer picks, and the hint is planned by the server that plays the table (the planner
needs the live table), its answers and refusals passed back unchanged."""

from __future__ import annotations

import pytest

from tests.support.games import EIGHT_BALL

from .servers import ServerSet

pytestmark = [pytest.mark.timeout(300), pytest.mark.redis, pytest.mark.postgres, pytest.mark.slow]


def test_a_hint_asked_of_another_server_is_planned_by_the_owner(servers) -> None:
    group: ServerSet = servers(2, store="sqlite", rack_seed=EIGHT_BALL)
    here, there = group.all
    with here.http() as client, there.http() as owner:
        for _ in range(8):  # new tables go to the least loaded server: soon one is there
            created = client.post("/api/rooms", json={"game": "practice", "listed": False})
            if there.address in created.json()["ws_url"]:
                break
        else:
            pytest.fail("no practice table was opened on the other server")
        room = created.json()["room_id"]
        ana = client.post(f"/api/rooms/{room}/join", json={"name": "Ana"}).json()

        asked_here = client.post(f"/api/rooms/{room}/hint", json={"token": ana["token"]})
        assert asked_here.status_code == 200, asked_here.text
        hint = asked_here.json()
        assert hint["level"] == "pro" and hint["place"] is not None  # ball in hand in practice
        # the owner plans the same table the same way: what came back is its plan
        assert owner.post(f"/api/rooms/{room}/hint", json={"token": ana["token"]}).json() == hint

        wrong = client.post(f"/api/rooms/{room}/hint", json={"token": "nope"})
        assert wrong.status_code == 403 and wrong.json()["detail"]["code"] == "bad_token"
        missing = client.post("/api/rooms/nosuchroom/hint", json={"token": ana["token"]})
        assert missing.status_code == 404
