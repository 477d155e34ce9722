import itertools

import numpy as np
import pytest

from server.engine import BallSet, rack, rack_slots

SOLIDS = set(range(1, 8))
STRIPES = set(range(9, 16))


def neighbour_gaps(balls: BallSet, radius: float) -> list[float]:
    p = balls.positions[balls.ids != 0]
    gaps = []
    for a, b in itertools.combinations(range(len(p)), 2):
        d = float(np.linalg.norm(p[a] - p[b])) - 2 * radius
        if d < 1e-3:  # neighbours only
            gaps.append(d)
    return gaps


@pytest.mark.parametrize("seed", range(10))
def test_eight_ball_rack(table, seed):
    balls = rack("eight_ball", table, seed=seed)
    assert sorted(balls.ids.tolist()) == list(range(16))
    assert balls.position_of(0) == table.head_spot
    slots = rack_slots("eight_ball", table)
    # Apex on the foot spot (within the jitter), 8 in the centre of the third row.
    assert np.allclose(balls.position_of(balls_at(balls, slots[0])), table.foot_spot, atol=1e-4)
    assert balls_at(balls, slots[4]) == 8
    corners = {balls_at(balls, slots[10]), balls_at(balls, slots[14])}
    assert len(corners & SOLIDS) == 1 and len(corners & STRIPES) == 1
    gaps = neighbour_gaps(balls, table.ball_radius)
    assert len(gaps) == 30  # a 15-ball triangle has 30 touching neighbour pairs
    assert all(0.0 <= g <= 1e-4 for g in gaps)


def balls_at(balls: BallSet, xy: tuple[float, float]) -> int:
    d = np.linalg.norm(balls.positions - np.array(xy), axis=1)
    return int(balls.ids[int(np.argmin(d))])


@pytest.mark.parametrize("seed", range(10))
def test_nine_ball_diamond(table, seed):
    balls = rack("nine_ball", table, seed=seed)
    assert sorted(balls.ids.tolist()) == list(range(10))
    slots = rack_slots("nine_ball", table)
    assert balls_at(balls, slots[0]) == 1
    assert balls_at(balls, slots[4]) == 9
    gaps = neighbour_gaps(balls, table.ball_radius)
    assert len(gaps) == 16  # the diamond's neighbour pairs
    assert all(0.0 <= g <= 1e-4 for g in gaps)


def test_racks_follow_the_seed(table):
    a = rack("eight_ball", table, seed=7)
    b = rack("eight_ball", table, seed=7)
    c = rack("eight_ball", table, seed=8)
    assert np.array_equal(a.positions, b.positions)
    assert not np.array_equal(a.positions, c.positions)


def test_unknown_game(table):
    with pytest.raises(ValueError):
        rack("snooker", table)
