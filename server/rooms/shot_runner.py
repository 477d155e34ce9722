"""Where shots are simulated: in threads of this process, or in worker processes.

Threads (the default) run one compiled call a shot that releases the GIL: the engine's
traced run (`ShotInMotion.run(trace=...)`: the ticks and, in the same pass, each tick with
contacts replayed up to them and thinned to the knots of the `motion` message), then
`protocol.motion` packs the knots, holding the GIL for a few microseconds. The Python
before and after (the strike, turning the kernel's arrays into events, the sounds and the
message's header: well under 1 ms) runs on the event loop. A
thread that ran all of `prepare_shot` had to win the GIL back from the busy loop after
every compiled or numpy call, and while it held it the loop waited in turn: under load
(100+ rooms) a 4 ms shot took 0.3-2 s to start and every room's stream stalled
(docs/performance.md).

A worker process (`POOL_SHOT_WORKERS=1`) has its own interpreter and the loop only
unpickles the result (~1 ms), but on 2 cores shared with the benchmark's
clients, one worker could not keep up with 100 shots a second. A worker process that dies
falls back to threads.
"""

from __future__ import annotations

import asyncio
import logging
import multiprocessing
import sys
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor
from concurrent.futures.process import BrokenProcessPool

from server.engine import BallSet, Shot, ShotInMotion, ShotResult, Table
from server.protocol import run_traced
from server.protocol.plan import ShotPlan, plan_shot

from .prepare import prepare_shot, warm_up

log = logging.getLogger(__name__)
SWITCH_INTERVAL = 0.001  # s: how soon a busy thread yields the GIL to a waiting one


class ShotRunner:
    def __init__(self, workers: int, frame_every: int) -> None:
        self.workers = workers
        self.frame_every = frame_every
        self._pool: ProcessPoolExecutor | None = None
        self._thread_pool: ThreadPoolExecutor | None = None

    @property
    def _threads(self) -> ThreadPoolExecutor:
        # Two, so one long shot does not hold up the others; more would only wait for a core.
        if self._thread_pool is None:
            self._thread_pool = ThreadPoolExecutor(2, thread_name_prefix="shots")
        return self._thread_pool

    async def start(self) -> None:
        """Start the worker processes and load the engine in them (then the first shot is
        as fast as any); without workers, load it in this process.

        A shot thread takes the GIL back after each compiled call; while the loop is busy
        (thousands of sockets) each hand-over waited up to the interpreter's switch interval,
        5 ms, and at 1,000 rooms the threads spent their time waiting, not simulating
        (docs/performance.md). 1 ms makes the loop hand it over sooner."""
        sys.setswitchinterval(SWITCH_INTERVAL)
        loop = asyncio.get_running_loop()
        if self.workers > 0:
            self._pool = ProcessPoolExecutor(
                self.workers, mp_context=multiprocessing.get_context("spawn")
            )
            await asyncio.gather(
                *(
                    loop.run_in_executor(self._pool, warm_up, self.frame_every)
                    for _ in range(self.workers)
                )
            )
        else:
            await loop.run_in_executor(self._threads, warm_up, self.frame_every)

    async def prepare(
        self, table: Table, before: BallSet, shot: Shot, shot_id: int
    ) -> tuple[ShotResult, ShotPlan]:
        args = (table, before, shot, shot_id, self.frame_every)
        if self._pool is not None:
            try:
                return await asyncio.get_running_loop().run_in_executor(
                    self._pool, prepare_shot, *args
                )
            except BrokenProcessPool:
                log.error("the shot worker process died; simulating in threads from now on")
                self._pool = None
        motion = ShotInMotion(table, before, shot)
        tracks = await asyncio.get_running_loop().run_in_executor(self._threads, run_traced, motion)
        result = motion.result()
        return result, plan_shot(result, tracks, shot_id, self.frame_every)

    def close(self) -> None:
        """Stop the workers and wait for them (a worker left running outlives the server)."""
        if self._pool is not None:
            self._pool.shutdown(wait=True, cancel_futures=True)
            self._pool = None
        if self._thread_pool is not None:
            self._thread_pool.shutdown(wait=True, cancel_futures=True)
            self._thread_pool = None
