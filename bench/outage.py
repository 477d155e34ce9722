"""PostgreSQL outage benchmark: three processes on a private Redis and PostgreSQL, rooms of
two bots playing, PostgreSQL stopped while lobby traffic opens tables through every
process, optionally the busiest process killed (kill -9) during the outage.

    .venv/bin/python -m bench.outage --rooms 12 --outage 20 [--kill] [--after 20]

Default cluster settings (lease 8 s, heartbeat 2 s). The bots (seat 0 of each room records
every `shot_result` it sees: shot id and outcome) play 8-ball hard and at random; a bot
whose socket closes asks `GET /api/rooms/{id}` through a live process for the room's new
`ws_url` and reconnects with its token. Timeline: `--warmup` s of play, PostgreSQL stopped
(`pg_ctl stop -m fast`) for `--outage` s while three clients keep posting `POST
/api/rooms` (one per process, each waiting for its answer), with `--kill` the process
playing most rooms killed a third of the way into it, PostgreSQL started again, `--after`
s more of play. Then it reads the store and prints:

- the fewest processes announced in Redis during the outage (sampled every 0.5 s);
- rooms moved: sockets closed with 1012 (`room_moved`) on rooms of processes that were
  not killed; with `--kill`, the killed process's rooms and how many played a shot after
  PostgreSQL came back (on another process);
- shots seen by the players, shots that started to be shown while PostgreSQL was down (a
  `motion` arriving from 0.5 s after the stop returned to the start; a shot struck before
  still plays out), seconds from PostgreSQL back to the next `motion`;
- shots undone (seen, not in the store) and rewritten (the store's outcome for a shot id,
  or a second showing of it, differs from what was first seen);
- the lobby's answers during the outage, by status.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import json
import random
import signal
import subprocess
import tempfile
import time
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import httpx
import redis
import websockets

from bench.cluster import private_redis, servers, stop_all, wait_healthy
from bench.load import action, action_place
from server.store import Database


@dataclass
class Seen:
    """What the players saw: per room, each shot id's outcome(s) and when."""

    shots: dict[str, dict[int, list[Any]]] = field(default_factory=dict)
    motions: list[float] = field(default_factory=list)  # when each shot's motion came
    moved: Counter = field(default_factory=Counter)  # room -> closes with 1012
    last: dict[str, float] = field(default_factory=dict)  # room -> its last shot's result
    closes: Counter = field(default_factory=Counter)


async def bot(
    room: str,
    url: str,
    token: str,
    seat: int,
    bases: list[str],
    seen: Seen,
    stop: asyncio.Event,
    seed: int,
) -> None:
    """One player; reconnects wherever the room went."""
    rng = random.Random(seed)
    while not stop.is_set():
        try:
            async with websockets.connect(f"{url}?token={token}", max_size=2**22) as ws:
                async for raw in ws:
                    if isinstance(raw, bytes):  # a shot's motion
                        if seat == 0:
                            seen.motions.append(time.monotonic())
                        continue
                    await on_message(ws, json.loads(raw), room, seat, seen, rng)
        except websockets.ConnectionClosed as exc:
            code = exc.rcvd.code if exc.rcvd else None
            seen.closes[code] += seat == 0
            if code == 1012 and seat == 0:
                seen.moved[room] += 1
        except OSError:
            pass
        if not stop.is_set():
            url = await where(room, bases, stop) or url


async def on_message(
    ws: Any, message: dict, room: str, seat: int, seen: Seen, rng: random.Random
) -> None:
    kind = message["type"]
    if kind == "state":
        todo = action(message, seat, rng)
        if todo is not None:
            await asyncio.sleep(rng.uniform(0.1, 0.4))
            await ws.send(json.dumps(todo))
    elif kind == "shot_result" and seat == 0 and message["shot"] is not None:
        seen.shots.setdefault(room, {}).setdefault(message["shot"], []).append(message["outcome"])
        seen.last[room] = time.monotonic()
    elif kind == "error" and message["code"] == "illegal_placement":
        await ws.send(json.dumps(action_place(rng)))


async def where(room: str, bases: list[str], stop: asyncio.Event) -> str | None:
    """The room's `ws_url`, asked through any process that answers."""
    async with httpx.AsyncClient(timeout=15) as http:
        while not stop.is_set():
            for base in bases:
                with contextlib.suppress(httpx.HTTPError):
                    reply = await http.get(f"{base}/api/rooms/{room}")
                    if reply.status_code == 200:
                        return str(reply.json()["ws_url"])
            await asyncio.sleep(0.5)
    return None


async def lobby(base: str, codes: Counter, until: asyncio.Event) -> None:
    async with httpx.AsyncClient(base_url=base, timeout=30) as http:
        while not until.is_set():
            try:
                reply = await http.post("/api/rooms", json={"game": "nine_ball"})
                codes[reply.status_code] += 1
            except httpx.HTTPError:
                codes["no answer"] += 1
                await asyncio.sleep(0.5)  # its process is gone


def announced(client: redis.Redis) -> int:
    nodes = [n.decode() for n in client.smembers("pool:nodes")]
    return sum(bool(client.exists(f"pool:node:{n}")) for n in nodes)


async def seat_rooms(base: str, rooms: int) -> list[tuple[str, str, list[str]]]:
    seated = []
    async with httpx.AsyncClient(base_url=base, timeout=60) as http:
        for _ in range(rooms):
            room = (
                await http.post(
                    "/api/rooms", json={"game": "eight_ball", "race_to": 15, "shot_clock": 0}
                )
            ).json()
            tokens = [
                (await http.post(f"/api/rooms/{room['room_id']}/join", json={"name": n})).json()[
                    "token"
                ]
                for n in ("Bot A", "Bot B")
            ]
            seated.append((room["room_id"], room["ws_url"], tokens))
    return seated


async def outage(args: argparse.Namespace) -> dict:
    from tests.support.postgres import running_postgres

    with (
        tempfile.TemporaryDirectory() as tmp,
        running_postgres() as pg,
        private_redis() as (redis_url, _),
    ):
        db_url = pg.create_database()
        started = servers(3, Path(tmp), {"POOL_DATABASE_URL": db_url, "POOL_REDIS_URL": redis_url})
        client = redis.Redis.from_url(redis_url)
        try:
            for i, (proc, base) in enumerate(started):
                await wait_healthy(base, proc, Path(tmp) / f"server-{i}.log")
            result = await timeline(args, pg, started, client)
        finally:
            stop_all([p for p, _ in started if p.poll() is None])
            client.close()
        result.update(compare(result.pop("seen"), db_url))
    return result


async def timeline(
    args: argparse.Namespace,
    pg: Any,
    started: list[tuple[subprocess.Popen, str]],
    client: redis.Redis,
) -> dict:
    bases = [b for _, b in started]
    seated = await seat_rooms(bases[0], args.rooms)
    seen, stop, lobby_done, codes = Seen(), asyncio.Event(), asyncio.Event(), Counter()
    bots = [
        asyncio.ensure_future(bot(room, url, tokens[s], s, bases, seen, stop, 1000 * i + s))
        for i, (room, url, tokens) in enumerate(seated)
        for s in (0, 1)
    ]
    await asyncio.sleep(args.warmup)
    hosts = Counter(url.split("/ws/")[0].replace("ws://", "http://") for _, url, _ in seated)
    victim = hosts.most_common(1)[0][0] if args.kill else None
    victim_rooms = {
        r for r, url, _ in seated if victim and victim.replace("http://", "ws://") in url
    }
    pg.stop()
    down = time.monotonic()
    fewest = 3
    traffic = [asyncio.ensure_future(lobby(b, codes, lobby_done)) for b in bases]
    while time.monotonic() - down < args.outage:
        if victim and time.monotonic() - down > args.outage / 3:
            proc = next(p for p, b in started if b == victim)
            proc.send_signal(signal.SIGKILL)
            proc.wait(10)
            bases.remove(victim)
            victim = None
        fewest = min(fewest, announced(client))
        await asyncio.sleep(0.5)
    lobby_done.set()
    await asyncio.gather(*traffic, return_exceptions=True)
    pg.start()
    up = time.monotonic()
    await asyncio.sleep(args.after)
    stop.set()
    for task in bots:
        task.cancel()
    await asyncio.gather(*bots, return_exceptions=True)
    after_up = [t - up for t in seen.motions if t > up]
    return {
        "fewest_announced": fewest,
        "rooms_moved": len([r for r in seen.moved if r not in victim_rooms]),
        "rooms_of_killed": len(victim_rooms),
        "rooms_of_killed_playing_after": len([r for r in victim_rooms if seen.last.get(r, 0) > up]),
        "shots_seen": sum(len(s) for s in seen.shots.values()),
        "motions_while_down": len([t for t in seen.motions if down + 0.5 < t < up]),
        "first_motion_after_up_s": round(min(after_up), 2) if after_up else None,
        "lobby": dict(codes),
        "closes": dict(seen.closes),
        "seen": seen,
    }


def compare(seen: Seen, db_url: str) -> dict:
    """Shots undone (seen, not stored) and rewritten (stored or shown again otherwise)."""
    db = Database(db_url)
    try:
        stored: dict[str, dict[int, Any]] = {}
        for match in db.run(lambda r: r.recent_matches(1000)):
            shots = db.run(lambda r, m=match.id: r.shots(m))
            stored.setdefault(match.room_id, {}).update({s.room_shot: s.outcome for s in shots})
    finally:
        db.close()
    undone = rewritten = 0
    for room, shots in seen.shots.items():
        for shot_id, outcomes in shots.items():
            first = json.dumps(outcomes[0], sort_keys=True)
            if any(json.dumps(o, sort_keys=True) != first for o in outcomes[1:]):
                rewritten += 1
            elif shot_id not in stored.get(room, {}):
                undone += 1
            elif json.dumps(stored[room][shot_id], sort_keys=True) != first:
                rewritten += 1
    return {"shots_undone": undone, "shots_rewritten": rewritten}


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(
        prog="python -m bench.outage", description=__doc__.splitlines()[0]
    )
    parser.add_argument("--rooms", type=int, default=12)
    parser.add_argument("--outage", type=float, default=20.0, help="seconds PostgreSQL is down")
    parser.add_argument("--kill", action="store_true", help="kill -9 the busiest process meanwhile")
    parser.add_argument("--warmup", type=float, default=10.0)
    parser.add_argument("--after", type=float, default=20.0, help="seconds of play after")
    args = parser.parse_args(argv)
    print(json.dumps(asyncio.run(outage(args)), indent=2))


if __name__ == "__main__":
    main()
