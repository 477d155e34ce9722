"""A friends' table is ranked only when both players agree: the creator with `ranked: true`
on the new room, each player again with `ranked: true` on their join."""

from __future__ import annotations

import pytest

from server.players import COUNTED_GAMES, KindRating, rate_match
from tests.api.test_players import Visitor, at_the_table, both_visit, break_rack, with_records
from tests.support.messages import state_where
from tests.support.rooms import create_room


def ranked_room(creator: Visitor, game: str = "eight_ball") -> str:
    made = creator.call("POST", "/api/rooms", json={"game": game, "ranked": True})
    assert made.status_code == 201, made.text
    assert made.json()["ranked"] is True
    return str(made.json()["room_id"])


def sit(visitor: Visitor, room_id: str, name: str, ranked: bool = True) -> dict:
    joined = visitor.call(
        "POST", f"/api/rooms/{room_id}/join", json={"name": name, "ranked": ranked}
    )
    assert joined.status_code == 200, joined.text
    return dict(joined.json())


def eight_ball(visitor: Visitor) -> dict:
    profile = visitor.call("GET", "/api/players/me").json()
    return dict(next(r for r in profile["ratings"] if r["game"] == "eight_ball"))


def test_a_ranked_friends_table_moves_both_ratings_by_glicko2(clocked_client, clock):
    ana, ben = Visitor(clocked_client), Visitor(clocked_client)
    with_records(clocked_client, clock.now, ana, ben)
    room_id = ranked_room(ana)
    assert clocked_client.get(f"/api/rooms/{room_id}").json()["ranked"] is True
    (listed,) = [
        r for r in clocked_client.get("/api/rooms").json()["rooms"] if r["room_id"] == room_id
    ]
    assert listed["ranked"] is True
    a = sit(ana, room_id, "Ana")
    b = sit(ben, room_id, "Ben")
    with at_the_table(clocked_client, room_id, a, b) as (wa, wb):
        both_visit(wa, wb)
        wb.send_json({"type": "concede"})
        state_where(wa, lambda s: s["match"]["match_over"] and s["match"]["match_winner"] == 0)
        # A rematch is friendly, as in a Play now room.
        wa.send_json({"type": "rematch"})
        wb.send_json({"type": "rematch"})
        state_where(wb, lambda s: s["match"] is not None and not s["match"]["match_over"])
        break_rack(wb, wa)
        wa.send_json({"type": "concede"})
        state_where(wb, lambda s: s["match"]["match_over"] and s["match"]["match_winner"] == 1)
    expect_a, expect_b = rate_match(
        KindRating(ana.id, "eight_ball"), KindRating(ben.id, "eight_ball"), True, clock.now
    )
    got_a, got_b = eight_ball(ana), eight_ball(ben)
    assert got_a["rating"] == pytest.approx(expect_a.rating.rating, abs=0.01)
    assert got_a["rd"] == pytest.approx(expect_a.rating.rd, abs=0.01)
    assert got_b["rating"] == pytest.approx(expect_b.rating.rating, abs=0.01)
    games = COUNTED_GAMES + 1
    assert (got_a["games"], got_a["wins"], got_b["games"], got_b["wins"]) == (games, 1, games, 0)
    (recent,) = ana.call("GET", "/api/players/me").json()["recent"]
    assert recent["room_id"] == room_id and recent["opponent"] == ben.profile["name"]


def test_a_join_without_agreement_is_refused_and_seats_nobody(clocked_client):
    ana, ben = Visitor(clocked_client), Visitor(clocked_client)
    room_id = ranked_room(ana)
    sit(ana, room_id, "Ana")
    refused = [
        ben.call("POST", f"/api/rooms/{room_id}/join", json={"name": "Ben"}),
        ben.call("POST", f"/api/rooms/{room_id}/join", json={"name": "Ben", "ranked": False}),
        clocked_client.post(f"/api/rooms/{room_id}/join", json={"name": "Cy", "ranked": True}),
    ]
    for response in refused:
        assert response.status_code == 409, response.text
        assert response.json()["detail"]["code"] == "ranked_needs_agreement"
    assert clocked_client.get(f"/api/rooms/{room_id}").json()["players"] == ["Ana", None]
    sit(ben, room_id, "Ben")  # agreeing now seats them
    assert clocked_client.get(f"/api/rooms/{room_id}").json()["players"] == ["Ana", "Ben"]


def test_an_unranked_friends_table_changes_no_rating(clocked_client):
    ana, ben = Visitor(clocked_client), Visitor(clocked_client)
    room_id = create_room(clocked_client)
    assert clocked_client.get(f"/api/rooms/{room_id}").json()["ranked"] is False
    a = sit(ana, room_id, "Ana")  # agreeing to an unranked table changes nothing
    b = sit(ben, room_id, "Ben")
    with at_the_table(clocked_client, room_id, a, b) as (wa, wb):
        break_rack(wa, wb)
        wb.send_json({"type": "concede"})
        state_where(wa, lambda s: s["match"]["match_over"])
    for player in (ana, ben):
        assert eight_ball(player)["games"] == 0
        assert player.call("GET", "/api/players/me").json()["recent"] == []


def test_practice_the_computer_and_strangers_cannot_open_a_ranked_table(clocked_client):
    ana = Visitor(clocked_client)
    for body, status, code in [
        ({"game": "practice", "ranked": True}, 422, "bad_ranked"),
        ({"game": "nine_ball", "ranked": True, "opponent": "pro"}, 422, "bad_ranked"),
    ]:
        response = ana.call("POST", "/api/rooms", json=body)
        assert response.status_code == status, response.text
        assert response.json()["detail"]["code"] == code
    stranger = clocked_client.post("/api/rooms", json={"game": "nine_ball", "ranked": True})
    assert stranger.status_code == 401 and stranger.json()["detail"]["code"] == "no_player"
    assert clocked_client.get("/api/rooms").json()["total"] == 0  # nothing opened
