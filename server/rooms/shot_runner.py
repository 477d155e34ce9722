"""Where shots are simulated and planned: threads of this process, or worker processes.

A thread preparing a shot must win the GIL from the busy event loop dozens of times (numpy
calls, the Python around the compiled engine), waiting out the switch interval each time:
under load (100+ rooms) a 4 ms shot took 0.3-2 s to start. A worker process
(`POOL_SHOT_WORKERS=1`) has its own interpreter and the loop only unpickles the result
(~1 ms), but on this 2-core machine, shared with the benchmark's clients, one worker could
not keep up with 100 shots a second (docs/performance.md), so threads stay the default.
A worker process that dies falls back to threads.
"""

from __future__ import annotations

import asyncio
import logging
import multiprocessing
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool

from server.engine import BallSet, Shot, ShotResult, Table

from .prepare import prepare_shot, warm_up
from .stream import ShotPlan

log = logging.getLogger(__name__)


class ShotRunner:
    def __init__(self, workers: int, frame_every: int, frames_per_message: int) -> None:
        self.workers = workers
        self.frame_every = frame_every
        self.frames_per_message = frames_per_message
        self._pool: ProcessPoolExecutor | None = None

    async def start(self) -> None:
        """Start the worker processes and load the engine in them (then the first shot is
        as fast as any); without workers, load it in this process."""
        loop = asyncio.get_running_loop()
        if self.workers > 0:
            self._pool = ProcessPoolExecutor(self.workers,
                                             mp_context=multiprocessing.get_context("spawn"))
            await asyncio.gather(*(loop.run_in_executor(self._pool, warm_up, self.frame_every)
                                   for _ in range(self.workers)))
        else:
            await asyncio.to_thread(warm_up, self.frame_every)

    async def prepare(self, table: Table, before: BallSet, shot: Shot,
                      shot_id: int) -> tuple[ShotResult, ShotPlan]:
        args = (table, before, shot, shot_id, self.frame_every, self.frames_per_message)
        if self._pool is not None:
            try:
                return await asyncio.get_running_loop().run_in_executor(
                    self._pool, prepare_shot, *args)
            except BrokenProcessPool:
                log.error("the shot worker process died; simulating in threads from now on")
                self._pool = None
        return await asyncio.to_thread(prepare_shot, *args)

    def close(self) -> None:
        """Stop the workers and wait for them (a worker left running outlives the server)."""
        if self._pool is not None:
            self._pool.shutdown(wait=True, cancel_futures=True)
            self._pool = None
