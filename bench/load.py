"""Load benchmark: N rooms of two bot players and a spectator against one real server.

    .venv/bin/python -m bench.load --rooms N --seconds S [--runs R] [--compression deflate]

Starts `python -m server` on a free loopback port (a subprocess of this one, stopped with
SIGTERM at the end, on a throw-away database), creates N 8-ball rooms, seats two bots in
each and adds a spectator (all `websockets` clients in this process). The bots play: place
the cue ball, call the 8, answer decisions and shoot hard at random (4..9 m/s, so balls are
nearly always moving); `--think` seconds pass between a `state` and the bot's action.
The clients run on uvloop (`--loop asyncio`: the standard loop) and this process's cyclic
garbage collector is paused during the measured window: the instrument's own pauses are not
the server's lateness, and the cheaper the bots, the less of the shared machine they take.

Prints, over the S measured seconds (after every client is connected), the median of the
runs:
- frames delivered per second (all clients) and per client (a `frame` message counts
  with the frames it carries `ahead`);
- frame lateness p50 / p99 / max: arrival time of the frame of tick k minus
  (time the shooter sent `shoot` + k/120 s), less the shot's own best arrival (which is the
  simulation plus loopback time, reported as `start` p50). This is how far the stream slips
  behind the tick schedule, the thing players feel as stutter;
- the server's own view (`GET /api/stats`): how late frame messages left the server
  against the shot's schedule, p50 / p99 ("sent"): the part of the lateness that is the
  server's, the rest being the network and the clients (this process, on the same cores);
- server CPU (process user+system time from /proc, all threads, in % of one core) and this
  client process's CPU, so a saturated client is visible; and the machine's steal time (a
  VM host taking the cores away: runs with high steal are slow for reasons outside the code);
- frames skipped: the share of a shot's frames a spectator did not get (an overloaded
  server skips frames that are already stale rather than send them late; a slow client's
  outbox drops them too);
- bytes per second per client on the wire (WebSocket frames as received from the socket,
  compressed when permessage-deflate was negotiated): over the whole window, and while balls
  are moving (a spectator's bytes from a shot's first to its last frame per second of shot);
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
import socket
import statistics
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

TICK_HZ = 120
HEAD_STRING = 0.635
TABLE = (2.54, 1.27)


class CountingConnection(ClientConnection):
    """Counts the bytes read from the socket (WebSocket framing included)."""

    received = 0

    def data_received(self, data: bytes) -> None:
        self.received += len(data)
        super().data_received(data)


@dataclass
class Stats:
    measuring: bool = False
    frames: int = 0
    lateness: list[float] = field(default_factory=list)
    starts: list[float] = field(default_factory=list)
    errors: Counter = field(default_factory=Counter)
    shots: int = 0
    rolling_bytes: int = 0
    rolling_seconds: float = 0.0
    spectator_frames: int = 0  # frames a spectator received of the shots it saw end ...
    planned_frames: int = 0  # ... and how many the stream had (the rest were skipped)


@dataclass
class RoomBots:
    room_id: str
    tokens: list[str]
    shoot_sent: dict[int, float] = field(default_factory=dict)  # shot id -> perf time
    last_shoot: float | None = None  # when a bot last sent `shoot`
    offsets: dict[int, list[float]] = field(default_factory=dict)


def percentile(values: list[float], p: float) -> float:
    if not values:
        return math.nan
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(round(p / 100 * (len(ordered) - 1))))]


# ---- the server --------------------------------------------------------------------------


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def start_server(
    port: int, db: Path, log: Path, deflate: bool, extra: dict[str, str] | None = None
) -> subprocess.Popen:
    """`deflate`: the server accepts permessage-deflate (`POOL_WS_DEFLATE`), the clients
    offer it. `extra`: more settings for the server's environment."""
    env = {
        **os.environ,
        "POOL_DB_PATH": str(db),
        "POOL_MAX_ROOMS": "5000",
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


def cpu_seconds(pid: int) -> float:
    """User + system CPU time of a process (all its threads)."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


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


async def make_room(http: httpx.AsyncClient) -> RoomBots:
    room = (
        await http.post("/api/rooms", json={"game": "eight_ball", "race_to": 15, "shot_clock": 0})
    ).json()["room_id"]
    tokens = [
        (await http.post(f"/api/rooms/{room}/join", json={"name": name})).json()["token"]
        for name in ("Bot A", "Bot B")
    ]
    return RoomBots(room, tokens)


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
    shot_first: dict[int, list] = {}  # spectator: shot -> [first time, bytes, frames]
    frame_every = [6]
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
                frame = parse_frame(raw)
                if frame is not None:
                    shot, tick, last, carried = frame
                    if shot not in bots.shoot_sent:
                        bots.shoot_sent[shot] = bots.last_shoot or now
                    if stats.measuring:
                        stats.frames += carried
                        offset = now - (bots.shoot_sent[shot] + tick / TICK_HZ)
                        bots.offsets.setdefault(shot, []).append(offset)
                    if seat is None:
                        if shot not in shot_first:
                            shot_first[shot] = [now, ws.received - len(raw), 0]
                        shot_first[shot][2] += carried
                        if last:
                            t0, b0, seen = shot_first.pop(shot)
                            if stats.measuring and now - t0 > 0.5:
                                stats.rolling_bytes += ws.received - b0
                                stats.rolling_seconds += now - t0
                            if stats.measuring:  # frames the server had for this shot
                                stats.spectator_frames += seen
                                stats.planned_frames += -(-tick // frame_every[0])
                    continue
                message = json.loads(raw)
                kind = message["type"]
                if kind == "welcome":
                    frame_every[0] = message["frame_every"]
                elif kind == "event" and message["shot"] not in bots.shoot_sent:
                    bots.shoot_sent[message["shot"]] = bots.last_shoot or now
                elif kind == "error":
                    stats.errors[f"error:{message['code']}"] += 1
                    if message["code"] == "illegal_placement" and seat is not None:
                        await ws.send(json.dumps(action_place(rng)))
                elif kind == "state" and seat is not None:
                    todo = action(message, seat, rng)
                    if pending is not None:
                        pending.cancel()
                    if todo is not None:
                        pending = asyncio.ensure_future(
                            act(ws, todo, bots, think * rng.uniform(0.5, 1.5), stats)
                        )
                elif kind == "shot_result" and message["shot"] is not None:
                    finish_shot(bots, message["shot"], stats)
        if not stop.is_set():
            stats.errors["closed:by server"] += 1
    except asyncio.CancelledError:
        if not stop.is_set():
            raise
    except websockets.ConnectionClosed as exc:
        if not stop.is_set():
            stats.errors[f"closed:{exc.rcvd.code if exc.rcvd else None}"] += 1
    except Exception as exc:  # noqa: BLE001 - a benchmark counts every failure
        stats.errors[f"exception:{type(exc).__name__}"] += 1
    finally:
        if pending is not None:
            pending.cancel()


FRAME_PREFIX = '{"type":"frame",'


def parse_frame(raw: str | bytes) -> tuple[int, int, bool, int] | None:
    """(shot, tick, last, frames carried) of a `frame` message, else None. The server writes
    a frame's keys in a fixed order (`type`, `seq`, `shot`, `tick`, `b`, `ahead`, `last`:
    docs/protocol.md), so 600 clients on the benchmark's one core need not decode every
    ball of every frame. Lateness is measured on the message's own tick; the frames it
    carries `ahead` arrive early by design and count as delivered."""
    if not isinstance(raw, str) or not raw.startswith(FRAME_PREFIX):
        return None
    _, _, shot, tick, _ = raw[:80].split(",", 4)
    return (int(shot[7:]), int(tick[7:]), raw.endswith(',"last":true}'), 1 + raw.count('{"tick":'))


def action_place(rng: random.Random) -> dict:
    return {
        "type": "place_cue",
        "x": rng.uniform(0.1, HEAD_STRING - 0.05),
        "y": rng.uniform(0.1, TABLE[1] - 0.1),
    }


async def act(ws, todo: dict, bots: RoomBots, delay: float, stats: Stats) -> None:
    await asyncio.sleep(delay)
    if todo["type"] == "shoot":
        bots.last_shoot = time.perf_counter()
    await ws.send(json.dumps(todo))


def finish_shot(bots: RoomBots, shot: int, stats: Stats) -> None:
    """Lateness of a shot's frames: offsets less the shot's best (its start latency)."""
    offsets = bots.offsets.pop(shot, None)
    if not offsets or not stats.measuring:
        return
    best = min(offsets)
    stats.starts.append(best)
    stats.lateness.extend(o - best for o in offsets)
    stats.shots += 1


# ---- one run ---------------------------------------------------------------------------------


async def run(
    rooms: int,
    seconds: float,
    compression: str | None,
    think: float,
    seed: int,
    server_log: Path | None = None,
) -> dict:
    port = free_port()
    base = f"http://127.0.0.1:{port}"
    with tempfile.TemporaryDirectory() as tmp:
        log = Path(tmp) / "server.log"
        proc = start_server(port, Path(tmp) / "bench.db", log, compression is not None)
        try:
            return await drive(proc, base, rooms, seconds, compression, think, seed)
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
) -> dict:
    await wait_healthy(base, proc)
    rng = random.Random(seed)
    async with httpx.AsyncClient(base_url=base, timeout=60) as http:
        all_bots = [await make_room(http) for _ in range(rooms)]
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
        for seat in (None, 0, 1):
            await spawn(bots, seat)
    ready.set()
    await asyncio.sleep(min(8.0, 2.0 + seconds / 4))  # warm up: every room starts shooting
    bytes0 = sum(ws.received for ws in connected)
    cpu0, own0, t0 = cpu_seconds(proc.pid), own_cpu_seconds(), time.perf_counter()
    all0, steal0 = machine_ticks()
    with no_cyclic_gc():
        stats.measuring = True
        await asyncio.sleep(seconds)
        stats.measuring = False
    elapsed = time.perf_counter() - t0
    async with httpx.AsyncClient(base_url=base, timeout=60) as http:
        server = (await http.get("/api/stats", params={"window": elapsed})).json()["stream"]
    cpu1, own1 = cpu_seconds(proc.pid), own_cpu_seconds()
    all1, steal1 = machine_ticks()
    bytes1 = sum(ws.received for ws in connected)
    stop.set()
    for task in tasks:
        task.cancel()
    await asyncio.gather(*tasks, return_exceptions=True)
    clients = len(connected)
    return {
        "rooms": rooms,
        "clients": clients,
        "seconds": elapsed,
        "frames_per_s": stats.frames / elapsed,
        "frames_per_s_client": stats.frames / elapsed / max(1, clients),
        "late_p50_ms": 1000 * percentile(stats.lateness, 50),
        "late_p99_ms": 1000 * percentile(stats.lateness, 99),
        "late_max_ms": 1000 * max(stats.lateness, default=math.nan),
        "start_p50_ms": 1000 * percentile(stats.starts, 50),
        "sent_p50_ms": server["late_p50_ms"] if server["frames"] else math.nan,
        "sent_p99_ms": server["late_p99_ms"] if server["frames"] else math.nan,
        "server_start_p50_ms": server["start_p50_ms"] if server["shots"] else math.nan,
        "server_start_p99_ms": server["start_p99_ms"] if server["shots"] else math.nan,
        "shots": stats.shots,
        "server_cpu": 100 * (cpu1 - cpu0) / elapsed,
        "steal_pct": 100 * (steal1 - steal0) / max(1, all1 - all0),
        "client_cpu": 100 * (own1 - own0) / elapsed,
        "bytes_per_s_client": (bytes1 - bytes0) / elapsed / max(1, clients),
        "rolling_bytes_per_s": stats.rolling_bytes / stats.rolling_seconds
        if stats.rolling_seconds
        else math.nan,
        "skipped_pct": 100 * (1 - stats.spectator_frames / stats.planned_frames)
        if stats.planned_frames
        else math.nan,
        "errors": dict(stats.errors),
    }


COLUMNS = [
    ("rooms", "rooms", "{:.0f}"),
    ("clients", "clients", "{:.0f}"),
    ("frames/s", "frames_per_s", "{:.0f}"),
    ("per client", "frames_per_s_client", "{:.1f}"),
    ("late p50 ms", "late_p50_ms", "{:.1f}"),
    ("late p99 ms", "late_p99_ms", "{:.1f}"),
    ("late max ms", "late_max_ms", "{:.0f}"),
    ("skipped %", "skipped_pct", "{:.1f}"),
    ("start p50 ms", "start_p50_ms", "{:.1f}"),
    ("sent p50 ms", "sent_p50_ms", "{:.1f}"),
    ("sent p99 ms", "sent_p99_ms", "{:.1f}"),
    ("server start p50 ms", "server_start_p50_ms", "{:.1f}"),
    ("server start p99 ms", "server_start_p99_ms", "{:.1f}"),
    ("shots", "shots", "{:.0f}"),
    ("server CPU %", "server_cpu", "{:.0f}"),
    ("client CPU %", "client_cpu", "{:.0f}"),
    ("steal %", "steal_pct", "{:.0f}"),
    ("B/s/client", "bytes_per_s_client", "{:.0f}"),
    ("B/s rolling", "rolling_bytes_per_s", "{:.0f}"),
]


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
        "--think", type=float, default=0.3, help="seconds a bot waits before acting (mean)"
    )
    parser.add_argument(
        "--loop",
        choices=("uvloop", "asyncio"),
        default="uvloop",
        help="the clients' event loop (uvloop, as uvicorn[standard] "
        "installs: cheaper, leaves more of the machine to the server)",
    )
    args = parser.parse_args(argv)
    if not 1 <= args.rooms <= 1000 or not 1 <= args.seconds <= 600:
        parser.error("rooms 1..1000, seconds 1..600")
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
