"""The computer's seats of a live room: each takes its turn when the match waits for it,
shows its cue in aim relays, and acts through the same room actions as a person."""

from __future__ import annotations

import functools
from typing import Protocol

from server.ai import Turn
from server.config import Settings
from server.engine import Shot
from server.protocol.outbound import AimRelay

from .computer import ComputerSeat
from .room import Room
from .stream import RoomStream


class Actions(Protocol):
    """What the live room does with a computer's turn, as with a person's."""

    def changed(self) -> None:
        """The room changed (a decision): clock, `state`, storage."""

    def start_shot(self, seat: int | None, shot: Shot, intended: Shot | None = None) -> None:
        """Strike `shot` for `seat`, then simulate and show it; `intended` is the plan
        before the arm's error (recorded beside the stroke, for the analysis)."""


class ComputerTurns:
    def __init__(
        self, room: Room, settings: Settings, stream: RoomStream, actions: Actions
    ) -> None:
        self.room = room
        self.stream = stream
        self.actions = actions
        self.pace = settings.pace
        self.seats = {
            seat: ComputerSeat(
                room,
                seat,
                level,
                settings.computer_pause,
                settings.computer_workers,
                settings.computer_starved,
            )
            for seat, level in room.computer.items()
        }

    def wake(self) -> None:
        """If the match now waits for a computer seat, let it take its turn."""
        for seat, computer in self.seats.items():
            if computer.due():
                computer.start(
                    functools.partial(self._act, seat),
                    functools.partial(self._aim, seat),
                    self.pace,
                )

    def cancel(self) -> None:
        for computer in self.seats.values():
            computer.cancel()

    def _aim(self, seat: int, angle: float, power: float) -> None:
        self.stream.relay(AimRelay(seat=seat, angle=angle, power=power, tip=(0.0, 0.0)), None)

    def _act(self, seat: int, turn: Turn, shot: Shot | None) -> None:
        room = self.room
        if turn.decision is not None:
            room.decide(seat, turn.decision)
            self.actions.changed()
            return
        if turn.push_out:
            room.push_out(seat)
        if turn.place is not None:
            room.place_cue(seat, *turn.place)
        if turn.call is not None and room.match is not None and room.match.game.requires_call:
            room.call_pocket(seat, turn.call)
        if turn.nominate is not None:
            room.nominate(seat, turn.nominate)
        if shot is not None:
            self.actions.start_shot(seat, shot, turn.shot)
