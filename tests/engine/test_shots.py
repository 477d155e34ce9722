"""Shots any pool player knows (physics-notes §5), played through the engine's own doors."""

import math

import numpy as np
import pytest

from server.engine import (
    DEFAULT_PARAMS,
    BallSet,
    MotionState,
    Shot,
    simulate,
    step,
    strike,
)

R = 0.028575
TICK = 1 / 120


def play_until(table, balls, shot, stop, max_ticks=2000):
    """Strike, then step tick by tick until `stop(balls, events_so_far)` holds."""
    events = [strike(balls, shot)]
    for k in range(max_ticks):
        events += step(table, balls, TICK, k * TICK)
        if stop(balls, events):
            return events
    raise AssertionError("condition never met")


def hit(a, b):
    return lambda _balls, events: any(e.kind == "ball" and set(e.ids) == {a, b} for e in events)


def velocity(balls, ball_id):
    return balls.velocities[balls.index(ball_id)].copy()


def angle_between(u, v):
    return math.degrees(math.acos(np.clip(u @ v / np.linalg.norm(u) / np.linalg.norm(v), -1, 1)))


def test_centre_hit_slides_then_rolls_at_five_sevenths(table):
    balls = BallSet.place({0: (0.4, 0.6)})
    play_until(table, balls, Shot(0.0, 2.0), lambda b, _: b.states[0] == MotionState.ROLLING)
    # It switched at exactly 5/7 V, then rolling resistance acted for the rest of that tick.
    rolling_loss = DEFAULT_PARAMS.u_roll * DEFAULT_PARAMS.g * TICK
    assert 2.0 * 5 / 7 - rolling_loss <= np.linalg.norm(balls.velocities[0]) <= 2.0 * 5 / 7
    # It rolled without slipping: w = z x v / R
    vx, vy = balls.velocities[0]
    assert balls.spins[0, :2] == pytest.approx([-vy / R, vx / R])


def test_stop_shot(table):
    # A stun ball (no spin yet) hits an object ball full: the cue ball stops dead and the
    # object ball takes its speed times e.
    balls = BallSet.place({0: (1.0, 0.6), 1: (1.0 + 2 * R + 0.005, 0.6)})
    events = play_until(table, balls, Shot(0.0, 3.0), hit(0, 1))
    impact = next(e for e in events if e.kind == "ball")
    v_cue, v_obj = velocity(balls, 0), velocity(balls, 1)
    assert np.linalg.norm(v_cue) < 0.05 * impact.speed
    assert v_obj[0] == pytest.approx(DEFAULT_PARAMS.e_ball * impact.speed, rel=0.03)
    assert abs(v_obj[1]) < 1e-9


def stun_cut_angle(cut, speed, params=DEFAULT_PARAMS):
    """Angle between the cue ball's and the object ball's paths after a stun cut: the
    normal impulse (1 + e)/2 v cos(cut) and the throw friction impulse, mu (TP A-14) times
    it or what stops the slip v sin(cut) / 7, whichever is smaller."""
    e, a, b, c = params.e_ball, params.u_ball_a, params.u_ball_b, params.u_ball_c
    normal = (1 + e) / 2 * speed * math.cos(cut)
    slip = speed * math.sin(cut)
    friction = min((a + b * math.exp(-c * slip)) * normal, slip / 7)
    n, t = np.array([math.cos(cut), math.sin(cut)]), np.array([-math.sin(cut), math.cos(cut)])
    obj = normal * n - friction * t
    cue = speed * np.array([1.0, 0.0]) - obj
    return angle_between(cue, obj)


@pytest.mark.parametrize("cut_deg", [15, 30, 45, 60])
def test_ninety_degree_rule(table, cut_deg):
    # Sliding, spin-free cue ball: after a cut it leaves along the tangent line, 90 degrees
    # from the object ball's path. With e < 1 it keeps (1 - e)/2 of its normal speed, and
    # throw friction takes some of its tangential speed: both close the angle a little
    # (Dr. Dave, "90 degree rule" FAQ and TP A-5: a few degrees under 90 in practice).
    cut = math.radians(cut_deg)
    obj = np.array([1.2, 0.6])
    contact = obj - 2 * R * np.array([math.cos(cut), math.sin(cut)])
    cue = contact - np.array([0.01, 0.0])
    balls = BallSet.place({0: tuple(cue), 1: tuple(obj)})
    events = play_until(table, balls, Shot(0.0, 4.0), hit(0, 1))
    impact = next(e for e in events if e.kind == "ball")
    expected = stun_cut_angle(cut, impact.speed / math.cos(cut))
    measured = angle_between(velocity(balls, 0), velocity(balls, 1))
    assert measured == pytest.approx(expected, abs=0.5)
    if cut_deg >= 30:
        # Was +-3 without throw; throw friction at a 30 degree cut costs another ~1.
        assert measured == pytest.approx(90, abs=4)


def test_thirty_degree_rule(table):
    # A naturally rolling cue ball at a half-ball hit ends up about 30 degrees off its line.
    balls = BallSet.place({0: (0.5, 0.6), 1: (1.3, 0.6 + R)})
    play_until(table, balls, Shot(0.0, 1.5, tip=(0.0, 0.4)), hit(0, 1))
    assert balls.states[0] == MotionState.SLIDING
    for k in range(200):  # until friction has bent the path back into a roll
        step(table, balls, TICK, k * TICK)
        if balls.states[0] == MotionState.ROLLING:
            break
    vx, vy = velocity(balls, 0)
    deflection = abs(math.degrees(math.atan2(vy, vx)))
    assert 27 <= deflection <= 34


@pytest.mark.parametrize("height,direction", [(0.4, +1), (-0.4, -1)])
def test_follow_and_draw(table, height, direction):
    balls = BallSet.place({0: (0.6, 0.6), 1: (0.9, 0.6)})
    play_until(table, balls, Shot(0.0, 2.0, tip=(0.0, height)), hit(0, 1))
    for k in range(200):
        step(table, balls, TICK, k * TICK)
        if balls.states[0] == MotionState.ROLLING:
            break
    vx, vy = velocity(balls, 0)
    assert vx * direction > 0.1  # follows through, or comes back
    assert abs(vy) < 1e-9


def test_straight_shot_into_a_corner_pocket_drops(table):
    obj = (0.3, 0.3)  # on the corner's diagonal
    cue = (0.7, 0.7)
    angle = math.atan2(obj[1] - cue[1], obj[0] - cue[0])
    result = simulate(table, BallSet.place({0: cue, 1: obj}), Shot(angle, 2.0, tip=(0, -0.3)))
    drop = next(e for e in result.events if e.kind == "pocket" and e.ids == (1,))
    assert table.pockets[drop.target].name == "bottom_left"
    assert not result.final.on_table[result.final.index(1)]
    assert 1 in result.pocketed()


def test_straight_shot_into_a_side_pocket_drops(table):
    mid = table.length / 2
    result = simulate(
        table, BallSet.place({0: (mid, 0.7), 1: (mid, 0.3)}), Shot(-math.pi / 2, 1.5, tip=(0, -0.3))
    )
    drop = next(e for e in result.events if e.kind == "pocket" and e.ids == (1,))
    assert table.pockets[drop.target].name == "bottom_side"


def test_a_shot_into_the_jaw_rattles_out(table):
    # Aim the object ball's centre straight at the far point of the side pocket.
    jaw = np.array([table.length / 2 + table.side_mouth / 2, 0.0])
    start = jaw + np.array([-0.25, 0.12])
    direction = (jaw - start) / np.linalg.norm(jaw - start)
    cue = start - direction * 0.2
    angle = math.atan2(direction[1], direction[0])
    result = simulate(
        table, BallSet.place({0: tuple(cue), 1: tuple(start)}), Shot(angle, 1.5, tip=(0, -0.2))
    )
    kinds = [(e.kind, e.ids) for e in result.events]
    assert ("jaw", (1,)) in kinds
    assert 1 not in result.pocketed()


def test_a_stun_cushion_rebound_keeps_hans_share_of_the_normal_speed(table):
    # The old test pinned e_cushion = 0.8 for the whole normal speed: with the contact on
    # the nose above the centre (Han 2005), a stun ball straight in keeps
    # (1 + e) cos^2 t + 2/7 sin^2 t - 1 of it (0.74 at e = 0.85; see test_cushion.py).
    balls = BallSet.place({0: (1.0, 0.04)})  # 11 mm from the rail: still a stun ball
    events = play_until(
        table, balls, Shot(-math.pi / 2, 2.0), lambda _b, ev: any(e.kind == "cushion" for e in ev)
    )
    bounce = next(e for e in events if e.kind == "cushion")
    vx, vy = velocity(balls, 0)
    assert table.cushions[bounce.target].normal == (0.0, 1.0)
    s = 2 * DEFAULT_PARAMS.cushion_nose - 1
    share = (1 + DEFAULT_PARAMS.e_cushion) * (1 - s * s) + 2 / 7 * s * s - 1
    assert vy == pytest.approx(share * bounce.speed, rel=0.03)
    assert abs(vx) < 1e-9


def rebound_tangent(table, side):
    balls = BallSet.place({0: (0.8, 0.4)})
    # Aimed so that the squirted path runs at -45 degrees: only the spin differs.
    squirt = Shot(-math.pi / 4, 2.0, tip=(side, 0.0)).squirt()
    play_until(
        table,
        balls,
        Shot(-math.pi / 4 - squirt, 2.0, tip=(side, 0.0)),
        lambda _b, ev: any(e.kind == "cushion" for e in ev),
    )
    return velocity(balls, 0)[0]


def test_side_spin_bends_the_rebound(table):
    # Running and reverse english throw the ball off the rail longer or shorter.
    plain = rebound_tangent(table, 0.0)
    left, right = rebound_tangent(table, -0.4), rebound_tangent(table, 0.4)
    assert min(left, right) < plain - 0.05 < plain + 0.05 < max(left, right)


def test_rolling_ball_turns_its_cels_by_the_distance_rolled(table):
    balls = BallSet.place({0: (0.3, 0.6)})
    play_until(table, balls, Shot(0.0, 1.0, tip=(0, 0.4)), lambda _b, _ev: True)
    phase0, x0 = balls.phases[0], balls.positions[0, 0]
    for k in range(30):
        step(table, balls, TICK, k * TICK)
    assert balls.states[0] == MotionState.ROLLING
    assert balls.phases[0] - phase0 == pytest.approx((balls.positions[0, 0] - x0) / R)


def test_a_stopped_ball_keeps_its_cel(table):
    result = simulate(table, BallSet.place({0: (0.3, 0.6)}), Shot(0.0, 0.6, tip=(0, 0.4)))
    cels = result.frames.cels[:, 0]
    assert len(set(cels.tolist())) > 4  # it turned while rolling
    rest_tick = int(next(e.time for e in result.events if e.kind == "rest") / TICK)
    assert len(set(cels[rest_tick:].tolist())) == 1
    assert cels.min() >= 0 and cels.max() < DEFAULT_PARAMS.cels


def test_a_stun_ball_does_not_turn_until_friction_spins_it(table):
    balls = BallSet.place({0: (0.3, 0.6)})
    strike(balls, Shot(0.0, 3.0))
    step(table, balls, TICK, 0.0)
    # After one tick a sliding ball has turned far less than distance / R.
    assert balls.phases[0] < 0.2 * (balls.positions[0, 0] - 0.3) / R
