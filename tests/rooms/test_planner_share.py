"""Hints share the planners fairly: behind the rooms' computer turns, one at a time, one per
requester, a bounded queue; a hint whose requester left is never planned."""

from __future__ import annotations

import asyncio
from collections.abc import Awaitable, Callable

import pytest

from server.rooms import ActionError
from server.rooms.planner_share import PlannerShare, PlanningBudget, planner_share

pytestmark = pytest.mark.timeout(30)


class OnePlanner:
    """A stand-in for one planner process: jobs run one at a time, in the order they were
    handed in (as a process pool serves its queue), each until the test lets it end."""

    def __init__(self) -> None:
        self.lock = asyncio.Lock()  # asyncio's lock wakes its waiters in order
        self.order: list[str] = []  # jobs, in the order they ran
        self.planned: list[str] = []  # jobs handed in (whether they ran yet or not)

    def job(self, name: str, steps: int = 3) -> Callable[[], Awaitable[str]]:
        async def run() -> str:
            self.planned.append(name)
            async with self.lock:
                self.order.append(name)
                for _ in range(steps):
                    await asyncio.sleep(0)
            return name

        return run


async def settle() -> None:
    for _ in range(50):
        await asyncio.sleep(0)


def ask(share: PlannerShare, keys: list, plan, waiting: int = 8, wait: float = 30.0):
    return asyncio.ensure_future(share.hint(keys, plan, max_waiting=waiting, max_wait=wait))


def test_a_flood_of_hints_puts_at_most_one_ahead_of_the_computer():
    """20 tables from 20 addresses ask for hints, then a computer in another room plans:
    it runs after at most the one hint already in the planner, however long the queue."""

    async def scenario() -> tuple[list[str], list]:
        share, planner = PlannerShare(slots=1), OnePlanner()
        asks = [
            ask(share, [("room", i), ("address", f"10.0.0.{i}")], planner.job(f"h{i}", 200))
            for i in range(20)
        ]
        await settle()
        with share.computer_planning():  # the computer's turn goes straight to the pool
            await planner.job("computer", steps=1)()
        await settle()
        results = await asyncio.gather(*asks, return_exceptions=True)
        while share.hints_out:
            await settle()
        return planner.order, results

    order, results = asyncio.run(scenario())
    assert order.index("computer") == 1  # behind the hint that was planning, no other
    refused = [r for r in results if isinstance(r, ActionError)]
    assert {r.code for r in refused} == {"hints_busy"}
    assert len(refused) == 20 - 1 - 8  # one planning, eight waiting, the rest refused
    assert len(order) == 1 + 9  # the computer and every hint that was not refused


def test_without_the_share_the_computer_waits_behind_every_hint():
    """The stand-in planner alone shows the starvation the share prevents."""

    async def scenario() -> list[str]:
        planner = OnePlanner()
        hints = [asyncio.ensure_future(planner.job(f"h{i}", 200)()) for i in range(20)]
        await settle()
        await planner.job("computer", steps=1)()
        await asyncio.gather(*hints)
        return planner.order

    assert asyncio.run(scenario()).index("computer") == 20


def test_one_hint_at_a_time_per_requester():
    async def scenario() -> list:
        share, planner = PlannerShare(slots=1), OnePlanner()
        first = ask(share, [("room", 1), ("address", "a")], planner.job("a1", steps=500))
        await settle()
        again = [
            ask(share, [("room", i), ("address", "a")], planner.job(f"a{i}")) for i in range(2, 21)
        ]
        same_table = ask(share, [("room", 1), ("address", "b")], planner.job("b1"))
        other = ask(share, [("room", 99), ("address", "c")], planner.job("c"))
        return await asyncio.gather(first, *again, same_table, other, return_exceptions=True)

    results = asyncio.run(scenario())
    assert results[0] == "a1" and results[-1] == "c"
    assert {r.code for r in results[1:-1]} == {"hint_pending"}


def test_a_hint_waits_while_the_computer_plans():
    async def scenario() -> tuple[list[str], list[str]]:
        share, planner = PlannerShare(slots=1), OnePlanner()
        with share.computer_planning():
            waiting = ask(share, [("room", 1)], planner.job("hint"))
            await settle()
            before = list(planner.planned)
        await waiting
        return before, planner.planned

    before, after = asyncio.run(scenario())
    assert before == [] and after == ["hint"]


def test_a_hint_whose_requester_left_is_never_planned():
    async def scenario() -> tuple[list[str], PlannerShare]:
        share, planner = PlannerShare(slots=1), OnePlanner()
        with share.computer_planning():
            left = ask(share, [("room", 1), ("address", "a")], planner.job("left"))
            stays = ask(share, [("room", 2), ("address", "b")], planner.job("stays"))
            await settle()
            left.cancel()  # the client disconnected while its hint waited
            await settle()
        assert await stays == "stays"
        again = ask(share, [("room", 1), ("address", "a")], planner.job("again"))
        assert await again == "again"  # the requester may ask anew
        return planner.planned, share

    planned, share = asyncio.run(scenario())
    assert planned == ["stays", "again"]
    assert (share.hints_out, share.holders, len(share.waiting)) == (0, set(), 0)


def test_a_hint_that_cannot_start_in_time_is_refused_unplanned():
    async def scenario() -> tuple[BaseException | str, list[str]]:
        share, planner = PlannerShare(slots=1), OnePlanner()
        with share.computer_planning():
            late = ask(share, [("room", 1)], planner.job("late"), wait=0.05)
            result = (await asyncio.gather(late, return_exceptions=True))[0]
        await settle()
        return result, planner.planned

    result, planned = asyncio.run(scenario())
    assert isinstance(result, ActionError) and result.code == "hint_timeout"
    assert planned == []


def test_a_hint_under_way_holds_the_planner_after_its_requester_left():
    """A plan started in a process cannot be taken back: until it ends no other hint goes
    in, so the computer still waits behind one hint at most."""

    async def scenario() -> tuple[list[str], list[str]]:
        share, planner = PlannerShare(slots=1), OnePlanner()
        gate = asyncio.Event()

        async def long_plan() -> str:
            planner.planned.append("running")
            await gate.wait()
            return "running"

        running = ask(share, [("room", 1)], long_plan)
        await settle()
        running.cancel()
        nxt = ask(share, [("room", 2)], planner.job("next"))
        await settle()
        before = list(planner.planned)
        gate.set()
        await nxt
        return before, planner.planned

    before, after = asyncio.run(scenario())
    assert before == ["running"] and after == ["running", "next"]


def test_each_server_loop_has_its_own_share():
    async def get(slots: int) -> PlannerShare:
        return planner_share(slots)

    one, two = asyncio.run(get(1)), asyncio.run(get(2))
    assert one is not two and two.slots == 2


def test_an_analysis_waits_while_any_computer_plans():
    """`computer_idle` returns at once with no computer planning, and otherwise only once
    the last computer turn being planned is done."""

    async def main():
        share = PlannerShare(slots=1)
        await asyncio.wait_for(share.computer_idle(), 1.0)
        with share.computer_planning():
            with share.computer_planning():
                waiting = asyncio.ensure_future(share.computer_idle())
                await settle()
                assert not waiting.done()
            await settle()
            assert not waiting.done()  # one computer still plans
        await settle()
        assert waiting.done()
        assert not share.idle_waiters

    asyncio.run(main())


class Clock:
    """The share's clock, moved by the stand-in plans (no sleeping)."""

    def __init__(self) -> None:
        self.now = 0.0

    def __call__(self) -> float:
        return self.now


def test_an_address_that_spent_its_planning_budget_is_refused_until_the_minute_passes():
    """20 s of planning a minute per address: three 8 s hints spend it, the fourth is
    refused at once (another address is still served), and a minute after the first
    hint ended the address may ask again."""
    clock = Clock()
    share = PlannerShare(slots=1, clock=clock)

    def plan(seconds: float) -> Callable[[], Awaitable[str]]:
        async def run() -> str:
            clock.now += seconds
            return "planned"

        return run

    async def ask_as(address: str) -> str:
        key = ("address", address)
        return await share.hint(
            [key], plan(8.0), max_waiting=8, max_wait=30.0, budgeted=[key], budget=20.0
        )

    async def scenario() -> list[str]:
        answers = [await ask_as("10.0.0.1") for _ in range(3)]  # ends at 8, 16 and 24 s
        for address in ("10.0.0.1", "10.0.0.2"):
            try:
                answers.append(await ask_as(address))
            except ActionError as exc:
                answers.append(exc.code)
        clock.now = 8.0 + 60.0  # the first plan leaves the minute: 16 s spent
        answers.append(await ask_as("10.0.0.1"))
        return answers

    answers = asyncio.run(scenario())
    assert answers == ["planned"] * 3 + ["planning_budget", "planned", "planned"]
    # At 76 s the plans that ended at 24 s and 76 s are within the minute.
    assert share.budget.spent(("address", "10.0.0.1")) == 16.0


def test_a_budget_forgets_requesters_without_a_plan_in_the_minute():
    clock = Clock()
    budget = PlanningBudget(clock=clock)
    budget.charge("a", 3.0)
    clock.now = 61.0
    budget.charge("b", 1.0)
    assert set(budget.plans) == {"b"} and budget.spent("a") == 0.0
