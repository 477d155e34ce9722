"""Crowds cannot hurt the players: chat credits per sender, a cap on spectators, presence
summed up, and social messages that give way to the game's in every outbox."""

from __future__ import annotations

import asyncio
from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from starlette.websockets import WebSocketDisconnect

from server.app import create_app
from server.config import Settings
from server.rooms import SeedSource
from server.rooms.connection import CLOSE_TOO_SLOW, Connection

pytestmark = pytest.mark.timeout(120)


@pytest.fixture
def settings(tmp_path: Path) -> Settings:
    return Settings(
        web_dir=tmp_path,
        db_path=tmp_path / "pool.db",
        pace=20.0,
        presence_interval=0.0,
        max_spectators=3,
        spectator_chat_burst=2,
        spectator_chat_per_second=0.01,
        player_chat_burst=4,
        player_chat_per_second=0.01,
        rate_burst=1000,
        spectator_rate_burst=1000,
    )


@pytest.fixture
def client(settings: Settings) -> Iterator[TestClient]:
    with TestClient(create_app(settings, seeds=SeedSource.fixed(5))) as c:
        yield c


def seated(client: TestClient) -> tuple[str, list[str]]:
    room_id = client.post("/api/rooms", json={"game": "eight_ball", "race_to": 3}).json()["room_id"]
    tokens = [
        client.post(f"/api/rooms/{room_id}/join", json={"name": n}).json()["token"]
        for n in ("Ana", "Ben")
    ]
    return room_id, tokens


def until(ws, kind: str) -> list[dict]:
    got = []
    while True:
        got.append(ws.receive_json())
        if got[-1]["type"] == kind:
            return got


def ping(ws) -> list[dict]:
    ws.send_json({"type": "ping", "id": 1})
    return until(ws, "pong")[:-1]


def test_chat_credits_per_sender_spectators_fewer(client: TestClient):
    room_id, tokens = seated(client)
    with (
        client.websocket_connect(f"/ws/rooms/{room_id}?token={tokens[0]}") as ana,
        client.websocket_connect(f"/ws/rooms/{room_id}") as fan,
    ):
        for ws in (ana, fan):
            ping(ws)
        fan_codes = []
        for i in range(4):
            fan.send_json({"type": "chat", "text": f"go {i}"})
            fan_codes.append([m.get("code") for m in ping(fan) if m["type"] == "error"])
        # told once; the rest of the streak is dropped without a reply (and not broadcast)
        assert fan_codes == [[], [], ["chat_rate_limited"], []]
        heard = [m["text"] for m in ping(ana) if m["type"] == "chat"]
        assert heard == ["go 0", "go 1"]
        ana_codes = []
        for i in range(6):
            ana.send_json({"type": "chat", "text": f"gl {i}"})
            ana_codes.append([m.get("code") for m in ping(ana) if m["type"] == "error"])
        assert ana_codes == [[]] * 4 + [["chat_rate_limited"], []]


def test_spectators_per_room_are_capped_with_a_clear_reason(client: TestClient):
    room_id, tokens = seated(client)
    watchers = [client.websocket_connect(f"/ws/rooms/{room_id}") for _ in range(3)]
    for ws in watchers:
        ws.__enter__()
        ping(ws)
    with (
        pytest.raises(WebSocketDisconnect) as refused,
        client.websocket_connect(f"/ws/rooms/{room_id}") as extra,
    ):
        extra.receive_json()
    assert (refused.value.code, refused.value.reason) == (1008, "room_crowded")
    with client.websocket_connect(f"/ws/rooms/{room_id}?token={tokens[1]}") as ben:
        assert ben.receive_json()["type"] == "welcome"  # players always get in
    for ws in watchers:
        ws.__exit__(None, None, None)


def test_a_stale_concession_is_refused(client: TestClient):
    room_id, tokens = seated(client)
    with (
        client.websocket_connect(f"/ws/rooms/{room_id}?token={tokens[0]}") as ana,
        client.websocket_connect(f"/ws/rooms/{room_id}?token={tokens[1]}") as ben,
    ):
        ping(ana), ping(ben)
        ana.send_json({"type": "concede", "game": 1})
        result = until(ana, "shot_result")[-1]
        assert result["cause"] == "concede" and result["score"] == [0, 1]
        ben.send_json({"type": "concede", "game": 1})  # sent before game 1 ended
        errors = [m for m in ping(ben) if m["type"] == "error"]
        assert [e["code"] for e in errors] == ["stale_action"]
        state = ping(ana)  # nothing changed for anyone
        assert all(m["type"] != "shot_result" for m in state)


def test_social_messages_never_cost_a_player_the_game_or_the_socket():
    async def scenario() -> tuple[Connection, list[str]]:
        sent: list[str] = []

        async def stuck(text: str) -> None:  # a player whose network is slow right now
            sent.append(text)

        conn = Connection(stuck, seat=0, name="Ana", limit=16)
        for i in range(1000):
            conn.push(f"chat {i}", social=True)
            if i % 10 == 0:
                conn.push(f"frame {i}", droppable=True)
            if i % 100 == 0:
                conn.push(f"state {i}")
        return conn, sent

    conn, _ = asyncio.run(scenario())
    queued = [text for text, _ in conn._queue]
    assert conn.close_code is None
    assert [t for t in queued if t.startswith("state")] == [
        f"state {i}" for i in range(0, 1000, 100)
    ]
    assert sum(t.startswith("chat") for t in queued) <= 16 // 4
    game_only = Connection(lambda _text: asyncio.sleep(0), seat=0, name="Ana", limit=4)
    for i in range(5):
        game_only.push(f"state {i}")
    assert game_only.close_code == CLOSE_TOO_SLOW  # only the game's own backlog closes


def test_a_flood_close_still_delivers_the_replies_owed(tmp_path: Path):
    """A spectator only chats and syncs: its budget is smaller than a player's (a crowd
    sending as fast as it may costs the server little). Past it the socket is closed 1008,
    after the replies it is owed; a player sending as much stays."""
    settings = Settings(
        web_dir=tmp_path,
        db_path=tmp_path / "pool.db",
        rate_burst=20,
        rate_per_second=0.01,
        spectator_rate_burst=5,
        spectator_rate_per_second=0.01,
        presence_interval=0.0,
    )
    with TestClient(create_app(settings, seeds=SeedSource.fixed(5))) as client:
        room_id, tokens = seated(client)
        with (
            client.websocket_connect(f"/ws/rooms/{room_id}?token={tokens[0]}") as ana,
            client.websocket_connect(f"/ws/rooms/{room_id}") as fan,
        ):
            for i in range(8):
                ana.send_json({"type": "ping", "id": i})
            assert pongs_into([], ana, 8) == list(range(8))  # still open
            for i in range(6):  # the sixth is one too many
                fan.send_json({"type": "ping", "id": i})
            pongs: list[int] = []
            with pytest.raises(WebSocketDisconnect) as closed:
                pongs_into(pongs, fan)
    assert pongs == [0, 1, 2, 3, 4]
    assert (closed.value.code, closed.value.reason) == (1008, "rate_limited")


def pongs_into(ids: list[int], ws, count: int | None = None) -> list[int]:
    """Add the ids of the pongs `ws` receives to `ids` (other messages skipped) until there
    are `count` (None: until the socket closes, which raises)."""
    while count is None or len(ids) < count:
        message = ws.receive_json()
        if message["type"] == "pong":
            ids.append(message["id"])
    return ids
