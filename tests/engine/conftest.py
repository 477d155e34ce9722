import math

import numpy as np
import pytest

from server.engine import BallSet, MotionState, Table, step
from server.engine.physics.motion import classify


@pytest.fixture(scope="session")
def table() -> Table:
    return Table.pool("9ft")


def pair_min_gap(positions: np.ndarray, on_table: np.ndarray, radius: float) -> float:
    """Smallest centre distance minus 2R over the balls on the table (inf if fewer than 2)."""
    p = positions[on_table]
    if len(p) < 2:
        return float("inf")
    d = np.linalg.norm(p[:, None, :] - p[None, :, :], axis=2)
    d[np.diag_indices(len(p))] = np.inf
    return float(d.min() - 2 * radius)


def frame_velocity(result, ball_id: int, tick_a: int, tick_b: int) -> np.ndarray:
    """Mean velocity of a ball between two frames (index into result.frames)."""
    row = int(np.flatnonzero(result.ids == ball_id)[0])
    pos = result.frames.positions
    return (pos[tick_b, row] - pos[tick_a, row]) / ((tick_b - tick_a) * result.frames.tick)


def first_event_time(result, kind: str, ids: tuple[int, ...] | None = None) -> float:
    for e in result.events:
        if e.kind == kind and (ids is None or set(ids) <= set(e.ids)):
            return e.time
    raise AssertionError(f"no {kind} event with {ids}")


def segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance from each point in p (K, 2) to the segment a-b."""
    ab = b - a
    t = np.clip(((p - a) @ ab) / (ab @ ab), 0.0, 1.0)
    return np.linalg.norm(p - (a + t[:, None] * ab), axis=1)


def in_play_area(table, positions: np.ndarray, tol: float = 1e-9) -> np.ndarray:
    """(K,) bool: a ball centred there lies on the bed (inside the cushion noses' box, at
    least R from every cushion segment and jaw point, on the table side of every pocket
    mouth) or on a pocket's shelf (past its mouth line, at least R inside both facings
    and from the jaw points, and not over the hole, where it would have dropped)."""
    r = table.ball_radius
    p = np.asarray(positions, dtype=float).reshape(-1, 2)
    jaws = np.array(table.jaws).reshape(-1, 2)
    clear_of_points = (np.linalg.norm(p[:, None] - jaws[None], axis=2) >= r - tol).all(axis=1)
    ok = (
        (p[:, 0] >= -tol)
        & (p[:, 0] <= table.length + tol)
        & (p[:, 1] >= -tol)
        & (p[:, 1] <= table.width + tol)
    )
    for c in table.cushions:
        ok &= segment_distance(p, np.array(c.start), np.array(c.end)) >= r - tol
    past_any = np.zeros(len(p), dtype=bool)
    on_shelf = np.zeros(len(p), dtype=bool)
    for pocket in table.pockets:
        a = np.array(pocket.jaws[0])
        past = (p - a) @ np.array(pocket.outward) > tol
        past_any |= past
        inside = past.copy()
        for start, end in pocket.facings:
            inside &= segment_distance(p, np.array(start), np.array(end)) >= r - tol
            # and on the throat's side of the facing's line
            f = np.array(end) - np.array(start)
            n = np.array([-f[1], f[0]])
            mid = (np.array(pocket.jaws[0]) + np.array(pocket.jaws[1])) / 2
            n = n if (mid - np.array(start)) @ n > 0 else -n
            inside &= (p - np.array(start)) @ n >= 0
        inside &= np.linalg.norm(p - np.array(pocket.hole), axis=1) >= pocket.hole_radius - tol
        on_shelf |= inside
    return ((ok & ~past_any) | on_shelf) & clear_of_points


def bank(table, speed, angle_deg, wz=0.0, gap=0.15, tick=1 / 120):
    """A ball rolling into `table`'s bottom rail at `angle_deg` from its normal, `gap` from
    it: (speed in, speed out once it rolls again, angle out from the normal in degrees)."""
    r = table.ball_radius
    balls = BallSet.place({0: (0.5, gap + r)})
    a = math.radians(angle_deg)
    vx, vy = speed * math.sin(a), -speed * math.cos(a)
    balls.velocities[0] = (vx, vy)
    balls.spins[0] = (-vy / r, vx / r, wz)
    classify(balls.velocities, balls.spins, balls.states, 0, r)
    speed_in = None
    for k in range(2000):
        before = float(np.linalg.norm(balls.velocities[0]))
        events = step(table, balls, tick, k * tick)
        if any(e.kind == "cushion" for e in events):
            assert speed_in is None, "a second cushion before it rolled"
            speed_in = before
        if speed_in is not None and balls.states[0] == MotionState.ROLLING:
            out = balls.velocities[0]
            angle = math.degrees(math.atan2(abs(out[0]), abs(out[1])))
            return speed_in, float(np.linalg.norm(out)), angle
    raise AssertionError("never rolled after the rail")
