"""SIGTERM and kill -9 of a real server process at 20 moments of shots (a fixed draw: right
after the strike, while the shot rolls, just after its result): after every restart the
players reconnect with their tokens and play on, and at the end the history has every shot
exactly once, numbered without a gap, each with the outcome the players were shown."""

from __future__ import annotations

import asyncio
import json
import math
import random
import signal
import subprocess
from pathlib import Path
from typing import Any

import httpx
import pytest
import websockets

from tests.support.games import BREAK_MESSAGE
from tests.support.live import ws_url
from tests.support.ports import free_port
from tests.support.process import server_process
from tests.support.rooms import seated_room

pytestmark = [pytest.mark.timeout(600), pytest.mark.slow]
MOMENTS = 20
FREE_SPOTS = ((0.5, 0.4), (0.3, 1.0), (0.45, 0.9), (0.2, 0.2), (0.55, 0.6), (0.1, 0.6))


class Player:
    """One seat's socket; reads JSON messages (binary motion frames are skipped: this test
    is about what is recorded, not how it is drawn) and keeps every `shot_result`."""

    def __init__(self, ws: Any, results: dict[int, dict]) -> None:
        self.ws = ws
        self.results = results
        self.state: dict = {}

    @classmethod
    async def connect(cls, address: str, room: str, token: str, results: dict) -> Player:
        player = cls(await websockets.connect(ws_url(address, room, token)), results)
        await player.until("state")
        return player

    async def until(self, kind: str) -> dict:
        while True:
            raw = await asyncio.wait_for(self.ws.recv(), 30)
            if isinstance(raw, bytes):
                continue
            message = json.loads(raw)
            if message["type"] == "shot_result":
                self.results[message["shot"]] = message["outcome"]
            elif message["type"] == "state":
                self.state = message
            if message["type"] in ("error", kind):
                return message

    async def send(self, message: dict) -> None:
        await self.ws.send(json.dumps(message))


async def settle(players: list[Player]) -> int:
    """Wait until no shot rolls (a shot cut by the stop is played again after a restart)
    and answer whatever the table asks for, until the seat to play may shoot; returns the
    shooter's index."""
    watcher = players[0]
    while True:
        state = watcher.state
        if state["phase"] == "rolling":
            await watcher.until("state")
            continue
        match = state["match"]
        if state["phase"] == "over":
            for p in players:
                await p.send({"type": "rematch"})
            await watcher.until("state")
            continue
        if match["decision"] is not None:
            decider = players[match["decision"]["seat"]]
            await decider.send({"type": "decide", "option": match["decision"]["options"][0]})
            await decider.until("state")
            watcher.state = decider.state
            continue
        shooter = players[match["turn"]]
        if not any(row[0] == 0 for row in state["balls"]):
            for x, y in FREE_SPOTS:
                await shooter.send({"type": "place_cue", "x": x, "y": y})
                if (await shooter.until("state"))["type"] == "state":
                    break
            watcher.state = shooter.state
            continue
        if match["requires_call"] and match.get("called") is None:
            await shooter.send({"type": "call", "pocket": 2})
            await shooter.until("state")
        return match["turn"]


async def play_round(
    address: str, room: str, tokens: list[str], results: dict, draw: random.Random, kill: bool
) -> None:
    """Reconnect, let the shot the last stop cut play out (a restart plays it again from its
    stored start), strike the next shot and return at this stop's moment, for the caller
    to stop the server (`kill` False: the shot is played to its end)."""
    players = [await Player.connect(address, room, t, results) for t in tokens]
    try:
        shooter = players[await settle(players)]
        angle, speed = draw.uniform(-math.pi, math.pi), draw.uniform(1.5, 4.0)
        shot = {"type": "shoot", "angle": angle, "speed": speed} if results else BREAK_MESSAGE
        moment, delay = draw.choice(("strike", "rolling", "result")), draw.uniform(0.0, 0.5)
        await shooter.send(shot)
        if moment == "rolling" and kill:
            await asyncio.sleep(delay)
        elif moment == "result" or not kill:
            await players[0].until("shot_result")
    finally:
        for p in players:
            await p.ws.close()


def stop(process: subprocess.Popen, how: signal.Signals) -> None:
    process.send_signal(how)
    process.wait(60)


def test_sigterm_and_kill_at_20_moments_leave_every_shot_in_the_history_once(
    tmp_path: Path,
) -> None:
    port, db = free_port(), tmp_path / "billiards.db"
    draw = random.Random(20)
    results: dict[int, dict] = {}
    address = f"127.0.0.1:{port}"
    signals = []
    for moment in range(MOMENTS + 1):
        with server_process(port, db) as process:
            if moment == 0:
                with httpx.Client(base_url=f"http://{address}", timeout=20) as client:
                    room, ta, tb = seated_room(client, "eight_ball", race_to=9, shot_clock=0)
            final = moment == MOMENTS
            asyncio.run(play_round(address, room, [ta, tb], results, draw, kill=not final))
            if final:
                with httpx.Client(base_url=f"http://{address}", timeout=20) as client:
                    history = history_of(client, room)
                stop(process, signal.SIGTERM)
            else:
                how = signal.SIGKILL if moment % 2 else signal.SIGTERM
                signals.append(how)
                stop(process, how)
    assert signals.count(signal.SIGKILL) == signals.count(signal.SIGTERM) == MOMENTS // 2

    shots = [shot for match in history for shot in match]
    numbers = [(s["match"], s["n"]) for s in shots]
    assert len(set(numbers)) == len(numbers)  # no shot twice
    for match in history:
        assert [s["n"] for s in match] == list(range(1, len(match) + 1))  # no gap
    room_shots = [s["shot_id"] for s in shots]
    assert room_shots == list(range(1, len(room_shots) + 1))  # every room shot, in order, once
    assert set(results) <= set(room_shots)  # every shot a player saw is in the history
    assert len(room_shots) >= MOMENTS // 2  # shots cut before they were saved may be lost
    for s in shots:
        if s["shot_id"] in results:
            seen = results[s["shot_id"]]
            assert s["outcome"]["pocketed"] == seen["pocketed"]
            assert s["outcome"]["fouls"] == seen["fouls"]


def history_of(client: httpx.Client, room: str) -> list[list[dict]]:
    """The shots of each match the room played, oldest match first."""
    listed = client.get("/api/matches", params={"limit": 50}).json()["matches"]
    ids = sorted(m["id"] for m in listed if m["room_id"] == room)
    out = []
    for match_id in ids:
        detail = client.get(f"/api/matches/{match_id}").json()
        out.append([{**s, "match": match_id} for s in detail["shots"]])
    return out
