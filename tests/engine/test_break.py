"""The break: a rack's touching balls resolve quickly, never overlap, never loop."""

import pytest

from server.engine import Shot, rack, simulate

from .conftest import in_play_area, pair_min_gap

MAX_EVENTS = 2000


@pytest.mark.parametrize("game", ["eight_ball", "nine_ball"])
@pytest.mark.parametrize("seed", range(12))
def test_every_rack_seed_breaks_to_rest(table, game, seed):
    balls = rack(game, table, seed=seed)
    result = simulate(table, balls, Shot(0.0, 10.0))
    assert result.stalled_ticks == 0
    assert len(result.events) < MAX_EVENTS
    assert result.final.at_rest()
    hits = [e for e in result.events if e.kind == "ball"]
    assert len(hits) >= len(balls) - 1  # the whole rack was driven apart
    for k in range(len(result.frames)):
        on = result.frames.on_table[k]
        assert pair_min_gap(result.frames.positions[k], on, table.ball_radius) >= -1e-9
        assert in_play_area(table, result.frames.positions[k][on]).all()


@pytest.mark.parametrize(
    "speed,angle,tip", [(12.0, 0.0, (0, 0)), (11.0, 0.01, (0.2, 0.3)), (8.0, -0.015, (0, -0.4))]
)
def test_hard_and_off_centre_breaks(table, speed, angle, tip):
    result = simulate(table, rack("eight_ball", table, seed=1), Shot(angle, speed, tip=tip))
    assert result.stalled_ticks == 0 and len(result.events) < MAX_EVENTS
    assert result.final.at_rest()


def test_perfectly_frozen_rack(table):
    # Every neighbour touching exactly: many zero-time contacts in a row.
    from server.engine import BallSet, rack_slots

    slots = rack_slots("eight_ball", table)
    d = 2 * table.ball_radius
    # Re-space the nominal lattice to exact contact.
    fx, fy = table.foot_spot
    placement = {0: table.head_spot}
    for ball, (x, y) in enumerate(slots, start=1):
        placement[ball] = (fx + (x - fx) * d / (d + 0.05e-3), fy + (y - fy) * d / (d + 0.05e-3))
    result = simulate(table, BallSet.place(placement), Shot(0.0, 10.0))
    assert result.stalled_ticks == 0 and len(result.events) < MAX_EVENTS
    assert result.final.at_rest()
