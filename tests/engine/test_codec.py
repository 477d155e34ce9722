"""`Shot`, `Table` and `BallSet` through the one codec (`server.codec`): exact round trips,
validation on load, and the stored forms that existing databases hold."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from server.codec import from_data, from_json, to_data, to_json
from server.engine import MAX_SPEED, BallSet, MotionState, Shot, Table, rack

# Floats that break careless encoders: signed zero, subnormals, the extremes.
AWKWARD = [
    -0.0,
    0.0,
    5e-324,
    -5e-324,
    2.2250738585072009e-308,
    1e-300,
    -1e-300,
    1.7976931348623157e308,
]
finite = st.one_of(st.sampled_from(AWKWARD), st.floats(allow_nan=False, allow_infinity=False))
small = st.one_of(
    st.sampled_from([-0.0, 0.0, 5e-324, -5e-324, 1e-300, -1e-300]),
    st.floats(-0.35, 0.35, allow_nan=False),
)
speeds = st.one_of(
    st.sampled_from([5e-324, 1e-300, MAX_SPEED]), st.floats(0.0, MAX_SPEED, exclude_min=True)
)
int64 = st.integers(-(2**63), 2**63 - 1)

ARRAYS = ("ids", "positions", "velocities", "spins", "states", "phases", "pockets")


def bits(x: float) -> str:
    return float(x).hex()


def same_array(a: np.ndarray, b: np.ndarray) -> bool:
    if a.dtype != b.dtype or a.shape != b.shape:
        return False
    if a.dtype == np.float64:
        return np.array_equal(a.view(np.int64), b.view(np.int64))
    return np.array_equal(a, b)


def same_balls(a: BallSet, b: BallSet) -> bool:
    return all(same_array(getattr(a, name), getattr(b, name)) for name in ARRAYS)


def round_trips(value: Any) -> list[Any]:
    kind = type(value)
    return [from_data(kind, to_data(value)), from_json(kind, to_json(value))]


# --- Shot ------------------------------------------------------------------------------


@settings(deadline=None)
@given(finite, speeds, small, small)
def test_a_shot_round_trips_bit_for_bit(
    angle: float, speed: float, side: float, height: float
) -> None:
    shot = Shot(angle, speed, (side, height))
    for back in round_trips(shot):
        assert isinstance(back, Shot)
        assert [bits(v) for v in (back.angle, back.speed, *back.tip)] == [
            bits(v) for v in (angle, speed, side, height)
        ]
        assert isinstance(back.tip, tuple)


def test_a_shot_is_plain_data() -> None:
    assert to_data(Shot(1.5, 3.0, (0.1, -0.2))) == {"angle": 1.5, "speed": 3.0, "tip": [0.1, -0.2]}
    assert from_data(Shot, {"angle": 1.5, "speed": 3.0}) == Shot(1.5, 3.0)


@pytest.mark.parametrize(
    "data",
    [
        {"angle": 0.0, "speed": 0.0},
        {"angle": 0.0, "speed": MAX_SPEED * 2},
        {"angle": 0.0, "speed": 1.0, "tip": [0.4, 0.4]},
        {"angle": "nan", "speed": 1.0},
        {"angle": 0.0, "speed": 1.0, "tip": [0.1]},
        {"speed": 1.0},
    ],
)
def test_an_invalid_shot_is_refused_on_load(data: dict) -> None:
    with pytest.raises(ValueError):
        from_data(Shot, data)
    with pytest.raises(ValueError):
        from_json(Shot, json.dumps(data))


# --- Table -----------------------------------------------------------------------------


@settings(deadline=None)
@given(st.tuples(finite, finite, finite, finite, finite))
def test_a_table_round_trips_bit_for_bit(values: tuple[float, ...]) -> None:
    table = Table(*values)
    for back in round_trips(table):
        assert isinstance(back, Table)
        fields = (back.length, back.width, back.ball_radius, back.corner_mouth, back.side_mouth)
        assert [bits(v) for v in fields] == [bits(v) for v in values]
        assert len(back.cushions) == len(back.pockets) == 6


def test_a_table_is_stored_as_its_constructor_fields() -> None:
    table = Table.pool("8ft")
    assert to_data(table) == {
        "length": 2.34,
        "width": 1.17,
        "ball_radius": table.ball_radius,
        "corner_mouth": table.corner_mouth,
        "side_mouth": table.side_mouth,
    }
    assert from_data(Table, to_data(table)) == table


def test_the_older_list_form_of_a_table_still_loads() -> None:
    table = Table.pool("7ft")
    stored = [table.length, table.width, table.ball_radius, table.corner_mouth, table.side_mouth]
    assert Table.from_fields(stored) == table
    assert from_data(Table, stored) == table
    assert from_json(Table, json.dumps(stored)) == table
    assert from_data(Table, [1.98, 0.99]) == table
    for bad in ([1.0], [1.0] * 6, ["x", 1.0]):
        with pytest.raises(ValueError):
            from_data(Table, bad)


def test_the_browser_view_is_not_the_stored_form() -> None:
    view = Table.pool().to_dict()
    assert {"cushions", "pockets", "head_spot"} <= view.keys()


# --- BallSet ---------------------------------------------------------------------------


@st.composite
def ball_sets(draw: st.DrawFn) -> BallSet:
    n = draw(st.integers(1, 16))

    def floats(*tail: int) -> np.ndarray:
        return draw(hnp.arrays(np.float64, (n, *tail), elements=finite))

    def ints() -> np.ndarray:
        return draw(hnp.arrays(np.int64, (n,), elements=int64))

    return BallSet(ints(), floats(2), floats(2), floats(3), ints(), floats(), ints())


@settings(deadline=None)
@given(ball_sets())
def test_a_ball_set_round_trips_bit_for_bit(balls: BallSet) -> None:
    for back in [*round_trips(balls), BallSet.from_dict(balls.to_dict())]:
        assert isinstance(back, BallSet)
        assert same_balls(back, balls)
        assert all(getattr(back, name).flags.c_contiguous for name in ARRAYS)


def test_the_stored_form_of_a_ball_set_is_unchanged() -> None:
    balls = rack("nine_ball", Table.pool(), seed=7)
    balls.states[3] = MotionState.POCKETED
    balls.pockets[3] = 2
    before_the_codec = {
        "ids": balls.ids.tolist(),
        "positions": balls.positions.tolist(),
        "velocities": balls.velocities.tolist(),
        "spins": balls.spins.tolist(),
        "states": balls.states.tolist(),
        "phases": balls.phases.tolist(),
        "pockets": balls.pockets.tolist(),
    }
    assert json.dumps(balls.to_dict()) == json.dumps(before_the_codec)
    assert to_data(balls) == before_the_codec
    assert same_balls(BallSet.from_dict(before_the_codec), balls)


def test_a_stored_ball_set_loads() -> None:
    stored = json.loads((Path(__file__).parent / "data" / "zeno_push.json").read_text())["balls"]
    balls = BallSet.from_dict(stored)
    assert balls.to_dict() == stored
    assert balls.positions.shape == (len(stored["ids"]), 2)


def test_a_ball_set_with_arrays_of_different_lengths_is_refused() -> None:
    data = BallSet.place({0: (0.5, 0.5), 1: (1.0, 0.5)}).to_dict()
    for name, bad in (("spins", [[0.0, 0.0]] * 2), ("phases", [0.0]), ("states", [0, 0, 0])):
        with pytest.raises(ValueError, match=name):
            BallSet.from_dict({**data, name: bad})


def test_an_empty_ball_set_keeps_its_shapes() -> None:
    empty = from_data(BallSet, {name: [] for name in ARRAYS})
    assert empty.positions.shape == (0, 2) and empty.spins.shape == (0, 3)
    assert same_balls(from_json(BallSet, to_json(empty)), empty)
