"""A hint flood against the computer: how long the computer in one room takes to answer a
person's shot, and how late two people's table in another room starts moving, quiet and
while a flood keeps asking for hints (the real planners, `POOL_COMPUTER_WORKERS`, and the
server's own hint limits: `POOL_HINT_QUEUE`, `POOL_HINT_WAIT`, `POOL_HINT_BUDGET`).

    python -m bench.hint_flood [--turns 4] [--addresses 20] [--one-address] [--workers 1]

Each turn: Ana (seat 0) plays a miss, the time from her shot's result to the computer's
`shot_result` is one sample. Meanwhile two players play hard shots in a room of their own
(`bench.crowd.Players`): each `shoot` to that player's `motion` is a sample of their p99.
The flood: `--addresses` practice tables, each asking for "Show me a shot" again as soon
as it has an answer; one per loopback address (127.0.0.x), or with `--one-address` all from
one (the audit's attack: the per-address allowance of tables).
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

from bench.crowd import Players
from bench.load import percentile
from server.config import Settings
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


async def players_room(address: str, players: Players, stop: asyncio.Event) -> list:
    """Two people playing in a room of their own (their tasks; stopped by `stop`)."""
    async with httpx.AsyncClient(base_url=f"http://{address}", timeout=60) as http:
        room = (await http.post("/api/rooms", json={"game": "eight_ball"})).json()["room_id"]
        tokens = [
            (await http.post(f"/api/rooms/{room}/join", json={"name": n})).json()["token"]
            for n in ("Ana", "Ben")
        ]
    return [
        asyncio.create_task(players.play(ws_url(address, room, t), i, stop))
        for i, t in enumerate(tokens)
    ]


async def measure(address: str, turns: int, addresses: int, one_address: bool) -> None:
    players, stop_players = Players(), asyncio.Event()
    playing = await players_room(address, players, stop_players)
    players.measuring = True
    quiet = await computer_replies(address, turns)
    quiet_starts, players.starts, players.measuring = players.starts, [], False
    stop, counts = asyncio.Event(), {}  # type: ignore[var-annotated]
    sources = (
        ["127.0.0.10"] * addresses
        if one_address
        else [f"127.0.0.{10 + i}" for i in range(addresses)]
    )
    tasks = [asyncio.create_task(flood(address, s, stop, counts)) for s in sources]
    await asyncio.sleep(3.0)
    players.measuring = True
    flooded = await computer_replies(address, turns)
    stop.set()
    stop_players.set()
    for task in tasks:  # a hint may be held for minutes: not waited for
        task.cancel()
    await asyncio.gather(*tasks, *playing, return_exceptions=True)
    where = "one address" if one_address else f"{addresses} addresses"
    for name, samples, starts in (
        ("quiet", quiet, quiet_starts),
        (f"flood ({where})", flooded, players.starts),
    ):
        print(
            f"{name}: computer's reply median {statistics.median(samples):.2f} s,"
            f" max {max(samples):.2f} s over {len(samples)} turns; players' shoot->motion"
            f" p99 {1000 * percentile(starts, 99):.0f} ms over {len(starts)}"
        )
    print(f"hint answers during the flood: {dict(sorted(counts.items()))}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--turns", type=int, default=4)
    parser.add_argument("--addresses", type=int, default=20)
    parser.add_argument("--one-address", action="store_true")
    parser.add_argument("--workers", type=int, default=1)
    args = parser.parse_args()
    settings = settings_in(
        Path(tempfile.mkdtemp()),
        pace=1.0,
        computer_workers=args.workers,
        shot_clock=600.0,
        hint_budget=Settings().hint_budget,  # the server's own, not the tests' unlimited one
    )
    with live_server(settings) as address:
        asyncio.run(measure(address, args.turns, args.addresses, args.one_address))


if __name__ == "__main__":
    main()
