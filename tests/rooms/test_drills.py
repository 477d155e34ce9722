"""Drills' practice tables: a position set up from the stored table when its seat is taken
(the ball in hand as it was, no break), a ghost 9-ball rack to break; kept through a
restart; scored shot by shot (a position by its first shot, the ghost's rack until a miss)."""

from __future__ import annotations

from server.engine import CUE, BallSet, Shot, Table, rack, simulate
from server.rooms.drills import DrillScore, DrillSetup, made, scored
from server.rooms.room import Room
from server.rooms.snapshot import room_from_snapshot, room_to_snapshot
from server.rules import Foul, Outcome
from server.rules.outcome import ANYWHERE, BEHIND_HEAD_STRING

TABLE = Table.pool("9ft")


def position() -> DrillSetup:
    balls = rack("eight_ball", TABLE, seed=3).with_ball(CUE, (0.5, 0.4))
    return DrillSetup(balls.to_dict(), ANYWHERE, 0.75, match_id=4, n=9)


def test_the_drill_table_is_the_stored_one_with_its_ball_in_hand() -> None:
    room = Room("r1", "practice", setup=position())
    room.join("Ana")
    assert room.match is not None
    game = room.match.game
    assert game.balls.to_dict() == position().balls
    assert (game.ball_in_hand, game.breaking) == (ANYWHERE, False)
    info = room.room_info().drill
    assert info is not None
    assert (info.kind, info.match, info.n, info.par, info.made) == ("position", 4, 9, 0.75, None)


def test_a_ghost_drill_is_a_nine_ball_rack_to_break_from_behind_the_line() -> None:
    room = Room("r3", "practice", setup=DrillSetup(kind="ghost"))
    room.join("Ana")
    assert room.match is not None
    game = room.match.game
    assert sorted(b for b in game.balls.on_table_ids() if b != CUE) == list(range(1, 10))
    assert game.ball_in_hand == BEHIND_HEAD_STRING


def test_a_drill_room_keeps_its_setup_and_score_through_a_restart() -> None:
    room = Room("r2", "practice", setup=position())
    room.drill = DrillScore(1, done=True)
    restored = room_from_snapshot(room_to_snapshot(room, None)).room
    assert restored.setup == position()
    assert restored.drill == DrillScore(1, done=True)
    restored.join("Ana")
    assert restored.match is not None
    assert restored.match.game.balls.to_dict() == position().balls


def _outcome(pocketed: tuple[int, ...], fouls: tuple[Foul, ...] = ()) -> Outcome:
    return Outcome(0, pocketed, fouls, bool(pocketed), 0, None, False, None, None, "")


def test_a_position_is_made_by_a_ball_pocketed_without_a_foul() -> None:
    assert made(_outcome((3,)))
    assert not made(_outcome(()))
    assert not made(_outcome((0,)))
    assert not made(_outcome((3, 0), (Foul("scratch", "Scratch."),)))


def _two_balls(first: int, second: int) -> BallSet:
    """The cue ball, `first` straight ahead of it near the foot rail's middle, `second` far
    to the side."""
    y = TABLE.width / 2
    return BallSet.place({CUE: (1.2, y), first: (1.6, y), second: (0.4, 0.3)})


def test_the_ghost_wins_when_the_lowest_ball_is_not_hit_first() -> None:
    balls = _two_balls(first=5, second=2)  # the 5 is hit first, the 2 is lower
    result = simulate(TABLE, balls, Shot(0.0, 3.0))
    after = scored(DrillSetup(kind="ghost"), DrillScore(4), balls, result, _outcome((5,)))
    assert after == DrillScore(4, done=True, won=False)


def test_a_ghost_rack_scores_the_balls_pocketed_in_order() -> None:
    balls = _two_balls(first=2, second=5)
    result = simulate(TABLE, balls, Shot(0.0, 3.0))
    after = scored(DrillSetup(kind="ghost"), DrillScore(4), balls, result, _outcome((2,)))
    assert after == DrillScore(5, done=False, won=False)
