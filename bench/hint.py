"""How long the first "Show me a shot" of a fresh server takes.

    .venv/bin/python -m bench.hint --runs 5 [--after 3]
    .venv/bin/python -m bench.hint --tries 20   # hints played as shown: how often they pot

Each run starts a fresh `python -m server` (a throw-away database), waits until it answers
`/health` and then `--after` seconds more (a newcomer opening the lobby and a practice
table takes longer than that), opens a practice table, takes its seat, and times the first
`POST /api/rooms/{id}/hint` (a racked table: the break), then a second one. Prints each
run and the medians.

`--tries N`: on one server, N practice tables (each its own rack): the break hint played
exactly as shown ("Try it", then Shoot), then the next hint (a pot, a safety or a kick on
the broken table) timed and played too; prints how often each dropped a ball (the pot:
its target) and the second hint's median time.
"""

from __future__ import annotations

import argparse
import json
import statistics
import tempfile
import time
from pathlib import Path

import httpx
from websockets.sync.client import connect

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


def play(base: str, room_id: str, token: str, hint: dict) -> list[int]:
    """Play `hint` as "Try it" sets it up; the balls that dropped."""
    url = base.replace("http", "ws", 1) + f"/ws/rooms/{room_id}?token={token}"
    with connect(url, max_size=None) as ws:
        x, y = hint["place"]
        ws.send(json.dumps({"type": "place_cue", "x": x, "y": y}))
        shot = {"type": "shoot", "angle": hint["angle"], "speed": hint["speed"]}
        ws.send(json.dumps({**shot, "tip": hint["tip"]}))
        while True:
            message = ws.recv(timeout=120)
            if isinstance(message, str) and (data := json.loads(message))["type"] == "error":
                raise RuntimeError(data)
            if isinstance(message, str) and data["type"] == "shot_result":
                return list(data["outcome"]["pocketed"])


def tries(count: int) -> None:
    """Break and next-shot hints played as shown on `count` practice tables."""
    broke = potted = pots = 0
    latencies = []
    with tempfile.TemporaryDirectory() as tmp:
        port = free_port()
        log = Path(tmp) / "server.log"
        proc = start_server(port, Path(tmp) / "billiards.db", log, False)
        base = f"http://127.0.0.1:{port}"
        try:
            with httpx.Client(base_url=base, timeout=30) as http:
                wait_healthy(http, log)
                for _ in range(count):
                    room = http.post("/api/rooms", json={"game": "practice"}).json()["room_id"]
                    token = http.post(f"/api/rooms/{room}/join", json={"name": "B"}).json()["token"]
                    _, hint = timed_hint(http, room, token)
                    broke += any(b != 0 for b in play(base, room, token, hint))
                    seconds, hint = timed_hint(http, room, token)
                    latencies.append(seconds)
                    dropped = play(base, room, token, hint)
                    if hint["kind"] == "pot":
                        pots += 1
                        potted += hint["target"] in dropped
        finally:
            proc.terminate()
            proc.wait(30)
    print(f"break hints that dropped a ball: {broke}/{count}")
    print(f"next hints that were pots: {pots}/{count}, of which went in: {potted}/{pots}")
    print(
        f"next hint's time: median {statistics.median(latencies):.3f} s, max {max(latencies):.3f} s"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--after", type=float, default=3.0, help="s after /health answers")
    parser.add_argument("--tries", type=int, default=0, help="hints played as shown instead")
    args = parser.parse_args()
    if args.tries:
        tries(args.tries)
        return
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
