"""Properties of raised strokes on random tables (hypothesis): whatever the elevation, tip
and speed, the shot ends, energy (with the height's) never rises, nothing ends up off the
bed but in a pocket or off the table, and every flight has ended at rest."""

import math

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from server.engine import (
    BALL_MASS,
    BALL_RADIUS,
    DEFAULT_PARAMS,
    MAX_ELEVATION,
    MAX_TIP,
    Shot,
    simulate,
    step,
    strike,
    tip_seen_level,
)

from .test_properties import TABLE, TICK, placements


@st.composite
def raised_strokes(draw):
    elevation = draw(st.floats(0.01, MAX_ELEVATION))
    r = draw(st.floats(0.0, MAX_TIP * 0.98))
    turn = draw(st.floats(-math.pi, math.pi))
    side, height = r * math.cos(turn), r * math.sin(turn)
    depth = math.sqrt(1 - side * side - height * height)
    if math.cos(elevation) * depth < math.sin(elevation) * height:
        height = 0.0  # a contact past the ball's top: none seen from behind names it
    angle = draw(st.floats(-math.pi, math.pi))
    speed = draw(st.floats(0.3, 8.0))
    return Shot(angle, speed, tip_seen_level((side, height), elevation), elevation)


SETTINGS = settings(
    max_examples=30,
    deadline=None,
    suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow],
)


@SETTINGS
@given(balls=placements(max_balls=6), shot=raised_strokes())
def test_a_raised_stroke_ends_without_gaining_energy(balls, shot):
    strike(balls, shot)
    energy = balls.mechanical_energy(BALL_MASS, BALL_RADIUS, DEFAULT_PARAMS.g)
    for k in range(4000):
        step(TABLE, balls, TICK, k * TICK)
        now = balls.mechanical_energy(BALL_MASS, BALL_RADIUS, DEFAULT_PARAMS.g)
        assert now <= energy * (1 + 1e-12) + 1e-12
        energy = now
        if balls.at_rest():
            break
    assert balls.at_rest()
    assert not balls.heights.any()


@SETTINGS
@given(balls=placements(max_balls=6), shot=raised_strokes())
def test_a_raised_stroke_leaves_every_ball_on_the_bed_or_out_of_play(balls, shot):
    result = simulate(TABLE, balls, shot)
    final = result.final
    assert result.stalled_ticks == 0
    on = final.on_table
    x, y = final.positions[on, 0], final.positions[on, 1]
    slack = 0.07  # a hanger on a pocket's shelf sits past the cushion line
    assert np.all((x > -slack) & (x < TABLE.length + slack))
    assert np.all((y > -slack) & (y < TABLE.width + slack))
