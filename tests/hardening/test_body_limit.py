"""Request bodies are capped before anything parses them: a declared size over
`max_body_bytes` is refused at once with 413, a chunked one as soon as it passes the cap."""

from __future__ import annotations

import socket
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from server.config import Settings
from tests.support.live import http, live_server
from tests.support.rooms import app_with
from tests.support.settings import settings_in

pytestmark = pytest.mark.timeout(120)
LIMIT = 4096
BIG = 20 * 1024 * 1024
JSON = {"content-type": "application/json"}


@pytest.fixture
def settings(tmp_path: Path) -> Settings:
    return settings_in(tmp_path, max_body_bytes=LIMIT)


@pytest.fixture
def client(settings: Settings) -> Iterator[TestClient]:
    with TestClient(app_with(settings)) as c:
        yield c


def padded(size: int) -> bytes:
    """A room body of `size` bytes (a valid one, but for its padding)."""
    head = b'{"game": "practice", "listed": false}'
    return head[:-1] + b" " * (size - len(head)) + b"}"


def refused(status: int, body: dict) -> bool:
    return status == 413 and body["detail"]["code"] == "body_too_large"


def test_a_declared_size_over_the_cap_is_refused(client: TestClient):
    response = client.post("/api/rooms", content=padded(LIMIT + 1), headers=JSON)
    assert refused(response.status_code, response.json())
    assert str(LIMIT) in response.json()["detail"]["message"]
    assert response.headers["connection"] == "close"
    assert client.post("/api/rooms", content=padded(LIMIT), headers=JSON).status_code == 201


def test_a_chunked_body_is_counted_as_it_arrives(client: TestClient):
    sent = []

    def chunks() -> Iterator[bytes]:
        body = padded(LIMIT * 4)
        for i in range(0, len(body), 1000):
            sent.append(i)
            yield body[i : i + 1000]

    response = client.post("/api/rooms", content=chunks(), headers=JSON)
    assert refused(response.status_code, response.json())
    assert sent  # (TestClient reads a generator whole: the real server's test shows the rest)
    small = client.post("/api/rooms", content=iter([padded(LIMIT)]), headers=JSON)
    assert small.status_code == 201, small.text


def test_the_setting_has_bounds():
    with pytest.raises(ValueError):
        Settings(max_body_bytes=10)
    with pytest.raises(ValueError):
        Settings(max_body_bytes=1 << 30)
    assert Settings().max_body_bytes == 64 * 1024


def _post_raw(address: str, head: bytes, body: Iterator[bytes]) -> tuple[bytes, float, int]:
    """Send a request by hand until the server stops taking it; (its answer, seconds to it,
    bytes of the body that were sent)."""
    host, port = address.split(":")
    started = time.monotonic()
    sent = 0
    with socket.create_connection((host, int(port)), timeout=20) as sock:
        sock.sendall(head)
        try:
            for chunk in body:
                sock.sendall(chunk)
                sent += len(chunk)
        except (BrokenPipeError, ConnectionResetError, TimeoutError):
            pass  # the server answered and closed: the rest was never read
        answer = b""
        try:
            while chunk := sock.recv(65536):
                answer += chunk
        except (ConnectionResetError, TimeoutError):
            pass
    return answer, time.monotonic() - started, sent


def test_a_real_server_refuses_20_mb_at_once(tmp_path: Path):
    settings = settings_in(tmp_path)  # the default cap, 64 KB
    piece = b" " * 65536
    with live_server(settings) as address:
        head = (
            f"POST /api/rooms HTTP/1.1\r\nHost: {address}\r\nContent-Type: application/json\r\n"
            f"Content-Length: {BIG}\r\n\r\n"
        ).encode()
        answer, seconds, sent = _post_raw(address, head, iter([piece] * (BIG // len(piece))))
        assert answer.startswith(b"HTTP/1.1 413"), answer[:200]
        assert b"body_too_large" in answer
        assert seconds < 5 and sent < BIG
        chunked = (
            f"POST /api/rooms HTTP/1.1\r\nHost: {address}\r\nContent-Type: application/json\r\n"
            "Transfer-Encoding: chunked\r\n\r\n"
        ).encode()
        framed = b"%x\r\n%s\r\n" % (len(piece), piece)
        answer, seconds, sent = _post_raw(address, chunked, iter([framed] * (BIG // len(piece))))
        assert answer.startswith(b"HTTP/1.1 413"), answer[:200]
        assert seconds < 5 and sent < BIG
        with http(address) as client:  # the server took nothing amiss
            assert client.post("/api/rooms", json={"game": "practice"}).status_code == 201
