"""Hints through the real API share the planners fairly: a flood of them from one address,
or from many, never puts more than the one hint under way ahead of the computer's turn in
another room; each address holds one hint at a time; the queue is bounded; a hint whose
client left before it started is never planned.

The planner is a stand-in (`OnePlanner`, patched over `plan_turn`): one process serving its
queue in order, as `POOL_COMPUTER_WORKERS=1` does, each hint taking a fixed time. What the
tests count is the order it ran things in, not the wall clock."""

from __future__ import annotations

import asyncio
import json
import logging
import threading
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import httpx
import pytest
import websockets

from server.ai import Turn
from server.engine import Shot
from server.rooms import computer
from tests.support.games import BREAK_MESSAGE
from tests.support.live import live_server, recv, send, ws_url
from tests.support.settings import settings_in

pytestmark = pytest.mark.timeout(120)
HINT_SECONDS = 0.4  # a hint's plan in the stand-in planner (a real one takes up to ~3 s)
real_plan_turn = computer.plan_turn


class OnePlanner:
    """One planner process: plans run one at a time in the order handed in. The computer's
    plans are the real ones; a hint is a fixed turn after `HINT_SECONDS`."""

    def __init__(self) -> None:
        self.lock: asyncio.Lock | None = None
        self.log: list[tuple[str, str]] = []  # ("ask" | "run", "hint" | "computer")
        # a hint also waits for `hold` when there is one (the server runs in its own thread)
        self.hold: threading.Event | None = None

    async def plan_turn(self, level: str, *args: Any) -> Turn:
        kind = "hint" if level == computer.HINT_LEVEL else "computer"
        self.lock = self.lock or asyncio.Lock()
        self.log.append(("ask", kind))
        async with self.lock:
            self.log.append(("run", kind))
            if kind == "computer":
                return await real_plan_turn(level, *args)
            await asyncio.sleep(HINT_SECONDS)
            if self.hold is not None:
                await asyncio.to_thread(self.hold.wait, 60)
            return Turn(place=(0.5, 0.6), shot=Shot(0.0, 3.0), kind="pot", target=1, pocket=0)

    def ahead_of_the_computer(self) -> list[int]:
        """For each computer plan: the hints that started between its ask and its run."""
        counts, waiting = [], None
        for event, kind in self.log:
            if (event, kind) == ("ask", "computer"):
                waiting = 0
            elif (event, kind) == ("run", "computer") and waiting is not None:
                counts.append(waiting)
                waiting = None
            elif (event, kind) == ("run", "hint") and waiting is not None:
                waiting += 1
        return counts


@pytest.fixture
def planner(monkeypatch: pytest.MonkeyPatch) -> OnePlanner:
    stand_in = OnePlanner()
    monkeypatch.setattr(computer, "plan_turn", stand_in.plan_turn)
    return stand_in


class Errors(logging.Handler):
    def __init__(self) -> None:
        super().__init__(logging.ERROR)
        self.records: list[logging.LogRecord] = []

    def emit(self, record: logging.LogRecord) -> None:
        self.records.append(record)


@pytest.fixture
def address(tmp_path: Path) -> Iterator[str]:
    """A real server; it must log no error (an "Exception in ASGI application")."""
    settings = settings_in(
        tmp_path, computer_workers=1, computer_pause=0.0, shot_clock=600.0, hint_queue=4
    )
    errors = Errors()
    logger = logging.getLogger("uvicorn.error")
    with live_server(settings) as where:
        logger.addHandler(errors)  # after uvicorn configured its loggers
        try:
            yield where
        finally:
            logger.removeHandler(errors)
    assert [r.getMessage() for r in errors.records] == []


def client_at(address: str, source: str) -> httpx.AsyncClient:
    """An HTTP client of the server from the loopback address `source` (127.0.0.x)."""
    transport = httpx.AsyncHTTPTransport(local_address=source)
    return httpx.AsyncClient(base_url=f"http://{address}", transport=transport, timeout=30)


async def practice_table(http: httpx.AsyncClient) -> tuple[str, str]:
    room = (await http.post("/api/rooms", json={"game": "practice", "listed": False})).json()
    seat = (await http.post(f"/api/rooms/{room['room_id']}/join", json={"name": "Pia"})).json()
    return room["room_id"], seat["token"]


async def ask_hint(http: httpx.AsyncClient, table: tuple[str, str]) -> tuple[int, str]:
    reply = await http.post(f"/api/rooms/{table[0]}/hint", json={"token": table[1]})
    body = reply.json()
    return reply.status_code, body["detail"]["code"] if reply.status_code != 200 else "ok"


async def computer_shoots(address: str) -> None:
    """Ana plays the club level until the computer has played a shot."""
    async with httpx.AsyncClient(base_url=f"http://{address}", timeout=30) as http:
        room = await http.post(
            "/api/rooms", json={"game": "eight_ball", "opponent": "club", "listed": False}
        )
        room_id = room.json()["room_id"]
        ana = (await http.post(f"/api/rooms/{room_id}/join", json={"name": "Ana"})).json()
    async with websockets.connect(ws_url(address, room_id, ana["token"])) as ws:
        while (await recv(ws))["type"] != "presence":
            pass
        await send(ws, BREAK_MESSAGE)
        shooters: list[int] = []
        while 1 not in shooters:
            message = await recv(ws, timeout=60)
            if message["type"] == "shot_result":
                shooters.append(message["outcome"]["shooter"])
            elif message["type"] == "state" and message["phase"] == "aiming" and shooters:
                match = message["match"]
                if match["turn"] == 0 and match["decision"] is None:  # Ana again: a miss
                    if match["ball_in_hand"]:
                        await send(ws, {"type": "place_cue", "x": 0.5, "y": 0.6})
                    await ws.send(json.dumps({"type": "shoot", "angle": 2.0, "speed": 3.0}))


@pytest.mark.slow  # many seconds: not in scripts/test --quick
def test_a_hint_flood_never_puts_more_than_one_hint_ahead_of_the_computer(
    address: str, planner: OnePlanner
):
    """20 addresses keep asking for hints while a person plays the computer elsewhere."""

    async def scenario() -> list[tuple[int, str]]:
        clients = [client_at(address, f"127.0.0.{10 + i}") for i in range(20)]
        tables = [await practice_table(c) for c in clients]
        done = asyncio.Event()
        answers: list[tuple[int, str]] = []

        async def keep_asking(http: httpx.AsyncClient, table: tuple[str, str]) -> None:
            while not done.is_set():
                answers.append(await ask_hint(http, table))
                await asyncio.sleep(0.05)

        flood = [
            asyncio.create_task(keep_asking(c, t)) for c, t in zip(clients, tables, strict=True)
        ]
        await asyncio.sleep(2 * HINT_SECONDS)  # the queue is full
        await computer_shoots(address)
        done.set()
        await asyncio.gather(*flood)
        for c in clients:
            await c.aclose()
        return answers

    answers = asyncio.run(scenario())
    ahead = planner.ahead_of_the_computer()
    assert ahead and max(ahead) == 0  # the hint under way ran before the computer asked
    codes = {code for _, code in answers}
    assert {"ok", "hints_busy"} <= codes and 500 not in {s for s, _ in answers}
    assert planner.log.count(("run", "hint")) >= 2  # hints were planned too, between turns


def test_one_address_holds_one_hint_at_a_time(address: str, planner: OnePlanner):
    async def scenario() -> list[tuple[int, str]]:
        planner.hold = threading.Event()  # the first hint stays under way until 19 are answered
        async with client_at(address, "127.0.0.5") as http:
            tables = [await practice_table(http) for _ in range(20)]
            asks = [asyncio.create_task(ask_hint(http, t)) for t in tables]
            pending = set(asks)
            while len(pending) > 1:
                _, pending = await asyncio.wait(pending, return_when=asyncio.FIRST_COMPLETED)
            planner.hold.set()
            return [await a for a in asks]

    answers = asyncio.run(scenario())
    assert sorted(answers).count((200, "ok")) == 1
    assert [a for a in answers if a != (200, "ok")] == [(429, "hint_pending")] * 19
    assert planner.log.count(("run", "hint")) == 1


def test_a_hint_whose_client_left_is_not_planned(address: str, planner: OnePlanner):
    async def scenario() -> list[tuple[int, str]]:
        clients = [client_at(address, f"127.0.0.{30 + i}") for i in range(3)]
        tables = [await practice_table(c) for c in clients]
        first = asyncio.create_task(ask_hint(clients[0], tables[0]))  # under way
        await asyncio.sleep(HINT_SECONDS / 4)
        leaving = asyncio.create_task(ask_hint(clients[1], tables[1]))  # waits
        await asyncio.sleep(HINT_SECONDS / 4)
        leaving.cancel()  # the client gives up: its connection closes
        await clients[1].aclose()
        answers = [await first, await ask_hint(clients[2], tables[2])]
        for c in clients:
            await c.aclose()
        return answers

    answers = asyncio.run(scenario())
    assert answers == [(200, "ok"), (200, "ok")]
    assert planner.log.count(("run", "hint")) == 2  # the one whose client left never ran


def test_an_address_that_spent_its_planning_budget_is_refused_with_429(
    tmp_path: Path, planner: OnePlanner
):
    """`POOL_HINT_BUDGET` 0.5 s: two hints of 0.4 s spend it; the third from that address
    is refused at once (`429 planning_budget`, nothing planned), another address is served."""
    settings = settings_in(tmp_path, computer_workers=1, hint_budget=0.5)

    async def scenario(where: str) -> list[tuple[int, str]]:
        async with client_at(where, "127.0.0.6") as http, client_at(where, "127.0.0.7") as other:
            table = await practice_table(http)
            answers = [await ask_hint(http, table) for _ in range(3)]
            answers.append(await ask_hint(other, await practice_table(other)))
            return answers

    with live_server(settings) as where:
        answers = asyncio.run(scenario(where))
    assert answers == [(200, "ok"), (200, "ok"), (429, "planning_budget"), (200, "ok")]
    assert planner.log.count(("run", "hint")) == 3
