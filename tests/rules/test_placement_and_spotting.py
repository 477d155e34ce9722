"""Ball in hand placement and re-spotting on the long string."""

from __future__ import annotations

import math

import pytest

from server.engine import BallSet
from server.rules import IllegalActionError
from server.rules.placement import can_place
from server.rules.spotting import SPOT_GAP, respot, spot_point

from .helpers import TABLE, crafted, hit, pot, rail

R = TABLE.ball_radius


def test_placement_inside_the_bed_and_clear_of_balls() -> None:
    balls = BallSet.place({0: (0.5, 0.5), 1: (1.0, 0.6)})
    assert can_place(TABLE, balls, "anywhere", 1.5, 0.6)
    assert not can_place(TABLE, balls, "anywhere", R - 1e-6, 0.6)  # into the cushion
    assert not can_place(TABLE, balls, "anywhere", 1.0, TABLE.width)  # on the rail
    assert not can_place(TABLE, balls, "anywhere", 1.0 + 2 * R - 1e-6, 0.6)  # overlaps the 1
    assert can_place(TABLE, balls, "anywhere", 1.0 + 2 * R, 0.6)  # frozen to it is fine
    assert can_place(TABLE, balls, "anywhere", 0.5, 0.5)  # where the cue ball already is
    for bad in (math.nan, math.inf, "1.0", None):
        assert not can_place(TABLE, balls, "anywhere", bad, 0.6)  # type: ignore[arg-type]
    assert not can_place(TABLE, balls, None, 1.5, 0.6)


def test_behind_the_head_string_means_x_at_most_head_string() -> None:
    balls = BallSet.place({0: (0.5, 0.5), 1: (1.5, 0.6)})
    assert can_place(TABLE, balls, "behind_head_string", TABLE.head_string, 0.6)
    assert not can_place(TABLE, balls, "behind_head_string", TABLE.head_string + 1e-9, 0.6)


def test_place_cue_needs_ball_in_hand(eight) -> None:
    eight.apply(0, crafted(eight.balls, hit(0, 1), *[rail(b) for b in (2, 3, 4, 5)]))
    with pytest.raises(IllegalActionError) as err:
        eight.place_cue(1, 0.5, 0.5)
    assert err.value.code == "no_ball_in_hand"
    with pytest.raises(IllegalActionError) as err:
        eight.place_cue(0, 0.5, 0.5)
    assert err.value.code == "not_your_turn"


def test_failed_placement_changes_nothing(eight) -> None:
    eight.apply(0, crafted(eight.balls, hit(0, 1), pot(2, 1), pot(0, 0)))
    before = eight.public_state()
    with pytest.raises(IllegalActionError) as err:
        eight.place_cue(1, *TABLE.foot_spot)  # on the apex ball
    assert err.value.code == "illegal_placement"
    assert eight.public_state() == before


def test_spot_on_the_foot_spot_when_free() -> None:
    balls = BallSet.place({0: (0.5, 0.5), 9: (0.1, 0.1)})
    assert spot_point(TABLE, balls, 9) == TABLE.foot_spot


def test_spot_behind_the_foot_spot_when_taken() -> None:
    fx, fy = TABLE.foot_spot
    balls = BallSet.place({0: (0.5, 0.5), 1: (fx, fy), 2: (fx + 2 * R + 0.01, fy + R), 9: (0, 0)})
    x, y = spot_point(TABLE, balls, 9)
    assert y == fy and x > fx
    for b in (1, 2):  # frozen to its neighbours, overlapping none
        bx, by = balls.position_of(b)
        assert math.hypot(x - bx, y - by) >= 2 * R
    # the nearest free point: the gap between the 1 and the 2 is too small, so past the 2
    bx, by = balls.position_of(2)
    assert x == pytest.approx(bx + math.sqrt((2 * R + SPOT_GAP) ** 2 - R * R))


def test_spot_in_front_when_the_line_behind_is_full() -> None:
    fx, fy = TABLE.foot_spot
    step = 2 * R + 0.001
    placement = {k + 1: (fx + k * step, fy) for k in range(12) if fx + k * step <= TABLE.length - R}
    assert placement[max(placement)][0] + step > TABLE.length - R  # the line is full
    placement[0] = (0.5, 0.5)
    placement[15] = (0.1, 0.1)
    balls = BallSet.place(placement)
    x, y = spot_point(TABLE, balls, 15)
    assert y == fy and x < fx and x == pytest.approx(fx - 2 * R - SPOT_GAP)


def test_respot_puts_the_ball_back_on_the_table() -> None:
    balls = BallSet.place({0: (0.5, 0.5), 9: (0.1, 0.1)})
    balls.states[balls.index(9)] = 4
    balls.pockets[balls.index(9)] = 0
    out = respot(TABLE, balls, (9,))
    assert 9 in out.on_table_ids() and out.position_of(9) == TABLE.foot_spot
    assert 9 not in balls.on_table_ids()  # the input is not modified
