"""A crowd in one room while two players play on a real server: 150 spectators chatting
and 30 reconnecting in a loop close no player socket, and every shot's result reaches both
players; one address reconnecting in a loop is refused past its quota. (How late the
players' tables start under such a crowd is measured by `python -m bench.crowd`.)

Each member of a crowd connects from a loopback address of its own (127.0.x.y all reach
the local host), as the people of a real crowd would: the per-address quota of spectator
sockets is tested on its own."""

from __future__ import annotations

import asyncio
import json
from pathlib import Path
from urllib.request import Request, urlopen

import pytest
from websockets.asyncio.client import connect
from websockets.exceptions import ConnectionClosed, InvalidStatus

from server.app import create_app
from server.config import Settings
from server.rooms import SeedSource
from tests.support.embedded import bound_socket, serving
from tests.support.messages import decoded

pytestmark = pytest.mark.timeout(240)
SHOTS = 4
CHATTERS = 150
CHURNERS = 30


async def player(
    url: str,
    seat: int,
    plays: asyncio.Event,
    stop: asyncio.Event,
    results: list[int],
    closes: list[object],
) -> None:
    """Plays whenever it is this seat's turn (answering any decision with its first
    option); counts the results it receives."""
    synced = placed = False
    try:
        async with connect(url, max_size=2**22) as ws:
            while not stop.is_set():
                if plays.is_set() and not synced:
                    synced = True
                    await ws.send(json.dumps({"type": "sync"}))
                try:
                    message = decoded(await asyncio.wait_for(ws.recv(), 0.5))
                except TimeoutError:
                    continue
                if message["type"] == "shot_result":
                    results.append(message["shot"])
                    placed = False
                if not (plays.is_set() and message["type"] == "state"):
                    continue
                match = message["match"]
                if message["phase"] != "aiming" or match is None:
                    continue
                decision = match["decision"]
                if decision is not None:
                    if decision["seat"] == seat:
                        await ws.send(
                            json.dumps({"type": "decide", "option": decision["options"][0]})
                        )
                    continue
                if match["turn"] != seat:
                    continue
                if match["ball_in_hand"] and not placed:  # the ball may stay in hand
                    placed = True
                    await ws.send(json.dumps({"type": "place_cue", "x": 0.5, "y": 0.6}))
                    continue
                await ws.send(
                    json.dumps({"type": "shoot", "angle": 0.4 * len(results), "speed": 4.0})
                )
    except ConnectionClosed as exc:
        closes.append((exc.rcvd.code, exc.rcvd.reason) if exc.rcvd else None)


def fan_address(i: int) -> tuple[str, int]:
    """A source address of its own for the `i`th member of a crowd (any free port)."""
    return (f"127.0.{1 + i // 250}.{1 + i % 250}", 0)


async def chatter(url: str, stop: asyncio.Event, i: int) -> None:
    async with connect(url, local_addr=fan_address(i)) as ws:
        n = 0
        while not stop.is_set():
            await ws.send(json.dumps({"type": "chat", "text": f"fan {i} says {n}"}))
            n += 1
            try:  # as fast as a spectator may (2 messages a second), reading meanwhile
                while True:
                    await asyncio.wait_for(ws.recv(), 0.55)
            except TimeoutError:
                pass


async def churner(url: str, stop: asyncio.Event, i: int) -> None:
    while not stop.is_set():
        try:
            async with connect(url, local_addr=fan_address(i)) as ws:
                await ws.recv()
        except InvalidStatus:  # past this address's quota: refused, after a delay
            pass


class Players:
    """Ana and Ben playing in `base` (once `plays` is set) until `until` has their results."""

    def __init__(self, base: str, tokens: list[str]) -> None:
        self.stop, self.plays = asyncio.Event(), asyncio.Event()
        self.results: list[int] = []
        self.closes: list[object] = []
        self.tasks = [
            asyncio.create_task(
                player(f"{base}?token={t}", i, self.plays, self.stop, self.results, self.closes)
            )
            for i, t in enumerate(tokens)
        ]

    async def until(self, results: int) -> None:
        """Wait (a minute at most) for `results` results or a closed player, then stop."""
        for _ in range(600):
            if len(self.results) >= results or self.closes:
                break
            await asyncio.sleep(0.1)
        self.stop.set()
        await asyncio.gather(*self.tasks, return_exceptions=True)


async def crowd(address: str, room_id: str, tokens: list[str]) -> tuple[list[int], list[object]]:
    base = f"ws://{address}/ws/rooms/{room_id}"
    players = Players(base, tokens)
    stop = players.stop
    fans = [asyncio.create_task(chatter(base, stop, i)) for i in range(CHATTERS)]
    fans += [asyncio.create_task(churner(base, stop, CHATTERS + i)) for i in range(CHURNERS)]
    await asyncio.sleep(2.0)  # the crowd is in
    players.plays.set()
    await players.until(2 * SHOTS)
    await asyncio.gather(*fans, return_exceptions=True)
    return players.results, players.closes


def seated_on(address: str) -> tuple[str, list[str]]:
    """An 8-ball room without a clock on the real server, Ana and Ben seated."""

    def post(path: str, body: dict) -> dict:
        request = Request(
            f"http://{address}{path}",
            json.dumps(body).encode(),
            {"content-type": "application/json"},
        )
        return json.loads(urlopen(request, timeout=10).read())

    room_id = post("/api/rooms", {"game": "eight_ball", "shot_clock": 0})["room_id"]
    return room_id, [
        post(f"/api/rooms/{room_id}/join", {"name": n})["token"] for n in ("Ana", "Ben")
    ]


@pytest.mark.slow  # many seconds: not in scripts/test --quick
def test_a_chatting_churning_crowd_closes_no_player(tmp_path: Path):
    settings = Settings(
        web_dir=tmp_path,
        db_path=tmp_path / "pool.db",
        pace=4.0,
        max_spectators=CHATTERS + CHURNERS + 10,
        shot_clock=0.0,
    )
    app = create_app(settings, seeds=SeedSource.fixed(5))
    with serving(app, settings, bound_socket()) as address:
        room_id, tokens = seated_on(address)
        results, closes = asyncio.run(crowd(address, room_id, tokens))
    assert closes == []  # no player was closed
    shots = sorted(set(results))
    assert len(shots) >= SHOTS - 1 and all(results.count(s) == 2 for s in shots[:-1])


async def burst(address: str, room_id: str, tokens: list[str]) -> tuple[list[int], list[object]]:
    """70 spectators chat at the same instant, then 200 connect and vanish without a close
    frame, while the players play on."""
    base = f"ws://{address}/ws/rooms/{room_id}"
    players = Players(base, tokens)
    fans = [await connect(base, local_addr=fan_address(i)) for i in range(70)]
    players.plays.set()
    await asyncio.gather(*(ws.send(json.dumps({"type": "chat", "text": "now!"})) for ws in fans))
    for i in range(200):
        ws = await connect(base, local_addr=fan_address(70 + i))
        ws.transport.abort()  # gone, no close handshake
    await players.until(4)
    await asyncio.gather(*(ws.close() for ws in fans), return_exceptions=True)
    return players.results, players.closes


@pytest.mark.slow  # many seconds: not in scripts/test --quick
def test_a_chat_burst_and_a_crowd_vanishing_close_no_player(tmp_path: Path):
    settings = Settings(
        web_dir=tmp_path, db_path=tmp_path / "pool.db", pace=4.0, max_spectators=300, shot_clock=0.0
    )
    with serving(
        create_app(settings, seeds=SeedSource.fixed(5)), settings, bound_socket()
    ) as address:
        room_id, tokens = seated_on(address)
        results, closes = asyncio.run(burst(address, room_id, tokens))
    assert closes == []
    shots = sorted(set(results))  # the last one may be stopped between the two players
    assert len(shots) >= 2 and all(results.count(s) == 2 for s in shots[:-1])


async def reconnecting(base: str, times: int, address: str) -> list[object]:
    """Open and close a spectator socket `times` times from `address`: the first message
    each time, or the refusal's HTTP status."""
    seen: list[object] = []
    for _ in range(times):
        try:
            async with connect(base, local_addr=(address, 0)) as ws:
                seen.append(json.loads(await ws.recv())["type"])
        except InvalidStatus as exc:
            seen.append(exc.response.status_code)
    return seen


@pytest.mark.slow  # many seconds: not in scripts/test --quick
def test_one_address_reconnecting_in_a_loop_is_refused_past_its_quota(tmp_path: Path):
    settings = Settings(
        web_dir=tmp_path, db_path=tmp_path / "pool.db", watch_rate="10/minute", shot_clock=0.0
    )
    with serving(create_app(settings), settings, bound_socket()) as address:
        room_id, tokens = seated_on(address)
        base = f"ws://{address}/ws/rooms/{room_id}"

        async def scenario() -> tuple[list[object], list[object], str]:
            looping = await reconnecting(base, 14, "127.0.0.1")
            elsewhere = await reconnecting(base, 1, "127.0.0.2")
            async with connect(f"{base}?token={tokens[0]}", local_addr=("127.0.0.1", 0)) as ws:
                player = json.loads(await ws.recv())["type"]
            return looping, elsewhere, player

        looping, elsewhere, player = asyncio.run(scenario())
    assert looping == ["welcome"] * 10 + [403] * 4
    assert elsewhere == ["welcome"]  # another address is not held back
    assert player == "welcome"  # a player's socket, with its token, is never counted
