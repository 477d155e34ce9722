"""What the rules tell the players: fouls, pending choices and the outcome of a shot.

Plain frozen dataclasses: their fields are the data sent to browsers and stored, through
`server.codec`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from server.codec import from_data, to_dict

ANYWHERE = "anywhere"
BEHIND_HEAD_STRING = "behind_head_string"
IN_D = "in_d"  # snooker: on or within the lines of the D (WPBSA 2.9 In-hand, 3.5)


@dataclass(frozen=True)
class Foul:
    """One foul on a shot.

    code: short tag ("scratch", "no_contact", "wrong_ball_first", "no_rail",
        "illegal_break", "shot_clock").
    message: a sentence for people, saying what went wrong.
    """

    code: str
    message: str


@dataclass(frozen=True)
class Decision:
    """A choice a player must make before play goes on; shooting is blocked until then.

    seat: who chooses. options: the words `Game.decide` accepts. prompt: the question.
    """

    seat: int
    options: tuple[str, ...]
    prompt: str

    def to_dict(self) -> dict[str, Any]:
        return to_dict(self)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Decision:
        return from_data(cls, data)


@dataclass(frozen=True)
class Outcome:
    """What one shot (or a shot-clock foul, a concession, a forfeit) did.

    shooter: the seat that acted. pocketed: object and cue balls that dropped, in order
    (balls later re-spotted included; see `spotted`). fouls: every foul on the shot.
    continues: the shooter stays at the table. next_turn: the seat to act next.
    ball_in_hand: None, "anywhere", "behind_head_string" or "in_d", for `next_turn`.
    frame_over / winner / reason: whether the game ended, who won, why (a sentence).
    message: what a player reads, e.g. "Foul: scratch. Ball in hand for Ana."
    spotted: balls put back on the table by the rules. decision: a choice now pending.
    """

    shooter: int
    pocketed: tuple[int, ...]
    fouls: tuple[Foul, ...]
    continues: bool
    next_turn: int
    ball_in_hand: str | None
    frame_over: bool
    winner: int | None
    reason: str | None
    message: str
    spotted: tuple[int, ...] = ()
    decision: Decision | None = None

    def to_dict(self) -> dict[str, Any]:
        """Plain JSON-able data, as browsers get it in `shot_result`."""
        return to_dict(self)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Outcome:
        """The inverse of `to_dict` (for stored games)."""
        return from_data(cls, data)
