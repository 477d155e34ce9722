"""Find racks and shots for `games` when physics or rules changed one of its games.

    .venv/bin/python -m tests.support.find_games [first_seed] [last_seed]

prints, for 8-ball and 9-ball, the first seeds (from `first_seed`) whose games do what the
docstrings in `games` describe, with the constants to put there; then run
`tests/rooms/test_known_games.py`. (The browser's break in `tests/e2e/test_play.py` is aimed
with the mouse at the apex ball, not quite `BREAK`: that test says whether it still pockets
the same ball.)
"""

from __future__ import annotations

import copy
import sys

from server.engine import Shot
from server.rooms import ActionError

from .games import (
    BREAK,
    EIGHT_BALL_PLACE,
    NINE_BALL_PLACE,
    SOFT_BREAK,
    seated,
    strike,
)

SCRATCH_TRIES = [
    Shot(angle, 3.0, tip)
    for angle in (2.2, 2.0, 2.4, 1.8, 2.6, -2.2, -2.0, 1.6, 2.8)
    for tip in ((0.1, -0.2), (0.0, 0.0))
]
GROUP_TRIES = [
    Shot(angle, speed)
    for angle in (-0.9, -0.5, -0.3, 0.0, 0.3, 0.5, 0.9, -1.2, 1.2, 2.5, -2.5, 3.0)
    for speed in (5.5, 4.0)
]
NINE_BREAK_TRIES = [
    Shot(angle, 9.0, tip)
    for angle in (0.0, 0.01, -0.01, 0.02, -0.02, 0.03, -0.03)
    for tip in ((0.0, 0.0), (0.0, 0.3), (0.0, -0.3))
]
FOUL_TRIES = [
    Shot(angle, speed)
    for angle in (0.4, 0.2, 0.0, -0.2, -0.4, 0.6, -0.6, 0.8, 1.0, -1.0)
    for speed in (9.0, 5.0)
]


def codes(outcome) -> list[str]:
    return [f.code for f in outcome.fouls]


def eight_ball(seed: int) -> str | None:
    """The game `games.EIGHT_BALL` describes, as constants, or None."""
    room, _ = seated("eight_ball", seed)
    opened = strike(room, BREAK)
    if opened.fouls or len(opened.pocketed) != 1 or opened.pocketed[0] == 8:
        return None
    soft, _ = seated("eight_ball", seed)
    if codes(strike(soft, SOFT_BREAK)) != ["illegal_break"]:
        return None
    for scratch in SCRATCH_TRIES:
        after_scratch = copy.deepcopy(room)
        foul = strike(after_scratch, scratch)
        if foul.pocketed != (0,) or codes(foul) != ["no_contact", "scratch"]:
            continue
        for group in GROUP_TRIES:
            played = copy.deepcopy(after_scratch)
            try:
                taken = strike(played, group, place=EIGHT_BALL_PLACE)
            except ActionError:
                break  # the place is not free
            if not taken.fouls and len(taken.pocketed) == 1 and taken.pocketed[0] != 8:
                return (
                    f"EIGHT_BALL = {seed}\nEIGHT_BALL_BREAK_BALL = {opened.pocketed[0]}\n"
                    f"EIGHT_BALL_SCRATCH = {scratch!r}\n"
                    f"EIGHT_BALL_GROUP_SHOT = {group!r}\n"
                    f"EIGHT_BALL_GROUP_BALL = {taken.pocketed[0]}"
                )
    return None


def nine_ball(seed: int) -> str | None:
    """The game `games.NINE_BALL` describes, as constants, or None."""
    for opening in NINE_BREAK_TRIES:
        room, _ = seated("nine_ball", seed)
        scratch = strike(room, opening)
        if scratch.pocketed != (0,) or codes(scratch) != ["scratch"]:
            continue
        for shot in FOUL_TRIES:
            played = copy.deepcopy(room)
            try:
                foul = strike(played, shot, place=NINE_BALL_PLACE)
            except ActionError:
                break  # the place is not free
            if (
                codes(foul) == ["wrong_ball_first"]
                and len(foul.pocketed) == 1
                and foul.pocketed[0] not in (0, 9)
                and not foul.spotted
            ):
                return (
                    f"NINE_BALL = {seed}\nNINE_BALL_BREAK = {opening!r}\n"
                    f"NINE_BALL_FOUL = {shot!r}\nNINE_BALL_FOUL_BALL = {foul.pocketed[0]}"
                )
    return None


def main(first: int = 0, last: int = 5000) -> None:
    for name, find in (("8-ball", eight_ball), ("9-ball", nine_ball)):
        found = 0
        for seed in range(first, last):
            constants = find(seed)
            if constants is not None:
                print(f"# {name}\n{constants}\n", flush=True)
                found += 1
                if found == 2:
                    break
        if not found:
            print(f"# {name}: nothing in seeds {first}..{last - 1}")


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:3]))
