"""Players through the real API: the profile a first visit makes (and keeps), names, seats
tied to the player, Play now pairing, the computer offered after 20 s alone (a manual
clock, no sleeping), a ranked match moving both ratings by Glicko-2, the leaderboard's
order, and the rate limits."""

from __future__ import annotations

import asyncio
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import httpx
import pytest
from fastapi.testclient import TestClient
from starlette.testclient import WebSocketTestSession

from server.players import COMPUTER_RATINGS, COUNTED_GAMES, KindRating, rate_match
from server.store.players import PlayerRows, RatingRecord
from tests.support.games import (
    BREAK_MESSAGE,
    EIGHT_BALL_GROUP_SHOT,
    EIGHT_BALL_PLACE,
    EIGHT_BALL_SCRATCH,
    shoot_message,
)
from tests.support.live import live_server
from tests.support.messages import receive_until, state_where
from tests.support.rooms import app_with, connect, create_room

COOKIE = "pool_player"
DEVICE_COOKIE = "pool_device"


class Visitor:
    """One browser: its own profile cookie, sent with each of its requests."""

    def __init__(self, client: TestClient) -> None:
        self.client = client
        response = client.get("/api/players/me")
        assert response.status_code == 200, response.text
        self.secret = response.cookies[COOKIE]
        self.set_cookie = response.headers["set-cookie"]
        self.profile = response.json()
        client.cookies.clear()  # each visitor sends its own

    @property
    def id(self) -> str:
        return self.profile["id"]

    def call(self, method: str, url: str, **kwargs: Any) -> httpx.Response:
        return self.client.request(
            method, url, headers={"Cookie": f"{COOKIE}={self.secret}"}, **kwargs
        )


def test_a_first_visit_makes_a_profile_that_a_reload_keeps(clocked_client):
    ana = Visitor(clocked_client)
    cookie = ana.set_cookie.lower()
    assert "httponly" in cookie and "samesite=lax" in cookie and "path=/" in cookie
    again = ana.call("GET", "/api/players/me")
    assert again.status_code == 200 and again.json()["id"] == ana.id
    assert "set-cookie" not in again.headers
    assert Visitor(clocked_client).id != ana.id  # another browser, another player
    shown = clocked_client.get(f"/api/players/{ana.id}").json()
    assert (shown["id"], shown["name"], shown["me"]) == (ana.id, ana.profile["name"], False)
    ratings = {r["game"]: r for r in shown["ratings"]}
    assert ratings["eight_ball"] == {
        "game": "eight_ball",
        "rating": 1500.0,
        "rd": 350.0,
        "conservative": 800.0,
        "provisional": True,
        "games": 0,
        "wins": 0,
    }
    assert clocked_client.get("/api/players/nobody").status_code == 404


def test_a_forged_cookie_is_a_stranger(clocked_client):
    response = clocked_client.get("/api/playnow", headers={"Cookie": f"{COOKIE}={'x' * 43}"})
    assert response.status_code == 401 and response.json()["detail"]["code"] == "no_player"


def test_names_are_checked_and_kept_as_text(clocked_client):
    ana = Visitor(clocked_client)
    renamed = ana.call("PATCH", "/api/players/me", json={"name": "  <b>Ana</b> "})
    assert renamed.status_code == 200 and renamed.json()["name"] == "<b>Ana</b>"
    for bad in ["   ", "x" * 25, "tab\there"]:
        refused = ana.call("PATCH", "/api/players/me", json={"name": bad})
        assert refused.status_code == 422, bad
    assert ana.call("GET", "/api/players/me").json()["name"] == "<b>Ana</b>"


def test_a_player_joining_a_room_again_gets_the_same_seat(clocked_client):
    room_id = create_room(clocked_client)
    ana, ben = Visitor(clocked_client), Visitor(clocked_client)
    first = ana.call("POST", f"/api/rooms/{room_id}/join", json={"name": "Ana"}).json()
    again = ana.call("POST", f"/api/rooms/{room_id}/join", json={"name": "Ana"}).json()
    assert (again["seat"], again["token"]) == (first["seat"], first["token"]) == (0, first["token"])
    other = ben.call("POST", f"/api/rooms/{room_id}/join", json={"name": "Ben"}).json()
    assert other["seat"] == 1 and other["token"] != first["token"]
    with connect(clocked_client, room_id, first["token"]) as ws:
        assert ws.receive_json()["seat"] == 0


def break_rack(breaker: Any, other: Any) -> None:
    """`breaker` breaks (`tests.support.games.EIGHT_BALL`: a legal break, it shoots
    again); both have seen the result."""
    breaker.send_json(BREAK_MESSAGE)
    for ws in (breaker, other):
        receive_until(ws, "shot_result")
        receive_until(ws, "state")


def both_visit(breaker: Any, other: Any) -> None:
    """Each side has a visit at the table (a ranked match is rated only then): `breaker`
    breaks and scratches, `other` takes ball in hand and pots a ball (`games.EIGHT_BALL`);
    both have seen every result."""
    break_rack(breaker, other)
    for shooter, message in (
        (breaker, shoot_message(EIGHT_BALL_SCRATCH)),
        (other, {"type": "place_cue", "x": EIGHT_BALL_PLACE[0], "y": EIGHT_BALL_PLACE[1]}),
        (other, shoot_message(EIGHT_BALL_GROUP_SHOT)),
    ):
        shooter.send_json(message)
        if message["type"] == "place_cue":
            receive_until(shooter, "state")
            continue
        for ws in (breaker, other):
            receive_until(ws, "shot_result")
            receive_until(ws, "state")


@contextmanager
def at_the_table(
    client: TestClient, room_id: str, a: dict, b: dict
) -> Iterator[tuple[WebSocketTestSession, WebSocketTestSession]]:
    """The sockets of the players seated by the joins `a` and `b`, each read up to its first
    `state`."""
    with connect(client, room_id, a["token"]) as wa, connect(client, room_id, b["token"]) as wb:
        receive_until(wa, "state")
        receive_until(wb, "state")
        yield wa, wb


def test_matches_in_the_players_seats_go_on_the_profile(clocked_client):
    room_id = create_room(clocked_client, race_to=2)
    ana, ben = Visitor(clocked_client), Visitor(clocked_client)
    a = ana.call("POST", f"/api/rooms/{room_id}/join", json={"name": "Ana"}).json()
    b = clocked_client.post(f"/api/rooms/{room_id}/join", json={"name": "Ben"}).json()  # no profile
    with at_the_table(clocked_client, room_id, a, b) as (wa, wb):
        break_rack(wa, wb)
        wb.send_json({"type": "concede"})
        state_where(wa, lambda s: s["match"]["score"] == [1, 0])
    (played,) = ana.call("GET", "/api/players/me").json()["matches"]
    assert played == {
        **played,
        "room_id": room_id,
        "game": "eight_ball",
        "players": ["Ana", "Ben"],
        "seat": 0,
        "status": "playing",
        "score": [1, 0],
        "won": None,  # the match (race to 2) goes on
        "replay": f"/m/{played['match_id']}",
    }
    assert ben.call("GET", "/api/players/me").json()["matches"] == []
    assert clocked_client.get(f"/api/matches/{played['match_id']}").json()["room_id"] == room_id


def with_records(client: TestClient, now: float, *visitors: Visitor) -> None:
    """Give each visitor a record of `COUNTED_GAMES` 8-ball games left at the starting
    rating (1500, RD 350), so that results against them count (the farm rule) and Glicko-2
    gives the numbers of two new players."""
    for visitor in visitors:
        record = RatingRecord(visitor.id, "eight_ball", 1500.0, 350.0, 0.06, COUNTED_GAMES, 0, now)
        client.app.state.store.run(lambda repo, r=record: PlayerRows(repo).save_rating(r))


def paired(ana: Visitor, ben: Visitor) -> tuple[dict, dict]:
    """Ana then Ben press Play now and are paired: each one's seat (`room_id`, `token`)."""
    play_now(ana)
    b = play_now(ben)["room"]
    return ana.call("GET", "/api/playnow").json()["room"], b


def play_now(visitor: Visitor, game: str = "eight_ball") -> dict:
    response = visitor.call("POST", "/api/playnow", json={"game": game})
    assert response.status_code == 200, response.text
    return response.json()


def test_play_now_pairs_two_players_into_one_new_room_as_opponents(clocked_client):
    ana, ben = Visitor(clocked_client), Visitor(clocked_client)
    waiting = play_now(ana)
    assert waiting["status"] == "waiting" and waiting["computer"] is None
    assert waiting["rating"] == 1500 and waiting["window"] == 100
    matched = play_now(ben)
    assert matched["status"] == "matched"
    seen = ana.call("GET", "/api/playnow", params={"wait": 5}).json()
    assert seen["status"] == "matched"
    a, b = seen["room"], matched["room"]
    assert a["room_id"] == b["room_id"] and (a["seat"], b["seat"]) == (0, 1)
    assert a["ranked"] and a["url"] == f"/r/{a['room_id']}"
    assert (a["opponent"], b["opponent"]) == (ben.profile["name"], ana.profile["name"])
    room = clocked_client.get(f"/api/rooms/{a['room_id']}").json()
    assert room["players"] == [ana.profile["name"], ben.profile["name"]]
    assert room["status"] == "playing"
    with (
        connect(clocked_client, a["room_id"], a["token"]) as wa,
        connect(clocked_client, b["room_id"], b["token"]) as wb,
    ):
        assert (wa.receive_json()["seat"], wb.receive_json()["seat"]) == (0, 1)
    # The same tokens come back from the room's own join: the seat is the player's.
    rejoin = ben.call("POST", f"/api/rooms/{b['room_id']}/join", json={"name": "Ben"}).json()
    assert (rejoin["seat"], rejoin["token"]) == (1, b["token"])


def test_one_queue_entry_per_player_and_nobody_plays_themselves(clocked_client):
    ana = Visitor(clocked_client)
    assert play_now(ana)["status"] == "waiting"
    assert play_now(ana)["status"] == "waiting"  # a second tab: the same one place
    assert play_now(ana, "nine_ball")["game"] == "nine_ball"  # moved, not doubled
    ben = Visitor(clocked_client)
    assert play_now(ben, "eight_ball")["status"] == "waiting"  # ana left eight-ball
    left = ana.call("DELETE", "/api/playnow").json()
    assert left == {**left, "status": "idle"}
    assert ana.call("GET", "/api/playnow").json()["status"] == "idle"


def wave(client: TestClient) -> int:
    """A wave of pairing now, on the server's loop (it runs every second by itself)."""
    assert client.portal is not None
    return client.portal.call(client.app.state.matchmaker.wave)


def test_the_window_widens_until_distant_ratings_meet(clocked_client, clock):
    store = clocked_client.app.state.store
    ana, ben = Visitor(clocked_client), Visitor(clocked_client)
    strong = RatingRecord(ben.id, "eight_ball", 1850.0, 60.0, 0.06, 40, 30, clock.now)
    store.run(lambda repo: PlayerRows(repo).save_rating(strong))
    play_now(ana)
    assert play_now(ben)["status"] == "waiting"  # 350 apart; the window is 100
    clock.advance(12.0)  # 100 + 20/s * 12 s = 340
    wave(clocked_client)
    assert ben.call("GET", "/api/playnow").json()["window"] == pytest.approx(340)
    clock.advance(1.0)  # 360
    wave(clocked_client)  # (or the server's own wave, if it came first)
    assert ana.call("GET", "/api/playnow").json()["status"] == "matched"


def test_nobody_suitable_for_20_seconds_offers_the_computer(clocked_client, clock):
    ana = Visitor(clocked_client)
    play_now(ana)
    early = ana.call("POST", "/api/playnow/computer")
    assert early.status_code == 409 and early.json()["detail"]["code"] == "not_offered"
    clock.advance(19.9)
    assert ana.call("GET", "/api/playnow").json()["computer"] is None
    clock.advance(0.1)
    offered = ana.call("GET", "/api/playnow").json()
    assert offered["status"] == "waiting" and offered["computer"] == "amateur"  # 1500
    taken = ana.call("POST", "/api/playnow/computer").json()
    assert taken["status"] == "matched" and taken["computer"] == "amateur"
    seat = taken["room"]
    assert not seat["ranked"] and seat["opponent"] == "Computer (amateur)"
    room = clocked_client.get(f"/api/rooms/{seat['room_id']}").json()
    assert room["players"][seat["seat"]] == ana.profile["name"] and room["status"] == "playing"
    assert ana.call("GET", "/api/playnow").json()["status"] == "matched"  # until queued again


def test_the_long_poll_returns_on_news_only(clocked_client, clock):
    """The offer wakes a waiting poll once; after it is shown, a poll waits for the next
    change (pairing, leaving) instead of answering at once in a loop."""
    ana = Visitor(clocked_client)
    matchmaker = clocked_client.app.state.matchmaker
    assert clocked_client.portal is not None
    play_now(ana)
    clock.advance(20.0)
    news = clocked_client.portal.start_task_soon(matchmaker.wait, ana.id, 30.0)
    news.result(timeout=10)  # the offer is news: answered at once
    assert ana.call("GET", "/api/playnow").json()["computer"] == "amateur"  # now shown
    quiet = clocked_client.portal.start_task_soon(matchmaker.wait, ana.id, 30.0)
    clocked_client.get("/health")  # the server's loop has run meanwhile
    assert not quiet.done()
    ana.call("DELETE", "/api/playnow")
    quiet.result(timeout=10)  # leaving woke it


def test_the_computer_offered_is_the_level_nearest_the_rating(clocked_client, clock):
    ana = Visitor(clocked_client)
    strong = RatingRecord(ana.id, "nine_ball", 2050.0, 60.0, 0.06, 40, 30, clock.now)
    clocked_client.app.state.store.run(lambda repo: PlayerRows(repo).save_rating(strong))
    play_now(ana, "nine_ball")
    clock.advance(20.0)
    assert ana.call("GET", "/api/playnow").json()["computer"] == "pro"
    assert COMPUTER_RATINGS["pro"] == 2080


def test_a_ranked_match_moves_both_ratings_by_glicko2(clocked_client, clock):
    ana, ben = Visitor(clocked_client), Visitor(clocked_client)
    with_records(clocked_client, clock.now, ana, ben)
    a, b = paired(ana, ben)
    with at_the_table(clocked_client, a["room_id"], a, b) as (wa, wb):
        both_visit(wa, wb)
        wb.send_json({"type": "concede"})
        over = state_where(wa, lambda s: s["match"]["match_over"])
        assert over["match"]["match_winner"] == 0
        # Only the room's first match is rated: a rematch is friendly.
        wa.send_json({"type": "rematch"})
        wb.send_json({"type": "rematch"})
        state_where(wa, lambda s: s["match"] is not None and not s["match"]["match_over"])
        rematch = state_where(wb, lambda s: not s["match"]["match_over"])
        assert rematch["match"]["turn"] == 1  # the breaks alternate
        break_rack(wb, wa)
        wa.send_json({"type": "concede"})
        state_where(wb, lambda s: s["match"]["match_over"] and s["match"]["match_winner"] == 1)
    expect_a, expect_b = rate_match(
        KindRating(ana.id, "eight_ball"), KindRating(ben.id, "eight_ball"), True, clock.now
    )
    mine = ana.call("GET", "/api/players/me").json()
    theirs = ben.call("GET", "/api/players/me").json()
    got_a = next(r for r in mine["ratings"] if r["game"] == "eight_ball")
    got_b = next(r for r in theirs["ratings"] if r["game"] == "eight_ball")
    assert got_a["rating"] == pytest.approx(expect_a.rating.rating, abs=0.01)
    assert got_a["rd"] == pytest.approx(expect_a.rating.rd, abs=0.01)
    assert got_b["rating"] == pytest.approx(expect_b.rating.rating, abs=0.01)
    assert got_a["rating"] > 1500 > got_b["rating"]
    assert (round(got_a["rating"], 2), round(got_b["rating"], 2)) == (1662.31, 1337.69)
    games = COUNTED_GAMES + 1
    assert (got_a["games"], got_a["wins"], got_b["games"], got_b["wins"]) == (games, 1, games, 0)
    (recent,) = mine["recent"]
    assert recent["won"] and recent["opponent"] == ben.profile["name"]
    assert recent["rating_before"] == 1500 and recent["room_id"] == a["room_id"]
    assert recent["replay"] == f"/m/{recent['match_id']}"
    assert clocked_client.get(f"/api/matches/{recent['match_id']}").status_code == 200
    played = [(m["score"], m["won"]) for m in mine["matches"]]
    assert played == [([0, 1], False), ([1, 0], True)]  # the rematch, then the ranked match
    board = clocked_client.get("/api/leaderboard/eight_ball").json()
    assert [s["player_id"] for s in board["provisional"]] == [ana.id, ben.id]
    assert board["ranked"] == []


def test_a_ranked_match_ended_before_any_shot_is_not_rated(clocked_client):
    """A no-show forfeits the frame when the grace ends; a concession before the break
    is the same: no shot, no rating (the history marks the match abandoned)."""
    ana, ben = Visitor(clocked_client), Visitor(clocked_client)
    play_now(ana)
    b = play_now(ben)["room"]
    with connect(clocked_client, b["room_id"], b["token"]) as wb:
        receive_until(wb, "state")
        wb.send_json({"type": "concede"})
        state_where(wb, lambda s: s["match"]["match_over"])
    for player in (ana, ben):
        profile = player.call("GET", "/api/players/me").json()
        # 8-ball, 9-ball, snooker, three-cushion
        assert [r["games"] for r in profile["ratings"]] == [0, 0, 0, 0]
        assert profile["recent"] == []
    assert clocked_client.get("/api/leaderboard/eight_ball").json()["provisional"] == []


def test_a_concession_before_the_other_side_played_is_not_rated(clocked_client):
    """The farm: a fresh profile paired by Play now breaks, the other concedes at once.
    Until each side has had a visit at the table the match is not rated."""
    ana, ben = Visitor(clocked_client), Visitor(clocked_client)
    a, b = paired(ana, ben)
    with at_the_table(clocked_client, a["room_id"], a, b) as (wa, wb):
        break_rack(wa, wb)
        wb.send_json({"type": "concede"})
        over = state_where(wa, lambda s: s["match"]["match_over"])
        assert over["match"]["match_winner"] == 0  # the game is won, not rated
    for player in (ana, ben):
        profile = player.call("GET", "/api/players/me").json()
        # 8-ball, 9-ball, snooker, three-cushion
        assert [r["games"] for r in profile["ratings"]] == [0, 0, 0, 0]
        assert [r["rating"] for r in profile["ratings"]] == [1500, 1500, 1500, 1500]


def farm_round(client: TestClient, farmer: Visitor, victim: Visitor) -> None:
    """The audit's farm, one round: paired by Play now, each side strikes, the victim
    concedes."""
    a, b = paired(farmer, victim)
    with at_the_table(client, a["room_id"], a, b) as (wa, wb):
        both_visit(wa, wb)
        wb.send_json({"type": "concede"})
        state_where(wa, lambda s: s["match"]["match_over"] and s["match"]["match_winner"] == 0)


def eight_ball_rating(visitor: Visitor) -> dict:
    profile = visitor.call("GET", "/api/players/me").json()
    return dict(next(r for r in profile["ratings"] if r["game"] == "eight_ball"))


def test_wins_over_fresh_profiles_do_not_move_a_rating(clocked_client, clock):
    """The farm rule through the API: three fresh profiles concede to a farmer after each
    side struck: the games are counted, the rating stays 1500; a win over a player with a
    record then moves it by Glicko-2."""
    farmer = Visitor(clocked_client)
    for _ in range(3):
        farm_round(clocked_client, farmer, Visitor(clocked_client))
    farmed = eight_ball_rating(farmer)
    assert (farmed["rating"], farmed["rd"], farmed["games"], farmed["wins"]) == (1500, 350, 3, 3)
    known = Visitor(clocked_client)
    with_records(clocked_client, clock.now, known)
    farm_round(clocked_client, farmer, known)
    expect, _ = rate_match(
        KindRating(farmer.id, "eight_ball", games=3, wins=3),
        KindRating(known.id, "eight_ball", games=COUNTED_GAMES),
        True,
        clock.now,
    )
    won = eight_ball_rating(farmer)
    assert won["rating"] == pytest.approx(expect.rating.rating, abs=0.01)
    assert (won["games"], won["wins"]) == (4, 4) and won["rating"] > 1600
    assert eight_ball_rating(known)["rating"] == 1500  # the farmer had 3 games: no record yet


def test_play_now_never_pairs_two_players_from_one_address(settings, clock):
    """Fresh profiles of one address conceding to one another farmed a rating: Play now
    pairs only players asking from different addresses."""
    strict = settings.replace(playnow_same_address=False)
    with TestClient(app_with(strict, clock=clock.clock)) as client:
        transport = client._transport  # TestClient names the peer's address here
        transport.client = ("10.0.0.1", 50000)
        ana, ben = Visitor(client), Visitor(client)
        assert play_now(ana)["status"] == "waiting"
        assert play_now(ben)["status"] == "waiting"  # the same address: not paired
        clock.advance(15.0)  # windows widened: ratings are no obstacle
        assert ben.call("GET", "/api/playnow").json()["status"] == "waiting"
        transport.client = ("10.0.0.2", 50000)
        cara = Visitor(client)
        matched = play_now(cara)
        assert matched["status"] == "matched"
        opponent = matched["room"]["opponent"]
        assert opponent in (ana.profile["name"], ben.profile["name"])
        other = ben if opponent == ana.profile["name"] else ana
        assert other.call("GET", "/api/playnow").json()["status"] == "waiting"


def test_play_now_never_pairs_two_profiles_of_one_browser(clocked_client, clock):
    """A browser keeps its `pool_device` cookie when it gets a new profile (the profile
    cookie lost, a guest pruned): two profiles of one device are never paired, even where
    one address may pair (this client's settings)."""
    first = clocked_client.get("/api/players/me")
    device = first.cookies[DEVICE_COOKIE]
    clocked_client.cookies.clear()
    again = clocked_client.get("/api/players/me", headers={"Cookie": f"{DEVICE_COOKIE}={device}"})
    assert DEVICE_COOKIE not in again.cookies  # the device is kept
    clocked_client.cookies.clear()
    profiles = [first.cookies[COOKIE], again.cookies[COOKIE]]
    assert profiles[0] != profiles[1]

    def press(secret: str, device_cookie: str) -> dict:
        cookies = f"{COOKIE}={secret}; {DEVICE_COOKIE}={device_cookie}"
        response = clocked_client.post(
            "/api/playnow", json={"game": "eight_ball"}, headers={"Cookie": cookies}
        )
        return dict(response.json())

    assert press(profiles[0], device)["status"] == "waiting"
    assert press(profiles[1], device)["status"] == "waiting"  # one device: not paired
    clock.advance(15.0)
    assert wave(clocked_client) == 0
    other = clocked_client.get("/api/players/me")
    stranger = (other.cookies[COOKIE], other.cookies[DEVICE_COOKIE])
    clocked_client.cookies.clear()
    assert stranger[1] != device
    assert press(*stranger)["status"] == "matched"


def test_the_leaderboard_orders_by_rating_minus_two_deviations(clocked_client, clock):
    people = {name: Visitor(clocked_client) for name in ["sure", "unsure", "low", "new"]}
    rows = {
        "unsure": (1900.0, 100.0, 12),  # 1700
        "sure": (1800.0, 40.0, 60),  # 1720
        "low": (1400.0, 50.0, 30),  # 1300
        "new": (2000.0, 300.0, 2),  # provisional
    }
    for name, (rating, rd, games) in rows.items():
        visitor = people[name]
        visitor.call("PATCH", "/api/players/me", json={"name": name})
        record = RatingRecord(visitor.id, "eight_ball", rating, rd, 0.06, games, 0, clock.now)
        clocked_client.app.state.store.run(lambda repo, r=record: PlayerRows(repo).save_rating(r))
    board = clocked_client.get("/api/leaderboard/eight_ball").json()
    assert [(s["rank"], s["name"], s["rating"], s["games"]) for s in board["ranked"]] == [
        (1, "sure", 1720.0, 60),
        (2, "unsure", 1700.0, 12),
        (3, "low", 1300.0, 30),
    ]
    assert [(s["rank"], s["name"]) for s in board["provisional"]] == [(None, "new")]
    assert clocked_client.get("/api/leaderboard/nine_ball").json()["ranked"] == []
    assert clocked_client.get("/api/leaderboard/practice").status_code == 422


def test_joining_and_leaving_the_queue_is_rate_limited(settings, clock):
    app = app_with(settings.replace(queue_rate="3/minute"), clock=clock.clock)
    with TestClient(app) as client:
        ana = Visitor(client)
        assert play_now(ana)["status"] == "waiting"
        assert ana.call("DELETE", "/api/playnow").status_code == 200
        assert play_now(ana)["status"] == "waiting"
        refused = ana.call("POST", "/api/playnow", json={"game": "eight_ball"})
        assert refused.status_code == 429 and refused.json()["detail"]["code"] == "rate_limited"
        assert Visitor(client).call("DELETE", "/api/playnow").status_code == 200  # per player


def test_new_profiles_are_rate_limited_per_address(settings):
    with TestClient(app_with(settings.replace(player_create_rate="2/minute"))) as client:
        Visitor(client)
        Visitor(client)
        refused = client.get("/api/players/me")
        assert refused.status_code == 429 and "set-cookie" not in refused.headers


def test_play_now_without_a_profile_is_refused(clocked_client):
    response = clocked_client.post("/api/playnow", json={"game": "eight_ball"})
    assert response.status_code == 401
    ana = Visitor(clocked_client)
    bad = ana.call("POST", "/api/playnow", json={"game": "practice"})
    assert bad.status_code == 422


async def _press_play_now(base: str, count: int) -> list[dict]:
    """`count` browsers, each with its own profile, press Play now at once, then read
    where they were sent."""
    async with httpx.AsyncClient(base_url=base, timeout=30) as setup:
        secrets = []
        for _ in range(count):
            made = await setup.get("/api/players/me")
            secrets.append(made.cookies[COOKIE])
            setup.cookies.clear()

    async def one(secret: str) -> dict:
        headers = {"Cookie": f"{COOKIE}={secret}"}
        async with httpx.AsyncClient(base_url=base, timeout=30, headers=headers) as browser:
            pressed = (await browser.post("/api/playnow", json={"game": "eight_ball"})).json()
            while pressed["status"] == "waiting":
                pressed = (await browser.get("/api/playnow", params={"wait": 10})).json()
            me = (await browser.get("/api/players/me")).json()
            return {"id": me["id"], "name": me["name"], **pressed}

    return await asyncio.gather(*(one(s) for s in secrets))


@pytest.mark.slow  # many seconds: not in scripts/test --quick
def test_a_hundred_concurrent_play_now_presses_make_fifty_rooms(settings):
    with live_server(settings) as address:
        seen = asyncio.run(_press_play_now(f"http://{address}", 100))
    assert all(s["status"] == "matched" for s in seen)
    rooms: dict[str, list[dict]] = {}
    for s in seen:
        rooms.setdefault(s["room"]["room_id"], []).append(s)
    assert len(rooms) == 50
    for pair in rooms.values():
        assert sorted(p["room"]["seat"] for p in pair) == [0, 1]
        assert len({p["id"] for p in pair}) == 2
        assert {p["room"]["opponent"] for p in pair} == {p["name"] for p in pair}
    assert len({s["id"] for s in seen}) == 100  # nobody twice


def test_a_ranked_room_brought_back_after_a_restart_is_still_rated(settings, clock):
    with TestClient(app_with(settings, clock=clock.clock)) as client:
        ana, ben = Visitor(client), Visitor(client)
        with_records(client, clock.now, ana, ben)
        a, b = paired(ana, ben)
    with TestClient(app_with(settings, clock=clock.clock)) as client:
        ana.client = ben.client = client
        with connect(client, a["room_id"], a["token"]) as wa:
            receive_until(wa, "state")
            with connect(client, b["room_id"], b["token"]) as wb:
                receive_until(wb, "state")
                both_visit(wa, wb)
                wa.send_json({"type": "concede"})
                over = state_where(wb, lambda s: s["match"]["match_over"])
                assert over["match"]["match_winner"] == 1
        mine = ana.call("GET", "/api/players/me").json()
        theirs = ben.call("GET", "/api/players/me").json()
    games = [COUNTED_GAMES + 1, 0, 0, 0]  # 8-ball, 9-ball, snooker, three-cushion
    assert [r["games"] for r in mine["ratings"]] == games
    assert mine["ratings"][0]["rating"] < 1500 < theirs["ratings"][0]["rating"]
    assert theirs["recent"][0]["won"] and not mine["recent"][0]["won"]
