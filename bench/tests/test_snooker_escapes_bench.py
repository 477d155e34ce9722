"""`python -m bench.escapes --kind snooker`: its tables are snookers on the red (WPBSA
Section 3, Rule 14's straight-line test finds no part of it in sight), drawn the same from
the same seed, and each stroke is counted once, legal or a foul."""

from __future__ import annotations

import numpy as np

from bench.snooker_escapes import RED, SHAPES, TABLE, Tally, set_up, snookered_table, tally
from server.ai import Bot
from server.engine import CUE
from server.rules.snooker_score import COLOUR_IDS
from server.rules.snooker_table import open_path


def test_the_tables_hide_the_red_and_repeat_from_a_seed() -> None:
    first = [snookered_table(np.random.default_rng(5)) for _ in range(2)]
    assert first[0] == first[1]
    rng = np.random.default_rng(7200)
    for _ in range(20):
        placement = snookered_table(rng)
        assert set(placement) == {CUE, RED, *COLOUR_IDS}
        balls = set_up(placement).balls
        assert sorted(balls.on_table_ids()) == sorted(placement)
        assert not open_path(TABLE, balls, [RED])


def test_each_stroke_is_legal_or_a_foul_and_each_plan_has_one_shape() -> None:
    tables = [set_up(snookered_table(np.random.default_rng(3)))]
    counts: Tally = tally(Bot("club"), tables, draws=3, seed=1)
    assert counts.strokes == 3 and counts.legal + counts.fouls == 3
    assert sum(counts.shapes.values()) == 1 and set(counts.shapes) <= set(SHAPES)
