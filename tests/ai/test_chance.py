"""The pot chance the search plans with, and the stroke speed it starts from, against the
engine."""

from __future__ import annotations

import math

from server.ai import Bot
from server.ai.aiming import aimed
from server.ai.geometry import FASTFIZ, GEOMETRIC, MIN_AIM_SIGMA, pot_options, speed_for
from server.ai.search import SPEED_FACTORS
from server.engine import BallSet, simulate

from .conftest import TABLE, straight_line

PRO = Bot(Bot.LEVELS[-1]).level


def _straight_pot(object_from_pocket: float, cue_behind: float) -> tuple[BallSet, float, float]:
    """A straight pot into corner 3: (balls, plain chance, fitted chance) at the pro's aim."""
    obj, cue = straight_line(3, object_from_pocket, cue_behind)
    balls = BallSet.place({0: cue, 1: obj})
    plain = pot_options(TABLE, balls, [1], max(PRO.aim, MIN_AIM_SIGMA))
    fitted = pot_options(TABLE, balls, [1], PRO.aim, model=FASTFIZ)
    assert plain and plain[0].pocket == 3 and fitted[0].pocket == 3
    return balls, plain[0].chance, fitted[0].chance


def test_the_fitted_chance_does_not_saturate_and_weighs_the_object_distance() -> None:
    _, plain_short, fitted_short = _straight_pot(0.3, 0.3)
    _, plain_long, fitted_long = _straight_pot(1.2, 0.3)
    # The plain estimate calls both near certain; the fit to the engine's rates over random
    # pots (`python -m bench.ai --only calibrate`) costs a long object-ball distance most.
    assert plain_short > 0.99 and plain_long > 0.9
    assert fitted_long < fitted_short < plain_short
    assert fitted_long < 0.9 * plain_long
    # A long cue-ball distance costs less than the same long object-ball distance.
    _, _, fitted_far_cue = _straight_pot(0.3, 1.2)
    assert fitted_long < fitted_far_cue


def test_only_the_top_level_plans_with_the_fitted_model() -> None:
    models = [Bot(level).level.chance_model for level in Bot.LEVELS]
    assert models[-1] == FASTFIZ
    assert all(m is GEOMETRIC for m in models[:-1])


def test_the_softest_pot_stroke_reaches_a_far_pocket() -> None:
    for object_from_pocket in (0.8, 1.3):
        balls, _, _ = _straight_pot(object_from_pocket, 0.4)
        option = pot_options(TABLE, balls, [1], PRO.aim)[0]
        shot = aimed(option.angle, speed_for(option) * SPEED_FACTORS[0], 0.0, 0.0)
        final = simulate(TABLE, balls, shot).final
        assert not final.on_table[final.index(1)], object_from_pocket
        assert int(final.pockets[final.index(1)]) == 3
        assert math.isclose(shot.angle, option.angle)
