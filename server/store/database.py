"""One SQLite connection on one thread: every store call runs there, in the order made.

Why a thread of its own: a write never holds up the event loop (the room only queues it),
reads from the HTTP API `await` it, and because it is one queue, a read sees every write
queued before it (the match list shows the shot that just ended). WAL journal with
`synchronous=NORMAL`: a crash loses at most the last few writes, never the database.
"""

from __future__ import annotations

import asyncio
import logging
import queue
import sqlite3
import threading
import time
from collections.abc import Callable
from concurrent.futures import Future
from pathlib import Path
from typing import TypeVar

from .repository import Repository
from .schema import migrate

log = logging.getLogger(__name__)
T = TypeVar("T")


class Database:
    def __init__(self, path: Path | str, write_retry: float = 600.0) -> None:
        self.path = Path(path)
        self.write_retry = write_retry  # s a write is retried while the file is locked
        self.closed = True
        self.open()

    def open(self) -> None:
        """Start the thread and open (and migrate) the file; nothing if already open."""
        if not self.closed:
            return
        self._jobs: queue.SimpleQueue = queue.SimpleQueue()
        self._ready: Future[None] = Future()
        self._thread = threading.Thread(target=self._run, name="billiards-store", daemon=True)
        self._thread.start()
        self._ready.result()  # raises if the file cannot be opened or migrated
        self.closed = False

    def _run(self) -> None:
        try:
            if self.path.parent != Path(""):
                self.path.parent.mkdir(parents=True, exist_ok=True)
            conn = sqlite3.connect(self.path, isolation_level=None, check_same_thread=True)
            conn.execute("PRAGMA journal_mode = WAL")
            conn.execute("PRAGMA synchronous = NORMAL")
            conn.execute("PRAGMA foreign_keys = ON")
            migrate(conn)
        except BaseException as exc:
            self._ready.set_exception(exc)
            return
        self._ready.set_result(None)
        repo = Repository(conn)
        while True:
            job = self._jobs.get()
            if job is None:
                break
            fn, future, retry_for = job
            if not future.set_running_or_notify_cancel():
                continue
            try:
                future.set_result(self._attempt(fn, repo, retry_for))
            except BaseException as exc:
                future.set_exception(exc)
        conn.close()

    def _attempt(self, fn: Callable[[Repository], T], repo: Repository, retry_for: float) -> T:
        """`fn(repo)`, tried again with backoff while another process holds the file: a
        lock must delay the history, not lose it. The queue waits meanwhile, so writes stay
        in order (a saved room is never older than the shot recorded before it)."""
        deadline = time.monotonic() + retry_for
        delay = 0.05
        while True:
            try:
                return fn(repo)
            except sqlite3.OperationalError as exc:
                transient = "locked" in str(exc) or "busy" in str(exc)
                if not transient or time.monotonic() + delay > deadline:
                    raise
                log.warning("store: %s; trying again in %.2f s", exc, delay)
                time.sleep(delay)
                delay = min(2 * delay, 2.0)

    def submit(self, fn: Callable[[Repository], T], retry_for: float = 10.0) -> Future[T]:
        """Queue `fn(repo)`; returns at once. While the file is locked by another process
        it is tried again for up to `retry_for` seconds."""
        future: Future[T] = Future()
        if self.closed:
            future.set_exception(RuntimeError("the store is closed"))
            return future
        self._jobs.put((fn, future, retry_for))
        return future

    def write(self, fn: Callable[[Repository], object], what: str) -> None:
        """Fire and forget; a failure is logged (the game goes on without that record)."""

        def done(future: Future) -> None:
            if future.exception() is not None:
                log.error("store: %s failed", what, exc_info=future.exception())

        self.submit(fn, retry_for=self.write_retry).add_done_callback(done)

    def run(self, fn: Callable[[Repository], T]) -> T:
        """Wait for the result (startup, shutdown, tests; not on the event loop)."""
        return self.submit(fn).result()

    async def call(self, fn: Callable[[Repository], T]) -> T:
        """Await the result from the event loop."""
        return await asyncio.wrap_future(self.submit(fn))

    def close(self) -> None:
        """Finish every queued job, then close the connection."""
        if self.closed:
            return
        self.closed = True
        self._jobs.put(None)
        self._thread.join()
