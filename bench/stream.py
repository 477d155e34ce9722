"""Bytes per client on the wire for a shot: a break, and ordinary shots, with and without
permessage-deflate.

    .venv/bin/python -m bench.stream [--runs 3] [--shots 20]

Starts a real uvicorn on loopback. For each run, plays a break in a fresh 8-ball room and
then `--shots` ordinary shots in a practice room (from the table each leaves, random
direction, speed 1..6 m/s and spin from a seeded generator), and counts what a spectator's
socket receives (WebSocket framing included) from the shot's `shoot` to the `state` after
it: bytes and messages, divided by the shot's duration (its `motion` message says). Prints
the median over the runs. Playback is sped up (`pace` 4): a shot's bytes do not depend on
it, and the per-second figure is per second of shot.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import random
import statistics
import tempfile
from pathlib import Path

import httpx
import websockets
from websockets.asyncio.client import ClientConnection

from server.app import create_app
from server.config import Settings
from server.protocol.motion import decode_motion
from server.store import Database
from tests.support.embedded import bound_socket, serving


class CountingConnection(ClientConnection):
    received = 0

    def data_received(self, data: bytes) -> None:
        self.received += len(data)
        super().data_received(data)


async def shot_cost(
    shooter: ClientConnection, watcher: CountingConnection, shoot: dict
) -> tuple[int, int, float, dict]:
    """(bytes, messages, seconds of shot, state after) a spectator gets for one shot."""
    start = watcher.received
    await shooter.send(json.dumps(shoot))
    messages = 0
    duration = 0.0
    while True:
        raw = await watcher.recv()
        messages += 1
        if isinstance(raw, bytes):
            duration = decode_motion(raw)["duration"]
            continue
        message = json.loads(raw)
        if message["type"] == "state" and duration and message["phase"] != "rolling":
            return watcher.received - start, messages, duration, message


async def reader(socket: ClientConnection) -> None:
    """The shooter reads everything too (a socket nobody reads stalls its room's sends)."""
    try:
        async for _ in socket:
            pass
    except websockets.ConnectionClosed:
        pass


async def room(http: httpx.AsyncClient, game: str, seats: int) -> tuple[str, str]:
    room_id = (await http.post("/api/rooms", json={"game": game})).json()["room_id"]
    tokens = [
        (await http.post(f"/api/rooms/{room_id}/join", json={"name": f"P{i}"})).json()["token"]
        for i in range(seats)
    ]
    return room_id, tokens[0]


async def one_run(address: str, compression: str | None, shots: int, seed: int) -> dict:
    rng = random.Random(seed)
    out: dict[str, list] = {"break": [], "shots": []}
    async with httpx.AsyncClient(base_url=f"http://{address}") as http:
        for kind in ("break", "shots"):
            room_id, token = await room(
                http, "eight_ball" if kind == "break" else "practice", 2 if kind == "break" else 1
            )
            url = f"ws://{address}/ws/rooms/{room_id}"
            async with (
                websockets.connect(f"{url}?token={token}", compression=compression) as player,
                websockets.connect(
                    url, compression=compression, create_connection=CountingConnection
                ) as watcher,
            ):
                drain = asyncio.create_task(reader(player))
                state = {}
                while state.get("type") != "state":  # welcome, state (presence may follow)
                    raw = await watcher.recv()
                    state = json.loads(raw) if isinstance(raw, str) else {}
                shot = {"type": "shoot", "angle": 0.0, "speed": 9.0}
                count = 1 if kind == "break" else shots + 1
                for i in range(count):
                    if state["match"].get("ball_in_hand"):
                        await player.send(json.dumps({"type": "place_cue", "x": 0.6, "y": 0.6}))
                        while True:  # the watcher's state after the placement
                            raw = await watcher.recv()
                            if isinstance(raw, str) and json.loads(raw)["type"] == "state":
                                state = json.loads(raw)
                                break
                    cost = await shot_cost(player, watcher, shot)
                    state = cost[3]
                    if kind == "break" or i > 0:  # the practice room's break is not counted
                        out[kind].append(cost[:3])
                    shot = {
                        "type": "shoot",
                        "angle": rng.uniform(-3.14, 3.14),
                        "speed": rng.uniform(1.0, 6.0),
                        "tip": [rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3)],
                    }
                drain.cancel()
    return {
        kind: (
            sum(c[0] for c in costs) / sum(c[2] for c in costs),
            sum(c[1] for c in costs) / len(costs),
            sum(c[0] for c in costs) / len(costs),
        )
        for kind, costs in out.items()
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--shots", type=int, default=20)
    args = parser.parse_args()
    settings = Settings().replace(pace=4.0, ws_deflate=True)
    scratch = Path(tempfile.mkdtemp(prefix="bench-stream-")) / "billiards.db"
    app = create_app(settings, store=Database(scratch))  # not the game's database
    print(
        f"{'shots':>15} {'compression':>12} {'B/s per client':>15} {'msgs/shot':>10} {'B/shot':>8}"
    )
    with serving(app, settings, bound_socket()) as address:
        for compression in (None, "deflate"):
            runs = [
                asyncio.run(one_run(address, compression, args.shots, seed))
                for seed in range(args.runs)
            ]
            for kind, name in (("break", "break"), ("shots", "ordinary shots")):
                rate = statistics.median(r[kind][0] for r in runs)
                messages = statistics.median(r[kind][1] for r in runs)
                size = statistics.median(r[kind][2] for r in runs)
                print(
                    f"{name:>15} {compression or 'none':>12} {rate:>15.0f} {messages:>10.1f} "
                    f"{size:>8.0f}"
                )


if __name__ == "__main__":
    main()
