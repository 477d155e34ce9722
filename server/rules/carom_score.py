"""The state of a three-cushion game that pool has no use for, and the point itself.

UMB "World Rules of Carom Billiard" (cited as "UMB Art. n"): Art. 23 Starting position,
cue-ball; Art. 24 Cannon; Art. 29 End of the match; Art. 83 Three cushions.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

from server.engine.rack import RED, WHITE, YELLOW

CUSHION = -1  # a cushion in a cue ball's path (`ShotFacts.cue_path`); balls are their ids
POINTS_TO_WIN = 15  # an online game's distance (UMB matches are 30 to 50 points)
CUSHIONS_NEEDED = 3


@dataclass(frozen=True)
class CaromScore:
    """points / innings / high_run: per seat. run: the striker's points in this inning.
    white: the seat playing the white (the opener, UMB Art. 23); the other plays the
    yellow. opener: the seat that played the first inning. race_to: points that win.
    equal_innings: the other player gets as many innings as the opener (UMB Art. 29);
    last_inning: that inning is being played. opening: the next stroke is the opening
    stroke, which must hit the red first (UMB Art. 23)."""

    points: tuple[int, ...] = (0, 0)
    innings: tuple[int, ...] = (1, 0)
    high_run: tuple[int, ...] = (0, 0)
    run: int = 0
    white: int = 0
    opener: int = 0
    race_to: int = POINTS_TO_WIN
    equal_innings: bool = False
    last_inning: bool = False
    opening: bool = True

    @classmethod
    def start(
        cls, opener: int, race_to: int = POINTS_TO_WIN, equal_innings: bool = False
    ) -> CaromScore:
        """The score before the opening stroke: the opener's first inning begun."""
        innings = (1, 0) if opener == 0 else (0, 1)
        return cls(
            innings=innings,
            white=opener,
            opener=opener,
            race_to=race_to,
            equal_innings=equal_innings,
        )

    @classmethod
    def start_alone(cls, race_to: int) -> CaromScore:
        """One player's score (practice): its first inning begun."""
        return cls(points=(0,), innings=(1,), high_run=(0,), race_to=race_to)

    def cue_ball(self, seat: int) -> int:
        """The ball `seat` strikes: the white for the opener's seat, else the yellow."""
        return WHITE if seat == self.white else YELLOW

    def average(self, seat: int) -> float:
        """Points per inning (the inning being played counts)."""
        return self.points[seat] / self.innings[seat] if self.innings[seat] else 0.0

    def scored(self, seat: int) -> CaromScore:
        """One more point to `seat`, in its run."""
        points = _bump(self.points, seat, 1)
        run = self.run + 1
        high = _set(self.high_run, seat, max(run, self.high_run[seat]))
        return replace(self, points=points, run=run, high_run=high, opening=False)

    def inning_over(self, next_seat: int) -> CaromScore:
        """The striker's inning ended; `next_seat` begins one."""
        return replace(self, run=0, innings=_bump(self.innings, next_seat, 1), opening=False)


def _bump(values: Sequence[int], seat: int, by: int) -> tuple[int, ...]:
    return tuple(v + by if s == seat else v for s, v in enumerate(values))


def _set(values: Sequence[int], seat: int, value: int) -> tuple[int, ...]:
    return tuple(value if s == seat else v for s, v in enumerate(values))


def is_point(path: Sequence[int], cue: int) -> bool:
    """UMB Art. 83: the cue ball meets both other balls and at least three cushions
    before it meets the second; the cushions and the first ball in any order, one
    cushion counted as often as it is met."""
    cushions, both = _to_second_ball(path, cue)
    return both and cushions >= CUSHIONS_NEEDED


def cushions_before_second(path: Sequence[int], cue: int) -> int:
    """The cushions the cue ball met before the second ball (all of them without one):
    what the screen counts as the shot plays."""
    return _to_second_ball(path, cue)[0]


def _to_second_ball(path: Sequence[int], cue: int) -> tuple[int, bool]:
    """The cushions met before the second ball, and whether the cue ball met it."""
    others = {WHITE, YELLOW, RED} - {cue}
    met: set[int] = set()
    cushions = 0
    for what in path:
        if what == CUSHION:
            cushions += 1
        elif what in others:
            met.add(what)
            if len(met) == len(others):
                return cushions, True
    return cushions, False
