"""One ball rolled alone across a table, tick by tick: how the pocket tests probe mouths."""

from __future__ import annotations

import math

from server.engine import BallSet, Event, MotionState, Table, step
from server.engine.physics.motion import classify

R = 0.028575  # the pool ball's radius (a table's own: `Table.ball_radius`)
TICK = 1 / 120
DECEL = 0.01 * 9.81  # a rolling ball's deceleration (u_roll g)


def roll(table: Table, start, direction, speed: float, travel: float = 0.8):
    """Roll one ball from `start` along the unit `direction`; stop when it drops, rests, or
    has rolled `travel` metres. Returns (balls, events)."""
    balls = BallSet.place({0: tuple(start)})
    r = table.ball_radius
    vx, vy = speed * direction[0], speed * direction[1]
    balls.velocities[0] = (vx, vy)
    balls.spins[0] = (-vy / r, vx / r, 0.0)
    classify(balls.velocities, balls.spins, balls.states, 0, r)
    disc = speed * speed - 2 * DECEL * travel
    cap = (speed - math.sqrt(disc)) / DECEL if disc > 0 else math.inf
    events: list[Event] = []
    for k in range(3000):
        if k * TICK > cap or balls.states[0] not in (MotionState.ROLLING, MotionState.SLIDING):
            break
        events += step(table, balls, TICK, k * TICK)
    return balls, events
