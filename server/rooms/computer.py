"""The computer's seat in a room: when the match waits for it, think (off the event loop),
show the cue moving, then act through the same room actions as a person.

The search runs in a worker process (`POOL_COMPUTER_WORKERS`, shared by every room of this
server, at Linux's idle scheduling class), on the game's data. Not in a
thread: about half of a plan is Python holding the GIL (the rules judging each simulated
shot), which the event loop needs for every other room (`python -m bench.ai --only loop`
measures the difference). With no workers (`POOL_COMPUTER_WORKERS=0`) it plans in a
thread, and so does a plan whose planners die, or starve: get almost no CPU while other
work at normal priority keeps every core busy (`POOL_COMPUTER_STARVED`). A plan depends
only on the position, the level and the room's seed, so a replayed position gets the
same turn wherever it is planned.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import multiprocessing
import os
import signal
import threading
import time
import weakref
from collections.abc import Callable, Hashable
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from server.ai import Bot, Turn
from server.ai.play import plan_data, warm_up
from server.codec import to_data
from server.engine import Shot
from server.priority import process_stat, run_when_idle

from .errors import ActionError
from .planner_share import planner_share
from .room import Room

log = logging.getLogger(__name__)
AIM_STEPS = 6  # aim relays while the cue swings round to the shot
MAX_STEPS = 4  # turns in a row before handing back (decision, then its shot, ...)
PARENT_CHECK = 1.0  # s between a planner's looks at whether its server is still there
# A plan whose planners got less than this share of a core while it waited at least
# `STARVED_AFTER` seconds (`POOL_COMPUTER_STARVED`) is planned in a thread (`_planned_in`).
STARVED_AFTER = 10.0
STARVED_SHARE = 0.1
STARVED_CHECK = 0.5  # s between looks at the planners' CPU while a plan is out
CPU_READ_EVERY = 0.25  # s a reading of the planners' CPU serves every plan waiting
THREAD_PLAN_NOTE = "planning in a thread"  # in the log when a plan falls back to a thread
_pools: dict[int, ProcessPoolExecutor] = {}  # workers -> the pool this process shares
# pool -> (loop time, its planners' CPU seconds then): the last reading, shared
_cpu_read: weakref.WeakKeyDictionary[ProcessPoolExecutor, tuple[float, float | None]] = (
    weakref.WeakKeyDictionary()
)
_fallback = ThreadPoolExecutor(1, thread_name_prefix="starved-plan")  # one at a time
_servers = 0  # running apps of this process that may plan in `_pools`
_stopped = False  # the last app stopped: plans still asked for run in a thread


def _pool(workers: int) -> ProcessPoolExecutor:
    """The planner processes shared by every computer seat of this server (started on the
    first plan; spawned, so they share nothing with the event loop's process)."""
    pool = _pools.get(workers)
    if pool is None:
        pool = _pools[workers] = ProcessPoolExecutor(
            workers,
            mp_context=multiprocessing.get_context("spawn"),
            initializer=start_planner,
            initargs=(os.getpid(),),
        )
    return pool


def _pids(pool: ProcessPoolExecutor) -> list[int]:
    """The pool's processes. Python has no public list of them (3.14 adds
    `terminate_workers` for what `stop_pool` does); its `_processes` maps pid to process."""
    return list(pool._processes or {})  # noqa: SLF001 (no public list, as said)


def _cpu_seconds(pool: ProcessPoolExecutor, now: float) -> float | None:
    """CPU time the pool's processes have had by about `now` (loop time); None when it
    cannot be read (no /proc, or none started yet). Read from /proc at most every
    `CPU_READ_EVERY` seconds for all the plans waiting on the pool: each plan out read it
    twice a second (40 µs a read), 3-4 % of the loop's samples with 50 computer rooms."""
    read = _cpu_read.get(pool)
    if read is not None and 0 <= now - read[0] < CPU_READ_EVERY:
        return read[1]
    stats = [process_stat(pid) for pid in _pids(pool)]
    seconds = [stat[1] for stat in stats if stat is not None]
    value = sum(seconds) if seconds else None
    _cpu_read[pool] = (now, value)
    return value


def stop_pool(pool: ProcessPoolExecutor) -> None:
    """End a pool's planners now. A plan they are still making is for a server that is
    stopping (a restarted server plans the turn again), and waiting for it would take
    minutes when they are starved."""
    for pid in _pids(pool):
        with contextlib.suppress(ProcessLookupError):
            os.kill(pid, signal.SIGTERM)
    pool.shutdown(wait=True, cancel_futures=True)


def _ready() -> None:
    """A planner's first task: nothing beyond its initializer (`start_planner`)."""


def warm_planners(workers: int) -> None:
    """Start the planner processes now rather than at the first plan: spawning one and
    loading the compiled kernels (numba's cache) takes seconds, which the first "Show me a
    shot" of a fresh server (or the computer's first turn) would otherwise wait for.
    `python -m server` calls it at start-up; tests leave the planners to start on demand."""
    if workers <= 0 or _stopped:
        return
    pool = _pool(workers)
    for _ in range(workers):
        pool.submit(_ready)


def open_planners() -> None:
    """A server of this process starts (its rooms may use the shared planners)."""
    global _servers, _stopped
    _servers += 1
    _stopped = False


def close_planners() -> None:
    """A server of this process stops; the last one stops the planner processes. uvicorn
    ends a process stopped by a signal with that signal once the app has shut down, so
    no exit handler would: without this, every restart left its planners running."""
    global _servers, _stopped
    _servers = max(0, _servers - 1)
    if _servers == 0:
        _stopped = True  # a seat still thinking must not start new ones
        for pool in _pools.values():
            stop_pool(pool)
        _pools.clear()


def _exit_with(server: int) -> None:
    """In a planner: end when the server that started it is gone (killed, so it could not
    stop its planners), instead of living on as an orphan; it may be gone already, since a
    planner takes a second or two to start."""
    while os.getppid() == server:
        time.sleep(PARENT_CHECK)
    os._exit(0)


def start_planner(server: int) -> None:
    """The planners run on CPU time the rooms do not want (Linux `SCHED_IDLE`). At `nice 10`
    a planner still made its core look busy, so the kernel woke the rooms' shot threads on
    the event loop's core, where they waited behind the loop: 1,000 rooms with 50 against
    the computer had a start p99 of 66-142 ms, at the idle class 54-61 ms
    (docs/ai.md). A core running only idle-class work counts as free; the computer's
    thinking pause hides a plan that waits a little; one that waits on a starved planner
    is planned in the server's process instead (`_planned_in`)."""
    run_when_idle()
    threading.Thread(target=_exit_with, args=(server,), daemon=True).start()
    warm_up()


async def plan_turn(
    level: str,
    seed: int,
    game: dict[str, Any],
    seat: int,
    workers: int,
    starved: float = STARVED_AFTER,
) -> Turn:
    """`Bot(level, seed).plan` of the game data `game` for `seat`, off the event loop: in a
    planner process when `workers` > 0, else in a thread. A planner process that dies, or
    that gets almost no CPU for `starved` seconds, leaves the plan to a thread: the
    computer then holds the GIL the rooms need for part of its plan, which beats a
    computer that never moves."""
    loop = asyncio.get_running_loop()
    if workers > 0 and not _stopped:
        pool = _pool(workers)
        future = loop.run_in_executor(pool, plan_data, level, seed, game, seat)
        try:
            if await _planned_in(future, pool, starved):
                return future.result()
        except asyncio.CancelledError:
            future.cancel()  # the seat stopped thinking (a concession, the room closing)
            raise
        except BrokenProcessPool:
            if not _stopped:  # else its server stopped it (`stop_pool`)
                log.error("a computer planner process died; %s this time", THREAD_PLAN_NOTE)
                _pools.pop(workers, None)
        else:
            future.cancel()  # if it has not started; a started one ends unread
            log.warning(
                "the computer's planners got under %.0f %% of a core for %.0f s (the machine"
                " is busy with other work); %s this time",
                100 * STARVED_SHARE,
                starved,
                THREAD_PLAN_NOTE,
            )
            return await loop.run_in_executor(_fallback, plan_data, level, seed, game, seat)
    return await asyncio.to_thread(plan_data, level, seed, game, seat)


async def _planned_in(
    future: asyncio.Future[Any], pool: ProcessPoolExecutor, starved: float
) -> bool:
    """Wait for a plan sent to the planners: True once it is done, False once it has waited
    `starved` seconds or more while the planners got under `STARVED_SHARE` of a core. At
    Linux's idle class they get no CPU at all while work at normal priority keeps every
    core busy; a backlog of plans keeps them busy, and a cold start compiles, so neither
    counts as starving."""
    loop = asyncio.get_running_loop()
    since = loop.time()
    cpu_since = _cpu_seconds(pool, since)
    while True:
        done, _ = await asyncio.wait({future}, timeout=STARVED_CHECK)
        if done:
            return True
        now = loop.time()
        cpu = _cpu_seconds(pool, now)
        if cpu is None or cpu_since is None:  # unknown: never called starved
            since, cpu_since = now, cpu
            continue
        waited = now - since
        if waited >= starved:
            if cpu - cpu_since < STARVED_SHARE * waited:
                return False
            since, cpu_since = now, cpu  # they are moving: judge the next stretch afresh


@dataclass
class ComputerSeat:
    """Plays `seat` of `room` at `level`. The room hands `start` its way to apply a turn
    (`apply(turn, shot)`) and to show the cue (`relay(angle, power)`)."""

    room: Room
    seat: int
    level: str
    pause: float  # s of "thinking" before a turn is shown, at pace 1
    workers: int = 0  # planner processes (0: plan in a thread)
    starved: float = STARVED_AFTER  # s a plan waits on starved planners before a thread takes it
    bot: Bot = field(init=False)
    task: asyncio.Task[None] | None = field(default=None, init=False)

    def __post_init__(self) -> None:
        self.bot = Bot(self.level, seed=self.room.seed)

    def due(self) -> bool:
        return self.room.acting_seat() == self.seat

    def start(
        self,
        apply: Callable[[Turn, Shot | None], None],
        relay: Callable[[float, float], None],
        pace: float,
    ) -> None:
        """Take the turn if it is ours and we are not already taking it."""
        if not self.due() or (self.task is not None and not self.task.done()):
            return
        self.task = asyncio.get_running_loop().create_task(self._turn(apply, relay, pace))

    def cancel(self) -> None:
        if self.task is not None:
            self.task.cancel()

    async def _turn(
        self,
        apply: Callable[[Turn, Shot | None], None],
        relay: Callable[[float, float], None],
        pace: float,
    ) -> None:
        """Play while the match waits for this seat: a decision can be followed by a shot
        of its own (it accepted the table, it re-racked and breaks)."""
        for _ in range(MAX_STEPS):
            if not self.due() or not await self._step(apply, relay, pace):
                return

    async def _step(
        self,
        apply: Callable[[Turn, Shot | None], None],
        relay: Callable[[float, float], None],
        pace: float,
    ) -> bool:
        """One planned turn, applied; False when it could not be."""
        match = self.room.match
        if match is None:
            return False
        game = to_data(match.game)  # the search works on its own copy
        started = asyncio.get_running_loop().time()
        try:
            with planner_share(self.workers).computer_planning():  # hints wait meanwhile
                turn = await plan_turn(
                    self.level, self.bot.seed, game, self.seat, self.workers, self.starved
                )
        except Exception:
            log.exception("room %s: the computer could not plan", self.room.room_id)
            return False
        thought = asyncio.get_running_loop().time() - started
        await asyncio.sleep(max(0.0, self.pause / pace - thought))
        if not self.due():
            return False  # the position changed meanwhile (a concession, a timeout)
        shot = None
        if turn.shot is not None and turn.decision is None:
            rng = np.random.default_rng([self.room.seed, self.room.shots_played])
            shot = self.bot.execute(turn.shot, rng, match.game.table)
            for step in range(1, AIM_STEPS + 1):  # the cue swings round and draws back
                relay(shot.angle, min(1.0, step / AIM_STEPS * shot.speed / 12.0))
                await asyncio.sleep(0.12 / pace)
            if not self.due():
                return False
        try:
            apply(turn, shot)
        except ActionError as exc:
            log.warning(
                "room %s: the computer's turn was refused: %s", self.room.room_id, exc.message
            )
            return False
        return True


HINT_LEVEL = Bot.LEVELS[-1]  # "Show me a shot" shows what the strongest level would play
HINT_QUEUE = 8  # hints that may wait for the planners (`POOL_HINT_QUEUE`)
HINT_WAIT = 15.0  # s a hint may wait for them before it is refused (`POOL_HINT_WAIT`)
HINT_BUDGET = 20.0  # s of planning an address may use in any minute (`POOL_HINT_BUDGET`)


@dataclass(frozen=True)
class HintAsk:
    """Who asks for a hint, and how long they may wait: `requester` names them beyond the
    table (("address", ip), ("player", id)), each holding one hint at a time."""

    requester: tuple[Hashable, ...] = ()
    max_waiting: int = HINT_QUEUE
    max_wait: float = HINT_WAIT
    budgeted: tuple[Hashable, ...] = ()  # requesters with a planning budget (the address)
    budget: float = HINT_BUDGET


async def hint(
    room: Room, token: str, workers: int, starved: float = STARVED_AFTER, ask: HintAsk = HintAsk()
) -> Turn:
    """The strongest level's turn for the player of a practice table, planned off the event
    loop and not taken (the learner sees the ghost ball, aim, power and spin). One hint at
    a time per table and per requester, after the rooms' computer turns
    (`planner_share`), so that nobody can queue up the planners' time."""
    seat = _hint_seat(room, token)

    async def plan() -> Turn:
        match = room.match
        if match is None or _hint_seat(room, token) != seat:
            raise ActionError("not_your_turn", "The table changed while the hint waited.")
        return await plan_turn(HINT_LEVEL, room.seed, to_data(match.game), seat, workers, starved)

    keys = (("room", room.room_id), *ask.requester)
    share = planner_share(workers)
    return await share.hint(
        keys,
        plan,
        max_waiting=ask.max_waiting,
        max_wait=ask.max_wait,
        budgeted=ask.budgeted,
        budget=ask.budget,
    )


def _hint_seat(room: Room, token: str) -> int:
    """The seat of `token` if a hint may be planned for it now, else the refusal."""
    seat = room.seat_of(token)
    if seat is None:
        raise ActionError("bad_token", "This token does not open a seat at this table.")
    if not room.practice:
        raise ActionError("not_practice", "Hints are for practice tables.")
    match = room.match
    if match is None or room.acting_seat() != seat or match.game.decision is not None:
        raise ActionError("not_your_turn", "A hint is for a table at rest, your shot to play.")
    return seat
