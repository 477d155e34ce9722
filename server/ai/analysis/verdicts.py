"""From values to words: the verdict on a shot, a player's accuracy, the turning points.

A value (the search's scale, -1 lost to +1 won) is read as a winning chance
`(value + 1) / 2`. A shot's loss is how much winning chance the played stroke gave away
against the pro level's best choice, both valued on the same noisy draws. The thresholds
(in winning chance, 0-1):

| verdict  | loss        | e.g.                                                       |
|----------|-------------|------------------------------------------------------------|
| best     | <= 0.03     | the pro's own choice, or one as good within the draws' spread |
| good     | <= 0.08     | a slightly harder pot, a less ideal leave                 |
| mistake  | <= 0.20     | a 70 % pot where a 95 % one was on, a poor safety         |
| blunder  | > 0.20      | a foul or a miss that hands over the table                |

0.03 is about the spread of a value averaged over the analysis' 64 draws (a pot of chance
p moves by ~0.6·sqrt(p(1-p)/64) ≈ 0.03); a foul against a good pot loses 0.3-0.6.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

BEST, GOOD, MISTAKE = 0.03, 0.08, 0.20
VERDICTS = ("best", "good", "mistake", "blunder")
TURNING_POINTS = 3  # the largest losses of a match, mistakes and blunders only
# Accuracy of one shot from its loss in percentage points (lichess's curve for chess
# moves): 100 for no loss, ~65 for 10 points, ~17 for 40.
ACC_A, ACC_K, ACC_B = 103.1668, 0.04354, 3.1669


def win_chance(value: float) -> float:
    """A value of the search (-1..+1) as a winning chance (0..1)."""
    return min(1.0, max(0.0, (value + 1.0) / 2.0))


def loss_of(best_value: float, played_value: float) -> float:
    """Winning chance the played stroke gave away against the best (never negative)."""
    return max(0.0, win_chance(best_value) - win_chance(played_value))


def verdict(loss: float) -> str:
    if loss <= BEST:
        return "best"
    if loss <= GOOD:
        return "good"
    if loss <= MISTAKE:
        return "mistake"
    return "blunder"


def shot_accuracy(loss: float) -> float:
    """0-100: how close to the best a shot was."""
    return min(100.0, max(0.0, ACC_A * math.exp(-ACC_K * 100.0 * loss) - ACC_B))


@dataclass(frozen=True)
class Judged:
    """What `accuracy` and `turning_points` need of a judged shot."""

    n: int
    seat: int
    loss: float


def accuracy(shots: list[Judged], seat: int) -> float | None:
    """The mean accuracy of `seat`'s shots, to one decimal (None: it played none)."""
    mine = [shot_accuracy(s.loss) for s in shots if s.seat == seat]
    return round(sum(mine) / len(mine), 1) if mine else None


def turning_points(shots: list[Judged]) -> list[int]:
    """The shots (their n, in match order) that cost the most: the largest losses among
    the mistakes and blunders."""
    costly = [s for s in shots if s.loss > GOOD]
    costly.sort(key=lambda s: (-s.loss, s.n))
    return sorted(s.n for s in costly[:TURNING_POINTS])
