"""The players' records on both backends (a SQLite file and a private PostgreSQL): profiles,
ratings, ranked rooms rated once in one transaction, and the matches of a player's seats."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from sqlalchemy import update

from server.ladder import RankedRoom, rate_in_store
from server.players import COUNTED_GAMES, KindRating, Rating, rate_match
from server.store import Database, Repository, schema
from server.store.players import PlayerRows, RankedRecord, RatingRecord
from tests.support.postgres import PostgresServer, postgres  # noqa: F401  (the fixture)

NOW = 1_795_700_416.3912654


@pytest.fixture(params=["sqlite", pytest.param("postgresql", marks=pytest.mark.postgres)])
def db(request: pytest.FixtureRequest, tmp_path: Path) -> Iterator[Database]:
    if request.param == "sqlite":
        target: str | Path = tmp_path / "billiards.db"
    else:
        server: PostgresServer = request.getfixturevalue("postgres")
        target = server.create_database()
    database = Database(target)
    yield database
    database.close()


def players(db: Database, *names: str) -> None:
    def add(repo: Repository) -> None:
        for name in names:
            PlayerRows(repo).add_player(name.lower(), name, f"hash-{name}", NOW)

    db.run(add)


def ranked_record(room: RankedRoom) -> RankedRecord:
    return RankedRecord(room.room_id, room.kind, room.players, room.names, NOW)


def test_profiles_round_trip_and_rename(db: Database) -> None:
    players(db, "Ana")
    found = db.run(lambda repo: PlayerRows(repo).player_by_secret("hash-Ana"))
    assert found is not None and (found.id, found.name, found.created_at) == ("ana", "Ana", NOW)
    assert db.run(lambda repo: PlayerRows(repo).player_by_secret("hash-nobody")) is None
    db.run(lambda repo: PlayerRows(repo).rename_player("ana", "<b>Ana</b>"))
    renamed = db.run(lambda repo: PlayerRows(repo).player("ana"))
    assert renamed is not None and renamed.name == "<b>Ana</b>"


def test_ratings_are_upserted_exactly_and_listed_per_kind(db: Database) -> None:
    players(db, "Ana", "Ben")
    exact = RatingRecord("ana", "eight_ball", 1464.0506705393013, 151.5165, 0.0599959, 3, 1, NOW)
    db.run(lambda repo: PlayerRows(repo).save_rating(exact))
    db.run(
        lambda repo: PlayerRows(repo).save_rating(
            RatingRecord("ben", "eight_ball", 1500, 350, 0.06, 0, 0, None)
        )
    )
    assert db.run(lambda repo: PlayerRows(repo).rating("ana", "eight_ball")) == exact
    later = RatingRecord("ana", "eight_ball", 1480.0, 140.0, 0.06, 4, 2, NOW + 1)
    db.run(lambda repo: PlayerRows(repo).save_rating(later))
    assert db.run(lambda repo: PlayerRows(repo).ratings("ana")) == [later]
    listed = db.run(lambda repo: PlayerRows(repo).rated("eight_ball"))
    assert listed == [(later, "Ana")]  # Ben has no game yet
    assert db.run(lambda repo: PlayerRows(repo).rated("nine_ball")) == []


def test_a_ranked_room_is_rated_once_from_the_stored_ratings(db: Database) -> None:
    players(db, "Ana", "Ben")
    ana = RatingRecord("ana", "nine_ball", 1600.0, 80.0, 0.06, 12, 7, NOW - 86_400)
    db.run(lambda repo: PlayerRows(repo).save_rating(ana))
    # Ben has a record (the farm rule: a result moves a rating only against one).
    ben = RatingRecord("ben", "nine_ball", 1500.0, 350.0, 0.06, COUNTED_GAMES, 0, NOW)
    db.run(lambda repo: PlayerRows(repo).save_rating(ben))
    room = RankedRoom("room-1", "nine_ball", ("ana", "ben"), ("Ana", "Ben"))
    db.run(lambda repo: PlayerRows(repo).add_ranked(ranked_record(room)))
    assert [r.room_id for r in db.run(lambda repo: PlayerRows(repo).open_ranked())] == ["room-1"]
    assert db.run(lambda repo: rate_in_store(PlayerRows(repo), room, 9, 1, NOW)) is True
    assert db.run(lambda repo: rate_in_store(PlayerRows(repo), room, 9, 0, NOW)) is False
    stored_a = KindRating("ana", "nine_ball", Rating(1600.0, 80.0, 0.06), 12, 7, NOW - 86_400)
    stored_b = KindRating("ben", "nine_ball", Rating(), COUNTED_GAMES, 0, NOW)
    new_a, new_b = rate_match(stored_a, stored_b, False, NOW)
    got_a = db.run(lambda repo: PlayerRows(repo).rating("ana", "nine_ball"))
    got_b = db.run(lambda repo: PlayerRows(repo).rating("ben", "nine_ball"))
    assert got_a is not None and got_b is not None
    assert (got_a.rating, got_a.rd, got_a.games, got_a.wins) == (
        new_a.rating.rating,
        new_a.rating.rd,
        13,
        7,
    )
    assert (got_b.rating, got_b.games, got_b.wins) == (new_b.rating.rating, COUNTED_GAMES + 1, 1)
    (result,) = db.run(lambda repo: PlayerRows(repo).ranked_of("ben", 10))
    assert (result.match_id, result.winner, result.finished_at) == (9, 1, NOW)
    assert result.before is not None and result.before[0][0] == 1600.0
    assert result.after == [
        [new_a.rating.rating, new_a.rating.rd, new_a.rating.volatility],
        [new_b.rating.rating, new_b.rating.rd, new_b.rating.volatility],
    ]
    assert db.run(lambda repo: PlayerRows(repo).open_ranked()) == []


def test_a_ranked_room_closed_without_a_winner_changes_no_rating(db: Database) -> None:
    players(db, "Ana", "Ben")
    room = RankedRoom("room-2", "eight_ball", ("ana", "ben"), ("Ana", "Ben"))
    db.run(lambda repo: PlayerRows(repo).add_ranked(ranked_record(room)))
    assert db.run(lambda repo: rate_in_store(PlayerRows(repo), room, None, None, NOW)) is True
    assert db.run(lambda repo: PlayerRows(repo).ratings("ana")) == []
    assert db.run(lambda repo: PlayerRows(repo).ranked_of("ana", 10)) == []  # not rated
    assert db.run(lambda repo: PlayerRows(repo).open_ranked()) == []
    assert db.run(lambda repo: rate_in_store(PlayerRows(repo), room, 3, 0, NOW)) is False


def test_a_players_seats_bring_their_matches(db: Database) -> None:
    players(db, "Ana")

    def play(repo: Repository) -> None:
        repo.start_match(1, "room-a", "eight_ball", ["Ana", "Ben"], 1, started_at=NOW)
        repo.finish_match(1, [1, 0], 0, "Ana won.", finished_at=NOW + 60)
        repo.start_match(2, "room-b", "nine_ball", ["Cy", "Ana"], 3, started_at=NOW + 100)
        repo.start_match(3, "room-c", "nine_ball", ["Cy", "Dee"], 3, started_at=NOW + 200)
        rows = PlayerRows(repo)
        rows.add_seat("hash-Ana", "room-a", 0, NOW)
        rows.add_seat("hash-Ana", "room-a", 0, NOW)  # a second join: one seat
        rows.add_seat("hash-nobody", "room-c", 0, NOW)  # no such player: nothing
        rows.add_player_seat("ana", "room-b", 1, NOW + 100)

    db.run(play)
    played = db.run(lambda repo: PlayerRows(repo).matches_of("ana", 10))
    assert [(m.match_id, m.seat, m.status, m.winner, m.shots) for m in played] == [
        (2, 1, "playing", None, 0),
        (1, 0, "finished", 0, 0),
    ]
    assert played[1].players == ["Ana", "Ben"] and played[1].finished_at == NOW + 60
    assert db.run(lambda repo: PlayerRows(repo).matches_of("ana", 1))[0].match_id == 2


def test_a_result_against_a_fresh_profile_moves_only_the_fresh_profile(db: Database) -> None:
    """The farm rule in the store's transaction: Ana (a record) beats Ben (none): Ben is
    rated against Ana, Ana keeps her rating; both games are counted."""
    players(db, "Ana", "Ben")
    ana = RatingRecord("ana", "eight_ball", 1600.0, 80.0, 0.06, 12, 7, NOW)
    db.run(lambda repo: PlayerRows(repo).save_rating(ana))
    room = RankedRoom("room-3", "eight_ball", ("ana", "ben"), ("Ana", "Ben"))
    db.run(lambda repo: PlayerRows(repo).add_ranked(ranked_record(room)))
    assert db.run(lambda repo: rate_in_store(PlayerRows(repo), room, 4, 0, NOW)) is True
    got_a = db.run(lambda repo: PlayerRows(repo).rating("ana", "eight_ball"))
    got_b = db.run(lambda repo: PlayerRows(repo).rating("ben", "eight_ball"))
    assert got_a is not None and got_b is not None
    assert (got_a.rating, got_a.rd, got_a.games, got_a.wins) == (1600.0, 80.0, 13, 8)
    _, expect_b = rate_match(
        KindRating("ana", "eight_ball", Rating(1600.0, 80.0, 0.06), 12, 7, NOW),
        KindRating("ben", "eight_ball"),
        True,
        NOW,
    )
    assert (got_b.rating, got_b.games, got_b.wins) == (expect_b.rating.rating, 1, 0)
    assert got_b.rating < 1500


def test_guests_that_never_played_are_pruned_once_old_enough(db: Database) -> None:
    """Only a guest made before the cutoff with no seat, no rating, no ranked room and not
    kept (waiting for Play now) is deleted; `limit` bounds one statement."""
    players(db, "Old", "Seated", "Rated", "Ranked", "Queued", "Twin", "Account")

    def make_account(repo: Repository) -> None:  # an account never plays to be kept
        with repo.transaction() as conn:
            conn.execute(
                update(schema.players)
                .where(schema.players.c.id == "account")
                .values(name_key="account", account_at=NOW)
            )

    db.run(make_account)
    db.run(lambda repo: PlayerRows(repo).add_player("new", "New", "hash-New", NOW + 10))
    db.run(lambda repo: PlayerRows(repo).add_player_seat("seated", "room-1", 0, NOW))
    rated = RatingRecord("rated", "eight_ball", 1500.0, 350.0, 0.06, 1, 0, NOW)
    db.run(lambda repo: PlayerRows(repo).save_rating(rated))
    room = RankedRoom("room-2", "eight_ball", ("old", "ranked"), ("Old", "Ranked"))
    db.run(lambda repo: PlayerRows(repo).add_ranked(ranked_record(room)))
    cutoff = NOW + 5
    prune = PlayerRows.prune_guests
    assert db.run(lambda repo: prune(PlayerRows(repo), cutoff, {"queued"}, 1)) == 1  # twin
    assert db.run(lambda repo: prune(PlayerRows(repo), cutoff, {"queued"}, 10)) == 0
    left = {"old", "seated", "rated", "ranked", "queued", "twin", "account", "new"}
    kept = {p for p in left if db.run(lambda repo, p=p: PlayerRows(repo).player(p)) is not None}
    assert kept == {"old", "seated", "rated", "ranked", "queued", "account", "new"}
    assert db.run(lambda repo: prune(PlayerRows(repo), cutoff, set(), 10)) == 1  # queued
