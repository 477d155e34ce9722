"""Through the real API: a Play now answer ends with its match (the lobby stays the lobby
afterwards); a seat taken without a name is the profile's name, an old client's name still
works; a refused name is one plain sentence; only a player who was at the table has left
it."""

from __future__ import annotations

import pytest

from server.api.name_errors import EMPTY, NOT_TEXT, TOO_LONG
from server.api.rooms import NO_PROFILE_NAME
from tests.support.messages import receive_until, state_where
from tests.support.rooms import connect, create_room

from .test_players import Visitor, paired, play_now


def test_a_play_now_answer_ends_with_its_match(clocked_client):
    ana, ben = Visitor(clocked_client), Visitor(clocked_client)
    play_now(ana)
    b = play_now(ben)["room"]
    assert ana.call("GET", "/api/playnow").json()["status"] == "matched"
    with connect(clocked_client, b["room_id"], b["token"]) as wb:
        receive_until(wb, "state")
        wb.send_json({"type": "concede"})
        state_where(wb, lambda s: s["match"]["match_over"])
    assert clocked_client.get(f"/api/rooms/{b['room_id']}").json()["status"] == "finished"
    for player in (ana, ben):
        assert player.call("GET", "/api/playnow").json()["status"] == "idle"
    # Pressing Play now again queues afresh.
    assert play_now(ana)["status"] == "waiting"


def test_a_seat_without_a_name_is_the_profiles_and_a_name_given_still_works(clocked_client):
    room_id = create_room(clocked_client)
    ana, ben = Visitor(clocked_client), Visitor(clocked_client)
    renamed = ana.call("PATCH", "/api/players/me", json={"name": "Ana"})
    assert renamed.status_code == 200
    seat = ana.call("POST", f"/api/rooms/{room_id}/join", json={})
    assert seat.status_code == 200 and seat.json()["name"] == "Ana"
    old = ben.call("POST", f"/api/rooms/{room_id}/join", json={"name": "Ben"})
    assert old.status_code == 200 and old.json()["name"] == "Ben"
    assert clocked_client.get(f"/api/rooms/{room_id}").json()["players"] == ["Ana", "Ben"]


def test_a_seat_without_a_name_nor_a_profile_is_refused_in_a_sentence(clocked_client):
    room_id = create_room(clocked_client)
    refused = clocked_client.post(f"/api/rooms/{room_id}/join", json={})
    assert refused.status_code == 422
    assert refused.json() == {"detail": {"code": "bad_name", "message": NO_PROFILE_NAME}}


@pytest.mark.parametrize(
    ("name", "sentence"),
    [("", EMPTY), ("x" * 25, TOO_LONG), ("x" * 300, TOO_LONG), (7, NOT_TEXT)],
)
def test_a_refused_name_is_one_plain_sentence(clocked_client, name, sentence):
    room_id = create_room(clocked_client)
    ana = Visitor(clocked_client)
    for method, url in (
        ("POST", f"/api/rooms/{room_id}/join"),
        ("PATCH", "/api/players/me"),
    ):
        refused = ana.call(method, url, json={"name": name})
        assert refused.status_code == 422
        assert refused.json() == {"detail": {"code": "bad_name", "message": sentence}}
        assert "String should" not in refused.text
    assert clocked_client.get(f"/api/rooms/{room_id}").json()["players"] == [None, None]


def test_other_refusals_keep_their_usual_answer(clocked_client):
    refused = clocked_client.post("/api/rooms", json={"game": "four_ball"})
    assert refused.status_code == 422
    assert isinstance(refused.json()["detail"], list)


def grace_where(ws, predicate, limit: int = 200) -> list[dict]:
    """The first `grace` list (of a `state` or a `presence`) that satisfies `predicate`."""
    for _ in range(limit):
        message = ws.receive_json()
        if "grace" in message and predicate(message["grace"]):
            return message["grace"]
    raise AssertionError("no such grace list")


def test_only_a_player_who_was_at_the_table_has_left_it(clocked_client):
    """Play now seats both at once: until Ben's page connects he is away but has not left;
    once he was there and dropped, he has."""
    ana, ben = Visitor(clocked_client), Visitor(clocked_client)
    a, b = paired(ana, ben)
    with connect(clocked_client, a["room_id"], a["token"]) as wa:
        first = receive_until(wa, "state")[-1]["grace"]
        assert [(g["seat"], g["left"]) for g in first] == [(b["seat"], False)]
        with connect(clocked_client, b["room_id"], b["token"]) as wb:
            receive_until(wb, "state")
            grace_where(wa, lambda g: g == [])
        away = grace_where(wa, lambda g: g != [])
        assert [(g["seat"], g["left"]) for g in away] == [(b["seat"], True)]
