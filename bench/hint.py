"""How long the first "Show me a shot" of a fresh server takes.

    .venv/bin/python -m bench.hint --runs 5 [--after 3]

Each run starts a fresh `python -m server` (a throw-away database), waits until it answers
`/health` and then `--after` seconds more (a newcomer opening the lobby and a practice
table takes longer than that), opens a practice table, takes its seat, and times the first
`POST /api/rooms/{id}/hint` (a racked table: the break), then a second one. Prints each
run and the medians.
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
import time
from pathlib import Path

import httpx

from bench.load import start_server
from tests.support.ports import free_port

HEALTH_WAIT = 120.0  # s a loaded machine may take to start a server


def wait_healthy(http: httpx.Client, log: Path) -> None:
    deadline = time.monotonic() + HEALTH_WAIT
    while time.monotonic() < deadline:
        try:
            if http.get("/health").status_code == 200:
                return
        except httpx.TransportError:
            pass
        time.sleep(0.1)
    raise RuntimeError(f"the server did not start:\n{log.read_text()[-3000:]}")


def timed_hint(http: httpx.Client, room_id: str, token: str) -> tuple[float, dict]:
    started = time.perf_counter()
    reply = http.post(f"/api/rooms/{room_id}/hint", json={"token": token}, timeout=120)
    reply.raise_for_status()
    return time.perf_counter() - started, reply.json()


def one_run(after: float) -> tuple[float, float, str]:
    """The first and second hint's seconds on a fresh server, and the first's kind."""
    with tempfile.TemporaryDirectory() as tmp:
        port = free_port()
        log = Path(tmp) / "server.log"
        proc = start_server(port, Path(tmp) / "billiards.db", log, False)
        try:
            with httpx.Client(base_url=f"http://127.0.0.1:{port}", timeout=30) as http:
                wait_healthy(http, log)
                time.sleep(after)
                room = http.post("/api/rooms", json={"game": "practice"}).json()["room_id"]
                token = http.post(f"/api/rooms/{room}/join", json={"name": "Bench"}).json()["token"]
                first, plan = timed_hint(http, room, token)
                second, _ = timed_hint(http, room, token)
                return first, second, plan["kind"]
        finally:
            proc.terminate()
            proc.wait(30)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--after", type=float, default=3.0, help="s after /health answers")
    args = parser.parse_args()
    firsts, seconds = [], []
    for run in range(args.runs):
        first, second, kind = one_run(args.after)
        firsts.append(first)
        seconds.append(second)
        print(f"run {run + 1}: first hint {first:.3f} s ({kind}), second {second:.3f} s")
    print(
        f"median of {args.runs}: first hint {statistics.median(firsts):.3f} s, "
        f"second {statistics.median(seconds):.3f} s"
    )


if __name__ == "__main__":
    main()
