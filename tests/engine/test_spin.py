"""Side spin (english) decays at a realistic rate: 5 u_sp g / (2R) = 10.9 rad/s^2.

Sources: Dr. Dave Alciatore's physical properties page (spin deceleration 5-15 rad/s^2)
and pooltool 0.6.0, whose u_sp = 10*2/5/9 R. POOLTOOL_ENGLISH_LEFT was measured with
pooltool 0.6.0 (own virtualenv, default parameters): one ball on `pt.Table.default()`
given a rolling state at speed v along the table's length with side spin
wz = 1.25 v / R (what a 0.5 R tip offset gives), `pt.simulate` then
`pt.continuize(dt=0.0005)`; the fraction of wz left at the first sample 1.2 m from the
start (a table's width, rail to rail on a 9 ft table).
"""

import pytest

from server.engine import DEFAULT_PARAMS, BallSet, step
from server.engine.physics.motion import classify

R = 0.028575
TICK = 1 / 120
POOLTOOL_ENGLISH_LEFT = {0.8: 0.4794, 1.0: 0.6809, 1.5: 0.8634}


def test_spin_decay_rate_is_dr_daves_and_pooltools():
    p = DEFAULT_PARAMS
    rate = 2.5 * p.u_spin * p.g / p.radius
    assert rate == pytest.approx(10.9, abs=0.05)  # pooltool: 2.5 * (10*2/5/9) * g
    assert 5.0 <= rate <= 15.0  # DA-PP


@pytest.mark.parametrize("speed", [0.8, 1.0, 1.5])
def test_english_left_after_crossing_the_table(table, speed):
    wz0 = 1.25 * speed / R
    balls = BallSet.place({0: (0.3, 0.6)})
    balls.velocities[0] = (speed, 0.0)
    balls.spins[0] = (0.0, speed / R, wz0)
    classify(balls.velocities, balls.spins, balls.states, 0, R)
    for k in range(1000):
        step(table, balls, TICK, k * TICK)
        if balls.positions[0, 0] - 0.3 >= 1.2:
            break
    left = balls.spins[0, 2] / wz0
    # One tick of travel is up to 12 mm, and 1.5 m/s spends ~0.09 rad/s of spin on it.
    assert left == pytest.approx(POOLTOOL_ENGLISH_LEFT[speed], abs=0.01)
    assert left > 0.45  # the old 37.8 rad/s^2 left none at 0.8 and 1 m/s
