"""Reading what a room sends, on any socket with `send_json` and `receive_json`: a
TestClient WebSocket session (`rooms.connect`), or `JsonSocket` around a `websockets` client
of a real server. A shot's binary `motion` message comes back decoded, as a dict
(`protocol.motion.decode_motion`), so a stream reads as one list of messages."""

from __future__ import annotations

import json
from collections.abc import Callable, Iterable
from typing import Any, Protocol

from server.protocol.motion import decode_motion
from server.protocol.outbound import replay_messages, server_messages


class Socket(Protocol):
    def send_json(self, data: Any) -> None: ...
    def receive_json(self) -> Any: ...


class JsonSocket:
    """A `websockets.sync` client connection with a TestClient socket's two methods."""

    def __init__(self, connection: Any, timeout: float = 30.0) -> None:
        self.connection = connection
        self.timeout = timeout

    def send_json(self, data: Any) -> None:
        self.connection.send(json.dumps(data))

    def receive_json(self) -> Any:
        return decoded(self.connection.recv(timeout=self.timeout))


def decoded(data: str | bytes) -> Any:
    """A received WebSocket message: JSON text, or the binary `motion` message."""
    return decode_motion(data) if isinstance(data, bytes) else json.loads(data)


def receive_any(session: Any) -> Any:
    """`receive_json` for a TestClient session that may also get binary messages."""
    message = session.receive()
    session._raise_on_close(message)
    text = message.get("text")
    return decoded(text if text is not None else message["bytes"])


def receive_until(ws: Socket, kind: str | Iterable[str], limit: int = 5000) -> list[dict]:
    """Messages up to and including the first whose type is `kind` (or one of them)."""
    kinds = {kind} if isinstance(kind, str) else set(kind)
    out = []
    for _ in range(limit):
        message = ws.receive_json()
        out.append(message)
        if message["type"] in kinds:
            return out
    raise AssertionError(f"no {kind} within {limit} messages")


def state_where(ws: Socket, predicate: Callable[[dict], bool], limit: int = 50) -> dict:
    """The first `state` that satisfies `predicate` (earlier ones are skipped)."""
    for _ in range(limit):
        state = receive_until(ws, "state")[-1]
        if predicate(state):
            return state
    raise AssertionError(f"no such state within {limit} states")


def greet(ws: Socket) -> tuple[dict, dict]:
    """Read the `welcome`, `state` and own `presence` every new connection gets first."""
    welcome = ws.receive_json()
    assert welcome["type"] == "welcome"
    state = ws.receive_json()
    assert state["type"] == "state" and state["seq"] == welcome["seq"]
    presence = ws.receive_json()
    assert presence["type"] == "presence" and presence["seq"] == welcome["seq"] + 1
    return welcome, state


def drain_presence(ws: Socket, count: int) -> None:
    """Read the `presence` messages of `count` members who connected after this one."""
    for _ in range(count):
        assert ws.receive_json()["type"] == "presence"


def roundtrip(ws: Any, payload: dict | str) -> list[dict]:
    """Send, then a ping; returns what came back before the pong (proves the socket lives).
    (TestClient sockets only: they take text as it is.)"""
    ws.send_text(payload if isinstance(payload, str) else json.dumps(payload))
    ws.send_text('{"type": "ping", "id": 99}')
    got = receive_until(ws, "pong")
    assert got[-1]["id"] == 99
    return got[:-1]


def errors_in(messages: list[dict]) -> list[dict]:
    return [m for m in messages if m["type"] == "error"]


def of_type(messages: list[dict], kind: str) -> list[dict]:
    return [m for m in messages if m["type"] == kind]


def motions(stream: list[dict]) -> list[dict]:
    """The decoded `motion` messages of a stream."""
    return [m for m in stream if m["type"] == "motion"]


def shot_payload(message: dict) -> dict:
    """A streamed message without its room sequence number."""
    return {k: v for k, v in message.items() if k != "seq"}


def is_subsequence(part: list, whole: list) -> bool:
    it = iter(whole)
    return all(any(x == y for y in it) for x in part)


def assert_valid(messages: Iterable[dict], replay: bool = False) -> None:
    """Each message is one of the server's message models (of a replay stream's, when
    `replay`), and the model is the one its `type` names."""
    adapter = replay_messages if replay else server_messages
    for m in messages:
        if m["type"] == "motion" and not replay:
            continue  # binary, checked byte by byte by its own tests
        model = adapter.validate_python(m)
        assert model.type == m["type"], m  # type: ignore[union-attr]
