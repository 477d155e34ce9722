"""A room's seat timers: the shot clock of the seat to act and the reconnection grace of
players whose socket dropped.

The timers only keep time and decide what their expiry means for the room (a timeout, a
forfeit, an abandoned match); what follows (the result, the next rack, the `state`) is the
live room's, told through `Referee`.
"""

from __future__ import annotations

import asyncio
import logging
from dataclasses import dataclass
from typing import Protocol

from server.protocol.outbound import ClockInfo, GraceInfo, ResultCause
from server.rules import Outcome

from .errors import ActionError
from .room import Room

log = logging.getLogger(__name__)
ROLLING_RETRY = 0.2  # s: a grace that ends while the balls roll waits for them this often


class Referee(Protocol):
    """What the live room does when a timer ends."""

    def next_turn(self, restart: bool) -> None:
        """The turn may have moved: wake the computer, (re)start the shot clock."""

    def conclude(self, cause: ResultCause, outcome: Outcome, absent: int | None = None) -> None:
        """A non-shot outcome to announce (a timeout, a forfeit)."""

    def abandon(self) -> None:
        """Every player left and none came back: the match stops without a winner."""


@dataclass
class _Timer:
    seat: int
    deadline: float  # loop time
    handle: asyncio.TimerHandle


class SeatTimers:
    """The shot clock (one seat at a time) and the grace periods (one per absent player)."""

    def __init__(self, room: Room, grace: float, referee: Referee) -> None:
        self.room = room
        self.grace = grace
        self.referee = referee
        self._clock: _Timer | None = None
        self._grace: dict[int, _Timer] = {}

    def cancel_all(self) -> None:
        self.cancel_clock()
        for seat in list(self._grace):
            self.cancel_grace(seat)

    # ---- shot clock ---------------------------------------------------------------------

    def clock_info(self) -> ClockInfo | None:
        if self._clock is None:
            return None
        remaining = max(0.0, self._clock.deadline - asyncio.get_running_loop().time())
        return ClockInfo(
            seat=self._clock.seat, remaining=round(remaining, 2), limit=self.room.shot_clock
        )

    def arm_clock(self, restart: bool) -> None:
        """Run the clock for the seat to act (none: stopped); `restart`: afresh even when
        that seat's clock already runs."""
        seat = self.room.acting_seat() if self.room.shot_clock > 0 else None
        if seat is None:
            self.cancel_clock()
            return
        if not restart and self._clock is not None and self._clock.seat == seat:
            return
        self.cancel_clock()
        loop = asyncio.get_running_loop()
        limit = self.room.clock_limit()  # longer on the room's first break
        self._clock = _Timer(
            seat, loop.time() + limit, loop.call_later(limit, self._on_clock, seat)
        )

    def cancel_clock(self) -> None:
        if self._clock is not None:
            self._clock.handle.cancel()
            self._clock = None

    def _on_clock(self, seat: int) -> None:
        self._clock = None
        if self.room.acting_seat() != seat:
            self.referee.next_turn(restart=True)
            return
        try:
            outcome = self.room.timeout(seat)
        except ActionError:
            log.warning("shot clock timeout refused in room %s", self.room.room_id)
            return
        self.referee.conclude("timeout", outcome)

    # ---- reconnection grace ---------------------------------------------------------------

    def grace_info(self) -> list[GraceInfo]:
        if not self._grace:
            return []
        now = asyncio.get_running_loop().time()
        return [
            GraceInfo(
                seat=t.seat, remaining=round(max(0.0, t.deadline - now), 2), left=self._seen(t.seat)
            )
            for t in sorted(self._grace.values(), key=lambda t: t.seat)
        ]

    def _seen(self, seat: int) -> bool:
        """The seat's player has been at the table (connected once)."""
        held = self.room.seats[seat]
        return held is not None and held.seen

    def start_grace(self, seat: int) -> None:
        """`seat`'s player is away: the seat is kept for the grace period (not in practice,
        outside a match, for the computer, or once the match is abandoned)."""
        room, match = self.room, self.room.match
        if room.practice or match is None or match.over or seat in self._grace:
            return
        if room.abandoned or seat in room.computer:
            return
        loop = asyncio.get_running_loop()
        self._grace[seat] = _Timer(
            seat, loop.time() + self.grace, loop.call_later(self.grace, self._on_grace, seat)
        )

    def grace_for_absent(self) -> None:
        """A match (re)starts: every seated player not connected has the grace period."""
        for i, s in enumerate(self.room.seats):
            if s is not None and not s.connected:
                self.start_grace(i)

    def cancel_grace(self, seat: int) -> None:
        timer = self._grace.pop(seat, None)
        if timer is not None:
            timer.handle.cancel()

    def _on_grace(self, seat: int) -> None:
        timer = self._grace.get(seat)
        seat_info = self.room.seats[seat]
        match = self.room.match
        if timer is None or seat_info is None or seat_info.connected:
            self._grace.pop(seat, None)
            return
        if match is None or match.over:
            self._grace.pop(seat, None)
            return
        if self.room.phase == "rolling":  # let the shot finish first
            loop = asyncio.get_running_loop()
            timer.handle = loop.call_later(ROLLING_RETRY, self._on_grace, seat)
            return
        if self._everyone_left():
            self.referee.abandon()
            return
        del self._grace[seat]
        outcome = self.room.forfeit(seat, f"{seat_info.name} left the table and did not come back.")
        self.referee.conclude("forfeit", outcome, absent=seat)

    def _everyone_left(self) -> bool:
        """Every person seated (the computer is not one) was here and is gone."""
        room = self.room
        people = [s for i, s in enumerate(room.seats) if i not in room.computer and s is not None]
        return all(s.seen and not s.connected for s in people)
