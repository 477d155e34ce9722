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


async def _never_returns(text: str) -> None:
    await asyncio.Event().wait()


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


def test_slow_spectator_has_stale_frames_skipped_but_keeps_what_matters(settings):
    # The spectator takes nothing until the players have seen the whole shot: its outbox
    # (100) overflows with hundreds of frames (one every 2 ticks), and the events (a few
    # dozen) must all survive.
    with make_client(
        settings, send_queue=100, send_timeout=30.0, pace=2.0, frame_every=2, frames_per_message=1
    ) as client:
        room_id, ta, _ = seated_room(client)
        with connect(client, room_id, ta) as a, connect(client, room_id) as s:
            greet(a)
            greet(s)
            live, slow = spectator_connection(client, room_id)
            fast_send = slow.send_text
            released = threading.Event()

            async def held(text: str) -> None:
                assert await asyncio.to_thread(released.wait, 30)  # until the test says
                await fast_send(text)

            slow.send_text = held
            receive_until(a, "presence")
            a.send_json(BREAK_MESSAGE)
            player = receive_until(a, "state")
            released.set()
            watcher = receive_until(s, "state")
    assert slow.dropped > 0
    player_frames = [m for m in player if m["type"] == "frame"]
    watcher_frames = [m for m in watcher if m["type"] == "frame"]
    assert len(watcher_frames) < len(player_frames)
    assert watcher_frames[-1] == player_frames[-1]  # the final frame is never skipped
    kept = [m for m in player if m["type"] != "frame"]
    assert [m for m in watcher if m["type"] != "frame"] == kept  # events, result, state
    missing = {m["seq"] for m in player} - {m["seq"] for m in watcher}
    assert missing and all(m["type"] == "frame" for m in player if m["seq"] in missing)
