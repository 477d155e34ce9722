"""`FanOut`: a room's messages reach its players at once and its spectators a few per turn of
the loop, in order; while a shot is simulated (`hold`) the spectators' copies wait."""

from __future__ import annotations

import asyncio

from server.rooms.connection import Connection
from server.rooms.fanout import PER_TURN, FanOut


async def _never(_: str) -> None:  # nothing is sent: the outboxes are inspected
    raise AssertionError("not sent in these tests")


def queued(conn: Connection) -> list[str | bytes]:
    return [message for message, _ in conn._queue]


async def turns(n: int) -> None:
    for _ in range(n):
        await asyncio.sleep(0)


def test_players_first_then_spectators_a_few_per_turn_in_order():
    async def scenario() -> None:
        fanout = FanOut()
        player = Connection(_never, 0, "Ana")
        crowd = [Connection(_never, None, None) for _ in range(3 * PER_TURN)]
        fanout.send([*crowd, player], "state 1")
        fanout.send([*crowd, player], "state 2")
        assert queued(player) == ["state 1", "state 2"]
        assert all(queued(c) == [] for c in crowd)
        await turns(1)
        assert sum(len(queued(c)) for c in crowd) == PER_TURN
        await turns(10)
        assert all(queued(c) == ["state 1", "state 2"] for c in crowd)

    asyncio.run(scenario())


def test_held_spectator_copies_wait_for_release_and_keep_their_order():
    async def scenario() -> None:
        fanout = FanOut()
        player = Connection(_never, 1, "Ben")
        fan = Connection(_never, None, None)
        fanout.send([fan, player], "state")
        fanout.hold()  # a shot is being simulated
        fanout.send([fan, player], "motion")
        fanout.send_one(fan, "reply")
        await turns(5)
        assert queued(player) == ["state", "motion"]
        assert queued(fan) == [] and fanout.pending == 3
        fanout.release()
        await turns(2)
        assert queued(fan) == ["state", "motion", "reply"] and fanout.pending == 0

    asyncio.run(scenario())
