"""The computer's planner processes end with their server: stopped (SIGTERM), the server
stops them; killed (kill -9), they notice within a second or two and end. Before, every
restart left them running, orphaned."""

from __future__ import annotations

import json
import signal
import time
from pathlib import Path

import httpx
import pytest
from websockets.sync.client import connect

from server.rooms.computer import PARENT_CHECK
from tests.support.games import BREAK_MESSAGE
from tests.support.live import ws_url
from tests.support.ports import free_port
from tests.support.process import server_process
from tests.support.waiting import until

pytestmark = [pytest.mark.timeout(240), pytest.mark.slow]


def parent_of(pid: int) -> int | None:
    """`pid`'s parent, or None once it has ended (gone, or a zombie)."""
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return None
    fields = stat.rsplit(")", 1)[1].split()  # after the command name, which may hold spaces
    return None if fields[0] == "Z" else int(fields[1])


def planners_over(db: Path) -> list[int]:
    """Every planner process of a server over `db`, whoever its parent is now (an orphan's
    is init): spawned workers inherit the server's environment, `POOL_DB_PATH` included."""
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            command = (entry / "cmdline").read_bytes()
            environment = (entry / "environ").read_bytes().split(b"\0")
        except OSError:
            continue
        ours = b"spawn_main" in command and f"POOL_DB_PATH={db}".encode() in environment
        if ours and parent_of(int(entry.name)) is not None:
            found.append(int(entry.name))
    return found


def computer_thinking(port: int, db: Path) -> list[int]:
    """Ana breaks against the computer, then plays soft taps until it is the computer's turn;
    returns its planners once it is planning."""
    http = httpx.Client(base_url=f"http://127.0.0.1:{port}", timeout=20)
    room = http.post("/api/rooms", json={"game": "eight_ball", "opponent": "beginner"}).json()
    ana = http.post(f"/api/rooms/{room['room_id']}/join", json={"name": "Ana"}).json()
    shot = BREAK_MESSAGE
    with connect(ws_url(f"127.0.0.1:{port}", room["room_id"], ana["token"])) as ws:
        deadline = time.monotonic() + 60
        while not planners_over(db):
            assert time.monotonic() < deadline, "the computer never started planning"
            try:
                message = ws.recv(timeout=0.2)
            except TimeoutError:
                continue
            state = json.loads(message) if isinstance(message, str) else {}
            match = state.get("match") or {}
            ours = match.get("turn") == 0 and match.get("decision") is None
            if state.get("type") == "state" and state["phase"] == "aiming" and ours:
                ws.send(json.dumps(shot))
                shot = {"type": "shoot", "angle": 0.0, "speed": 0.2}
    return planners_over(db)


@pytest.mark.parametrize("how", [signal.SIGTERM, signal.SIGKILL], ids=["sigterm", "kill-9"])
def test_planners_end_with_their_server(tmp_path: Path, how: signal.Signals):
    port, db = free_port(), tmp_path / "pool.db"
    with server_process(port, db) as process:
        assert computer_thinking(port, db)
        process.send_signal(how)
        process.wait(60)
    # Stopped, the server waited for them; killed, they look for it every PARENT_CHECK s
    # (one that was still starting, too).
    until(lambda: not planners_over(db), 5 * PARENT_CHECK + 10, "a planner outlived its server")
