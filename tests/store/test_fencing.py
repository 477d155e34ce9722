"""Room ownership cannot split: every room-scoped write may carry the owner's fencing
epoch, and once a higher epoch is stored for the room (another process took it over), a
write with the old one is refused and changes nothing. Shots replayed after a failover are
recorded once. Two `Database`s on one store stand for two server processes."""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

from server.store import Database, Repository, StaleOwner
from server.store.schema import room_owners

SHOT = {"angle": 0.25, "speed": 6.0, "tip": [0.0, 0.0]}
TABLE = [2.54, 1.27, 0.028575, 0.114, 0.127]


def shot(repo: Repository, room_shot: int, epoch: int | None, **extra: object) -> int:
    return repo.record_shot(
        1, room_shot, 1, 0, SHOT, TABLE, {"ids": []}, {"n": room_shot}, epoch=epoch, **extra
    )


@pytest.fixture
def two(target: str | Path) -> Iterator[tuple[Database, Database]]:
    """The old owner's store and the new owner's, on the same database."""
    old, new = Database(target), Database(target)
    yield old, new
    old.close()
    new.close()


def everything(db: Database) -> tuple:
    """All a room's records, to show a refused write changed nothing."""

    def read(repo: Repository) -> tuple:
        return (
            repo.recent_matches(10),
            repo.games(1),
            repo.shots(1),
            [(r.room_id, r.data) for r in repo.rooms()],
            repo.room_epoch("room"),
        )

    return db.run(read)


def test_claims_only_go_forward(db: Database) -> None:
    assert db.run(lambda r: r.room_epoch("room")) is None
    db.run(lambda r: r.claim_room("room", 3, owner="http://a:8001"))
    db.run(lambda r: r.claim_room("room", 3, owner="http://a:8001"))  # a repeat is fine
    db.run(lambda r: r.claim_room("room", 5, owner="http://b:8001"))
    with pytest.raises(StaleOwner) as refused:
        db.run(lambda r: r.claim_room("room", 4, owner="http://a:8001"))
    assert (refused.value.room_id, refused.value.epoch, refused.value.stored) == ("room", 4, 5)
    assert db.run(lambda r: r.room_epoch("room")) == 5
    assert db.run(lambda r: r.room_epoch("other")) is None  # rooms are fenced apart


def test_two_owners_never_share_an_epoch(db: Database) -> None:
    """Should two processes get the same epoch (Redis lost its counter mid-takeover), the
    second claim is refused; a write that claimed the room first names no owner."""
    db.run(lambda r: r.save_room("room", "{}", epoch=4))  # claims 4, owner unknown
    db.run(lambda r: r.claim_room("room", 4, owner="http://a:8001"))
    db.run(lambda r: r.claim_room("room", 4, owner="http://a:8001"))
    with pytest.raises(StaleOwner) as refused:
        db.run(lambda r: r.claim_room("room", 4, owner="http://b:8001"))
    assert refused.value.stored == 4
    db.run(lambda r: r.claim_room("room", 5, owner="http://b:8001"))
    assert db.run(lambda r: r.room_epoch("room")) == 5


WRITES: dict[str, Callable[[Repository, int], object]] = {
    "save_room": lambda r, e: r.save_room("room", '{"v":"stale"}', epoch=e),
    "delete_room": lambda r, e: r.delete_room("room", epoch=e),
    "start_match": lambda r, e: r.start_match(2, "room", "eight_ball", ["A", "B"], 1, epoch=e),
    "record_shot": lambda r, e: shot(r, 9, e),
    "record_game": lambda r, e: r.record_game(1, 2, 1, "stale", "shot", [1, 1], epoch=e),
    "update_score": lambda r, e: r.update_score(1, [5, 5], epoch=e),
    "finish_match": lambda r, e: r.finish_match(1, [1, 0], 0, "stale", epoch=e),
}


@pytest.mark.parametrize("write", sorted(WRITES))
def test_a_stale_owners_write_is_refused_and_changes_nothing(
    two: tuple[Database, Database], write: str
) -> None:
    old, new = two

    def play(repo: Repository) -> None:  # the old owner, epoch 1, plays a shot
        repo.claim_room("room", 1, owner="old")
        repo.start_match(1, "room", "eight_ball", ["A", "B"], 3, started_at=10.0, epoch=1)
        shot(repo, 1, 1, played_at=11.0)
        repo.record_game(1, 1, 0, "A won.", "shot", [1, 0], finished_at=12.0, epoch=1)
        repo.save_room("room", '{"v":1}', epoch=1)

    old.run(play)
    new.run(lambda r: r.claim_room("room", 2, owner="new"))  # the lease passed on
    before = everything(new)
    with pytest.raises(StaleOwner):
        old.run(lambda r: WRITES[write](r, 1))
    assert everything(new) == before
    new.run(lambda r: WRITES[write](r, 2))  # the owner's own write goes through
    assert everything(new) != before


def test_the_owner_row_is_locked_until_the_claim_commits(two: tuple[Database, Database]) -> None:
    """A write checked while the new owner's claim is in flight waits for it, and then is
    refused: the check sees the claim, not the row as it was before."""
    old, new = two
    old.run(lambda r: r.claim_room("room", 1))
    claiming, release = threading.Event(), threading.Event()

    def slow_claim(repo: Repository) -> None:
        with repo.transaction():
            repo.claim_room("room", 2)
            claiming.set()
            assert release.wait(30)

    claimed = new.submit(slow_claim)
    assert claiming.wait(30)
    stale = old.submit(lambda r: r.save_room("room", "{}", epoch=1), retry_for=30)
    with pytest.raises(TimeoutError):
        stale.result(timeout=0.5)  # held up by the claim's lock
    release.set()
    claimed.result(timeout=30)
    with pytest.raises(StaleOwner):
        stale.result(timeout=30)
    assert new.run(lambda r: r.rooms()) == []


def test_a_write_with_an_epoch_claims_a_room_never_claimed(db: Database) -> None:
    db.run(lambda r: r.save_room("room", "{}", epoch=7))
    assert db.run(lambda r: r.room_epoch("room")) == 7
    with pytest.raises(StaleOwner):
        db.run(lambda r: r.save_room("room", '{"v":2}', epoch=6))


def test_a_closed_room_stays_fenced(db: Database) -> None:
    """Deleting a room keeps its owner row: a stale owner cannot bring it back."""
    db.run(lambda r: r.claim_room("room", 1))
    db.run(lambda r: r.save_room("room", "{}", epoch=1))
    db.run(lambda r: r.claim_room("room", 2))
    db.run(lambda r: r.delete_room("room", epoch=2))
    with pytest.raises(StaleOwner):
        db.run(lambda r: r.save_room("room", '{"back":true}', epoch=1))
    assert db.run(lambda r: r.rooms()) == []


def test_a_shot_replayed_after_a_failover_is_recorded_once(
    two: tuple[Database, Database],
) -> None:
    old, new = two
    old.run(lambda r: r.claim_room("room", 1))
    old.run(lambda r: r.start_match(1, "room", "nine_ball", ["A", "B"], 1, epoch=1))
    assert [old.run(lambda r, n=n: shot(r, n, 1, motion="m")) for n in (1, 2)] == [1, 2]
    # the old owner died mid-shot 3 after storing it; the new owner plays it again
    assert old.run(lambda r: shot(r, 3, 1, played_at=30.0)) == 3
    new.run(lambda r: r.claim_room("room", 2))
    assert new.run(lambda r: shot(r, 3, 2, played_at=31.0)) == 3  # the stored one's number
    assert new.run(lambda r: shot(r, 4, 2)) == 4
    stored = new.run(lambda r: r.shots(1))
    assert [(s.n, s.room_shot) for s in stored] == [(1, 1), (2, 2), (3, 3), (4, 4)]
    assert stored[2].played_at == 30.0  # the first recording stays


def test_match_ids_reserved_by_two_processes_never_collide(
    two: tuple[Database, Database],
) -> None:
    first, second = two
    first.run(lambda r: r.start_match(41, "r", "practice", ["A"], 1))
    blocks = [first.run(lambda r: r.reserve_match_ids(10))]
    blocks.append(second.run(lambda r: r.reserve_match_ids(10)))
    blocks.append(first.run(lambda r: r.reserve_match_ids(1)))
    assert blocks == [range(42, 52), range(52, 62), range(62, 63)]
    with pytest.raises(ValueError):
        first.run(lambda r: r.reserve_match_ids(0))


def test_owners_of_rooms_long_gone_are_pruned(db: Database) -> None:
    for room in ("gone-old", "live-old", "gone-new"):
        db.run(lambda r, room=room: r.claim_room(room, 1))
    db.run(lambda r: r.save_room("live-old", "{}", epoch=1))

    # backdate two claims to 1000 s ago; the third stays new
    def backdate(repo: Repository) -> None:
        for room in ("gone-old", "live-old"):
            repo.run_in_transaction(
                room_owners.update().where(room_owners.c.room_id == room).values(claimed_at=1.0)
            )

    db.run(backdate)
    assert db.run(lambda r: r.prune_room_owners(before=100.0)) == 1
    epochs = {
        room: db.run(lambda r, room=room: r.room_epoch(room))
        for room in ("gone-old", "live-old", "gone-new")
    }
    assert epochs == {"gone-old": None, "live-old": 1, "gone-new": 1}
