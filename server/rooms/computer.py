"""The computer's seat in a room: when the match waits for it, think (off the event loop),
show the cue moving, then act through the same room actions as a person.

The search runs in a thread (`Bot.plan` spends its time in the engine's compiled code, which
releases the GIL), on a copy of the game, so no other room waits for it. Its random draws
come from the room's seed and the shot number: a replayed position gets the same turn.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from server.ai import Bot, Turn
from server.codec import from_data, to_data
from server.engine import Shot
from server.rules import Game

from .errors import ActionError
from .room import Room

log = logging.getLogger(__name__)
AIM_STEPS = 6  # aim relays while the cue swings round to the shot
MAX_STEPS = 4  # turns in a row before handing back (decision, then its shot, ...)


@dataclass
class ComputerSeat:
    """Plays `seat` of `room` at `level`. The room hands `start` its way to apply a turn
    (`apply(turn, shot)`) and to show the cue (`relay(angle, power)`)."""

    room: Room
    seat: int
    level: str
    pause: float  # s of "thinking" before a turn is shown, at pace 1
    bot: Bot = field(init=False)
    task: asyncio.Task | None = field(default=None, init=False)

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
        game = from_data(Game, to_data(match.game))  # the search works on its own copy
        started = asyncio.get_running_loop().time()
        try:
            turn = await asyncio.to_thread(self.bot.plan, game, self.seat)
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
            shot = self.bot.execute(turn.shot, rng)
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
