"""One connection on one thread: every store call runs there, in the order made.

Why a thread of its own: a write never holds up the event loop (the room only queues it),
reads from the HTTP API `await` it, and because it is one queue, a read sees every write
queued before it (the match list shows the shot that just ended). A read awaited from the
loop has a deadline of its own (`read_deadline`): behind writes that wait out an outage it
gives up with `StoreUnavailable` instead of waiting with them. A write that meets a
passing failure (another process holds the SQLite file; PostgreSQL restarting or out of
reach) is tried again with backoff on a new connection while the queue waits, so the
history is delayed, never lost or reordered. On PostgreSQL the writes queued together
share one transaction (a commit there is a round trip and a flush to disk).

Writes made on the event loop are handed to the thread once per turn of the loop, together:
each hand-over wakes the thread, and the GIL's trip there and back cost the loop more than
building the rows did (a shot makes three or four writes, often in the same turn).
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import queue
import threading
import time
from collections import deque
from collections.abc import Callable
from concurrent.futures import Future
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeVar

from .backend import database_url, is_transient, make_engine
from .errors import StaleOwner, StoreUnavailable
from .migrate import upgrade
from .repository import Repository

log = logging.getLogger(__name__)
T = TypeVar("T")


@dataclass
class _Job:
    fn: Callable[[Repository], Any]
    future: Future[Any]
    retry_for: float
    batchable: bool
    until: float | None = None  # store clock time past which it is neither run nor retried


class Database:
    """The store. `target` is a SQLite file's path or a `postgresql://` URL. `batch`: how
    many queued writes may share a transaction. `start_retry`: how long opening and
    migrating is tried again through passing failures (two processes starting on one new
    SQLite file: SQLite tells one of them "locked" at once as both turn its journal to
    WAL) before the process gives up. `read_deadline`: how long `call` waits for an
    answer. `sleep` and `clock` are how it waits between tries (a test injects its own)."""

    def __init__(
        self,
        target: Path | str,
        write_retry: float = 600.0,
        *,
        batch: int | None = None,
        start_retry: float = 30.0,
        read_deadline: float = 10.0,
        sleep: Callable[[float], None] = time.sleep,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self.url = database_url(target)
        self.backend = self.url.get_backend_name()  # "sqlite" | "postgresql"
        self.path = Path(self.url.database or "") if self.backend == "sqlite" else None
        self.write_retry = write_retry  # s a queued write is retried through failures
        self.start_retry = start_retry  # s opening and migrating is retried
        self.read_deadline = read_deadline  # s `call` waits for its answer
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
        # Items: a `_Job`, a list of them (one turn's writes), or None (stop).
        self._jobs: queue.SimpleQueue[_Job | list[_Job] | None] = queue.SimpleQueue()
        self._turn: list[_Job] = []  # writes made in this turn of the loop, not yet handed
        self._turn_lock = threading.Lock()
        self._ready: Future[None] = Future()
        self._thread = threading.Thread(target=self._run, name="billiards-store", daemon=True)
        self._thread.start()
        self._ready.result()  # raises if the database cannot be opened or migrated
        self.closed = False

    def _connect(self) -> Repository:
        """Connect and migrate. On failure the connections are given back: the server
        stops then, but a caller that goes on (a test, a tool) keeps no file open."""
        repo = Repository(make_engine(self.url))
        try:
            self._attempt(_migrate, repo, self.start_retry)
        except BaseException:
            repo.close()
            raise
        return repo

    def _run(self) -> None:
        try:
            repo = self._connect()
        except BaseException as exc:
            self._ready.set_exception(exc)
            return
        self._ready.set_result(None)
        backlog: deque[_Job] = deque()  # taken from the queue, in order, not yet run
        stopping = False
        while backlog or not stopping:
            if not backlog:
                stopping = self._take(self._jobs.get(), backlog)
                continue
            job = backlog.popleft()
            batch = [job]
            while job.batchable and len(batch) < self.batch:
                if not backlog and not stopping:
                    try:
                        stopping = self._take(self._jobs.get_nowait(), backlog)
                    except queue.Empty:
                        break
                if not backlog or not backlog[0].batchable:
                    break  # a job that runs alone waits for the next round
                batch.append(backlog.popleft())
            self._execute(batch, repo)
        repo.close()

    @staticmethod
    def _take(item: _Job | list[_Job] | None, backlog: deque[_Job]) -> bool:
        """Add a queue item to `backlog`; True if it is the stop signal."""
        if item is None:
            return True
        backlog.extend(item if isinstance(item, list) else (item,))
        return False

    def _execute(self, batch: list[_Job], repo: Repository) -> None:
        """Run the jobs; queued writes together in one transaction (one commit), each in a
        savepoint of its own, so one refused write does not undo the others."""
        jobs = [job for job in batch if job.future.set_running_or_notify_cancel()]
        if len(jobs) == 1:
            job = jobs[0]
            retry_for = job.retry_for if job.until is None else job.until - self.clock()
            if retry_for <= 0:  # its caller has given up on it
                job.future.set_exception(StoreUnavailable("the read's deadline passed"))
                return
            try:
                job.future.set_result(self._attempt(job.fn, repo, retry_for))
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
        self,
        fn: Callable[[Repository], T],
        retry_for: float = 10.0,
        batchable: bool = False,
        *,
        deadline: float | None = None,
    ) -> Future[T]:
        """Queue `fn(repo)`; returns at once. Through passing failures it is tried again
        for up to `retry_for` seconds. `batchable`: it may share a transaction with the
        writes queued next to it (each of them a single, idempotent write). `deadline`:
        seconds from now past which it is not started, nor tried again (it runs alone)."""
        future: Future[T] = Future()
        if self.closed:
            future.set_exception(RuntimeError("the store is closed"))
            return future
        until = None if deadline is None else self.clock() + deadline
        self._hand_over()  # this turn's writes first: everything runs in the order made
        self._jobs.put(_Job(fn, future, retry_for, batchable and until is None, until))
        return future

    def _later_this_turn(self, job: _Job) -> None:
        """Queue `job` with the other writes of this turn of the running loop."""
        with self._turn_lock:
            self._turn.append(job)
            first = len(self._turn) == 1
        if first:
            asyncio.get_running_loop().call_soon(self._hand_over)

    def _hand_over(self) -> None:
        with self._turn_lock:
            jobs, self._turn = self._turn, []
        if jobs:
            self._jobs.put(jobs)

    def write(self, fn: Callable[[Repository], T], what: str) -> Future[T]:
        """Fire and forget (retried for `write_retry` s); a failure is logged and the game
        goes on without that record. The future tells a caller that cares, e.g. about a
        `StaleOwner` refusal."""

        def done(future: Future[T]) -> None:
            exc = future.exception()
            if isinstance(exc, StaleOwner):
                log.warning("store: %s refused: %s", what, exc)
            elif exc is not None:
                log.error("store: %s failed", what, exc_info=exc)

        try:
            asyncio.get_running_loop()
        except RuntimeError:  # not on the event loop (startup, tests): queue it now
            future = self.submit(fn, retry_for=self.write_retry, batchable=True)
        else:
            future = Future()
            if self.closed:
                future.set_exception(RuntimeError("the store is closed"))
            else:
                self._later_this_turn(_Job(fn, future, self.write_retry, True))
        future.add_done_callback(done)
        return future

    def run(self, fn: Callable[[Repository], T]) -> T:
        """Wait for the result (startup, shutdown, tests; not on the event loop)."""
        return self.submit(fn).result()

    async def call(self, fn: Callable[[Repository], T], *, wait: bool = False) -> T:
        """Await the result from the event loop, at most `read_deadline` seconds: later,
        or when the database cannot be reached, `StoreUnavailable` (the request is
        dropped if it has not started). `wait`: no deadline (a drain's flush must see
        every queued write stored)."""
        if wait:
            return await asyncio.wrap_future(self.submit(fn, retry_for=self.write_retry))
        limit = self.read_deadline
        future = self.submit(fn, retry_for=limit, deadline=limit)
        try:
            # asyncio.timeout, not wait_for: on Python 3.11 wait_for can swallow a
            # cancellation that meets the answer, and a cancelled task then runs on
            async with asyncio.timeout(limit):
                return await asyncio.wrap_future(future)
        except TimeoutError:
            raise StoreUnavailable(f"no answer within {limit:g} s") from None
        except Exception as exc:
            if is_transient(exc):
                raise StoreUnavailable(_first_line(exc)) from exc
            raise

    def close(self) -> None:
        """Finish every queued job, then close the connection."""
        if self.closed:
            return
        self.closed = True
        self._hand_over()
        self._jobs.put(None)
        self._thread.join()


def _first_line(exc: BaseException) -> str:
    """The driver's message (no statement, no parameters), e.g. "database is locked"."""
    text = str(getattr(exc, "orig", None) or exc).strip()
    return text.splitlines()[0] if text else exc.__class__.__name__


def _each_in_a_savepoint(repo: Repository, fns: list[Callable[[Repository], Any]]) -> list[Any]:
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


def _migrate(repo: Repository) -> None:
    """Bring the schema to the newest revision, in one write transaction."""
    with repo.transaction() as conn:
        upgrade(conn)
