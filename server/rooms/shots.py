"""`ShotPlayer`: a struck shot simulated off the event loop, judged, then shown.

The whole shot is simulated and judged before anyone sees it (`ShotRunner`); its motion
then goes to every member at once and the room waits, at the room's pace, for it to be
shown before the live room records the outcome and announces it (`ShotEnd`): history,
replays and the lobby must not tell a shot's outcome before its members have seen it.

A shot shown is a shot kept: its motion goes out only once the shot's start (the room as
it was, with the shot) is stored, so whoever plays the room next (a restart, another
process after this one died) replays that same shot, bit for bit, never an older table.
The store's write runs while the shot is simulated, so it costs nothing when the store
answers; when it does not (PostgreSQL out of reach) the table waits, and its members are
told so every `SAVING_NOTICE` seconds, until the write lands.
"""

from __future__ import annotations

import asyncio
import logging
import time
from concurrent.futures import Future
from typing import Any, Protocol

from server.engine import BallSet, Shot, ShotResult
from server.protocol import ShotPlan
from server.protocol.outbound import ErrorMessage
from server.rules import Outcome
from server.store import StaleOwner

from .metrics import StreamMetrics
from .room import Room
from .shot_runner import ShotRunner
from .stream import RoomStream

log = logging.getLogger(__name__)
SLOW_SHOT = 0.25  # s from strike to stream start worth a warning in the log
SAVING_NOTICE = 2.0  # s a shot waits for its start to be stored before members are told
SAVING = ErrorMessage(
    code="saving",
    message="Saving the table before the shot is shown; play goes on once it is stored.",
    ref=None,  # not a refusal: the shot was taken and will be shown
)


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

    def start(
        self, seat: int, shot: Shot, shot_id: int, before: BallSet, kept: Future[Any] | None = None
    ) -> None:
        """Play a shot the room has begun (`Room.begin_shot`). `kept`: the store's write of
        its start, which the motion waits for (None: nothing to wait for)."""
        self.stream.hold()  # the spectators' copies wait while the shot is simulated
        self._task = asyncio.get_running_loop().create_task(
            self._play(seat, shot, shot_id, before, time.perf_counter(), kept)
        )

    def cancel(self) -> None:
        if self._task is not None:
            self._task.cancel()

    async def _play(
        self,
        seat: int,
        shot: Shot,
        shot_id: int,
        before: BallSet,
        started: float,
        kept: Future[Any] | None,
    ) -> None:
        judged = await self._judge(shot, shot_id, before, started)
        if judged is None:
            return
        outcome, plan = judged
        if kept is not None and not await self._kept(kept, shot_id):
            return
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

    async def _kept(self, kept: Future[Any], shot_id: int) -> bool:
        """Wait until the shot's start is stored, telling the members while it takes long.
        False: the store refused it (another process owns the room now and replays the
        shot; this one drops the room). Another failure (the store gave up after its
        retries) is logged and the shot shown: the table must not stay busy for ever."""
        stored = asyncio.wrap_future(kept)
        while not (await asyncio.wait({stored}, timeout=SAVING_NOTICE))[0]:
            self.stream.relay(SAVING, exclude=None)
        failure = stored.exception()
        if isinstance(failure, StaleOwner):
            return False
        if failure is not None:
            log.error("room %s shot %s shown unstored: %s", self.room.room_id, shot_id, failure)
        return True

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
