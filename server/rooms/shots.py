"""`ShotPlayer`: a struck shot simulated off the event loop, judged, then shown.

The whole shot is simulated and judged before anyone sees it (`ShotRunner`); its motion
then goes to every member at once and the room waits, at the room's pace, for it to be
shown before the live room records the outcome and announces it (`ShotEnd`): history,
replays and the lobby must not tell a shot's outcome before its members have seen it.
"""

from __future__ import annotations

import asyncio
import logging
import time
from typing import Protocol

from server.engine import BallSet, Shot, ShotResult
from server.protocol import ShotPlan
from server.rules import Outcome

from .metrics import StreamMetrics
from .room import Room
from .shot_runner import ShotRunner
from .stream import RoomStream

log = logging.getLogger(__name__)
SLOW_SHOT = 0.25  # s from strike to stream start worth a warning in the log


class ShotEnd(Protocol):
    """What the live room does once a shot is over."""

    def shot_shown(
        self, seat: int, shot: Shot, shot_id: int, before: BallSet, outcome: Outcome, plan: ShotPlan
    ) -> None:
        """The shot was shown to the end: record it, announce its result, go on."""

    def shot_failed(self) -> None:
        """The shot could not be simulated or judged: the table is as before it."""


class ShotPlayer:
    def __init__(
        self,
        room: Room,
        stream: RoomStream,
        runner: ShotRunner,
        metrics: StreamMetrics,
        pace: float,
        end: ShotEnd,
    ) -> None:
        self.room = room
        self.stream = stream
        self.runner = runner
        self.metrics = metrics
        self.pace = pace
        self.end = end
        self._task: asyncio.Task[None] | None = None

    def start(self, seat: int, shot: Shot, shot_id: int, before: BallSet) -> None:
        """Play a shot the room has begun (`Room.begin_shot`)."""
        self.stream.hold()  # the spectators' copies wait while the shot is simulated
        self._task = asyncio.get_running_loop().create_task(
            self._play(seat, shot, shot_id, before, time.perf_counter())
        )

    def cancel(self) -> None:
        if self._task is not None:
            self._task.cancel()

    async def _play(
        self, seat: int, shot: Shot, shot_id: int, before: BallSet, started: float
    ) -> None:
        judged = await self._judge(shot, shot_id, before, started)
        if judged is None:
            return
        outcome, plan = judged
        await self._show(plan, shot_id, started)
        self.end.shot_shown(seat, shot, shot_id, before, outcome, plan)

    async def _judge(
        self, shot: Shot, shot_id: int, before: BallSet, started: float
    ) -> tuple[Outcome, ShotPlan] | None:
        """Simulate, plan the motion and judge; None when that failed (logged, the shot
        undone). The result (hundreds of small objects) is let go on return, not after the
        seconds it takes to show the shot: fewer live objects for the cyclic collector to
        walk (docs/performance.md)."""
        room = self.room
        assert room.match is not None
        try:
            result, plan = await self.runner.prepare(room.match.game.table, before, shot, shot_id)
            prepared = time.perf_counter()
            outcome = room.apply_shot(result)
            self._log_if_slow(shot, shot_id, result, started, prepared)
        except Exception:
            log.exception("shot %s in room %s failed", shot_id, room.room_id)
            room.abort_shot()
            self.end.shot_failed()
            return None
        finally:
            self.stream.release()
        return outcome, plan

    def _log_if_slow(
        self, shot: Shot, shot_id: int, result: ShotResult, started: float, prepared: float
    ) -> None:
        judged = time.perf_counter()
        if judged - started > SLOW_SHOT:
            log.warning(
                "room %s shot %s: %.0f ms to simulate and plan, %.0f ms to judge "
                "(%d ticks, %d events, %s)",
                self.room.room_id,
                shot_id,
                1000 * (prepared - started),
                1000 * (judged - prepared),
                len(result.frames),
                len(result.events),
                shot,
            )

    async def _show(self, plan: ShotPlan, shot_id: int, started: float) -> None:
        """The whole motion at the strike (clients play it on their own clock), then wait
        until it has been shown."""
        loop = asyncio.get_running_loop()
        start = loop.time()
        self.metrics.shot_started(start, time.perf_counter() - started)
        try:
            self.stream.broadcast_motion(plan)
            self.metrics.sent(start, loop.time() - start)
            delay = start + plan.duration / self.pace - loop.time()
            if delay > 0:
                await asyncio.sleep(delay)
            self.room.show(plan.last, plan.frames)
        except Exception:  # a bug here must not leave the table busy for ever
            log.exception("streaming shot %s in room %s failed", shot_id, self.room.room_id)
        self.stream.motion_shown()
