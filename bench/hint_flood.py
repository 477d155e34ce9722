"""A hint flood against the computer: how long the computer in one room takes to answer a
person's shot, and how late two people's table in another room starts moving, quiet and
while a flood keeps asking for hints (the real planners, `POOL_COMPUTER_WORKERS`, and the
server's own hint limits: `POOL_HINT_QUEUE`, `POOL_HINT_WAIT`, `POOL_HINT_BUDGET`).

    python -m bench.hint_flood [--turns 4] [--addresses 20] [--one-address] [--workers 1]

Each turn: Ana (seat 0) plays a miss, the time from her shot's result to the computer's
`shot_result` is one sample. Meanwhile two players play hard shots in a room of their own
(`bench.crowd.Players`): each `shoot` to that player's `motion` is a sample of their p99.
The flood: `--addresses` practice tables, each broken, then asking for "Show me a shot"
again as soon as it has an answer; one per loopback address (127.0.0.x), or with
`--one-address` all from one (the audit's attack: the per-address allowance of tables),
and its player's socket kept open. The server runs as `python
-m server` (its own defaults, but for a long shot clock and real-time pace), the flood in a
process of its own at idle priority, so that neither slows the players' measurement down.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import statistics
import sys
import tempfile
import time
from pathlib import Path

import httpx
import websockets

from bench.crowd import Players
from bench.load import percentile, start_server, wait_healthy
from server.priority import run_when_idle
from tests.support.games import BREAK_MESSAGE, EIGHT_BALL
from tests.support.live import recv, send, ws_url
from tests.support.ports import free_port


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
    """One flooding table: opened from `source`, broken (so that each hint plans a real
    position, up to seconds, not a break), then asked for hints until the flood stops."""
    transport = httpx.AsyncHTTPTransport(local_address=source)
    async with httpx.AsyncClient(
        base_url=f"http://{address}", transport=transport, timeout=60
    ) as http:
        while not stop.is_set():
            room, seat = await practice_table(http)
            url = ws_url(address, room["room_id"], seat["token"])
            async with websockets.connect(url) as ws:  # the player stays at the table
                await break_rack(ws)
                await ask_hints(http, room["room_id"], seat["token"], stop, counts)


async def break_rack(ws: websockets.ClientConnection) -> None:
    while (await recv(ws))["type"] != "presence":
        pass
    await send(ws, BREAK_MESSAGE)
    while (await recv(ws, timeout=60))["type"] != "shot_result":
        pass


async def ask_hints(
    http: httpx.AsyncClient, room_id: str, token: str, stop: asyncio.Event, counts: dict
) -> None:
    """Ask again as soon as answered, until the flood stops or the table is gone."""
    while not stop.is_set():
        try:
            reply = await http.post(f"/api/rooms/{room_id}/hint", json={"token": token})
        except httpx.TimeoutException:  # gave up after 60 s, as a browser might
            counts["no answer in 60 s"] = counts.get("no answer in 60 s", 0) + 1
            continue
        code = "ok" if reply.status_code == 200 else reply.json()["detail"]["code"]
        counts[code] = counts.get(code, 0) + 1
        if code == "unknown_room":
            return
        await asyncio.sleep(0.05)


async def practice_table(http: httpx.AsyncClient) -> tuple[dict, dict]:
    """A private practice table and its seat."""
    room = (await http.post("/api/rooms", json={"game": "practice", "listed": False})).json()
    seat = (await http.post(f"/api/rooms/{room['room_id']}/join", json={"name": "P"})).json()
    return room, seat


async def players_room(address: str, players: Players, stop: asyncio.Event) -> list:
    """Two people playing in a room of their own (their tasks; stopped by `stop`)."""
    async with httpx.AsyncClient(base_url=f"http://{address}", timeout=60) as http:
        made = await http.post("/api/rooms", json={"game": "eight_ball", "race_to": 15})
        room = made.json()["room_id"]
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
    command = [sys.executable, "-m", "bench.hint_flood", "--flood-only", address]
    command += ["--addresses", str(addresses)] + (["--one-address"] if one_address else [])
    flooder = await asyncio.create_subprocess_exec(
        *command, stdin=asyncio.subprocess.PIPE, stdout=asyncio.subprocess.PIPE
    )
    await asyncio.sleep(3.0)
    players.measuring = True
    flooded = await computer_replies(address, turns)
    stop_players.set()
    out, _ = await flooder.communicate(b"")  # stdin closed: the flood stops and counts
    await asyncio.gather(*playing, return_exceptions=True)
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
    print(f"hint answers during the flood: {out.decode().strip().splitlines()[-1]}")
    print(f"players' shots played {players.played}, sockets closed {players.closed}")


async def flood_only(address: str, addresses: int, one_address: bool) -> dict[str, int]:
    """The flood until this process's stdin closes; the answers it got, by code."""
    stop, counts = asyncio.Event(), {}  # type: ignore[var-annotated]
    sources = (
        ["127.0.0.10"] * addresses
        if one_address
        else [f"127.0.0.{10 + i}" for i in range(addresses)]
    )
    tasks = [asyncio.create_task(flood(address, s, stop, counts)) for s in sources]
    await asyncio.get_running_loop().run_in_executor(None, sys.stdin.read)
    stop.set()
    for task in tasks:  # a hint may be held for minutes: not waited for
        task.cancel()
    await asyncio.gather(*tasks, return_exceptions=True)
    return dict(sorted(counts.items()))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--turns", type=int, default=4)
    parser.add_argument("--addresses", type=int, default=20)
    parser.add_argument("--one-address", action="store_true")
    parser.add_argument("--workers", type=int, default=1)
    parser.add_argument("--flood-only", help=argparse.SUPPRESS)  # the flood's own process
    args = parser.parse_args()
    if args.flood_only:
        run_when_idle()  # a real flood's clients are on other machines
        counts = asyncio.run(flood_only(args.flood_only, args.addresses, args.one_address))
        print(json.dumps(counts))
        return
    asyncio.run(run(args.turns, args.addresses, args.one_address, args.workers))


async def run(turns: int, addresses: int, one_address: bool, workers: int) -> None:
    with tempfile.TemporaryDirectory() as scratch:
        port = free_port()
        extra = {
            "POOL_PACE": "1.0",
            "POOL_COMPUTER_WORKERS": str(workers),
            "POOL_SHOT_CLOCK": "600",
            "POOL_RACK_SEED": str(EIGHT_BALL),  # `BREAK_MESSAGE` is a legal break of it
        }
        proc = start_server(
            port, Path(scratch) / "pool.db", Path(scratch) / "server.log", False, extra
        )
        address = f"127.0.0.1:{port}"
        try:
            await wait_healthy(f"http://{address}", proc)
            await measure(address, turns, addresses, one_address)
        finally:
            proc.terminate()
            proc.wait(30)


if __name__ == "__main__":
    main()
