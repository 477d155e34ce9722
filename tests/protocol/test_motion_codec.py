"""The `motion` message: a shot traced by the engine (tests/engine/test_trace.py), packed.

`run_traced` must leave the engine's result exact, every contact must be drawn where the
engine has it, and the bytes must say what docs/protocol.md says they say (the decoder
here, `decode_motion`, is checked against the tracer's own numbers; the web client's
decoder is checked against an encoder written from the doc).
"""

from __future__ import annotations

import base64
import math

import numpy as np
import pytest

from server.engine import BALL_RADIUS, Shot, ShotInMotion, Table, rack, simulate
from server.protocol import plan_shot, run_traced, trace
from server.protocol.motion import (
    PHASE_STEPS,
    TOLERANCE,
    decode_motion,
    motion_bytes,
    with_seq,
)
from server.protocol.plan import motion_messages, motion_text, stored_motion
from tests.support.games import BREAK, EIGHT_BALL
from tests.support.results import assert_same_result

TABLE = Table.pool("9ft")


def traced(seed: int, shot: Shot):
    balls = rack("eight_ball", TABLE, seed=seed)
    result = simulate(TABLE, balls, shot)
    tracks = trace(TABLE, balls, shot)
    return result, tracks, plan_shot(result, tracks, 5, 6)


def at(track: dict, t: float) -> tuple[float, float]:
    """Where a decoded track puts its ball at t: the straight line between knots."""
    ts = track["t"]
    if t >= ts[-1]:
        return track["x"][-1], track["y"][-1]
    i = max(k for k in range(len(ts)) if ts[k] <= t)
    f = (t - ts[i]) / (ts[i + 1] - ts[i]) if ts[i + 1] > ts[i] else 1.0
    x = track["x"][i] + (track["x"][i + 1] - track["x"][i]) * f
    return x, track["y"][i] + (track["y"][i + 1] - track["y"][i]) * f


@pytest.mark.parametrize(
    ("seed", "shot"),
    [(EIGHT_BALL, BREAK), (28, Shot(-1.008541877928577, 4.930159020213607)), (3, Shot(2.0, 6.0))],
)
def test_one_pass_gives_the_engines_result_bit_for_bit(seed, shot):
    """`run_traced` runs the ticks once for the engine and the tracks: `motion.result()` is
    `simulate`'s result exactly (frames, events, the table at rest, stalled ticks)."""
    balls = rack("eight_ball", TABLE, seed=seed)
    expected = simulate(TABLE, balls, shot)
    motion = ShotInMotion(TABLE, balls, shot)
    run_traced(motion)
    got = motion.result()
    assert_same_result(got, expected)


def test_every_contact_is_drawn_where_the_engine_has_it():
    result, _, plan = traced(EIGHT_BALL, BREAK)
    motion = decode_motion(plan.motion)
    tracks = {t["id"]: t for t in motion["tracks"]}
    cushions = TABLE.cushion_array()
    checked = 0
    for event in result.events:
        if event.kind == "ball":
            a, b = (at(tracks[i], event.time) for i in event.ids)
            assert abs(math.dist(a, b) - 2 * BALL_RADIUS) < 2 * TOLERANCE
            checked += 1
        elif event.kind == "cushion":
            x, y = at(tracks[event.ids[0]], event.time)
            c = cushions[event.target]
            off = (x - c[0]) * c[4] + (y - c[1]) * c[5] - BALL_RADIUS
            assert abs(off) < TOLERANCE
            checked += 1
    assert checked > 50


def test_the_bytes_decode_to_the_knots_within_their_units():
    result, tracks, plan = traced(EIGHT_BALL, BREAK)
    motion = decode_motion(with_seq(plan.motion, 77))
    assert (motion["seq"], motion["shot"]) == (77, 5)
    assert motion["duration"] == pytest.approx(len(result.frames) / 120, abs=1e-6)
    assert [t["id"] for t in motion["tracks"]] == tracks.ids.tolist()
    for b, track in enumerate(motion["tracks"]):
        knots = tracks.knots[tracks.offsets[b] : tracks.offsets[b + 1]]
        assert track["t"] == pytest.approx(tracks.times[knots].tolist(), abs=0.6e-6)
        assert track["x"] == pytest.approx(tracks.positions[knots, b, 0].tolist(), abs=0.6e-4)
        assert track["y"] == pytest.approx(tracks.positions[knots, b, 1].tolist(), abs=0.6e-4)
        rolled = np.array(track["phase"]) - track["phase"][0]
        exact = tracks.phases[knots, b] - tracks.phases[knots[0], b]
        assert np.abs(rolled - exact).max() < 2 * math.pi / PHASE_STEPS
    pockets = {t["id"]: t["pocket"] for t in motion["tracks"] if t["pocket"] is not None}
    dropped = {e.ids[0]: e.target for e in result.events if e.kind == "pocket"}
    assert pockets == dropped and dropped


def test_a_still_ball_has_one_knot_and_a_stopped_one_ends_where_it_stops():
    result, _, plan = traced(EIGHT_BALL, Shot(math.pi / 2, 1.0))  # away from the rack
    motion = decode_motion(plan.motion)
    lone = [t["id"] for t in motion["tracks"] if len(t["t"]) == 1]
    assert lone == list(range(1, 16))
    final = result.final
    for track in motion["tracks"]:
        x, y = final.positions[final.index(track["id"])]
        assert math.dist((track["x"][-1], track["y"][-1]), (x, y)) < 1e-4


def test_stored_motion_round_trips_and_bad_bytes_are_refused():
    _, _, plan = traced(EIGHT_BALL, BREAK)
    text = motion_text(plan)
    assert [kind for _, kind, _ in motion_messages(text)] == ["motion"]
    assert stored_motion(text, 5) == plan.motion
    with pytest.raises(ValueError):
        decode_motion(plan.motion + b"\0")
    with pytest.raises(ValueError):
        decode_motion(b"\x02" + plan.motion[1:])
    assert base64.b64decode(text.split(" ", 2)[2]) == plan.motion


def test_an_empty_shot_is_a_header_and_its_sounds():
    message = motion_bytes(9, 0.0, b"", 0, [])
    assert decode_motion(message) == {
        "type": "motion",
        "seq": 0,
        "shot": 9,
        "duration": 0.0,
        "tracks": [],
        "sounds": [],
    }
