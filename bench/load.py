"""Load benchmark: N rooms of two bot players and a spectator against one real server.

    .venv/bin/python -m bench.load --rooms N --seconds S [--runs R] [--compression deflate]

Starts `python -m server` on a free loopback port (a subprocess of this one, stopped with
SIGTERM at the end, on a throw-away database), creates N 8-ball rooms, seats two bots in
each and adds a spectator (all `websockets` clients in this process). The bots play: place
the cue ball, call the 8, answer decisions and shoot hard at random (4..9 m/s, so balls are
nearly always moving); `--think` seconds pass between a `state` and the bot's action.
`--computer K`: K of the rooms seat one bot against the computer opponent (the top level,
planning in the server's `POOL_COMPUTER_WORKERS` processes) instead of a second bot.
`--analyses K`: K finished matches (club-level self-play) are stored before the server
starts and their analyses asked for as the warm-up begins, so that they run (in the
server's idle-class analysis planner, `POOL_ANALYSIS_*`) during the measured window; the
result says how many were ready by its end.
The clients run on uvloop (`--loop asyncio`: the standard loop) and this process's cyclic
garbage collector is paused from the warm-up to the end of the window (its one full pass,
0.3-0.4 s at 1,000 rooms, falls in the warm-up): the instrument's own pauses are not the
server's lateness, and the cheaper the bots, the less of the shared machine they take.

Prints, over the S measured seconds (after every client is connected), the median of the
runs:
- `motion` messages received per second (all clients; one a shot and client: the whole
  shot comes at the strike, docs/protocol.md);
- shot start p50 / p99 / max: from the shooter's `shoot` to the shot's `motion` arriving,
  at every client of the room (the players and the spectator), for the shots struck in the
  window (their motions may come up to GRACE seconds after it);
- frames in hand: of every tick of every shot at every client, the share whose motion had
  arrived before the tick was due to be drawn, ticks being due START_BUDGET (0.1 s) +
  k/120 s after the `shoot` (so 100 % when every motion comes within 0.1 s);
- the server's own view (`GET /api/stats`): from the room taking `shoot` to its `motion`
  leaving (simulation, tracing, judging, any wait for a thread or the loop), p50 / p99;
- server CPU (process user+system time from /proc, all threads, in % of one core), the
  part of it its event loop took (the main thread; also per shot the server started in the
  window, a figure that moves far less from run to run than the latencies), its
  computer planners' CPU (the processes it started; idle-class, so they take only what
  the rooms leave) and this client process's CPU, so a saturated client is visible (per
  shot too: the same work in every run, so it tells how fast the machine ran; on a VM
  whose neighbours slow it down without any steal showing, the runs with a high p99 are
  the ones where it is high); and
  the machine's steal time (a VM host taking the cores away: runs with high steal are slow
  for reasons outside the code);
- bytes per second per client on the wire (WebSocket frames as received from the socket,
  compressed when permessage-deflate was negotiated): over the whole window, and per second
  of shot (a spectator's bytes from a shot's `motion` to its `shot_result`, over the shots'
  durations);
- errors: client exceptions, unexpected closes, `error` messages by code.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import gc
import json
import math
import os
import random
import resource
import signal
import statistics
import struct
import subprocess
import sys
import tempfile
import time
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

import httpx
import websockets
from websockets.asyncio.client import ClientConnection

from bench.analysis import store_match
from server.ai.analysis.selfplay import self_play
from server.priority import process_stat
from server.rooms.computer import THREAD_PLAN_NOTE
from server.store import Database
from tests.support.ports import free_port

TICK_HZ = 120
HEAD_STRING = 0.635
TABLE = (2.54, 1.27)
COMPUTER_LEVEL = "pro"  # the level of the computer in `--computer` rooms (the costliest)


class CountingConnection(ClientConnection):
    """Counts the bytes read from the socket (WebSocket framing included)."""

    received = 0

    def data_received(self, data: bytes) -> None:
        self.received += len(data)
        super().data_received(data)


@dataclass
class Stats:
    measuring: bool = False  # bytes and shots shown count while this is set
    # Starts count by when the `shoot` was sent: in [opened, closed). A shot struck just
    # before the window whose motion came inside it would carry this process's own pauses
    # (and the burst of actions they released) into the figures.
    opened: float = math.inf
    closed: float = math.inf
    motions: int = 0  # `motion` messages received (one a shot and client)
    starts: list[float] = field(default_factory=list)  # shoot sent -> motion, every client
    ticks: int = 0  # the shots' ticks, summed over the clients that got them ...
    in_hand: int = 0  # ... and those in hand before they were due
    errors: Counter = field(default_factory=Counter)
    shots: int = 0
    rolling_bytes: int = 0
    rolling_seconds: float = 0.0

    def motion_came(self, sent: float, now: float, duration: float) -> None:
        """A shot's motion came at `now`: timed if its `shoot` was sent in the window (NaN,
        a shot nobody here struck: never)."""
        if self.opened <= sent < self.closed:
            count_motion(self, now - sent, duration)


@dataclass
class RoomBots:
    room_id: str
    tokens: list[str]
    shoot_sent: dict[int, float] = field(default_factory=dict)  # shot id -> perf time
    last_shoot: float | None = None  # when a bot last sent `shoot`
    computer: bool = False  # the second seat is the computer's (`--computer`)


def percentile(values: list[float], p: float) -> float:
    if not values:
        return math.nan
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, round(p / 100 * (len(ordered) - 1)))]


# ---- the server --------------------------------------------------------------------------


def start_server(
    port: int, db: Path, log: Path, deflate: bool, extra: dict[str, str] | None = None
) -> subprocess.Popen:
    """`deflate`: the server accepts permessage-deflate (`POOL_WS_DEFLATE`), the clients
    offer it. `extra`: more settings for the server's environment."""
    env = {
        **os.environ,
        "POOL_DB_PATH": str(db),
        "POOL_MAX_ROOMS": "5000",
        # every bot comes from this one address: lift the per-client quotas
        "POOL_MAX_ROOMS_PER_CLIENT": "5000",
        "POOL_ROOM_CREATE_RATE": "100000/minute",
        "POOL_JOIN_RATE": "100000/minute",
        "POOL_WATCH_RATE": "100000/minute",
        "POOL_WS_DEFLATE": "1" if deflate else "0",
        **(extra or {}),
    }
    out = log.open("w")
    return subprocess.Popen(
        [
            sys.executable,
            "-m",
            "server",
            "--host",
            "127.0.0.1",
            "--port",
            str(port),
            "--log-level",
            "warning",
        ],
        env=env,
        stdout=out,
        stderr=subprocess.STDOUT,
    )


def cpu_seconds(pid: int, thread: int | None = None) -> float:
    """User + system CPU time of a process (all its threads), or of its one thread
    `thread` (`thread=pid`: the main thread, the server's event loop)."""
    stat = process_stat(pid, thread)
    if stat is None:
        raise ProcessLookupError(pid)
    return stat[1]


def children_cpu_seconds(pid: int) -> float:
    """User + system CPU time of the processes `pid` started (the server's computer
    planners): how much of the machine the computer's thinking took."""
    total = 0.0
    for entry in Path("/proc").glob("[0-9]*"):
        stat = process_stat(int(entry.name))  # None: a process that ended meanwhile
        if stat is not None and stat[0] == pid:
            total += stat[1]
    return total


def own_cpu_seconds() -> float:
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def machine_ticks() -> tuple[int, int]:
    """(all, stolen) CPU ticks of the machine (/proc/stat): a VM's host can take cores away
    ("steal"), which shows as a slow server that is not the server's fault."""
    fields = [int(v) for v in Path("/proc/stat").read_text().split("\n", 1)[0].split()[1:]]
    steal = fields[7] if len(fields) > 7 else 0
    return sum(fields[:8]), steal


async def wait_healthy(base: str, proc: subprocess.Popen) -> None:
    deadline = time.monotonic() + 60
    async with httpx.AsyncClient(base_url=base) as http:
        while True:
            if proc.poll() is not None:
                raise RuntimeError("the server exited at start")
            with contextlib.suppress(httpx.TransportError):
                if (await http.get("/health")).status_code == 200:
                    return
            if time.monotonic() > deadline:
                raise RuntimeError("the server did not start")
            await asyncio.sleep(0.2)


# ---- the bots ------------------------------------------------------------------------------


async def make_room(http: httpx.AsyncClient, opponent: str | None = None) -> RoomBots:
    """A room of two bots, or (`opponent`: a computer level) of one bot and the computer."""
    body = {"game": "eight_ball", "race_to": 15, "shot_clock": 0}
    if opponent is not None:
        body["opponent"] = opponent
    room = (await http.post("/api/rooms", json=body)).json()["room_id"]
    tokens = [
        (await http.post(f"/api/rooms/{room}/join", json={"name": name})).json()["token"]
        for name in (("Bot A",) if opponent else ("Bot A", "Bot B"))
    ]
    return RoomBots(room, tokens, computer=opponent is not None)


def action(state: dict, seat: int, rng: random.Random) -> dict | None:
    """What a bot at `seat` sends for this `state`, or None when it is not its move."""
    match = state.get("match")
    if state.get("phase") == "over" and seat not in state["room"]["rematch"]:
        return {"type": "rematch"}
    if state.get("phase") != "aiming" or match is None:
        return None
    decision = match.get("decision")
    if decision is not None:
        return (
            {"type": "decide", "option": decision["options"][0]}
            if decision["seat"] == seat
            else None
        )
    if match["turn"] != seat:
        return None
    cue_on = any(row[0] == 0 for row in state["balls"])
    if match.get("ball_in_hand") and not cue_on:
        right = (
            HEAD_STRING - 0.05 if match["ball_in_hand"] == "behind_head_string" else TABLE[0] - 0.1
        )
        return {
            "type": "place_cue",
            "x": rng.uniform(0.1, right),
            "y": rng.uniform(0.1, TABLE[1] - 0.1),
        }
    if match.get("requires_call") and match.get("called_pocket") is None:
        return {"type": "call", "pocket": rng.randrange(6)}
    return {
        "type": "shoot",
        "angle": rng.uniform(-math.pi, math.pi),
        "speed": rng.uniform(4.0, 9.0),
        "tip": [0.0, 0.0],
    }


async def client(
    base_ws: str,
    bots: RoomBots,
    seat: int | None,
    stats: Stats,
    stop: asyncio.Event,
    compression: str | None,
    think: float,
    connected: list[CountingConnection],
    ready: asyncio.Event,
    rng: random.Random,
) -> None:
    """One socket: a bot player (seat 0/1) or the spectator (None)."""
    url = f"{base_ws}/ws/rooms/{bots.room_id}"
    if seat is not None:
        url += f"?token={bots.tokens[seat]}"
    pending: asyncio.Task | None = None
    shown: dict[int, tuple[int, float]] = {}  # spectator: shot -> (bytes before, duration)
    try:
        async with websockets.connect(
            url,
            compression=compression,
            max_size=2**20,
            create_connection=CountingConnection,
            open_timeout=60,
            ping_interval=None,
        ) as ws:
            connected.append(ws)
            await ready.wait()
            async for raw in ws:  # the task is cancelled when the run is over
                now = time.perf_counter()
                if isinstance(raw, bytes):  # a shot's `motion`: the whole shot, at once
                    shot, duration = parse_motion(raw)
                    if shot not in bots.shoot_sent:
                        # A computer's shot was sent by nobody here: it is not timed.
                        late = math.nan if bots.computer else now
                        bots.shoot_sent[shot] = bots.last_shoot or late
                        if bots.computer:
                            bots.last_shoot = None
                    sent = bots.shoot_sent[shot]
                    stats.motion_came(sent, now, duration)
                    if seat is None:
                        shown[shot] = (ws.received - len(raw), duration)
                    continue
                message = json.loads(raw)
                kind = message["type"]
                if kind == "error":
                    stats.errors[f"error:{message['code']}"] += 1
                    if message["code"] == "illegal_placement" and seat is not None:
                        await ws.send(json.dumps(action_place(rng)))
                elif kind == "state" and seat is not None:
                    todo = action(message, seat, rng)
                    if pending is not None:
                        pending.cancel()
                    if todo is not None:
                        pending = asyncio.ensure_future(
                            act(ws, todo, bots, think * rng.uniform(0.5, 1.5))
                        )
                elif kind == "shot_result" and seat is None and message["shot"] in shown:
                    before, duration = shown.pop(message["shot"])
                    bots.shoot_sent.pop(message["shot"], None)
                    if stats.measuring:
                        stats.shots += 1
                        stats.rolling_bytes += ws.received - before
                        stats.rolling_seconds += duration
        if not stop.is_set():
            stats.errors["closed:by server"] += 1
    except asyncio.CancelledError:
        if not stop.is_set():
            raise
    except websockets.ConnectionClosed as exc:
        if not stop.is_set():
            stats.errors[f"closed:{exc.rcvd.code if exc.rcvd else None}"] += 1
    except Exception as exc:
        stats.errors[f"exception:{type(exc).__name__}"] += 1
    finally:
        if pending is not None:
            pending.cancel()


MOTION_HEADER = struct.Struct("<BBIIIBH")  # docs/protocol.md, `motion`
START_BUDGET = 0.1  # s from `shoot` by which a shot's playback should start
GRACE = 3.0  # s after the window for the motions of the shots struck in it


def parse_motion(raw: bytes) -> tuple[int, float]:
    """(shot, duration in s) from a `motion` message's header: 3,000 clients on the
    benchmark's one core need not decode every track."""
    _, _, _, shot, duration, _, _ = MOTION_HEADER.unpack_from(raw)
    return shot, duration / 1e6


def count_motion(stats: Stats, start: float, duration: float) -> None:
    """A client got a shot's motion `start` s after its `shoot`. Its tick k is due to be
    drawn START_BUDGET + k/120 s after the `shoot` (playback starting within the budget):
    in hand if the motion came by then."""
    ticks = max(1, round(duration * TICK_HZ))
    late = max(0, math.ceil((start - START_BUDGET) * TICK_HZ - 1e-9))
    stats.motions += 1
    stats.starts.append(start)
    stats.ticks += ticks
    stats.in_hand += max(0, ticks - late)


def action_place(rng: random.Random) -> dict:
    return {
        "type": "place_cue",
        "x": rng.uniform(0.1, HEAD_STRING - 0.05),
        "y": rng.uniform(0.1, TABLE[1] - 0.1),
    }


async def act(ws, todo: dict, bots: RoomBots, delay: float) -> None:
    await asyncio.sleep(delay)
    if todo["type"] == "shoot":
        bots.last_shoot = time.perf_counter()
    await ws.send(json.dumps(todo))


# ---- one run ---------------------------------------------------------------------------------


async def run(
    rooms: int,
    seconds: float,
    compression: str | None,
    think: float,
    seed: int,
    server_log: Path | None = None,
    computer: int = 0,
    warmup: float = 20.0,
    analyses: int = 0,
) -> dict:
    port = free_port()
    base = f"http://127.0.0.1:{port}"
    with tempfile.TemporaryDirectory() as tmp:
        log = Path(tmp) / "server.log"
        if analyses:
            store_finished_matches(Path(tmp) / "bench.db", analyses, seed)
        proc = start_server(port, Path(tmp) / "bench.db", log, compression is not None)
        try:
            result = await drive(
                proc, base, rooms, seconds, compression, think, seed, computer, warmup, analyses
            )
            # The server logs each computer plan it had to make in its own process (its
            # planners starved of CPU, or dead): the rooms paid for those in GIL time.
            result["plans_in_thread"] = log.read_text().count(THREAD_PLAN_NOTE)
            return result
        except Exception:
            print(log.read_text()[-3000:], file=sys.stderr)
            raise
        finally:
            proc.send_signal(signal.SIGTERM)
            try:
                proc.wait(30)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()
            if server_log is not None:
                with server_log.open("a") as out:
                    out.write(log.read_text())


@contextlib.contextmanager
def no_cyclic_gc():
    """Measure the server, not this process's garbage collector: a full collection over the
    600 clients' objects paused every client here for up to ~70 ms, which counted as frame
    lateness. During the window only reference counting frees memory."""
    gc.collect()
    gc.freeze()
    gc.disable()
    try:
        yield
    finally:
        gc.enable()
        gc.unfreeze()


async def drive(
    proc: subprocess.Popen,
    base: str,
    rooms: int,
    seconds: float,
    compression: str | None,
    think: float,
    seed: int,
    computer: int = 0,
    warmup: float = 20.0,
    analyses: int = 0,
) -> dict:
    await wait_healthy(base, proc)
    rng = random.Random(seed)
    async with httpx.AsyncClient(base_url=base, timeout=60) as http:
        all_bots = [
            await make_room(http, COMPUTER_LEVEL if i < computer else None) for i in range(rooms)
        ]
    stats, stop, ready = Stats(), asyncio.Event(), asyncio.Event()
    connected: list[CountingConnection] = []
    base_ws = base.replace("http", "ws")
    tasks = []
    gate = asyncio.Semaphore(50)

    async def spawn(bots: RoomBots, seat: int | None) -> None:
        async with gate:
            tasks.append(
                asyncio.ensure_future(
                    client(
                        base_ws,
                        bots,
                        seat,
                        stats,
                        stop,
                        compression,
                        think,
                        connected,
                        ready,
                        random.Random(rng.random()),
                    )
                )
            )
            while len(tasks) > len(connected) + sum(t.done() for t in tasks):
                await asyncio.sleep(0.01)

    for bots in all_bots:
        for seat in (None, *range(len(bots.tokens))):  # a spectator and the bot players
            await spawn(bots, seat)
    ready.set()
    async with httpx.AsyncClient(base_url=base, timeout=60) as http:
        for match_id in range(1, analyses + 1):  # queued now, analysed in the window
            await http.get(f"/api/matches/{match_id}/analysis")
    with no_cyclic_gc():  # its one full collection, 0.3-0.4 s at 1,000 rooms, in the warm-up
        await asyncio.sleep(warmup)  # every room starts shooting; the bursts settle
        bytes0 = sum(ws.received for ws in connected)
        cpu0, own0, t0 = cpu_seconds(proc.pid), own_cpu_seconds(), time.perf_counter()
        loop0 = cpu_seconds(proc.pid, thread=proc.pid)
        planners0 = children_cpu_seconds(proc.pid)
        all0, steal0 = machine_ticks()
        stats.measuring, stats.opened = True, t0
        await asyncio.sleep(seconds)
        stats.measuring, stats.closed = False, time.perf_counter()
        elapsed = stats.closed - t0
        cpu1, own1 = cpu_seconds(proc.pid), own_cpu_seconds()
        loop1 = cpu_seconds(proc.pid, thread=proc.pid)
        planners1 = children_cpu_seconds(proc.pid)
        all1, steal1 = machine_ticks()
        bytes1 = sum(ws.received for ws in connected)
        async with httpx.AsyncClient(base_url=base, timeout=60) as http:
            server = (await http.get("/api/stats", params={"window": elapsed})).json()["stream"]
            answers = [
                (await http.get(f"/api/matches/{match_id}/analysis")).status_code
                for match_id in range(1, analyses + 1)
            ]
        # The window's last shots: their motions may still be on the way.
        await asyncio.sleep(GRACE)
    stop.set()
    for task in tasks:
        task.cancel()
    await asyncio.gather(*tasks, return_exceptions=True)
    clients = len(connected)

    def per_shot(seconds: float) -> float:
        """ms per shot the server started in the window."""
        return 1000 * seconds / server["shots"] if server["shots"] else math.nan

    return {
        "rooms": rooms,
        "clients": clients,
        "seconds": elapsed,
        "motions_per_s": stats.motions / elapsed,
        "start_p50_ms": 1000 * percentile(stats.starts, 50),
        "start_p99_ms": 1000 * percentile(stats.starts, 99),
        "start_max_ms": 1000 * max(stats.starts, default=math.nan),
        "in_hand_pct": 100 * stats.in_hand / stats.ticks if stats.ticks else math.nan,
        "shot_seconds": stats.rolling_seconds / stats.shots if stats.shots else math.nan,
        "server_start_p50_ms": server["start_p50_ms"] if server["shots"] else math.nan,
        "server_start_p99_ms": server["start_p99_ms"] if server["shots"] else math.nan,
        "shots": stats.shots,
        "server_cpu": 100 * (cpu1 - cpu0) / elapsed,
        "loop_cpu": 100 * (loop1 - loop0) / elapsed,
        "loop_ms_per_shot": per_shot(loop1 - loop0),
        "planner_cpu": 100 * (planners1 - planners0) / elapsed,
        "steal_pct": 100 * (steal1 - steal0) / max(1, all1 - all0),
        "client_cpu": 100 * (own1 - own0) / elapsed,
        "client_ms_per_shot": per_shot(own1 - own0),
        "bytes_per_s_client": (bytes1 - bytes0) / elapsed / max(1, clients),
        "rolling_bytes_per_s": stats.rolling_bytes / stats.rolling_seconds
        if stats.rolling_seconds
        else math.nan,
        "analyses_ready": answers.count(200),
        "errors": dict(stats.errors),
    }


COLUMNS = [
    ("rooms", "rooms", "{:.0f}"),
    ("clients", "clients", "{:.0f}"),
    ("motions/s", "motions_per_s", "{:.0f}"),
    ("in hand %", "in_hand_pct", "{:.2f}"),
    ("start p50 ms", "start_p50_ms", "{:.1f}"),
    ("start p99 ms", "start_p99_ms", "{:.1f}"),
    ("start max ms", "start_max_ms", "{:.0f}"),
    ("server start p50 ms", "server_start_p50_ms", "{:.1f}"),
    ("server start p99 ms", "server_start_p99_ms", "{:.1f}"),
    ("shots", "shots", "{:.0f}"),
    ("shot s", "shot_seconds", "{:.2f}"),
    ("server CPU %", "server_cpu", "{:.0f}"),
    ("loop CPU %", "loop_cpu", "{:.0f}"),
    ("loop ms/shot", "loop_ms_per_shot", "{:.2f}"),
    ("planner CPU %", "planner_cpu", "{:.0f}"),
    ("plans in thread", "plans_in_thread", "{:.0f}"),
    ("client CPU %", "client_cpu", "{:.0f}"),
    ("client ms/shot", "client_ms_per_shot", "{:.2f}"),
    ("steal %", "steal_pct", "{:.0f}"),
    ("B/s/client", "bytes_per_s_client", "{:.0f}"),
    ("B/s rolling", "rolling_bytes_per_s", "{:.0f}"),
    ("analyses ready", "analyses_ready", "{:.0f}"),
]


def store_finished_matches(db_path: Path, count: int, seed: int) -> None:
    """`count` finished matches of club-level self-play, stored as ids 1..count."""
    db = Database(db_path)
    try:
        for match_id in range(1, count + 1):
            shots = self_play("eight_ball", ("club", "club"), seed * 1000 + match_id)
            db.run(lambda repo, i=match_id, s=shots: store_match(repo, i, s))
    finally:
        db.close()


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(
        prog="python -m bench.load", description=__doc__.splitlines()[0]
    )
    parser.add_argument("--rooms", type=int, default=10)
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--runs", type=int, default=1, help="report the median of R runs")
    parser.add_argument(
        "--compression",
        choices=("deflate", "none"),
        default="none",
        help="deflate: the server accepts permessage-deflate and the clients "
        "offer it, as browsers do (default: the server's default, off)",
    )
    parser.add_argument(
        "--server-log",
        type=Path,
        default=None,
        help="append the server's log (warnings: slow shots...) to this file",
    )
    parser.add_argument(
        "--warmup",
        type=float,
        default=20.0,
        help="seconds between the last client connecting and the measured window: every "
        "room is playing, and the server's collector has moved the burst of new "
        "connections' objects to its old generation (a one-time pass, ~0.2-0.4 s at "
        "1,000 rooms, that a server pays after a restart, not in its steady state)",
    )
    parser.add_argument(
        "--think", type=float, default=0.3, help="seconds a bot waits before acting (mean)"
    )
    parser.add_argument(
        "--loop",
        choices=("uvloop", "asyncio"),
        default="uvloop",
        help="the clients' event loop (uvloop, as uvicorn[standard] "
        "installs: cheaper, leaves more of the machine to the server)",
    )
    parser.add_argument(
        "--analyses",
        type=int,
        default=0,
        help="finished matches whose analyses run during the window",
    )
    parser.add_argument(
        "--computer",
        type=int,
        default=0,
        help=f"of the rooms, this many have one bot playing the computer ({COMPUTER_LEVEL})",
    )
    args = parser.parse_args(argv)
    if not 1 <= args.rooms <= 1000 or not 1 <= args.seconds <= 600:
        parser.error("rooms 1..1000, seconds 1..600")
    if not 0 <= args.computer <= args.rooms:
        parser.error("computer 0..rooms")
    compression = None if args.compression == "none" else "deflate"
    if args.loop == "uvloop":
        import uvloop

        asyncio.set_event_loop_policy(uvloop.EventLoopPolicy())
    results = []
    for i in range(args.runs):
        result = asyncio.run(
            run(
                args.rooms,
                args.seconds,
                compression,
                args.think,
                seed=i,
                server_log=args.server_log,
                computer=args.computer,
                warmup=args.warmup,
                analyses=args.analyses,
            )
        )
        results.append(result)
        print(
            f"run {i + 1}: "
            + ", ".join(f"{name} {fmt.format(result[key])}" for name, key, fmt in COLUMNS),
            f"errors {result['errors']}",
            flush=True,
        )
    print(
        f"\nmedian of {len(results)} run(s), {args.seconds:g} s each, "
        f"compression {args.compression}:"
    )
    for name, key, fmt in COLUMNS:
        print(f"  {name:>13}: {fmt.format(statistics.median(r[key] for r in results))}")
    errors: Counter = Counter()
    for r in results:
        errors.update(r["errors"])
    print(f"  {'errors':>13}: {dict(errors) or 'none'}")


if __name__ == "__main__":
    main()
