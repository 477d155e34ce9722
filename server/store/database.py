"""One connection on one thread: every store call runs there, in the order made.

Why a thread of its own: a write never holds up the event loop (the room only queues it),
reads from the HTTP API `await` it, and because it is one queue, a read sees every write
queued before it (the match list shows the shot that just ended). A write that meets a
passing failure (another process holds the SQLite file; PostgreSQL restarting or out of
reach) is tried again with backoff on a new connection while the queue waits, so the
history is delayed, never lost or reordered. On PostgreSQL the writes queued together
share one transaction (a commit there is a round trip and a flush to disk).
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import queue
import threading
import time
from collections.abc import Callable
from concurrent.futures import Future
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeVar

from .backend import database_url, is_transient, make_engine
from .errors import StaleOwner
from .migrate import upgrade
from .repository import Repository

log = logging.getLogger(__name__)
T = TypeVar("T")


@dataclass
class _Job:
    fn: Callable[[Repository], Any]
    future: Future
    retry_for: float
    batchable: bool


class Database:
    """The store. `target` is a SQLite file's path or a `postgresql://` URL. `batch`: how
    many queued writes may share a transaction. `sleep` and `clock` are how it waits
    between tries (a test injects its own)."""

    def __init__(
        self,
        target: Path | str,
        write_retry: float = 600.0,
        *,
        batch: int | None = None,
        sleep: Callable[[float], None] = time.sleep,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self.url = database_url(target)
        self.backend = self.url.get_backend_name()  # "sqlite" | "postgresql"
        self.path = Path(self.url.database or "") if self.backend == "sqlite" else None
        self.write_retry = write_retry  # s a queued write is retried through failures
        # queued writes run this many to a transaction (PostgreSQL: a commit is a round trip
        # and a flush to disk; a SQLite commit in WAL mode flushes nothing)
        self.batch = batch if batch is not None else (64 if self.backend == "postgresql" else 1)
        self.sleep = sleep
        self.clock = clock
        self.closed = True
        self.open()

    def __repr__(self) -> str:
        return f"Database({self.url.render_as_string(hide_password=True)!r})"

    def open(self) -> None:
        """Start the thread, connect and migrate; nothing if already open."""
        if not self.closed:
            return
        self._jobs: queue.SimpleQueue = queue.SimpleQueue()
        self._ready: Future[None] = Future()
        self._thread = threading.Thread(target=self._run, name="billiards-store", daemon=True)
        self._thread.start()
        self._ready.result()  # raises if the database cannot be opened or migrated
        self.closed = False

    def _run(self) -> None:
        try:
            repo = Repository(make_engine(self.url))
            with repo.transaction() as conn:
                upgrade(conn)
        except BaseException as exc:
            self._ready.set_exception(exc)
            return
        self._ready.set_result(None)
        held: _Job | None = None
        while True:
            job = held or self._jobs.get()
            held = None
            if job is None:
                break
            batch = [job]
            while job.batchable and len(batch) < self.batch:
                try:
                    more = self._jobs.get_nowait()
                except queue.Empty:
                    break
                if more is None:
                    self._jobs.put(None)  # stop, once this batch is done
                    break
                if not more.batchable:
                    held = more  # runs alone, next
                    break
                batch.append(more)
            self._execute(batch, repo)
        repo.close()

    def _execute(self, batch: list[_Job], repo: Repository) -> None:
        """Run the jobs; queued writes together in one transaction (one commit), each in a
        savepoint of its own, so one refused write does not undo the others."""
        jobs = [job for job in batch if job.future.set_running_or_notify_cancel()]
        if len(jobs) == 1:
            job = jobs[0]
            try:
                job.future.set_result(self._attempt(job.fn, repo, job.retry_for))
            except BaseException as exc:
                job.future.set_exception(exc)
            return
        if not jobs:
            return
        fns = [job.fn for job in jobs]
        try:
            outcomes = self._attempt(
                lambda r: _each_in_a_savepoint(r, fns), repo, max(j.retry_for for j in jobs)
            )
        except BaseException as exc:
            for job in jobs:
                job.future.set_exception(exc)
            return
        for job, (ok, value) in zip(jobs, outcomes, strict=True):
            if ok:
                job.future.set_result(value)
            else:
                job.future.set_exception(value)

    def _attempt(self, fn: Callable[[Repository], T], repo: Repository, retry_for: float) -> T:
        """`fn(repo)`, tried again with backoff (0.05 s doubling to 2 s) through passing
        failures for up to `retry_for` seconds. The queue waits meanwhile, so writes stay
        in order (a saved room is never older than the shot recorded before it)."""
        deadline = self.clock() + retry_for
        delay = 0.05
        while True:
            try:
                result = fn(repo)
                repo.settle(ok=True)
                return result
            except Exception as exc:
                with contextlib.suppress(Exception):
                    repo.settle(ok=False)
                if not is_transient(exc):
                    raise
                repo.reset()  # a new connection for the next try
                if self.clock() + delay > deadline:
                    raise
                log.warning("store: %s; trying again in %.2f s", _first_line(exc), delay)
                self.sleep(delay)
                delay = min(2 * delay, 2.0)

    def submit(
        self, fn: Callable[[Repository], T], retry_for: float = 10.0, batchable: bool = False
    ) -> Future[T]:
        """Queue `fn(repo)`; returns at once. Through passing failures it is tried again
        for up to `retry_for` seconds. `batchable`: it may share a transaction with the
        writes queued next to it (each of them a single, idempotent write)."""
        future: Future[T] = Future()
        if self.closed:
            future.set_exception(RuntimeError("the store is closed"))
            return future
        self._jobs.put(_Job(fn, future, retry_for, batchable))
        return future

    def write(self, fn: Callable[[Repository], T], what: str) -> Future[T]:
        """Fire and forget (retried for `write_retry` s); a failure is logged and the game
        goes on without that record. The future tells a caller that cares, e.g. about a
        `StaleOwner` refusal."""

        def done(future: Future) -> None:
            exc = future.exception()
            if isinstance(exc, StaleOwner):
                log.warning("store: %s refused: %s", what, exc)
            elif exc is not None:
                log.error("store: %s failed", what, exc_info=exc)

        future = self.submit(fn, retry_for=self.write_retry, batchable=True)
        future.add_done_callback(done)
        return future

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


def _first_line(exc: BaseException) -> str:
    """The driver's message (no statement, no parameters), e.g. "database is locked"."""
    text = str(getattr(exc, "orig", None) or exc).strip()
    return text.splitlines()[0] if text else exc.__class__.__name__


def _each_in_a_savepoint(repo: Repository, fns: list[Callable[[Repository], Any]]) -> list:
    """Run `fns` in one transaction, each in a savepoint: (True, result) or (False, error)
    each. A passing failure (the connection) fails the whole batch, to be tried again."""
    outcomes: list[tuple[bool, Any]] = []
    with repo.transaction() as conn:
        for fn in fns:
            savepoint = conn.begin_nested()
            try:
                value = fn(repo)
            except Exception as exc:
                if is_transient(exc):
                    raise
                savepoint.rollback()
                outcomes.append((False, exc))
            else:
                savepoint.commit()
                outcomes.append((True, value))
    return outcomes
