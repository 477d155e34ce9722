"""Under attack: what floods do to the players of a real server.

    .venv/bin/python -m bench.crowd [--runs 3] [--seconds 12] [--warmup 5]

Starts `python -m server` on a free loopback port (throw-away database) and measures, for
each flood, the two players of one room playing hard shots: how late each player's table
starts moving (from the shooter's `shoot` to the shot's `motion` arriving at that player;
p50 / p99), how late the shot's result comes after its motion has played
(`shot_result` arrival minus the motion's arrival and duration; p99), the player sockets
closed, the shot results lost, and what the flood got through:
- quiet: the two players alone;
- crowd: 150 spectators chatting as fast as a spectator may (the socket's budget, 2
  messages a second; faster is closed) and 30 reconnecting in a loop (`chat`, `churn`:
  either half alone), each from a loopback address of its own;
- rooms: one client trying to open 5,000 rooms (then: can another client open one?);
- listing: 2,000 rooms open and 8 clients listing them back to back (shot start p99 from
  the server's `/api/stats`).
The players play from the start; their shots count after `--warmup` s, once the flood is
in. Shots are shown at 4x speed (`POOL_PACE`), so a window holds dozens of them. Prints, for
each flood, the players' lateness over the shots of all the runs together (n: how many
arrivals) and the median of the runs for the rest.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import json
import statistics
import sys
import tempfile
import time
from pathlib import Path

import httpx
from websockets.asyncio.client import connect
from websockets.exceptions import ConnectionClosed, InvalidStatus

from bench.load import parse_motion, percentile, start_server, wait_healthy
from server.config import Settings
from server.priority import run_when_idle
from tests.support.ports import free_port

DEFAULTS = Settings()  # the server's default limits (not read from this environment)
# The server shows each shot this many times faster than real time (`POOL_PACE`): more shots
# in a window, so the p99 is over dozens of shots, not a handful; how late a table starts
# moving does not depend on it.
PACE = 4.0
# A chatting spectator sends as fast as the server lets a spectator's socket send without
# closing it (faster is closed 1008 within seconds: then it costs nothing more).
CHAT_EVERY = 1.05 / DEFAULTS.spectator_rate_per_second


class Players:
    """Two players taking turns with hard shots; records how late each player's table
    starts and ends each shot, and the results."""

    def __init__(self) -> None:
        self.shot_sent = 0.0  # when the shooter sent the latest `shoot`
        self.starts: list[float] = []  # `shoot` -> `motion`, at each player
        self.ends: list[float] = []  # `shot_result` after the motion's end, at each player
        self.results = 0
        self.played = 0  # results since the start, measured or not
        self.measuring = False  # set once the flood is in (the warm-up is over)
        self.closed: list[str] = []
        self.chat = 0
        self.presence = 0

    async def play(self, url: str, seat: int, stop: asyncio.Event) -> None:
        motion_end: float | None = None  # when this player's playback of the shot ends
        placed = False
        try:
            async with connect(url, max_size=2**22) as ws:
                await ws.send(json.dumps({"type": "sync"}))
                while not stop.is_set():
                    try:
                        raw = await asyncio.wait_for(ws.recv(), 0.5)
                    except TimeoutError:
                        continue
                    now = time.perf_counter()
                    if isinstance(raw, bytes):  # a shot's `motion`: the whole shot at once
                        _, duration = parse_motion(raw)
                        if self.measuring:
                            self.starts.append(now - self.shot_sent)
                        motion_end = now + duration / PACE
                        continue
                    message = json.loads(raw)
                    kind = message["type"]
                    if kind == "chat":
                        self.chat += self.measuring
                    elif kind == "presence":
                        self.presence += self.measuring
                    elif kind == "shot_result":
                        self.played += 1
                        self.results += self.measuring
                        if motion_end is not None and self.measuring:
                            self.ends.append(now - motion_end)
                        motion_end, placed = None, False
                    elif kind == "state" and message["phase"] == "aiming":
                        await self._act(ws, message["match"], seat, placed)
                        placed = placed or bool(message["match"]["ball_in_hand"])
        except ConnectionClosed as exc:
            self.closed.append(f"{exc.rcvd.code} {exc.rcvd.reason}" if exc.rcvd else "?")

    async def _act(self, ws, match: dict, seat: int, placed: bool) -> None:
        decision = match["decision"]
        if decision is not None:
            if decision["seat"] == seat:
                await ws.send(json.dumps({"type": "decide", "option": decision["options"][0]}))
            return
        if match["turn"] != seat:
            return
        if match["ball_in_hand"] and not placed:
            await ws.send(json.dumps({"type": "place_cue", "x": 0.5, "y": 0.6}))
            return
        if match.get("requires_call"):
            await ws.send(json.dumps({"type": "call", "pocket": 0}))
        self.shot_sent = time.perf_counter()
        angle = (0.7 * self.played + 0.2) % 6.0  # within the protocol's `max_angle`
        await ws.send(json.dumps({"type": "shoot", "angle": angle, "speed": 7.0}))


def fan_address(i: int) -> tuple[str, int]:
    """The `i`th member of a crowd connects from a loopback address of its own (127.0.x.y
    all reach the local host), as the people of a real crowd would; the server's quotas are
    per address."""
    return (f"127.0.{1 + i // 250}.{1 + i % 250}", 0)


async def chatter(url: str, stop: asyncio.Event, counts: dict, i: int) -> None:
    with contextlib.suppress(Exception):
        async with connect(url, local_addr=fan_address(i)) as ws:
            while not stop.is_set():
                await ws.send(json.dumps({"type": "chat", "text": "what a shot"}))
                counts["sent"] += 1
                with contextlib.suppress(TimeoutError):
                    while True:
                        await asyncio.wait_for(ws.recv(), CHAT_EVERY)


async def churner(url: str, stop: asyncio.Event, counts: dict, i: int) -> None:
    while not stop.is_set():
        try:
            async with connect(url, local_addr=fan_address(i)) as ws:
                await ws.recv()
                counts["reconnects"] += 1
        except InvalidStatus:  # past the address's quota of spectator sockets
            counts["refused"] += 1
        except Exception:
            pass


async def room_flood(base: str, stop: asyncio.Event, counts: dict) -> None:
    async with httpx.AsyncClient(base_url=base) as http:
        while not stop.is_set() and counts["tried"] < 5000:
            response = await http.post("/api/rooms", json={"game": "eight_ball"})
            counts["tried"] += 1
            counts["made"] += response.status_code == 201


async def list_flood(base: str, stop: asyncio.Event, counts: dict) -> None:
    async with httpx.AsyncClient(base_url=base, timeout=30) as http:
        while not stop.is_set():
            await http.get("/api/rooms")
            counts["listed"] += 1


async def one_run(flood: str, seconds: float, warmup: float) -> dict:
    with tempfile.TemporaryDirectory() as scratch:
        port = free_port()
        # The listing flood needs 2,000 rooms from this one address: lift its limits there;
        # the others meet the server's own (`start_server` lifts them for `bench.load`).
        extra = (
            {"POOL_MAX_ROOMS_PER_CLIENT": "5000", "POOL_ROOM_CREATE_RATE": "100000/minute"}
            if flood == "listing"
            else {
                "POOL_MAX_ROOMS_PER_CLIENT": str(DEFAULTS.max_rooms_per_client),
                "POOL_ROOM_CREATE_RATE": DEFAULTS.room_create_rate,
                "POOL_JOIN_RATE": DEFAULTS.join_rate,
                "POOL_WATCH_RATE": DEFAULTS.watch_rate,
            }
        )
        extra |= {"POOL_MAX_SPECTATORS": "500", "POOL_SHOT_CLOCK": "0", "POOL_PACE": str(PACE)}
        proc = start_server(
            port,
            Path(scratch) / "pool.db",
            Path(scratch) / "server.log",
            deflate=False,
            extra=extra,
        )
        base = f"http://127.0.0.1:{port}"
        try:
            await wait_healthy(base, proc)
            return await measure(flood, base, port, seconds, warmup)
        finally:
            proc.terminate()
            proc.wait(30)


async def measure(flood: str, base: str, port: int, seconds: float, warmup: float) -> dict:
    async with httpx.AsyncClient(base_url=base, timeout=60) as http:
        if flood == "listing":
            for _ in range(2000):
                await http.post("/api/rooms", json={"game": "eight_ball"})
        room = (await http.post("/api/rooms", json={"game": "eight_ball"})).json()["room_id"]
        tokens = [
            (await http.post(f"/api/rooms/{room}/join", json={"name": n})).json()["token"]
            for n in ("Ana", "Ben")
        ]
    ws_base = f"ws://127.0.0.1:{port}/ws/rooms/{room}"
    stop = asyncio.Event()
    players = Players()
    counts = {"sent": 0, "reconnects": 0, "refused": 0, "tried": 0, "made": 0, "listed": 0}
    tasks = [
        asyncio.create_task(players.play(f"{ws_base}?token={t}", i, stop))
        for i, t in enumerate(tokens)
    ]
    # The flood runs in a process of its own, so its clients do not slow the players'
    # measurement down (server, players and flood share the host's cores),
    # on CPU time nobody else wants (`server.priority`).
    flooder = None
    if flood != "quiet":
        flooder = await asyncio.create_subprocess_exec(
            sys.executable,
            "-m",
            "bench.crowd",
            "--flood-only",
            flood,
            "--base",
            base,
            "--room",
            room,
            "--seconds",
            str(warmup + seconds),
            stdout=asyncio.subprocess.PIPE,
        )
    # The players play from the start, but their shots count only once the flood is in:
    # a crowd connecting at once is a burst of its own (the collector's one pass over the new
    # sockets' objects, tens of ms), not what a crowd that is there does to a game.
    await asyncio.sleep(warmup)
    players.measuring = True
    await asyncio.sleep(seconds)
    async with httpx.AsyncClient(base_url=base, timeout=60) as http:
        stats = (await http.get("/api/stats", params={"window": seconds})).json()
    # Another client (another loopback address) can still open a table.
    elsewhere = httpx.AsyncHTTPTransport(local_address="127.0.0.2")
    async with httpx.AsyncClient(base_url=base, timeout=60, transport=elsewhere) as http:
        other = await http.post("/api/rooms", json={"game": "practice"})
    stop.set()
    await asyncio.gather(*tasks, return_exceptions=True)
    if flooder is not None:
        out, _ = await flooder.communicate()
        counts.update(json.loads(out.decode().strip().splitlines()[-1]))
    return {
        "starts": players.starts,
        "ends": players.ends,
        "start_p99_ms": stats["stream"]["start_p99_ms"] or 0.0,
        "results": players.results / 2,
        "closed": len(players.closed),
        "chat_per_s": players.chat / 2 / seconds,
        "presence_per_s": players.presence / 2 / seconds,
        "flood_per_s": (
            counts["sent"]
            + counts["reconnects"]
            + counts["refused"]
            + counts["tried"]
            + counts["listed"]
        )
        / (warmup + seconds),
        "reconnects_per_s": counts["reconnects"] / (warmup + seconds),
        "rooms_made": counts["made"],
        "other_client": other.status_code,
    }


async def flood_only(flood: str, base: str, room: str, seconds: float) -> dict:
    stop = asyncio.Event()
    counts = {"sent": 0, "reconnects": 0, "refused": 0, "tried": 0, "made": 0, "listed": 0}
    ws_base = base.replace("http://", "ws://") + f"/ws/rooms/{room}"
    if flood in ("crowd", "chat", "churn"):
        chatters = 0 if flood == "churn" else 150
        churners = 0 if flood == "chat" else 30
        tasks = [asyncio.create_task(chatter(ws_base, stop, counts, i)) for i in range(chatters)]
        tasks += [
            asyncio.create_task(churner(ws_base, stop, counts, chatters + i))
            for i in range(churners)
        ]
    elif flood == "rooms":
        tasks = [asyncio.create_task(room_flood(base, stop, counts))]
    else:
        tasks = [asyncio.create_task(list_flood(base, stop, counts)) for _ in range(8)]
    await asyncio.sleep(seconds)
    stop.set()
    await asyncio.gather(*tasks, return_exceptions=True)
    return counts


def main() -> None:
    parser = argparse.ArgumentParser(
        prog="python -m bench.crowd",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--seconds", type=float, default=12.0)
    parser.add_argument(
        "--warmup", type=float, default=5.0, help="s of play before measuring (the flood comes in)"
    )
    parser.add_argument("--floods", default="quiet,crowd,rooms,listing")
    parser.add_argument("--flood-only", help=argparse.SUPPRESS)
    parser.add_argument("--base", help=argparse.SUPPRESS)
    parser.add_argument("--room", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.flood_only:
        run_when_idle()  # a real crowd's clients are on other machines
        print(
            json.dumps(asyncio.run(flood_only(args.flood_only, args.base, args.room, args.seconds)))
        )
        return
    print(
        f"{'flood':>8} {'flood/s':>8} {'joins/s':>8} {'n':>4} {'late p50':>9} {'late p99':>9} "
        f"{'end p99':>8} {'start p99':>10} "
        f"{'results':>8} {'closed':>7} {'chat/s':>7} {'pres/s':>7} {'rooms':>6} {'other':>6}"
    )
    for flood in args.floods.split(","):
        runs = [asyncio.run(one_run(flood, args.seconds, args.warmup)) for _ in range(args.runs)]

        def median(key: str, runs: list[dict] = runs) -> float:
            return statistics.median(r[key] for r in runs)

        # Lateness over every shot of every run together: a run has a few dozen shots.
        starts = [late for r in runs for late in r["starts"]]
        ends = [late for r in runs for late in r["ends"]]
        print(
            f"{flood:>8} {median('flood_per_s'):8.0f} {median('reconnects_per_s'):8.0f} "
            f"{len(starts):4d} {1000 * percentile(starts, 50):9.1f} "
            f"{1000 * percentile(starts, 99):9.1f} {1000 * percentile(ends, 99):8.1f} "
            f"{median('start_p99_ms'):10.1f} "
            f"{median('results'):8.1f} {median('closed'):7.0f} {median('chat_per_s'):7.1f} "
            f"{median('presence_per_s'):7.1f} {median('rooms_made'):6.0f} "
            f"{median('other_client'):6.0f}",
            flush=True,
        )


if __name__ == "__main__":
    main()
