"""A member that does not read never slows the room: it is skipped, then dropped.

TestClient's in-memory socket never blocks, so the spectator's transport is replaced by
one that blocks (or crawls) the way a peer that stopped reading does on a real network.
"""

from __future__ import annotations

import asyncio
import threading

import pytest
from starlette.websockets import WebSocketDisconnect

from tests.support.games import BREAK_MESSAGE
from tests.support.messages import drain_presence, greet, receive_until
from tests.support.rooms import connect, make_client, seated_room

pytestmark = pytest.mark.timeout(60)


def spectator_connection(client, room_id):
    live = client.app.state.registry.get(room_id)
    (conn,) = [c for c in live.members.values() if c.seat is None]
    return live, conn


async def _never_returns(_text: str) -> None:
    await asyncio.Event().wait()


@pytest.mark.slow  # many seconds: not in scripts/test --quick
def test_spectator_that_never_reads_does_not_slow_the_players(settings):
    with make_client(settings, send_timeout=0.5) as client:
        room_id, ta, tb = seated_room(client)
        with (
            connect(client, room_id, ta) as a,
            connect(client, room_id, tb) as b,
            connect(client, room_id) as s,
        ):
            for ws in (a, b, s):
                greet(ws)
            live, stuck = spectator_connection(client, room_id)
            stuck.send_text = _never_returns
            drain_presence(a, 2)  # the later arrivals' presence
            drain_presence(b, 1)
            a.send_json(BREAK_MESSAGE)
            streams = [receive_until(ws, "state") for ws in (a, b)]
            assert streams[0] == streams[1]
            seqs = [m["seq"] for m in streams[0]]
            assert seqs == list(range(seqs[0], seqs[0] + len(seqs)))  # nothing skipped
            assert streams[0][-2]["type"] == "shot_result"
            with pytest.raises(WebSocketDisconnect) as closed:
                for _ in range(100):
                    s.receive_json()
            assert closed.value.code == 1013  # dropped: reconnect and get a fresh state
            assert stuck.id not in live.members
            assert live.room.spectators == 0


def test_slow_spectator_loses_aim_relays_first_never_the_shot(settings):
    """A spectator whose outbox fills while it crawls: the aim relays (droppable) go, the
    shot's `motion`, its result and the table at rest all arrive."""
    with make_client(settings, send_queue=8, send_timeout=30.0, pace=4.0) as client:
        room_id, ta, _ = seated_room(client)
        with connect(client, room_id, ta) as a, connect(client, room_id) as s:
            greet(a)
            greet(s)
            _, slow = spectator_connection(client, room_id)
            fast_text, fast_bytes = slow.send_text, slow.send_bytes
            released = threading.Event()

            async def held_text(text: str) -> None:
                assert await asyncio.to_thread(released.wait, 30)  # until the test says
                await fast_text(text)

            async def held_bytes(data: bytes) -> None:
                assert await asyncio.to_thread(released.wait, 30)
                await fast_bytes(data)

            slow.send_text, slow.send_bytes = held_text, held_bytes
            receive_until(a, "presence")
            for i in range(20):  # more relays than the outbox holds
                a.send_json({"type": "aim", "angle": i / 100, "power": 0.5})
            a.send_json(BREAK_MESSAGE)
            player = receive_until(a, "shot_result")
            released.set()
            watcher = receive_until(s, "shot_result")
    assert slow.dropped > 0
    aims = [m for m in watcher if m["type"] == "aim"]
    assert len(aims) < 20
    (motion,) = [m for m in player if m["type"] == "motion"]
    assert [m for m in watcher if m["type"] == "motion"] == [motion]
    assert watcher[-1] == player[-1]  # the result


def test_stats_count_the_messages_dropped_for_slow_clients(settings):
    """`frames_skipped` in `GET /api/stats`: what members' outboxes dropped because their
    client was behind (here a stuck spectator's aim relays)."""
    with make_client(settings, send_queue=8, send_timeout=30.0) as client:
        room_id, ta, _ = seated_room(client)
        with connect(client, room_id, ta) as a, connect(client, room_id) as s:
            greet(a)
            greet(s)
            assert client.get("/api/stats").json()["stream"]["frames_skipped"] == 0
            _, stuck = spectator_connection(client, room_id)
            stuck.send_text = _never_returns
            receive_until(a, "presence")
            for i in range(20):  # more relays than the outbox holds
                a.send_json({"type": "aim", "angle": i / 100, "power": 0.5})
            a.send_json({"type": "ping", "id": 1})
            receive_until(a, "pong")  # the relays have all been handed out
            skipped = client.get("/api/stats").json()["stream"]["frames_skipped"]
            assert skipped == stuck.dropped > 0
