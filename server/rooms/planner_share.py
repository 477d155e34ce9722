"""The planners shared fairly between the rooms' computer and practice hints.

The computer's turns and "Show me a shot" plan in the same processes
(`POOL_COMPUTER_WORKERS`), and a process pool serves its queue in order: 20 hints queued
ahead of a computer's turn kept that computer silent for minutes. Here hints wait outside the
pool, in their own bounded queue, and one goes in only while no computer turn wants the
planners, one at a time: a computer's turn waits behind at most one hint. Each requester
holds at most one hint at a time (per table, per address, per player); a hint whose
requester left before it started is dropped unplanned; a full queue is refused at once
(`hints_busy`), and a hint that cannot start within `max_wait` seconds is refused
(`hint_timeout`) rather than planned for a requester who has likely given up. Each
address also has a planning budget (`PlanningBudget`: seconds of planning in any minute),
so that twenty tables of one address asking in turn cannot keep the planners to themselves:
once it is spent, its hints are refused at once (`planning_budget`) until the oldest
plans leave the minute.

One share per event loop, so per server, whatever the rooms and routes that use it.
"""

from __future__ import annotations

import asyncio
import contextlib
import math
import time
import weakref
from collections import deque
from collections.abc import Awaitable, Callable, Hashable, Iterable, Iterator
from dataclasses import dataclass, field
from typing import TypeVar

from .errors import ActionError

T = TypeVar("T")
HINT_SLOTS = 1  # hints in the planners at once (whatever the number of planners)


BUDGET_WINDOW = 60.0  # s: a planning budget is counted over any minute


@dataclass
class PlanningBudget:
    """The planning time each requester (an address) used in the last `window` s: the
    wall time of each of its plans, counted from the plan's end, on `clock`."""

    window: float = BUDGET_WINDOW
    clock: Callable[[], float] = time.monotonic
    plans: dict[Hashable, deque[tuple[float, float]]] = field(default_factory=dict)

    def spent(self, key: Hashable) -> float:
        """Seconds of planning `key` used in the last `window` s."""
        done = self.plans.get(key)
        if done is None:
            return 0.0
        since = self.clock() - self.window
        while done and done[0][0] <= since:
            done.popleft()
        if not done:
            del self.plans[key]
            return 0.0
        return sum(seconds for _, seconds in done)

    def charge(self, key: Hashable, seconds: float) -> None:
        """Count a plan of `key` that just ended; forget requesters with none in the window
        (one plan ends at a time, so this sweep stays small)."""
        now = self.clock()
        for old in [k for k, done in self.plans.items() if done[-1][0] <= now - self.window]:
            del self.plans[old]
        self.plans.setdefault(key, deque()).append((now, seconds))


@dataclass
class PlannerShare:
    """Who may use the planners now. `slots`: planner processes (a thread counts as one).
    `clock`: the time plans are measured on (for the planning budgets)."""

    slots: int = 1
    computer: int = 0  # computer turns being planned
    hints_out: int = 0  # hints handed to the planners (running, or queued in the pool)
    waiting: deque[asyncio.Future[None]] = field(default_factory=deque)
    holders: set[Hashable] = field(default_factory=set)  # requesters with a hint asked
    idle_waiters: list[asyncio.Future[None]] = field(default_factory=list)  # the analyses
    clock: Callable[[], float] = time.monotonic
    budget: PlanningBudget = field(init=False)

    def __post_init__(self) -> None:
        self.budget = PlanningBudget(clock=self.clock)

    @contextlib.contextmanager
    def computer_planning(self) -> Iterator[None]:
        """Around a computer's turn being planned: hints wait meanwhile."""
        self.computer += 1
        try:
            yield
        finally:
            self.computer -= 1
            self._wake()
            if self.computer == 0:
                for waiter in self.idle_waiters:
                    if not waiter.done():
                        waiter.set_result(None)
                self.idle_waiters.clear()

    async def computer_idle(self) -> None:
        """Return once no computer's turn is being planned: the match analyses start each
        shot only then, never ahead of a room's computer."""
        while self.computer > 0:
            waiter: asyncio.Future[None] = asyncio.get_running_loop().create_future()
            self.idle_waiters.append(waiter)
            try:
                await waiter
            finally:
                if waiter in self.idle_waiters:
                    self.idle_waiters.remove(waiter)

    def _free(self) -> bool:
        return self.hints_out < HINT_SLOTS and self.computer < max(1, self.slots)

    def _wake(self) -> None:
        """Hand the planners to the longest waiting hint, if they are free for one."""
        while self.waiting and self._free():
            ready = self.waiting.popleft()
            if not ready.done():
                self.hints_out += 1  # taken now, so that no second hint slips in
                ready.set_result(None)

    async def hint(
        self,
        keys: Iterable[Hashable],
        plan: Callable[[], Awaitable[T]],
        *,
        max_waiting: int,
        max_wait: float,
        budgeted: Iterable[Hashable] = (),
        budget: float = math.inf,
    ) -> T:
        """`plan()` once the planners are free for a hint. Refused at once while one of
        `keys` (the table, the address, the player) has a hint asked, while one of
        `budgeted` (the address) has used `budget` s of planning in the last minute, or
        while `max_waiting` hints wait already; refused after `max_wait` s without a
        start."""
        keys, budgeted = set(keys), set(budgeted)
        if keys & self.holders:
            raise ActionError("hint_pending", "A hint for you is on its way already.")
        if any(self.budget.spent(key) >= budget for key in budgeted):
            raise ActionError(
                "planning_budget",
                "You have used the computer's planning time for this minute; ask again soon.",
            )
        if (not self._free() or self.waiting) and len(self.waiting) >= max_waiting:
            raise ActionError("hints_busy", "Too many hints are waiting; ask again in a moment.")
        self.holders |= keys
        try:
            await self._turn(max_wait)
        except BaseException:
            self.holders -= keys
            raise
        return await self._run(keys, plan, budgeted)

    async def _turn(self, max_wait: float) -> None:
        """Wait until this hint may go to the planners (a slot taken on return)."""
        if self._free() and not self.waiting:
            self.hints_out += 1
            return
        ready: asyncio.Future[None] = asyncio.get_running_loop().create_future()
        self.waiting.append(ready)
        try:
            await asyncio.wait_for(asyncio.shield(ready), max_wait)
        except BaseException as exc:
            if ready.done() and not ready.cancelled():
                self._release()  # it was handed the slot just as its requester left
            else:
                ready.cancel()
                with contextlib.suppress(ValueError):
                    self.waiting.remove(ready)
            if isinstance(exc, TimeoutError):
                raise ActionError(
                    "hint_timeout", "The computer was busy too long; ask again in a moment."
                ) from None
            raise

    async def _run(
        self, keys: set[Hashable], plan: Callable[[], Awaitable[T]], budgeted: set[Hashable]
    ) -> T:
        """Plan; the slot and the keys are held until the planners are done with it, even
        if the requester leaves meanwhile (a plan under way cannot be taken back from a
        process, and another hint queued behind it would delay the computer more). Its
        time is charged to each of `budgeted` when it ends."""
        started = self.clock()
        task = asyncio.ensure_future(plan())

        def done(finished: asyncio.Future[T]) -> None:
            if not finished.cancelled():
                finished.exception()  # read here: a requester that left never reads it
            for key in budgeted:
                self.budget.charge(key, self.clock() - started)
            self.holders -= keys
            self._release()

        task.add_done_callback(done)
        return await asyncio.shield(task)

    def _release(self) -> None:
        self.hints_out -= 1
        self._wake()


_shares: weakref.WeakKeyDictionary[asyncio.AbstractEventLoop, PlannerShare] = (
    weakref.WeakKeyDictionary()
)


def planner_share(slots: int) -> PlannerShare:
    """The share of the running event loop (its server), told the planners' number."""
    loop = asyncio.get_running_loop()
    share = _shares.get(loop)
    if share is None:
        share = _shares[loop] = PlannerShare()
    share.slots = slots
    return share
