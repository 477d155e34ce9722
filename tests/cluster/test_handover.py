"""Handing rooms over: a process told to stop (SIGTERM) hands its rooms to the others at
once, long before its leases would expire; a process paused past its lease (SIGSTOP, as a
long GC pause or a frozen VM would) wakes up, tries to record the shot it was playing, is
refused by the store (a newer owner claimed the room) and stops playing the room.

Both play the 9-ball rack of `games.NINE_BALL` (the break scratches; Ben puts the cue ball
down and his shot pockets a ball on a foul)."""

from __future__ import annotations

import asyncio
import signal
import time

import pytest

from tests.support.games import NINE_BALL, NINE_BALL_FOUL, NINE_BALL_FOUL_BALL, shoot_message

from .servers import ServerSet
from .sockets import connect, recv, send, until
from .takeover import all_closed, break_and_place, moved, seated

pytestmark = [pytest.mark.timeout(360), pytest.mark.redis, pytest.mark.postgres, pytest.mark.slow]


def test_sigterm_hands_the_rooms_over_at_once(servers) -> None:
    # leases of 30 s: a room waiting for its lease to expire would wait that long
    group: ServerSet = servers(3, rack_seed=NINE_BALL, lease_ttl=30.0)
    room, url, ana, ben = seated(group.all[0])
    owner = group.by_url(url)
    loop = asyncio.new_event_loop()
    try:
        a, b, placed = loop.run_until_complete(break_and_place(url, ana, ben))
        started = time.monotonic()
        owner.terminate()  # (uvicorn exits by the signal again once shut down)
        loop.run_until_complete(all_closed((a, b)))
        detail, _ = moved(group.others(owner)[0], room, url, within=10.0)
        took = time.monotonic() - started
        assert took < 10.0  # a third of the lease: handed over, not expired
        assert group.by_url(detail["ws_url"]) in group.others(owner)
        assert "drained 1 rooms" in owner.output()
        assert "Application shutdown complete" in owner.output()

        async def play_on() -> None:
            b2, welcome, state = await connect(detail["ws_url"], ben)
            assert welcome["seat"] == 1 and state["phase"] == "aiming"
            assert state["match"] == placed["match"]  # Ben's turn, his cue ball placed
            assert state["balls"] == placed["balls"]
            await send(b2, shoot_message(NINE_BALL_FOUL))
            result = (await until(b2, "shot_result"))[-1]
            assert (result["shot"], result["outcome"]["pocketed"]) == (2, [NINE_BALL_FOUL_BALL])
            await b2.close()

        loop.run_until_complete(play_on())
    finally:
        loop.close()


def test_a_paused_owner_is_refused_when_it_wakes(servers) -> None:
    group: ServerSet = servers(2, rack_seed=NINE_BALL, pace=1.0, lease_ttl=2.0)
    room, url, ana, ben = seated(group.all[0])
    owner = group.by_url(url)
    other = group.others(owner)[0]
    loop = asyncio.new_event_loop()
    try:
        a, b, _ = loop.run_until_complete(break_and_place(url, ana, ben))
        loop.run_until_complete(send(b, shoot_message(NINE_BALL_FOUL)))
        loop.run_until_complete(recv(b))  # the shot is under way ...
        time.sleep(0.3)  # ... and stored (paused inside a write, it would hold SQLite's lock)
        owner.pause()
        try:
            detail, _ = moved(other, room, url, within=15.0)  # taken over meanwhile
            time.sleep(6.0)  # long enough for the shot the paused owner plays to end
        finally:
            owner.resume()
        # awake, it finishes the shot and writes it with its old epoch: refused. Its
        # heartbeat finds the lease gone meanwhile; the store's thread logs the refusal,
        # often after the heartbeat has dropped the room.
        owner.wait_for_output(
            f"record shot refused: room {room}: epoch 1 is stale, 2 owns it",
            f"room {room} is owned elsewhere now; dropped here",
            within=15.0,
        )
        loop.run_until_complete(all_closed((a, b)))  # it closed the room's sockets
        with owner.http() as client:  # and now sends its clients to the new owner
            assert client.get(f"/api/rooms/{room}").json()["ws_url"] == detail["ws_url"]

        async def on_the_new_owner() -> None:
            b2, _, state = await connect(detail["ws_url"], ben)
            if state["phase"] == "rolling":
                state = (await until(b2, "state"))[-1]
            assert state["phase"] == "aiming" and state["match"]["turn"] == 0
            await b2.close()

        loop.run_until_complete(on_the_new_owner())
        with other.http() as client:  # the shot is in the history once, the new owner's
            match = client.get("/api/matches").json()["matches"][0]
            shots = client.get(f"/api/matches/{match['id']}").json()["shots"]
        assert [(s["shot_id"], s["seat"]) for s in shots] == [(1, 0), (2, 1)]
    finally:
        loop.close()


def test_sigusr1_prints_the_stacks_and_the_process_plays_on(servers) -> None:
    # what `Server.terminate` collects from a process that does not stop
    group: ServerSet = servers(1, store="sqlite")
    server = group.all[0]
    server.proc.send_signal(signal.SIGUSR1)
    # every thread's stack, the event loop's among them (in uvicorn's `Server.run`)
    server.wait_for_output("(most recent call first):", "uvicorn/server.py", within=10.0)
    with server.http() as client:
        assert client.get("/health").status_code == 200
    assert server.terminate() in (0, -signal.SIGTERM)
