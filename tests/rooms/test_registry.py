"""The room registry with an injected clock and fixed seeds: which rack each new room gets,
when idle and never-joined rooms expire (at their time to live, not before), the room
limit, bringing saved rooms back; and `SeedSource` itself."""

from __future__ import annotations

import asyncio

import pytest

from server.config import Settings
from server.rooms import ActionError, RoomRegistry, SeedSource
from server.rooms.clock import ManualClock
from server.rooms.connection import Connection
from server.rooms.registry import CLOSE_EXPIRED
from server.rooms.room import Room
from server.rooms.snapshot import room_to_snapshot
from server.store import RoomSnapshot
from tests.support.settings import FAST

# practice_ttl as long as idle_ttl: the tests below of rooms in general use practice rooms.
SETTINGS = FAST.replace(idle_ttl=100.0, waiting_ttl=40.0, practice_ttl=100.0, max_rooms=3)


class Recorder:
    """An observer that notes which rooms were changed, closed, restored or unreadable."""

    def __init__(self) -> None:
        self.calls: list[tuple[str, str]] = []

    def room_changed(self, room: Room) -> None:
        self.calls.append(("changed", room.room_id))

    def room_closed(self, room: Room) -> None:
        self.calls.append(("closed", room.room_id))

    def room_restored(self, room: Room, match_id: int | None) -> None:  # noqa: ARG002 (the observer's signature)
        self.calls.append(("restored", room.room_id))

    def room_unreadable(self, room_id: str) -> None:
        self.calls.append(("unreadable", room_id))


async def _never(_text: str) -> None:
    raise AssertionError("nothing is sent in these tests")


def member(seat: int | None) -> Connection:
    return Connection(_never, seat, None if seat is None else "Ana")


@pytest.fixture
def clock() -> ManualClock:
    return ManualClock(now=1_767_000_000.0, ticks=500.0)


def registry_with(
    clock: ManualClock, *seeds: int, settings: Settings = SETTINGS
) -> tuple[RoomRegistry, Recorder]:
    observer = Recorder()
    registry = RoomRegistry(
        settings,
        observer,
        clock=clock.clock,  # type: ignore[arg-type]
        seeds=SeedSource.fixed(*seeds) if seeds else None,
    )
    return registry, observer


def test_new_rooms_get_the_fixed_seeds_in_turn_and_the_clock_time(clock) -> None:
    registry, observer = registry_with(clock, 7, 8)
    first = registry.create("eight_ball", race_to=3)
    clock.advance(5.0)
    second = registry.create("nine_ball", shot_clock=20.0)
    clock.advance(5.0)
    third = registry.create("practice")
    rooms = [first.room, second.room, third.room]
    assert [r.seed for r in rooms] == [7, 8, 7]  # again from the first
    assert [r.created_at for r in rooms] == [1_767_000_000.0, 1_767_000_005.0, 1_767_000_010.0]
    assert [r.shot_clock for r in rooms] == [SETTINGS.shot_clock, 20.0, 0.0]
    assert first.room.race_to == 3 and len({r.room_id for r in rooms}) == 3
    assert [registry.get(r.room_id) for r in rooms] == [first, second, third]
    assert registry.get("nosuchroom00") is None
    assert registry.listing() == [third, second, first]  # newest first
    assert observer.calls == [("changed", r.room_id) for r in rooms]
    first.room.join("Ana")
    first.room.join("Ben")
    assert first.room.match is not None and first.room.match.seed == 7


def test_a_room_nobody_joined_expires_after_the_waiting_ttl_and_not_before(clock) -> None:
    registry, observer = registry_with(clock, 1)
    live = registry.create("eight_ball")
    clock.advance(SETTINGS.waiting_ttl)
    assert registry.sweep() == [] and not live.closed  # exactly the ttl: not yet
    clock.advance(0.001)
    assert registry.sweep() == [live.room.room_id]
    assert live.closed and registry.get(live.room.room_id) is None
    assert ("closed", live.room.room_id) in observer.calls
    assert registry.sweep() == []


def test_a_room_someone_joined_lives_for_the_idle_ttl_from_its_last_use(clock) -> None:
    registry, _ = registry_with(clock, 1)
    live = registry.create("eight_ball")
    live.room.join("Ana")
    clock.advance(30.0)
    live.on_joined()  # joined 30 s after it opened: the idle clock starts again
    clock.advance(SETTINGS.waiting_ttl + 1)
    assert registry.sweep() == []  # past the waiting ttl, but someone joined
    clock.advance(SETTINGS.idle_ttl - SETTINGS.waiting_ttl - 1)
    assert registry.sweep() == []  # exactly the idle ttl since the join
    clock.advance(0.001)
    assert registry.sweep() == [live.room.room_id]


def test_a_room_with_a_member_never_expires_and_idles_from_when_they_left(clock) -> None:
    registry, _ = registry_with(clock, 1)
    live = registry.create("practice")
    seat, _ = live.room.join("Ana")
    live.on_joined()
    conn = member(seat)
    live.attach(conn)
    clock.advance(10 * SETTINGS.idle_ttl)
    assert registry.sweep() == []
    live.detach(conn)
    clock.advance(SETTINGS.idle_ttl)
    assert registry.sweep() == []
    assert registry.sweep(clock.ticks + 0.001) == [live.room.room_id]  # an explicit time
    assert conn.close_code is None  # it had left; nobody was connected to close


def test_a_practice_table_closes_soon_after_its_player_left(clock) -> None:
    """Nobody else plays it: once its player left it is gone after `practice_ttl`, no
    longer listed, and no longer one of its owner's open tables."""
    settings = SETTINGS.replace(practice_ttl=20.0, max_rooms_per_client=1)
    registry, _ = registry_with(clock, 1, settings=settings)
    live = registry.create("practice", owner="1.2.3.4")
    seat, _ = live.room.join("Ana")
    live.on_joined()
    conn = member(seat)
    live.attach(conn)
    with pytest.raises(ActionError):
        registry.create("practice", owner="1.2.3.4")  # one open table allowed
    clock.advance(SETTINGS.idle_ttl)
    assert registry.sweep() == []  # played as long as she likes
    live.detach(conn)
    clock.advance(20.0)
    assert registry.sweep() == []
    clock.advance(0.001)
    assert registry.sweep() == [live.room.room_id]
    assert registry.listing() == []
    assert registry.create("practice", owner="1.2.3.4").room.practice


def test_the_room_limit_refuses_new_rooms_until_one_expires(clock) -> None:
    registry, _ = registry_with(clock, 1)
    rooms = [registry.create("eight_ball") for _ in range(SETTINGS.max_rooms)]
    with pytest.raises(ActionError) as full:
        registry.create("eight_ball")
    assert full.value.code == "too_many_rooms"
    assert len(registry.rooms) == SETTINGS.max_rooms
    clock.advance(SETTINGS.waiting_ttl / 2)
    rooms[0].touch()  # used: it stays; the others expire
    clock.advance(SETTINGS.waiting_ttl / 2 + 1)
    assert sorted(registry.sweep()) == sorted(r.room.room_id for r in rooms[1:])
    registry.create("eight_ball")
    assert len(registry.rooms) == 2


def test_restore_brings_saved_rooms_back_and_skips_unreadable_or_live_ones(clock) -> None:
    saved = Room("r00m1d_saved", "nine_ball", race_to=2, seed=349, created_at=5.0)
    saved.join("Ana")
    saved.join("Ben")

    async def main() -> None:
        registry, observer = registry_with(clock, 1)
        live = registry.create("eight_ball")
        snapshots = [
            RoomSnapshot("r00m1d_saved", room_to_snapshot(saved, 4)),
            RoomSnapshot("r00m1d_bad00", {"version": 99}),
            RoomSnapshot(
                live.room.room_id, room_to_snapshot(Room(live.room.room_id, "practice"), None)
            ),
        ]
        restored = registry.restore(snapshots)
        try:
            assert [r.room.room_id for r in restored] == ["r00m1d_saved"]
            back = restored[0].room
            assert (back.seed, back.race_to, back.created_at) == (349, 2, 5.0)
            assert back.match is not None and back.match.to_dict() == saved.match.to_dict()
            assert [s.connected for s in back.seats if s is not None] == [False, False]
            assert registry.get(live.room.room_id) is live  # the live room was kept
            assert ("unreadable", "r00m1d_bad00") in observer.calls
            assert ("restored", "r00m1d_saved") in observer.calls
            assert [g.seat for g in restored[0].grace_info()] == [0, 1]  # seats wait
            assert restored[0].ever_joined
        finally:
            registry.close_all(CLOSE_EXPIRED, "test over")

    asyncio.run(main())


def test_fixed_seeds_cycle_and_the_default_is_random() -> None:
    fixed = SeedSource.fixed(3, 1, 4)
    assert [fixed.next() for _ in range(7)] == [3, 1, 4, 3, 1, 4, 3]
    assert [SeedSource.fixed(42).next() for _ in range(2)] == [42, 42]
    secret = SeedSource()
    draws = [secret.next() for _ in range(20)]
    assert all(0 <= d < 2**31 for d in draws)
    assert len(set(draws)) > 1


def test_manual_clock_moves_only_when_told() -> None:
    clock = ManualClock(now=100.0, ticks=0.0)
    assert (clock.clock.wall(), clock.clock.monotonic()) == (100.0, 0.0)
    clock.advance(2.5)
    assert (clock.clock.wall(), clock.clock.monotonic()) == (102.5, 2.5)
