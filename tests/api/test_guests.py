"""Guest pruning through the API, on a manual clock: a guest that never played is deleted
`POOL_GUEST_TTL` after it was made (its browser gets a new profile), one that took a seat
or waits for Play now is kept."""

from __future__ import annotations

from server.config import Settings
from tests.api.test_players import Visitor, play_now
from tests.support.rooms import create_room


def prune(client) -> int:
    """One pruning now, on the server's loop (it runs every `POOL_GUEST_PRUNE_EVERY` s)."""
    assert client.portal is not None
    return int(client.portal.call(client.app.state.guests.prune))


def test_a_guest_that_never_played_is_pruned_after_the_ttl(clocked_client, clock):
    settings: Settings = clocked_client.app.state.settings
    idle, seated, queued = (Visitor(clocked_client) for _ in range(3))
    room_id = create_room(clocked_client)
    joined = seated.call("POST", f"/api/rooms/{room_id}/join", json={"name": "Ben"})
    assert joined.status_code == 200
    assert play_now(queued)["status"] == "waiting"
    clock.advance(settings.guest_ttl - 1)
    assert prune(clocked_client) == 0  # not old enough yet
    clock.advance(2)
    assert prune(clocked_client) == 1
    assert clocked_client.get(f"/api/players/{idle.id}").status_code == 404
    again = idle.call("GET", "/api/players/me")  # the old cookie: a new profile
    assert again.status_code == 200 and again.json()["id"] != idle.id
    for kept in (seated, queued):
        assert kept.call("GET", "/api/players/me").json()["id"] == kept.id
    assert prune(clocked_client) == 0
