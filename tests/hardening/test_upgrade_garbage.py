"""WebSockets that come and go leave nothing for the cyclic garbage collector: their HTTP
protocol objects are freed by reference counting when the socket closes. (A crowd
reconnecting in a loop otherwise filled the young generation with protocol/parser cycles,
and the collector's passes stopped the server for milliseconds at a time.)"""

from __future__ import annotations

import asyncio
import gc
import json
from collections.abc import Iterator
from pathlib import Path
from urllib.request import Request, urlopen

import pytest
from uvicorn.protocols.http.httptools_impl import HttpToolsProtocol
from websockets.asyncio.client import connect

from server.app import create_app
from server.config import Settings
from tests.support.embedded import bound_socket, serving
from tests.support.waiting import until

SOCKETS = 20


def http_protocols() -> int:
    """HTTP protocol objects still in memory, reachable or not (the collector is off)."""
    return sum(issubclass(type(o), HttpToolsProtocol) for o in gc.get_objects())


@pytest.fixture
def collector_off() -> Iterator[None]:
    gc.collect()
    gc.disable()
    try:
        yield
    finally:
        gc.enable()
        gc.collect()


async def come_and_go(url: str) -> None:
    for _ in range(SOCKETS):
        async with connect(url) as ws:
            await ws.recv()  # the room's `state`: the server is done with the handshake


@pytest.mark.usefixtures("collector_off")
def test_closed_websockets_leave_no_http_protocol_behind(tmp_path: Path):
    settings = Settings(web_dir=tmp_path, db_path=tmp_path / "pool.db")
    with serving(create_app(settings), settings, bound_socket()) as address:
        request = Request(
            f"http://{address}/api/rooms",
            json.dumps({"game": "practice"}).encode(),
            {"content-type": "application/json"},
        )
        room_id = json.loads(urlopen(request, timeout=10).read())["room_id"]
        before = http_protocols()
        asyncio.run(come_and_go(f"ws://{address}/ws/rooms/{room_id}"))
        # The server thread sees each close a moment after the client: wait for the last.
        until(
            lambda: http_protocols() <= before,
            10,
            f"HTTP protocols of {SOCKETS} closed WebSockets are still in memory",
        )
