"""Run the app under uvicorn in a background thread: for tests and benchmarks that need a
real server on a real socket inside their own process."""

from __future__ import annotations

import socket
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import uvicorn

from server.__main__ import uvicorn_config
from server.config import Settings


@contextmanager
def serving(
    app: Any, settings: Settings, sock: socket.socket, timeout: float = 30.0
) -> Iterator[str]:
    """Serve `app` on the bound socket `sock` (closed afterwards); yields "host:port".
    Stopping runs the app's shutdown (sockets closed with 1012, the store flushed)."""
    host, port = sock.getsockname()[:2]
    server = uvicorn.Server(uvicorn_config(app, host, port, settings, log_level="warning"))
    thread = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, daemon=True)
    thread.start()
    deadline = time.monotonic() + timeout
    while not server.started:
        if not thread.is_alive() or time.monotonic() > deadline:
            raise RuntimeError("the server did not start")
        time.sleep(0.02)
    try:
        yield f"{host}:{port}"
    finally:
        server.should_exit = True
        thread.join(timeout)
        sock.close()
        if thread.is_alive():
            raise RuntimeError("the server did not stop")


def bound_socket(port: int = 0, host: str = "127.0.0.1") -> socket.socket:
    """A TCP socket bound to `host:port` (0: any free port), reusable right after a stop."""
    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    sock.bind((host, port))
    return sock
