"""The `motion` message of a shot where a ball flies: version 2, a height per knot
(docs/protocol.md, `motion`). A shot where every ball stays on the bed is still version 1,
byte for byte what it was (tests/protocol/test_motion_codec.py)."""

from __future__ import annotations

import math

import numpy as np

from server.engine import (
    BALL_RADIUS,
    BallSet,
    Shot,
    ShotInMotion,
    Table,
    simulate,
    tip_seen_level,
)
from server.protocol import plan_shot, trace
from server.protocol.motion import MOTION_VERSION_HEIGHTS, TOLERANCE, TRACE, decode_motion

TABLE = Table.pool("9ft")


def jump(degrees: float, speed: float, angle: float = 0.0) -> Shot:
    elevation = math.radians(degrees)
    return Shot(angle, speed, tip_seen_level((0.0, 0.0), elevation), elevation)


def planned(balls: BallSet, shot: Shot):
    result = simulate(TABLE, balls, shot)
    tracks = trace(TABLE, balls, shot)
    return result, tracks, plan_shot(result, tracks, 7, 6)


def height_at(track: dict, t: float) -> float:
    """The decoded track's height at t: the straight line between knots."""
    return float(np.interp(t, track["t"], track["z"]))


def test_a_jump_is_version_2_and_its_heights_follow_the_engine():
    balls = BallSet.place({0: (0.5, 0.6), 1: (0.7, 0.6), 2: (2.0, 0.6)})
    _, tracks, plan = planned(balls, jump(40, 5.0))
    assert plan.motion[1] == MOTION_VERSION_HEIGHTS == tracks.version
    motion = decode_motion(plan.motion)
    cue = next(t for t in motion["tracks"] if t["id"] == 0)
    blocker = next(t for t in motion["tracks"] if t["id"] == 1)
    assert max(cue["z"]) > 2 * BALL_RADIUS  # over the blocker
    assert not any(blocker["z"]) and not cue["off_table"]
    lands = [s for s in motion["sounds"] if s["kind"] == "land"]
    assert lands and lands[0]["ids"] == [0]  # the landing's thud
    # Every sample of the engine's trace up to the cue ball's last knot is within the
    # tolerance (plus 0.05 mm of rounding) of the drawn height.
    engine = ShotInMotion(TABLE, balls, jump(40, 5.0))
    engine.run(trace=TRACE)
    samples = engine.trace
    assert samples.heights is not None
    row = int(np.flatnonzero(samples.ids == 0)[0])
    for t, z in zip(samples.times, samples.heights[:, row], strict=True):
        if t <= cue["t"][-1]:
            assert abs(height_at(cue, t) - z) <= TOLERANCE + 5e-5


def test_a_ball_off_the_table_is_marked_so():
    balls = BallSet.place({0: (1.0, 0.15), 3: (2.0, 1.0)})
    _, _, plan = planned(balls, jump(45, 8.0, angle=-math.pi / 2))
    cue = next(t for t in decode_motion(plan.motion)["tracks"] if t["id"] == 0)
    assert cue["off_table"] and cue["pocket"] is None


def test_a_level_shot_stays_version_1():
    balls = BallSet.place({0: (0.5, 0.6), 1: (0.7, 0.6)})
    _, tracks, plan = planned(balls, Shot(0.0, 5.0))
    assert plan.motion[1] == 1 == tracks.version
    assert all("z" not in t for t in decode_motion(plan.motion)["tracks"])
