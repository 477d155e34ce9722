"""Which object balls the cue ball passed over before it first touched one: the WPBSA's
Jump Shot (Section 2 Definitions, "Jump Shot": the cue ball passes over any part of an
object ball), read from a played shot's frames and event times.

Before the cue ball's first contact with a ball only the cue ball moves, so every object
ball is where `before` has it. A cue ball on the bed never comes within 2R of a ball
without touching it; one whose centre came nearer in plan view than 2R, with no contact
between them, passed over that ball in the air. The cue ball's track is rebuilt from the
frames (its position at every tick's end) and the times of its own events (strike,
landing, cushion, jaw): in the air no horizontal force acts, so its plan-view track is a
straight line between events, and the knot at an event inside a tick is found by carrying
on the neighbouring tick's straight line to the event's time. That is exact in flight for
one event inside a tick; on the bed (a swerve's curve) a tick's chord strays from the track
by well under a tenth of a millimetre. A centre nearer than 2R less `MARGIN` is "over"
the ball; the margin keeps those chord errors from calling a ball passed close by on the
bed, and means a jump over less than the outer millimetre of a ball is not seen.

A `Settled` shot (the computer's search) has no frames: it cannot tell, and reads nothing.
"""

from __future__ import annotations

import numpy as np

from server.engine import CUE, BallSet, EventKind, FlightKind, MotionState, ShotResult

MARGIN = 1e-3  # m: how far inside 2R the centres must come to count as over (see above)
_OWN = {EventKind.CUSHION, EventKind.JAW, FlightKind.LAND}  # the cue ball's turns
_ENDS = {EventKind.BALL, EventKind.POCKET, FlightKind.OFF_TABLE}  # its track stops there
_SLACK = 1e-12  # s: an event this near a tick's end is at it


def passed_over(
    before: BallSet, result: ShotResult, radius: float, cue: int = CUE
) -> tuple[int, ...]:
    """Ids of the object balls the cue ball passed over before its first contact with a
    ball (the first ball it touched is never among them), in `before`'s order."""
    frames = result.frames
    if len(frames) == 0:
        return ()
    row = before.index(cue)
    turns, end = _cue_events(result, cue, len(frames) * frames.tick)
    track = _track(before.positions[row], frames.positions[:, row], frames.tick, turns, end)
    if len(track) < 2:
        return ()
    first = result.first_contact(cue)
    others = [
        r
        for r, ball in enumerate(before.ids.tolist())
        if ball not in (cue, first) and before.states[r] != MotionState.POCKETED
    ]
    if not others:
        return ()
    near = _nearest(track, before.positions[others])
    over = near < 2 * radius - MARGIN
    return tuple(int(before.ids[r]) for r, hit in zip(others, over.tolist(), strict=True) if hit)


def _cue_events(result: ShotResult, cue: int, duration: float) -> tuple[list[float], float]:
    """The times of the cue ball's turns before its track ends, and when it ends: its first
    contact with a ball, its drop or flight off the table, or the end of the shot."""
    turns: list[float] = []
    for e in result.events:
        if e.time <= 0.0 or cue not in e.ids:
            continue
        if e.kind in _ENDS:
            return turns, min(e.time, duration)
        if e.kind in _OWN:
            turns.append(e.time)
    return turns, duration


def _track(
    start: np.ndarray, ends: np.ndarray, tick: float, turns: list[float], end: float
) -> np.ndarray:
    """The cue ball's plan-view knots from the strike to `end`: the position at every
    tick's end before it and a knot at each tick's first turn and at `end` (module
    docstring: each carried on from a neighbouring tick with no turn of its own)."""
    full = min(int(end / tick + _SLACK), len(ends))  # ticks wholly before the end
    points = np.vstack([start[None, :], ends[: full + 1]])  # points[k]: at k * tick
    chords = np.diff(points, axis=0) / tick  # chords[k]: the mean velocity over tick k
    busy = {int(t / tick) for t in turns}
    busy |= {int(t / tick) - 1 for t in turns if abs(t / tick - round(t / tick)) < _SLACK}

    def at(t: float) -> np.ndarray:
        k = int(t / tick)
        if k - 1 >= 0 and k - 1 not in busy:
            return np.asarray(points[k] + chords[k - 1] * (t - k * tick))
        if k + 1 < len(chords) and k + 1 not in busy:
            return np.asarray(points[k + 1] - chords[k + 1] * ((k + 1) * tick - t))
        if k < len(chords):
            return np.asarray(points[k] + chords[k] * (t - k * tick))
        return np.asarray(points[min(k, len(points) - 1)])

    times, knots, seen = [], [], set()
    for t in turns:
        k = int(t / tick)
        if t < end and k < full and k not in seen and t - k * tick > _SLACK:
            seen.add(k)
            times.append(t)
            knots.append(at(t))
    if end - full * tick > _SLACK:
        times.append(end)
        knots.append(at(end))
    if not knots:
        return points[: full + 1]
    order = np.argsort(np.concatenate([np.arange(full + 1) * tick, times]), kind="stable")
    return np.vstack([points[: full + 1], knots])[order]


def _nearest(track: np.ndarray, centres: np.ndarray) -> np.ndarray:
    """Each centre's plan-view distance to the polyline `track`."""
    a, b = track[:-1], track[1:]
    ab = b - a
    length2 = np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-30)
    rel = centres[:, None, :] - a[None, :, :]
    s = np.clip(np.einsum("nij,ij->ni", rel, ab) / length2, 0.0, 1.0)
    gap = rel - s[..., None] * ab[None, :, :]
    return np.asarray(np.sqrt(np.einsum("nij,nij->ni", gap, gap)).min(axis=1))
