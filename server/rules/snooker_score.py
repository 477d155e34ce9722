"""The state of a snooker frame that pool has no use for: the points, the break, the ball
on, a nominated ball, a free ball, misses in a row and the re-spotted black.

WPBSA "Official Rules of the Games of Snooker and English Billiards" (the rulebook the
docstrings cite as "WPBSA s.r", Section s, Rule r; the edition revised November 2019):
2.11 Ball On, 2.12 Nominated Ball, 2.13 Free Ball, 3.1 Description (the balls' values),
3.3 Mode of Play.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from server.engine.rack import COLOURS, REDS

RED = "red"  # the ball on is a red (any red)
COLOUR = "colour"  # after a red: any colour, the one the striker nominates
VALUES: dict[int, int] = {
    **dict.fromkeys(REDS, 1),
    **{b: 2 + k for k, b in enumerate(COLOURS.values())},
}
COLOUR_IDS: tuple[int, ...] = tuple(COLOURS.values())  # yellow (2) to black (7)
NAMES: dict[int, str] = {ball: name for name, ball in COLOURS.items()}
BLACK = COLOURS["black"]


@dataclass(frozen=True)
class FrameScore:
    """points: each seat's points in the frame. current_break: the striker's points in
    this visit. on: RED, COLOUR, or a colour's name once the reds are gone (the lowest
    colour on the table). nominated: the ball the striker nominated (a colour when on
    COLOUR; the free ball). free_ball: the striker plays a free ball (WPBSA 3.12).
    misses: per seat, the misses in a row that count toward three (WPBSA 3.14).
    respotted_black: the frame was tied and the black re-spotted (WPBSA 3.4).
    highest_break: per seat.
    """

    points: tuple[int, ...] = (0, 0)
    current_break: int = 0
    on: str = RED
    nominated: int | None = None
    free_ball: bool = False
    misses: tuple[int, ...] = (0, 0)
    respotted_black: bool = False
    highest_break: tuple[int, ...] = (0, 0)

    @classmethod
    def start(cls, seats: int) -> FrameScore:
        return cls(points=(0,) * seats, misses=(0,) * seats, highest_break=(0,) * seats)


def reds_left(on_table: Sequence[int]) -> list[int]:
    return [b for b in on_table if b in VALUES and VALUES[b] == 1]


def colours_left(on_table: Sequence[int]) -> list[int]:
    return [b for b in COLOUR_IDS if b in on_table]


def on_after_turn(on_table: Sequence[int]) -> str:
    """The ball on for the player coming to the table: a red while any is left, else the
    lowest-valued colour (WPBSA 3.3 Mode of Play)."""
    if reds_left(on_table):
        return RED
    left = colours_left(on_table)
    return NAMES[left[0]] if left else NAMES[BLACK]


def balls_on(score: FrameScore, on_table: Sequence[int]) -> list[int]:
    """The balls the striker may hit first (WPBSA 2.11 Ball On): any red; any
    colour (only the nominated one once nominated); the lowest colour; and a free ball."""
    if score.on == RED:
        on = reds_left(on_table)
    elif score.on == COLOUR:
        on = [score.nominated] if score.nominated is not None else colours_left(on_table)
    else:
        on = [COLOURS[score.on]]
    if score.free_ball and score.nominated is not None and score.nominated not in on:
        on = [*on, score.nominated]
    return on


def value_on(score: FrameScore) -> int:
    """The value of the ball on (a free ball is worth the ball on it stands for, 2.13)."""
    if score.on == RED:
        return 1
    if score.on == COLOUR:
        return VALUES.get(score.nominated, 0) if score.nominated is not None else 0
    return VALUES[COLOURS[score.on]]


def remaining(score: FrameScore, on_table: Sequence[int]) -> int:
    """The points still on the table for the striker: 8 a red (with a black after it),
    7 for the colour after a red, and the colours from the ball on up (2 to 7: 27)."""
    reds = len(reds_left(on_table))
    colours = colours_left(on_table)
    if score.on in (RED, COLOUR):
        after_red = 7 if score.on == COLOUR else 0
        return 8 * reds + after_red + 27
    return sum(VALUES[c] for c in colours)


def snookers_required(score: FrameScore, on_table: Sequence[int], seat: int) -> int:
    """How many 4-point penalties `seat` needs to draw level, 0 when the points remaining
    are enough (a tie goes to the re-spotted black)."""
    behind = max(score.points) - score.points[seat]
    short = behind - remaining(score, on_table)
    return 0 if short <= 0 else -(-short // 4)
