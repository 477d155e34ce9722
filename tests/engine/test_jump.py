"""Jump shots: a raised cue drives the cue ball into the slate, which throws it back up.

Sources: the strike is TP A.30's (`test_elevation.py`); the slate gives back half the
downward speed (ball-table restitution 0.5, Alciatore's physical-properties page) and its
friction acts on the landing (u_slide). pooltool 0.6.0 has no flight to compare with: these
are the facts a player knows. A jump needs the cue raised more for a nearer blocker: with
the cue's axis through the centre, 30 degrees at 6 m/s clears a ball 25 cm ahead, 35 at
5-6 m/s one 20-25 cm ahead, 40 at 4-5 m/s one 20-25 cm ahead, and a ball 15 cm ahead
wants 45 degrees; 30 degrees at 4 m/s does not clear one 20 cm ahead (as on a real
table, where a short jump wants a steep cue).
"""

import hashlib
import itertools
import math

import numpy as np
import pytest

from server.engine import (
    BALL_MASS,
    BALL_RADIUS,
    DEFAULT_PARAMS,
    BallSet,
    Shot,
    settle,
    simulate,
    simulate_traced,
    step,
    strike,
    tip_seen_level,
)
from server.engine.tracing import Tolerance

TICK = 1 / 120
CUE_AT = (0.5, 0.6)
BEHIND = (2.0, 0.6)  # 1.5 m on, past where the jump comes down


def jump(degrees: float, speed: float, angle: float = 0.0) -> Shot:
    """A jump stroke: the cue's axis through the ball's centre, raised `degrees`."""
    elevation = math.radians(degrees)
    return Shot(angle, speed, tip_seen_level((0.0, 0.0), elevation), elevation)


def first_ball_contact(result) -> tuple[int, ...] | None:
    return next((e.ids for e in result.events if e.kind == "ball"), None)


@pytest.mark.parametrize(
    ("degrees", "speed", "gap"),
    [(30, 6.0, 0.25), (35, 5.0, 0.25), (35, 6.0, 0.20), (35, 6.0, 0.25), (40, 4.0, 0.20),
     (40, 5.0, 0.20), (40, 5.0, 0.25), (45, 4.0, 0.15), (45, 5.0, 0.15)],
)  # fmt: skip
def test_a_jump_clears_the_blocker_and_hits_the_ball_behind(table, degrees, speed, gap):
    balls = BallSet.place({0: CUE_AT, 1: (CUE_AT[0] + gap, CUE_AT[1]), 2: BEHIND})
    result = simulate(table, balls, jump(degrees, speed))
    assert first_ball_contact(result) == (0, 2)
    # It passed over the blocker in the air, the centres more than 2R apart (every tick).
    state = balls.copy()
    strike(state, jump(degrees, speed))
    over = []
    for k in range(60):
        step(table, state, TICK, k * TICK)
        dx, dy = state.positions[0] - state.positions[1]
        dz = state.heights[0, 0] - state.heights[1, 0]
        assert math.sqrt(dx * dx + dy * dy + dz * dz) > 2 * BALL_RADIUS
        if abs(dx) < BALL_RADIUS:
            over.append(dz)
    assert over and min(over) > 2 * BALL_RADIUS * math.sqrt(0.75)


def test_the_same_stroke_level_hits_the_blocker(table):
    balls = BallSet.place({0: CUE_AT, 1: (CUE_AT[0] + 0.2, CUE_AT[1]), 2: BEHIND})
    assert first_ball_contact(simulate(table, balls, Shot(0.0, 5.0))) == (0, 1)


def test_too_flat_a_jump_lands_on_the_blocker(table):
    # 30 degrees at 4 m/s rises 5 cm at most: it meets the blocker in the air, a collision.
    balls = BallSet.place({0: CUE_AT, 1: (CUE_AT[0] + 0.2, CUE_AT[1]), 2: BEHIND})
    result = simulate(table, balls, jump(30, 4.0))
    assert first_ball_contact(result) == (0, 1)
    assert result.events[1].kind == "ball"  # before the cue ball came down


def test_the_hop_dies_and_the_ball_rolls_on(table):
    result = simulate(table, BallSet.place({0: CUE_AT}), jump(40, 5.0))
    lands = [e for e in result.events if e.kind == "land"]
    assert len(lands) >= 3
    assert all(b.speed < a.speed for a, b in itertools.pairwise(lands))
    assert not result.final.heights.any()
    assert result.final.on_table_ids() == [0]


def test_a_jumped_ball_can_leave_the_table(table):
    # 45 degrees at 8 m/s, 15 cm from the bottom rail, straight at it: over the nose.
    balls = BallSet.place({0: (1.0, 0.15), 3: (2.0, 1.0)})
    result = simulate(table, balls, jump(45, 8.0, angle=-math.pi / 2))
    off = [e for e in result.events if e.kind == "off_table"]
    assert [e.ids for e in off] == [(0,)]
    assert result.final.off_table_ids() == [0]
    assert result.final.pocketed_ids() == [0]  # out of play, like a pocketed ball
    assert result.final.pockets[0] == -2  # but in no pocket


def test_a_ball_landing_over_a_hole_drops(table):
    # 40 degrees at 4 m/s comes down 0.8 m on: over the bottom side pocket's hole.
    result = simulate(table, BallSet.place({0: (1.27, 0.72)}), jump(40, 4.0, -math.pi / 2))
    assert [(e.kind, e.target) for e in result.events[1:]] == [("pocket", 1)]


def test_a_ball_landing_past_the_table_is_off_it(table):
    # The same jump from further back flies over the side pocket's mouth and its shelf.
    result = simulate(table, BallSet.place({0: (1.27, 0.6)}), jump(40, 4.0, -math.pi / 2))
    assert [e.kind for e in result.events[1:]] == ["off_table"]


def mechanical_energy(balls: BallSet) -> float:
    return balls.mechanical_energy(BALL_MASS, BALL_RADIUS, DEFAULT_PARAMS.g)


@pytest.mark.parametrize("case", [(40, 5.0), (30, 4.0), (80, 3.0)])
def test_energy_never_rises_in_flight_bounces_and_contacts(table, case):
    balls = BallSet.place({0: CUE_AT, 1: (CUE_AT[0] + 0.2, CUE_AT[1]), 2: BEHIND})
    strike(balls, jump(*case))
    energy = mechanical_energy(balls)
    for k in range(6000):
        step(table, balls, TICK, k * TICK)
        now = mechanical_energy(balls)
        assert now <= energy * (1 + 1e-12) + 1e-12
        energy = now
        if balls.at_rest():
            break
    assert balls.at_rest()


def digest(balls: BallSet) -> str:
    h = hashlib.sha256()
    arrays = (balls.positions, balls.velocities, balls.spins, balls.states, balls.heights)
    for array in (*arrays, balls.phases, balls.pockets):
        h.update(np.ascontiguousarray(array).tobytes())
    return h.hexdigest()


def test_a_jump_is_bit_identical_every_way_it_is_run(table):
    balls = BallSet.place({0: CUE_AT, 1: (CUE_AT[0] + 0.2, CUE_AT[1]), 2: BEHIND})
    shot = jump(40, 5.0, angle=0.05)
    first, second = simulate(table, balls, shot), simulate(table, balls, shot)
    assert digest(first.final) == digest(second.final)
    assert np.array_equal(first.frames.positions, second.frames.positions)
    assert digest(settle(table, balls, shot).final) == digest(first.final)
    traced, _ = simulate_traced(table, balls, shot, Tolerance(0.001, 0.1))
    assert digest(traced.final) == digest(first.final)
    stepped = balls.copy()
    strike(stepped, shot)
    for k in range(len(first.frames)):
        step(table, stepped, TICK, k * TICK)
    assert np.array_equal(stepped.positions, first.final.positions)
    assert np.array_equal(stepped.states, first.final.states)
