"""Accounts benchmark: what a password costs the server, and what the event loop keeps.

    python -m bench.accounts [--checks 10] [--signins 8]

Prints the median wall and CPU time of one argon2id hash and one check with
`argon2-cffi`'s defaults (what `server.accounts.Hasher` uses), then the wall time of
`--signins` concurrent `POST /api/login` (wrong passwords: the same work as right ones) on
the app through `httpx`'s ASGI transport, and the longest the event loop was held while
they ran: the hashing runs in worker threads, so the loop stays free.
"""

from __future__ import annotations

import argparse
import asyncio
import statistics
import tempfile
import time
from pathlib import Path

import httpx

from server.accounts import Hasher
from server.app import create_app
from server.config import Settings

PASSWORD = "correct horse battery staple"


def timed(fn: object, n: int) -> tuple[float, float]:
    walls, cpus = [], []
    for _ in range(n):
        wall, cpu = time.perf_counter(), time.process_time()
        fn()  # type: ignore[operator]
        walls.append(time.perf_counter() - wall)
        cpus.append(time.process_time() - cpu)
    return statistics.median(walls), statistics.median(cpus)


async def loop_stall(stop: asyncio.Event) -> float:
    """The longest gap between two turns of the loop while `stop` is unset."""
    worst, last = 0.0, time.perf_counter()
    while not stop.is_set():
        await asyncio.sleep(0.001)
        now = time.perf_counter()
        worst, last = max(worst, now - last), now
    return worst


async def signins(count: int) -> tuple[float, float]:
    directory = Path(tempfile.mkdtemp())
    settings = Settings(db_path=directory / "b.db", login_rate="100000/minute")
    app = create_app(settings)
    async with app.router.lifespan_context(app):
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://bench") as client:
            body = {"name": "Nobody", "password": PASSWORD}
            stop = asyncio.Event()
            watcher = asyncio.create_task(loop_stall(stop))
            started = time.perf_counter()
            answers = await asyncio.gather(
                *(client.post("/api/login", json={**body, "name": f"N{i}"}) for i in range(count))
            )
            wall = time.perf_counter() - started
            stop.set()
            stall = await watcher
    assert all(a.status_code == 401 for a in answers)
    return wall, stall


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--checks", type=int, default=10)
    parser.add_argument("--signins", type=int, default=8)
    args = parser.parse_args()
    hasher = Hasher()
    stored = hasher.hash(PASSWORD)
    hash_wall, hash_cpu = timed(lambda: hasher.hash(PASSWORD), args.checks)
    check_wall, check_cpu = timed(lambda: hasher.verify(stored, PASSWORD), args.checks)
    print(f"argon2id hash:  {hash_wall * 1000:6.0f} ms wall, {hash_cpu * 1000:6.0f} ms CPU")
    print(f"argon2id check: {check_wall * 1000:6.0f} ms wall, {check_cpu * 1000:6.0f} ms CPU")
    wall, stall = asyncio.run(signins(args.signins))
    print(
        f"{args.signins} concurrent sign-ins: {wall:.2f} s in all, "
        f"the event loop held at most {stall * 1000:.0f} ms"
    )


if __name__ == "__main__":
    main()
