"""A ball pushed by its own spin against a still ball collided again at zero time forever:
every tick hit the event cap and the shot ran to the 300 s guard (minutes of CPU, the
server stalled). Now a stalled tick stops the balls of that contact and the shot ends."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from server.engine import BallSet, Shot, Table, simulate

pytestmark = pytest.mark.timeout(120)
DATA = json.loads((Path(__file__).parent / "data" / "zeno_push.json").read_text())
SHOT = Shot(DATA["shot"]["angle"], DATA["shot"]["speed"], tuple(DATA["shot"].get("tip", (0, 0))))


def test_a_zeno_contact_ends_the_shot_quickly_without_overlap() -> None:
    table = Table.pool("9ft")
    result = simulate(table, BallSet.from_dict(DATA["balls"]), SHOT)
    assert result.stalled_ticks >= 1  # the loop was met and cut
    assert len(result.frames) < 20 * 120  # seconds of play, not the 300 s guard
    assert result.final.at_rest()
    on = result.final.on_table
    pos = result.final.positions[on]
    d = np.linalg.norm(pos[:, None] - pos[None, :], axis=2)
    d[np.diag_indices(len(pos))] = np.inf
    assert d.min() >= 2 * table.ball_radius - 1e-9


def test_the_stalled_tick_reports_each_contact_once() -> None:
    result = simulate(Table.pool("9ft"), BallSet.from_dict(DATA["balls"]), SHOT)
    assert len(result.events) < 500  # not the 5000 repeats of the stalled tick
