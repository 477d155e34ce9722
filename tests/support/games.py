"""The racks the server tests play: fixed seeds whose games are known.

A room gets its rack seed from the app's `SeedSource`; the tests build their apps with
`SeedSource.fixed(seed)` and one of these seeds, so every run plays the same game and a test
asserts what happens instead of branching on whatever a random rack gave. Each game below
was found by simulating the shots; `tests/rooms/test_known_games.py` replays every claim on a
bare `Room`, so a change of physics or rules that alters one of these games fails there,
naming the game, before the server tests that rely on it fail in stranger ways.
"""

from __future__ import annotations

import functools

from server.engine import Shot, simulate
from server.rooms import Room
from server.rules import Outcome


def shoot_message(shot: Shot) -> dict:
    """The `shoot` message for `shot`."""
    return {"type": "shoot", "angle": shot.angle, "speed": shot.speed, "tip": list(shot.tip)}


BREAK = Shot(0.0, 9.0)
"""The break every test plays: from the head spot straight up the table, full speed."""
BREAK_MESSAGE = shoot_message(BREAK)

EIGHT_BALL = 2942
"""8-ball rack seed 2942 (the first game of a match with this seed):

- `BREAK` pockets `EIGHT_BALL_BREAK_BALL` and nothing else: a legal break, the table stays
  open, Ana shoots again. (The browser's break in `tests/e2e/test_play.py`, aimed with the
  mouse at the apex ball, does the same.) It rolls for `eight_ball_break_ticks()` ticks.
- Then `EIGHT_BALL_SCRATCH` touches no ball and the cue ball drops: a foul, Ben has ball in
  hand anywhere.
- Ben puts the cue ball at `EIGHT_BALL_PLACE` and `EIGHT_BALL_GROUP_SHOT` pockets
  `EIGHT_BALL_GROUP_BALL` and nothing else: Ben takes its group and shoots again.
- A soft break instead, `SOFT_BREAK`, is illegal: no ball drops and fewer than four reach
  a rail; Ben decides (accept, rerack or rerack_opponent_breaks).

(The same game under the engine before commit b7eb5cd's cushion and pocket model and
after it.)
"""
EIGHT_BALL_BREAK_BALL = 6
EIGHT_BALL_SCRATCH = Shot(1.6, 3.0)
EIGHT_BALL_PLACE = (0.4, 0.3)
EIGHT_BALL_GROUP_SHOT = Shot(3.0, 5.5)
EIGHT_BALL_GROUP_BALL = 10
SOFT_BREAK = Shot(0.0, 1.5)
EIGHT_BALL_BREAK_SAYS = (
    f"Ana pocketed the {EIGHT_BALL_BREAK_BALL}. Legal break. The table is open. Ana shoots again."
)
"""What the players read after the break of `EIGHT_BALL`."""

NINE_BALL = 63
"""9-ball rack seed 63:

- `NINE_BALL_BREAK` (a touch left of straight, with follow) scratches: the cue ball drops,
  no object ball does. Ben has ball in hand anywhere (and may push out).
- Ben puts the cue ball at `NINE_BALL_PLACE` and `NINE_BALL_FOUL` hits a wrong ball first
  and pockets `NINE_BALL_FOUL_BALL`: a foul (the ball stays down), Ana has ball in hand
  anywhere.

(The same game under the engine before commit b7eb5cd's cushion and pocket model and
after it.)
"""
NINE_BALL_BREAK = Shot(-0.01, 9.0, (0.0, 0.3))
NINE_BALL_PLACE = (0.5, 0.4)
NINE_BALL_FOUL = Shot(-0.2, 9.0)
NINE_BALL_FOUL_BALL = 6


@functools.cache
def eight_ball_break_ticks() -> int:
    """How long `BREAK` rolls in the `EIGHT_BALL` rack, in ticks, as the engine has it (the
    stream must end on exactly that tick)."""
    room, _ = seated("eight_ball", EIGHT_BALL)
    assert room.match is not None
    return len(simulate(room.match.game.table, room.match.game.balls, BREAK).frames)


def seated(game: str = "eight_ball", seed: int = EIGHT_BALL, **options) -> tuple[Room, list[str]]:
    """A bare `Room` racked with `seed`, Ana and Ben seated (only Ana at a practice table):
    the room and their tokens."""
    room = Room("r00m1d_abcde", game, seed=seed, **options)
    names = ["Ana"] if room.practice else ["Ana", "Ben"]
    return room, [room.join(name)[1] for name in names]


def strike(room: Room, shot: Shot, place: tuple[float, float] | None = None) -> Outcome:
    """The acting seat of a bare `room` plays `shot` as the server does (begin, simulate,
    judge, end), first putting the cue ball at `place` (ball in hand)."""
    seat = room.acting_seat()
    assert seat is not None and room.match is not None
    if place is not None:
        room.place_cue(seat, *place)
    _, before = room.begin_shot(seat)
    outcome = room.apply_shot(simulate(room.match.game.table, before, shot))
    room.end_shot()
    return outcome
