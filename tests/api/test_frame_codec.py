"""The compiled frame encoder writes exactly what `json.dumps` would."""

from __future__ import annotations

import json

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from server.engine import Shot, Table, rack, simulate
from server.protocol.frame_codec import encode_frames
from server.protocol.plan import frame_rows, plan_shot


def reference(shot_id, ticks, ids, mm, cels, on_table, last) -> list[str]:
    out = []
    for j, tick in enumerate(ticks.tolist()):
        rows = [
            [int(i), int(mm[j, b, 0]), int(mm[j, b, 1]), int(cels[j, b])]
            for b, i in enumerate(ids.tolist())
            if on_table[j, b]
        ]
        payload = {"shot": shot_id, "tick": tick, "b": rows}
        if j == last:
            payload["last"] = True
        out.append(json.dumps(payload, separators=(",", ":")))
    return out


@st.composite
def frame_arrays(draw):
    count = draw(st.integers(1, 6))
    n = draw(st.integers(0, 16))
    ints = st.integers(-(2**63), 2**63 - 1)
    ticks = draw(hnp.arrays(np.int64, count, elements=st.integers(0, 10**6)))
    ids = draw(hnp.arrays(np.int64, n, elements=st.integers(0, 15)))
    mm = draw(hnp.arrays(np.int64, (count, n, 2), elements=ints))
    cels = draw(hnp.arrays(np.int64, (count, n), elements=st.integers(0, 63)))
    on = draw(hnp.arrays(np.bool_, (count, n)))
    last = draw(st.integers(-1, count - 1))
    return draw(st.integers(0, 2**40)), ticks, ids, mm, cels, on, last


@settings(max_examples=200, deadline=None)
@given(frame_arrays())
def test_same_text_as_json_dumps(arrays):
    assert encode_frames(*arrays) == reference(*arrays)


def test_a_real_shot_streams_the_rows_of_its_ticks():
    table = Table.pool("9ft")
    result = simulate(table, rack("eight_ball", table, seed=4), Shot(0.02, 8.0))
    plan = plan_shot(result, 7, 6)
    frames = [m for m in plan if m.kind == "frame"]
    assert [m.tick for m in frames][-1] == len(result.frames)
    for m in frames:
        frame = result.frames[m.tick - 1]
        expected = frame_rows(result.ids, frame.positions, frame.cels, frame.on_table)
        payload = m.payload
        assert payload["b"] == [list(row) for row in expected]
        assert payload["shot"] == 7 and payload["tick"] == m.tick
        assert payload.get("last", False) is (m is frames[-1]) is (not m.droppable)
        assert plan.frames.rows(m.frame) == expected


@settings(max_examples=300)
@given(
    shot_id=st.integers(0, 10**6),
    tick=st.integers(0, 36_000),
    time=st.floats(0, 300, allow_nan=False),
    speed=st.floats(0, 20, allow_nan=False),
    kind=st.sampled_from(["strike", "ball", "cushion", "jaw", "pocket"]),
    ids=st.lists(st.integers(0, 15), min_size=1, max_size=2),
    target=st.integers(-1, 40),
)
def test_event_text_is_what_json_dumps_gives(shot_id, tick, time, speed, kind, ids, target):
    from server.codec import encode
    from server.engine import Event
    from server.protocol.plan import event_body

    event = Event(time, kind, tuple(ids), speed, target)
    assert event_body(shot_id, tick, event) == encode(
        {
            "shot": shot_id,
            "tick": tick,
            "t": round(time, 4),
            "kind": kind,
            "ids": ids,
            "speed": round(speed, 3),
            "target": target,
        }
    )


def test_an_event_that_is_not_finite_is_refused():
    import pytest

    from server.engine import Event
    from server.protocol.plan import event_body

    with pytest.raises(ValueError):
        event_body(1, 2, Event(0.1, "ball", (0, 1), float("inf"), -1))


def test_sounds_close_together_share_a_message_and_none_is_lost():
    """A break: each event message carries the sounds of one frame message's span (`also`);
    flattened, they are exactly the sounds chosen, in time order."""
    from server.protocol.plan import _sounds

    table = Table.pool("9ft")
    result = simulate(table, rack("eight_ball", table, seed=3), Shot(0.0, 9.0))
    plan = plan_shot(result, 7, 6, 4)
    messages = [json.loads(m.body) for m in plan if m.kind == "event"]
    flat = [e for m in messages for e in [m, *m.get("also", ())]]
    chosen = _sounds(result.events, result.frames.tick)
    assert [(e["tick"], e["kind"], e["t"]) for e in flat] == [
        (tick, ev.kind, round(ev.time, 4)) for tick, ev in chosen
    ]
    assert len(messages) < len(flat) / 2
    window = 6 * 4 * result.frames.tick
    for m in messages:
        assert all(m["t"] <= a["t"] < m["t"] + window + 1e-4 for a in m.get("also", ()))
