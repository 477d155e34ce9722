"""`ShotPlan.shown_at`: which of a shot's frames a member joining at an instant is shown in
its `state` (`state.shot.tick`, `state.balls`); the `motion` message then plays on from
there."""

from __future__ import annotations

from server.engine import TICK_HZ, Shot, Table, rack, simulate
from server.protocol import plan_shot, trace


def _plan():
    table = Table.pool("9ft")
    balls = rack("eight_ball", table, seed=3)
    shot = Shot(0.0, 9.0)
    result = simulate(table, balls, shot)
    return result, plan_shot(result, trace(table, balls, shot), 1, 6)


def test_a_joiner_is_shown_the_latest_frame_due():
    result, plan = _plan()
    assert plan.shown_at(0.0).tick == 6  # nothing due yet: the first frame
    assert plan.shown_at(0.25).tick == 30  # tick 30 is due at 0.25 s
    assert plan.shown_at(0.25 - 1e-6).tick == 24
    assert plan.shown_at(100.0).tick == len(result.frames)  # over: the last frame
    shown = plan.shown_at(0.5)
    assert plan.frames.ticks[shown.frame] == shown.tick == 60
    assert shown.at == 60 / TICK_HZ


def test_the_last_frame_is_the_table_at_rest():
    result, plan = _plan()
    last = plan.last
    assert last.tick == len(result.frames)
    rows = plan.frames.rows(last.frame)
    final = result.final
    assert sorted(r[0] for r in rows) == final.ids[final.on_table].tolist()
