"""Bytes per client on the wire while a break is streamed, per frame rate and compression.

    .venv/bin/python -m bench.stream [--runs 3]

Starts a real uvicorn on loopback, plays a break in a fresh room for each configuration and
counts the bytes a spectator's socket receives (WebSocket framing included) from the strike
to the shot's last `state`, divided by the shot's duration (ticks / 120). Prints the median
of several runs. Playback is sped up (bytes per shot-second do not depend on it).
"""

from __future__ import annotations

import argparse
import asyncio
import json
import statistics
import tempfile
from pathlib import Path

import httpx
import websockets
from websockets.asyncio.client import ClientConnection

from server.app import create_app
from server.config import Settings
from server.embedded import bound_socket, serving
from server.store import Database


class CountingConnection(ClientConnection):
    received = 0

    def data_received(self, data: bytes) -> None:
        self.received += len(data)
        super().data_received(data)


async def one_break(address: str, compression: str | None) -> tuple[float, int, int]:
    """(bytes per shot-second, frames, ticks) seen by a spectator during one break.

    The shooter does not read: `max_queue=None` lets its client buffer everything so its
    close handshake is not stuck behind unread messages.
    """
    async with httpx.AsyncClient(base_url=f"http://{address}") as http:
        room = (await http.post("/api/rooms", json={"game": "eight_ball"})).json()["room_id"]
        token = (await http.post(f"/api/rooms/{room}/join", json={"name": "A"})).json()["token"]
        await http.post(f"/api/rooms/{room}/join", json={"name": "B"})
    url = f"ws://{address}/ws/rooms/{room}"
    async with (
        websockets.connect(f"{url}?token={token}", compression=compression, max_queue=None) as a,
        websockets.connect(url, compression=compression, create_connection=CountingConnection) as s,
    ):
        for _ in range(3):
            await s.recv()
        await a.send(json.dumps({"type": "shoot", "angle": 0.0, "speed": 9.0}))
        start = None
        frames = ticks = 0
        while True:
            message = json.loads(await s.recv())
            if start is None:
                start = s.received - len(json.dumps(message))  # roughly: count from here
            if message["type"] == "frame":
                frames += 1 + len(message.get("ahead", ()))
                ticks = message["tick"]
            if message["type"] == "state" and ticks:
                break
        return (s.received - start) / (ticks / 120), frames, ticks


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    print(
        f"{'frames/s':>8} {'per msg':>7} {'compression':>12} {'bytes/s per client':>19} "
        f"{'frames':>7}"
    )
    for every, per_message in ((2, 1), (4, 1), (6, 1), (6, 2), (6, 4)):
        # pace 2: fast enough, and never so fast that the room skips stale frames
        settings = Settings().replace(
            frame_every=every, frames_per_message=per_message, pace=2.0, ws_deflate=True
        )
        scratch = Path(tempfile.mkdtemp(prefix="bench-stream-")) / "billiards.db"
        app = create_app(settings, store=Database(scratch))  # not the game's database
        with serving(app, settings, bound_socket()) as address:
            for compression in (None, "deflate"):
                runs = [asyncio.run(one_break(address, compression)) for _ in range(args.runs)]
                rate = statistics.median(r[0] for r in runs)
                frames = statistics.median(r[1] for r in runs)
                print(
                    f"{120 // every:>8} {per_message:>7} {compression or 'none':>12} "
                    f"{rate:>19.0f} {frames:>7.0f}"
                )


if __name__ == "__main__":
    main()
