"""Cluster benchmark: the same rooms of bot players on one process, then on three processes
sharing a private Redis (cluster mode), all on the local host.

    .venv/bin/python -m bench.cluster --rooms 30 --seconds 20 --runs 3 [--store postgres]
    .venv/bin/python -m bench.cluster --handover kill --rooms 30 --runs 3   # or drain
    .venv/bin/python -m bench.cluster --leases 10000
    .venv/bin/python -m bench.cluster --heartbeat-cost 1000

Each run starts the servers (`python -m server`, a throw-away store: one SQLite file, or
with `--store postgres` a private PostgreSQL for both modes), opens the rooms through the
first process (in a cluster they are placed on the least loaded one; the room's `ws_url`
says where), seats two bots in each, lets them play hard breaks and random shots for the
measured window, and prints the median of the runs:

- rooms per process (how evenly new rooms were spread);
- shots per second (all rooms);
- CPU of the servers (all processes, user+system from /proc, % of one core) and of
  redis-server, per room: ms of CPU per second per room;
- the extra CPU per room that cluster mode costs (servers + Redis, cluster minus one
  process), and Redis's share of it;
- Redis commands per second and per shot (`INFO stats` total_commands_processed, less
  the benchmark's own INFO calls; by command from `INFO commandstats`: a script's
  EVALSHA counts once, the commands it runs count under their own names too), and
  Redis's memory (`used_memory` with the rooms, less without) per room.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import json
import math
import random
import signal
import statistics
import subprocess
import tempfile
import time
from collections import Counter
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

import httpx
import redis
import websockets

from bench.load import action, action_place, cpu_seconds, start_server
from tests.support.ports import free_port

SETTINGS = {
    "POOL_MAX_ROOMS_PER_CLIENT": "100000",
    "POOL_ROOM_CREATE_RATE": "100000/minute",
    "POOL_JOIN_RATE": "100000/minute",
    "POOL_WATCH_RATE": "100000/minute",
    "POOL_PRESENCE_INTERVAL": "0",
}


@dataclass
class Tally:
    shots: int = 0
    measuring: bool = False
    errors: Counter = field(default_factory=Counter)


@contextlib.contextmanager
def private_redis() -> Iterator[tuple[str, int]]:
    """A private redis-server (the tests' helper): its URL and pid."""
    from tests.support.redis import redis_server

    with redis_server() as server:
        client = redis.Redis.from_url(server.url)
        pid = int(client.info("server")["process_id"])
        client.close()
        yield server.url, pid


@contextlib.contextmanager
def store_for(kind: str, folder: Path) -> Iterator[dict[str, str]]:
    """The environment that points the servers at one shared store."""
    if kind == "postgres":
        from tests.support.postgres import running_postgres

        with running_postgres() as pg:
            yield {"POOL_DATABASE_URL": pg.create_database()}
        return
    yield {"POOL_DB_PATH": str(folder / "bench.db")}


async def bot(url: str, token: str, seat: int, tally: Tally, stop: asyncio.Event, seed: int):
    """One player: acts on each `state` that waits for it, counts the shots it sees end
    (seat 0 only, so each shot counts once)."""
    rng = random.Random(seed)
    try:
        async with websockets.connect(f"{url}?token={token}", max_size=2**22) as ws:
            async for raw in ws:
                if isinstance(raw, bytes):
                    continue  # a shot's motion
                message = json.loads(raw)
                kind = message["type"]
                if kind == "state":
                    todo = action(message, seat, rng)
                    if todo is not None:
                        await asyncio.sleep(rng.uniform(0.1, 0.4))
                        await ws.send(json.dumps(todo))
                elif kind == "shot_result" and seat == 0 and message["shot"] is not None:
                    tally.shots += tally.measuring
                elif kind == "error":
                    tally.errors[message["code"]] += 1
                    if message["code"] == "illegal_placement":
                        await ws.send(json.dumps(action_place(rng)))
    except websockets.ConnectionClosed as exc:
        if not stop.is_set():
            tally.errors[f"closed:{exc.rcvd.code if exc.rcvd else None}"] += 1


async def play(bases: list[str], rooms: int, seconds: float, seed: int, probe) -> dict:
    """Open `rooms` through the first server, two bots each; measure for `seconds`."""
    tally, stop = Tally(), asyncio.Event()
    empty = probe()
    async with httpx.AsyncClient(base_url=bases[0], timeout=60) as http:
        seated = []
        for _ in range(rooms):
            created = await http.post(
                "/api/rooms", json={"game": "eight_ball", "race_to": 15, "shot_clock": 0}
            )
            room = created.json()
            tokens = [
                (await http.post(f"/api/rooms/{room['room_id']}/join", json={"name": n})).json()
                for n in ("Bot A", "Bot B")
            ]
            seated.append((room["ws_url"], [t["token"] for t in tokens]))
    spread = Counter(url.split("/ws/")[0] for url, _ in seated)
    tasks = [
        asyncio.ensure_future(bot(url, tokens[seat], seat, tally, stop, seed * 1000 + i))
        for i, (url, tokens) in enumerate(seated)
        for seat in (0, 1)
    ]
    await asyncio.sleep(3.0)  # every room under way
    before = probe()
    tally.measuring = True
    started = time.perf_counter()
    await asyncio.sleep(seconds)
    tally.measuring = False
    elapsed = time.perf_counter() - started
    after = probe()
    stop.set()
    for task in tasks:
        task.cancel()
    await asyncio.gather(*tasks, return_exceptions=True)
    return {
        "spread": sorted(spread.values(), reverse=True),
        "elapsed": elapsed,
        "shots": tally.shots,
        "errors": dict(tally.errors),
        **{k: after[k] - before[k] for k in ("server_cpu", "redis_cpu", "commands")},
        "memory": after["memory"] - empty["memory"],
        "by_command": {
            k: after["by_command"][k] - before["by_command"].get(k, 0) for k in after["by_command"]
        },
    }


def servers(n: int, folder: Path, env: dict[str, str]) -> list[tuple[subprocess.Popen, str]]:
    started = []
    for i in range(n):
        port = free_port()
        extra = {**SETTINGS, **env}
        if "POOL_REDIS_URL" in env:
            extra["POOL_PUBLIC_URL"] = f"http://127.0.0.1:{port}"
        log = folder / f"server-{i}.log"
        started.append((start_server(port, folder / "unused.db", log, False, extra), port))
    return [(proc, f"http://127.0.0.1:{port}") for proc, port in started]


async def wait_healthy(base: str, proc: subprocess.Popen, log: Path, timeout: float = 180.0):
    """Until the server answers /health (a loaded machine starts three slowly)."""
    deadline = time.monotonic() + timeout
    async with httpx.AsyncClient(base_url=base) as http:
        while True:
            if proc.poll() is not None or time.monotonic() > deadline:
                raise RuntimeError(f"the server did not start:\n{log.read_text()[-3000:]}")
            with contextlib.suppress(httpx.TransportError):
                if (await http.get("/health")).status_code == 200:
                    return
            await asyncio.sleep(0.2)


def stop_all(procs: list[subprocess.Popen]) -> None:
    for proc in procs:
        proc.send_signal(signal.SIGTERM)
    for proc in procs:
        try:
            proc.wait(30)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


async def one_mode(cluster: bool, rooms: int, seconds: float, seed: int, store: str) -> dict:
    with (
        tempfile.TemporaryDirectory() as tmp,
        store_for(store, Path(tmp)) as store_env,
        contextlib.ExitStack() as stack,
    ):
        env = dict(store_env)
        redis_pid, client = None, None
        if cluster:
            url, redis_pid = stack.enter_context(private_redis())
            env["POOL_REDIS_URL"] = url
            client = redis.Redis.from_url(url)
        started = servers(3 if cluster else 1, Path(tmp), env)
        try:
            for i, (proc, base) in enumerate(started):
                await wait_healthy(base, proc, Path(tmp) / f"server-{i}.log")

            def probe() -> dict:
                sample = {
                    "server_cpu": sum(cpu_seconds(p.pid) for p, _ in started),
                    "redis_cpu": cpu_seconds(redis_pid) if redis_pid else 0.0,
                    "commands": 0.0,
                    "memory": 0.0,
                    "by_command": {},
                }
                if client is not None:
                    sample["commands"] = float(client.info("stats")["total_commands_processed"])
                    sample["memory"] = float(client.info("memory")["used_memory"])
                    sample["by_command"] = {
                        k.removeprefix("cmdstat_"): v["calls"]
                        for k, v in client.info("commandstats").items()
                    }
                return sample

            result = await play([b for _, b in started], rooms, seconds, seed, probe)
        finally:
            stop_all([p for p, _ in started])
            if client is not None:
                client.close()
    result["commands"] = max(0.0, result["commands"] - 6)  # the probes' own INFO calls
    result["by_command"].pop("info", None)
    return result


def summary(result: dict, rooms: int) -> dict:
    t = result["elapsed"]
    cpu = 100 * result["server_cpu"] / t
    redis_cpu = 100 * result["redis_cpu"] / t
    return {
        "spread": result["spread"],
        "shots_per_s": result["shots"] / t,
        "server_cpu": cpu,
        "redis_cpu": redis_cpu,
        "ms_per_room_s": 10 * (cpu + redis_cpu) / rooms,  # % of a core -> ms per s, per room
        "commands_per_s": result["commands"] / t,
        "commands_per_shot": result["commands"] / result["shots"] if result["shots"] else 0.0,
        "redis_bytes_per_room": result["memory"] / rooms,
        "per_shot": {
            k: round(v / result["shots"], 2)
            for k, v in sorted(result["by_command"].items(), key=lambda kv: -kv[1])
            if v and result["shots"]
        },
        "errors": result["errors"],
    }


# ---- failover and drain ----------------------------------------------------------------


async def handover(rooms: int, how: str, store: str) -> dict:
    """Three processes with the default lease settings, `rooms` seated rooms opened through
    the first; the process playing the most is killed (`kill`: kill -9) or stopped
    (`drain`: SIGTERM). Returns, for its rooms, the seconds until each answered from
    another process (asked through a survivor every 50 ms)."""
    with (
        tempfile.TemporaryDirectory() as tmp,
        store_for(store, Path(tmp)) as store_env,
        private_redis() as (url, _),
    ):
        started = servers(3, Path(tmp), {**store_env, "POOL_REDIS_URL": url})
        try:
            for i, (proc, base) in enumerate(started):
                await wait_healthy(base, proc, Path(tmp) / f"server-{i}.log")
            async with httpx.AsyncClient(base_url=started[0][1], timeout=30) as http:
                placed = []
                for _ in range(rooms):
                    room = (await http.post("/api/rooms", json={"game": "eight_ball"})).json()
                    for name in ("Ana", "Ben"):
                        await http.post(f"/api/rooms/{room['room_id']}/join", json={"name": name})
                    placed.append(room)
            hosts = Counter(
                r["ws_url"].split("/ws/")[0].replace("ws://", "http://") for r in placed
            )
            victim_base = hosts.most_common(1)[0][0]
            victim = next(p for p, b in started if b == victim_base)
            survivor = next(b for _, b in started if b != victim_base)
            mine = [r for r in placed if victim_base.replace("http://", "ws://") in r["ws_url"]]
            await asyncio.sleep(1.0)
            t0 = time.perf_counter()
            victim.send_signal(signal.SIGKILL if how == "kill" else signal.SIGTERM)
            took: dict[str, float] = {}
            async with httpx.AsyncClient(base_url=survivor, timeout=30) as http:
                while len(took) < len(mine) and time.perf_counter() - t0 < 60:
                    for room in mine:
                        if room["room_id"] in took:
                            continue
                        reply = await http.get(f"/api/rooms/{room['room_id']}")
                        if reply.status_code == 200 and reply.json()["ws_url"] != room["ws_url"]:
                            took[room["room_id"]] = time.perf_counter() - t0
                    await asyncio.sleep(0.05)
        finally:
            stop_all([p for p, _ in started])
    times = sorted(took.values())
    return {
        "rooms": len(mine),
        "back": len(times),
        "median_s": statistics.median(times) if times else math.nan,
        "max_s": times[-1] if times else math.nan,
    }


def lease_cost(rooms: int, repeats: int = 15) -> dict:
    """Redis alone: the time one heartbeat's lease renewal of `rooms` rooms takes (the RENEW
    script, one call: Redis's own time from `INFO commandstats`, and the wall time with the
    client's packing), and the memory a room's keys take."""
    from server.cluster import keys, scripts

    with private_redis() as (url, _):
        client = redis.Redis.from_url(url, decode_responses=True)
        empty = float(client.info("memory")["used_memory"])
        acquire = client.register_script(scripts.ACQUIRE)
        renew = client.register_script(scripts.RENEW)
        ids = [f"room{i:09d}" for i in range(rooms)]
        summary = json.dumps(
            {"node": "0123456789ab", "listed": True, "room_id": "x" * 12, "game": "eight_ball",
             "race_to": 3, "shot_clock": 60.0, "seats": 2, "status": "playing",
             "players": ["A player name", "Another name"], "spectators": 3, "score": [1, 2],
             "created_at": 1.7e9}
        )  # fmt: skip
        pipe = client.pipeline(transaction=False)
        for room_id in ids:
            acquire(
                keys=[keys.lease(room_id), keys.epoch(room_id)],
                args=["0123456789ab", 60000, 0],
                client=pipe,
            )
            pipe.set(keys.room(room_id), summary)
            pipe.zadd(keys.LISTED, {room_id: 1.7e9})
            pipe.sadd(keys.node_rooms("0123456789ab"), room_id)
        pipe.execute()
        full = float(client.info("memory")["used_memory"])
        lease_keys = [k for r in ids for k in (keys.lease(r), keys.epoch(r))]
        args = ["0123456789ab", 60000, *([1] * rooms)]
        times = []
        renew(keys=lease_keys, args=args)  # loads the script
        client.config_resetstat()
        for _ in range(repeats):
            t0 = time.perf_counter()
            assert all(int(x) == 1 for x in renew(keys=lease_keys, args=args))
            times.append(time.perf_counter() - t0)
        inside = client.info("commandstats")["cmdstat_evalsha"]["usec_per_call"]
        client.close()
    return {
        "rooms": rooms,
        "renew_ms_wall": 1000 * statistics.median(times),  # with the client's packing
        "renew_ms_in_redis": inside / 1000,  # Redis's own time per call
        "renew_us_per_room": inside / rooms,
        "bytes_per_room": (full - empty) / rooms,
        "summary_bytes": len(summary),
    }


def heartbeat_cost(rooms: int, repeats: int = 20) -> dict:
    """The cluster's own work in a server process: one process (in this one) owning `rooms`
    rooms over a private Redis and a throw-away SQLite store; the CPU time of one heartbeat
    (renew every lease, announce, publish the summaries that changed, look for dead
    processes), with no summary changed and with every one changed."""
    from server.cluster import Cluster
    from server.config import Settings
    from server.rooms import RoomRegistry
    from server.store import Database

    async def measure(url: str, folder: Path) -> dict:
        settings = Settings(
            redis_url=url,
            public_url="http://127.0.0.1:9",
            max_rooms=rooms,
            max_rooms_per_client=rooms,
        )
        store = Database(folder / "cost.db")
        registry = RoomRegistry(settings)
        cluster = Cluster(settings, registry, store)
        await cluster.start()
        try:
            for _ in range(rooms):
                await cluster.own_new(registry.create("eight_ball"))
            quiet, busy = [], []
            for i in range(repeats):
                if i % 2:
                    for live in registry.rooms.values():
                        live.room.spectators += 1  # every summary changed
                t0 = time.process_time()
                await cluster.beat()
                (busy if i % 2 else quiet).append(time.process_time() - t0)
        finally:
            await cluster.stop()
            store.close()
        return {
            "rooms": rooms,
            "beat_ms_quiet": 1000 * statistics.median(quiet),
            "beat_ms_all_changed": 1000 * statistics.median(busy),
            "us_per_room_quiet": 1e6 * statistics.median(quiet) / rooms,
            "us_per_room_changed": 1e6 * statistics.median(busy) / rooms,
        }

    with private_redis() as (url, _), tempfile.TemporaryDirectory() as tmp:
        return asyncio.run(measure(url, Path(tmp)))


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(prog="python -m bench.cluster", description=__doc__)
    parser.add_argument("--rooms", type=int, default=30)
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--store", choices=("sqlite", "postgres"), default="sqlite")
    parser.add_argument(
        "--handover",
        choices=("kill", "drain"),
        help="instead: how long the rooms of a killed (kill -9) or drained (SIGTERM) "
        "process take to answer from another one, default lease settings",
    )
    parser.add_argument(
        "--leases",
        type=int,
        metavar="N",
        help="instead: Redis's time to renew N rooms' leases in one call, and memory per room",
    )
    parser.add_argument(
        "--heartbeat-cost",
        type=int,
        metavar="N",
        help="instead: a server process's CPU for one heartbeat with N rooms",
    )
    args = parser.parse_args(argv)
    if not 3 <= args.rooms <= 600 or not 5 <= args.seconds <= 600:
        parser.error("rooms 3..600, seconds 5..600")
    if args.leases:
        print(lease_cost(args.leases))
        return
    if args.heartbeat_cost:
        print(heartbeat_cost(args.heartbeat_cost))
        return
    if args.handover:
        results = []
        for i in range(args.runs):
            results.append(asyncio.run(handover(args.rooms, args.handover, args.store)))
            print(f"run {i + 1}: {results[-1]}", flush=True)
        print(
            f"\nmedian of {args.runs} run(s), {args.handover}: rooms back "
            f"{statistics.median(r['back'] for r in results):.0f} of "
            f"{statistics.median(r['rooms'] for r in results):.0f}, "
            f"median {statistics.median(r['median_s'] for r in results):.2f} s, "
            f"last {statistics.median(r['max_s'] for r in results):.2f} s"
        )
        return
    runs: dict[str, list[dict]] = {"one process": [], "three processes + Redis": []}
    for i in range(args.runs):
        for name, cluster in (("one process", False), ("three processes + Redis", True)):
            result = summary(
                asyncio.run(one_mode(cluster, args.rooms, args.seconds, i, args.store)),
                args.rooms,
            )
            runs[name].append(result)
            print(f"run {i + 1}, {name}: {result}", flush=True)

    def med(name: str, key: str) -> float:
        return statistics.median(r[key] for r in runs[name])

    one, many = "one process", "three processes + Redis"
    print(
        f"\nmedian of {args.runs} run(s), {args.rooms} rooms, {args.seconds:g} s, "
        f"store {args.store}:"
    )
    for name in runs:
        print(
            f"  {name}: rooms per process {runs[name][-1]['spread']}, "
            f"{med(name, 'shots_per_s'):.1f} shots/s, servers {med(name, 'server_cpu'):.0f} % "
            f"CPU, redis {med(name, 'redis_cpu'):.1f} %, "
            f"{med(name, 'ms_per_room_s'):.2f} ms CPU per room-second"
        )
    extra = med(many, "ms_per_room_s") - med(one, "ms_per_room_s")
    redis_share = 10 * med(many, "redis_cpu") / args.rooms
    print(f"  extra CPU per room in cluster mode: {extra:.2f} ms/s (Redis's: {redis_share:.3f})")
    print(
        f"  Redis: {med(many, 'commands_per_s'):.0f} commands/s, "
        f"{med(many, 'commands_per_shot'):.1f} per shot, "
        f"{med(many, 'redis_bytes_per_room'):.0f} bytes of memory per room"
    )
    print(f"  Redis commands per shot by kind (last run): {runs[many][-1]['per_shot']}")


if __name__ == "__main__":
    main()
