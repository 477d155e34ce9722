"""The analysis queue: finished matches analysed in the background, bounded, stored once.

A match's analysis is asked for by the first request for it (`request`, lazily: nobody
pays for the analysis of a match nobody looks at). The queue is the store's `analyses`
table, so in a cluster any process may take a match, and exactly one does (a conditional
update claims it; `server.store.analyses`). Each process runs at most
`POOL_ANALYSIS_AT_ONCE` analyses, in its own planner processes
(`POOL_ANALYSIS_WORKERS`, at Linux's idle class like the computer's, so they only get
CPU time the rooms leave), one shot at a time, each started only while no room's computer
is planning (`PlannerShare.computer_idle`): an analysis never holds up a computer's move
by more than the shot in hand. The result is stored once and served from the store.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import multiprocessing
import os
import time
import uuid
from collections.abc import Callable
from concurrent.futures import Executor, ProcessPoolExecutor, ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import Any

from server.ai.analysis import MatchAnalysis, ShotVerdict, StoredShot, judge_nth, summarise
from server.codec import encode, to_data
from server.config import Settings
from server.store import Database, MatchRecord, Repository, ShotRecord
from server.store.analyses import FAILED, READY, AnalysisRecord, AnalysisRows

from .computer import start_planner, stop_pool
from .planner_share import planner_share

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class Answer:
    """What a request for an analysis finds: `status` "ready" (with the stored `result`,
    JSON), "pending" (with the `position` in the queue), "failed", or why there is none:
    "unknown" (no such match), "playing" (not over yet), "busy" (the queue is full)."""

    status: str
    position: int = 0
    result: str | None = None


def stored_shot(record: ShotRecord) -> StoredShot:
    """The analysis' view of a stored shot: the computer's intended stroke is judged when it
    was kept (older rows have none: their stroke as played is judged)."""
    return StoredShot(
        record.n,
        record.game,
        record.seat,
        record.shot,
        record.table,
        record.balls,
        record.outcome,
        record.intended,
    )


@dataclass
class AnalysisQueue:
    """This process's part of the analysis queue (one per server)."""

    store: Database
    settings: Settings
    owner: str = field(default_factory=lambda: f"{os.getpid()}-{uuid.uuid4().hex[:8]}")
    clock: Callable[[], float] = time.time
    running: set[asyncio.Task[None]] = field(default_factory=set)
    _pool: Executor | None = field(default=None, init=False)
    _pump: asyncio.Task[None] | None = field(default=None, init=False)
    _again: bool = field(default=False, init=False)
    _closed: bool = field(default=False, init=False)

    async def request(self, match_id: int) -> Answer:
        """The analysis of `match_id`: stored, or queued now (and this process set to work
        on the queue), or why not."""
        limit, now = self.settings.analysis_queue, self.clock()

        def ask(repo: Repository) -> tuple[str, AnalysisRecord | None, int]:
            rows = AnalysisRows(repo)
            found = rows.get(match_id)
            if found is None:
                match = repo.match(match_id)
                if match is None:
                    return "unknown", None, 0
                if match.status == "playing":
                    return "playing", None, 0
                if rows.waiting() >= limit:
                    return "busy", None, 0
                found = rows.request(match_id, now)
            return found.status, found, rows.position(found)

        status, record, position = await self.store.call(ask)
        if status in ("unknown", "playing", "busy"):
            return Answer(status)
        assert record is not None
        if status == READY:
            return Answer("ready", result=record.result)
        if status == FAILED:
            return Answer("failed", result=record.result)
        self.kick()
        return Answer("pending", position=position)

    def kick(self) -> None:
        """Take queued analyses while this process has room for them."""
        if self._closed:
            return
        if self._pump is not None and not self._pump.done():
            self._again = True
            return
        self._pump = asyncio.get_running_loop().create_task(self._take())

    async def _take(self) -> None:
        settings = self.settings
        self._again = True
        while self._again and not self._closed:
            self._again = False
            while len(self.running) < settings.analysis_at_once:
                match_id = await self.store.call(self._claim)
                if match_id is None:
                    break
                task = asyncio.get_running_loop().create_task(self._run(match_id))
                self.running.add(task)
                task.add_done_callback(self._done)

    def _claim(self, repo: Repository) -> int | None:
        now = self.clock()
        return AnalysisRows(repo).claim(self.owner, now, now - self.settings.analysis_stale)

    def _done(self, task: asyncio.Task[None]) -> None:
        self.running.discard(task)
        self.kick()

    async def _run(self, match_id: int) -> None:
        """Analyse a claimed match and store the result (or the error)."""
        ok, text = True, ""
        try:
            text = encode(to_data(await self.analyse(match_id)))
        except asyncio.CancelledError:
            raise  # the server stops: another process (or the next start) takes it over
        except Exception as exc:  # a match the analysis cannot read: say so, once
            log.exception("the analysis of match %s failed", match_id)
            ok, text = False, f"{type(exc).__name__}: {exc}"
        await self.store.call(
            lambda repo: AnalysisRows(repo).finish(match_id, self.owner, text, self.clock(), ok)
        )

    async def analyse(self, match_id: int) -> MatchAnalysis:
        """The stored match judged shot by shot in the planners, each shot only while no
        room's computer is planning."""

        def load(repo: Repository) -> tuple[MatchRecord | None, list[ShotRecord]]:
            return repo.match(match_id), repo.shots(match_id)

        match, records = await self.store.call(load)
        if match is None:
            raise LookupError(f"no match {match_id}")
        shots = [stored_shot(r) for r in records]
        share = planner_share(self.settings.computer_workers)
        loop = asyncio.get_running_loop()
        judged: list[ShotVerdict] = []
        for k in range(len(shots)):
            await share.computer_idle()
            judged.append(
                await loop.run_in_executor(
                    self._executor(), judge_nth, *self._args(match, shots, k)
                )
            )
        return summarise(match_id, match.kind, match.players, judged)

    def _args(self, match: MatchRecord, shots: list[StoredShot], k: int) -> tuple[Any, ...]:
        return (match.id, match.kind, match.players, shots, k, self.settings.analysis_budget)

    def _executor(self) -> Executor:
        """The analysis' own planner processes (started on first use, at the idle
        class), or one thread with `POOL_ANALYSIS_WORKERS=0`."""
        if self._pool is None:
            workers = self.settings.analysis_workers
            if workers > 0:
                self._pool = ProcessPoolExecutor(
                    workers,
                    mp_context=multiprocessing.get_context("spawn"),
                    initializer=start_planner,
                    initargs=(os.getpid(),),
                )
            else:
                self._pool = ThreadPoolExecutor(1, thread_name_prefix="analysis")
        return self._pool

    async def drained(self) -> None:
        """Return once this process has no analysis under way nor any left to take."""
        while True:
            tasks = [t for t in (self._pump, *self.running) if t is not None and not t.done()]
            if not tasks:
                return
            await asyncio.wait(tasks)

    async def close(self) -> None:
        """Stop: analyses under way are left claimed, for another process (or the next
        start, once the claim is stale) to take over."""
        self._closed = True
        tasks = [t for t in (self._pump, *self.running) if t is not None]
        for task in tasks:
            task.cancel()
        for task in tasks:
            with contextlib.suppress(asyncio.CancelledError):
                await task
        pool, self._pool = self._pool, None
        if isinstance(pool, ProcessPoolExecutor):
            await asyncio.to_thread(stop_pool, pool)
        elif pool is not None:
            pool.shutdown(wait=False, cancel_futures=True)
