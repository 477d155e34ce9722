"""On a real server: wrong JSON types are refused, seat tokens never reach the log, and a
frame of invalid UTF-8 closes its socket with 1007 and one log line, not a traceback."""

from __future__ import annotations

import base64
import json
import logging
import os
import socket
import urllib.request
from collections.abc import Iterator
from pathlib import Path

import pytest
from websockets.sync.client import connect

from server.app import create_app
from server.config import Settings
from tests.support.embedded import bound_socket, serving

pytestmark = pytest.mark.timeout(120)


class Collect(logging.Handler):
    def __init__(self) -> None:
        super().__init__(logging.DEBUG)
        self.lines: list[str] = []

    def emit(self, record: logging.LogRecord) -> None:
        self.lines.append(self.format(record))


@pytest.fixture
def server(tmp_path: Path) -> Iterator[tuple[str, Collect]]:
    settings = Settings(web_dir=tmp_path, db_path=tmp_path / "pool.db", pace=20.0)
    collect = Collect()
    collect.setFormatter(logging.Formatter("%(levelname)s %(message)s"))
    loggers = [logging.getLogger(n) for n in ("uvicorn.error", "uvicorn.access")]
    with serving(create_app(settings), settings, bound_socket()) as address:
        for logger in loggers:  # the access log at its usual level, caught here
            logger.setLevel(logging.INFO)
            logger.addHandler(collect)
        yield address, collect
    for logger in loggers:
        logger.removeHandler(collect)


def post(address: str, path: str, body: dict) -> dict:
    request = urllib.request.Request(
        f"http://{address}{path}", json.dumps(body).encode(), {"content-type": "application/json"}
    )
    with urllib.request.urlopen(request, timeout=10) as response:
        return json.loads(response.read())


def test_tokens_never_reach_the_log(server):
    address, log = server
    room_id = post(address, "/api/rooms", {"game": "eight_ball"})["room_id"]
    tokens = [
        post(address, f"/api/rooms/{room_id}/join", {"name": n})["token"] for n in ("Ana", "Ben")
    ]
    for token in tokens:
        with connect(f"ws://{address}/ws/rooms/{room_id}?token={token}") as ws:
            assert json.loads(ws.recv(timeout=10))["type"] == "welcome"
    handshakes = [line for line in log.lines if "WebSocket /ws/rooms/" in line]
    assert len(handshakes) >= 2  # the handshakes are logged ...
    assert all("token=[redacted]" in line for line in handshakes)
    text = "\n".join(log.lines)
    assert not any(token in text for token in tokens)  # ... without their tokens


def test_wrong_json_types_are_refused_not_coerced(server):
    address, _ = server
    room_id = post(address, "/api/rooms", {"game": "practice"})["room_id"]
    token = post(address, f"/api/rooms/{room_id}/join", {"name": "Ana"})["token"]
    wrong = [
        '{"type": "shoot", "angle": "0.0", "speed": 5}',
        '{"type": "shoot", "angle": true, "speed": 5}',
        '{"type": "place_cue", "x": "0.4", "y": 0.5}',
        '{"type": "ping", "id": "7"}',
        '{"type": "call", "pocket": 1.0}',
        '{"type": "chat", "text": 5}',
    ]
    with connect(f"ws://{address}/ws/rooms/{room_id}?token={token}") as ws:
        for _ in range(3):
            ws.recv(timeout=10)  # welcome, state, presence
        for text in wrong:
            ws.send(text)
            reply = json.loads(ws.recv(timeout=10))
            assert (reply["type"], reply["code"]) == ("error", "bad_message"), text
        ws.send('{"type": "ping", "id": 7}')
        assert json.loads(ws.recv(timeout=10))["type"] == "pong"


def raw_text_frame(address: str, path: str, payload: bytes) -> bytes:
    """Open a socket by hand and send one masked text frame holding `payload`."""
    host, port = address.split(":")
    with socket.create_connection((host, int(port)), timeout=10) as sock:
        key = base64.b64encode(os.urandom(16)).decode()
        sock.sendall(
            f"GET {path} HTTP/1.1\r\nHost: {address}\r\nUpgrade: websocket\r\n"
            f"Connection: Upgrade\r\nSec-WebSocket-Key: {key}\r\n"
            "Sec-WebSocket-Version: 13\r\n\r\n".encode()
        )
        buffer = b""
        while b"\r\n\r\n" not in buffer:
            buffer += sock.recv(4096)
        mask = os.urandom(4)
        sock.sendall(
            bytes([0x81, 0x80 | len(payload)])
            + mask
            + bytes(b ^ mask[i % 4] for i, b in enumerate(payload))
        )
        received = b""
        while True:
            chunk = sock.recv(4096)
            if not chunk:
                return received
            received += chunk
            if b"\x88\x02" in received:  # a close frame with its code
                return received


def test_invalid_utf8_closes_with_1007_and_one_line(server):
    address, log = server
    room_id = post(address, "/api/rooms", {"game": "practice"})["room_id"]
    for _ in range(3):
        received = raw_text_frame(address, f"/ws/rooms/{room_id}", b"\xff\xfe\xfd")
        close = received[received.index(b"\x88\x02") :]
        assert int.from_bytes(close[2:4], "big") == 1007
    complaints = [line for line in log.lines if "Invalid UTF-8" in line]
    assert len(complaints) == 3 and all(line.startswith("WARNING") for line in complaints)
    assert not any("Traceback" in line or "UnicodeDecodeError" in line for line in log.lines)
