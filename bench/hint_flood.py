"""A hint flood against the computer: how long the computer in one room takes to answer a
person's shot, quiet and while other addresses keep asking for hints (the real planners,
`POOL_COMPUTER_WORKERS`).

    python -m bench.hint_flood [--turns 4] [--addresses 20] [--workers 1]

Each turn: Ana (seat 0) plays a miss, the time from her shot's result to the computer's
`shot_result` is one sample. The flood: one practice table per loopback address
(127.0.0.x), each asking for "Show me a shot" again as soon as it has an answer.
"""

from __future__ import annotations

import argparse
import asyncio
import statistics
import tempfile
import time
from pathlib import Path

import httpx
import websockets

from tests.support.games import BREAK_MESSAGE
from tests.support.live import live_server, recv, send, ws_url
from tests.support.settings import settings_in


async def computer_replies(address: str, turns: int) -> list[float]:
    """Seconds from Ana's shot result to the computer's, `turns` times."""
    async with httpx.AsyncClient(base_url=f"http://{address}", timeout=60) as http:
        room = await http.post(
            "/api/rooms", json={"game": "eight_ball", "opponent": "club", "listed": False}
        )
        room_id = room.json()["room_id"]
        ana = (await http.post(f"/api/rooms/{room_id}/join", json={"name": "Ana"})).json()
    samples: list[float] = []
    async with websockets.connect(ws_url(address, room_id, ana["token"])) as ws:
        while (await recv(ws))["type"] != "presence":
            pass
        await send(ws, BREAK_MESSAGE)
        ours = None
        while len(samples) < turns:
            message = await recv(ws, timeout=120)
            if message["type"] == "shot_result":
                if message["outcome"]["shooter"] == 0:
                    ours = time.monotonic()
                elif ours is not None:
                    samples.append(time.monotonic() - ours)
                    ours = None
            elif message["type"] == "state" and message["phase"] == "aiming":
                match = message["match"]
                if match and match["turn"] == 0 and match["decision"] is None:
                    if match["ball_in_hand"]:
                        await send(ws, {"type": "place_cue", "x": 0.5, "y": 0.6})
                    await send(ws, {"type": "shoot", "angle": 2.0, "speed": 3.0})
    return samples


async def flood(address: str, source: str, stop: asyncio.Event, counts: dict[str, int]) -> None:
    transport = httpx.AsyncHTTPTransport(local_address=source)
    async with httpx.AsyncClient(
        base_url=f"http://{address}", transport=transport, timeout=60
    ) as http:
        room = (await http.post("/api/rooms", json={"game": "practice", "listed": False})).json()
        seat = (await http.post(f"/api/rooms/{room['room_id']}/join", json={"name": "P"})).json()
        while not stop.is_set():
            try:
                reply = await http.post(
                    f"/api/rooms/{room['room_id']}/hint", json={"token": seat["token"]}
                )
            except httpx.TimeoutException:  # gave up after 60 s, as a browser might
                counts["no answer in 60 s"] = counts.get("no answer in 60 s", 0) + 1
                continue
            code = "ok" if reply.status_code == 200 else reply.json()["detail"]["code"]
            counts[code] = counts.get(code, 0) + 1
            await asyncio.sleep(0.05)


async def measure(address: str, turns: int, addresses: int) -> None:
    quiet = await computer_replies(address, turns)
    stop, counts = asyncio.Event(), {}  # type: ignore[var-annotated]
    sources = [f"127.0.0.{10 + i}" for i in range(addresses)]
    tasks = [asyncio.create_task(flood(address, s, stop, counts)) for s in sources]
    await asyncio.sleep(3.0)
    flooded = await computer_replies(address, turns)
    stop.set()
    for task in tasks:  # a hint may be held for minutes: not waited for
        task.cancel()
    await asyncio.gather(*tasks, return_exceptions=True)
    for name, samples in (("quiet", quiet), ("flood", flooded)):
        print(
            f"{name}: computer's reply median {statistics.median(samples):.2f} s,"
            f" max {max(samples):.2f} s over {len(samples)} turns"
        )
    print(f"hint answers during the flood: {dict(sorted(counts.items()))}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--turns", type=int, default=4)
    parser.add_argument("--addresses", type=int, default=20)
    parser.add_argument("--workers", type=int, default=1)
    args = parser.parse_args()
    settings = settings_in(
        Path(tempfile.mkdtemp()),
        pace=1.0,
        computer_workers=args.workers,
        shot_clock=600.0,
    )
    with live_server(settings) as address:
        asyncio.run(measure(address, args.turns, args.addresses))


if __name__ == "__main__":
    main()
