"""Comparing two runs of the engine bit for bit."""

from __future__ import annotations

import numpy as np

from server.engine import ShotResult


def assert_same_result(got: ShotResult, expected: ShotResult) -> None:
    """Frames, events, the table at rest and the stalled ticks, bit for bit."""
    assert got.frames.positions.tobytes() == expected.frames.positions.tobytes()
    assert np.array_equal(got.frames.cels, expected.frames.cels)
    assert np.array_equal(got.frames.on_table, expected.frames.on_table)
    assert got.events == expected.events
    assert got.final.to_dict() == expected.final.to_dict()
    assert got.stalled_ticks == expected.stalled_ticks
