"""Drills' practice tables: a position set up from the stored table when its seat is taken
(the ball in hand as it was, no break), a ghost 9-ball rack to break; kept through a
restart; scored shot by shot (a position by its first shot, the ghost's rack until a miss,
a line-up run rack after rack until a miss); Rerack starts another ghost rack or run."""

from __future__ import annotations

import math

from server.engine import CUE, BallSet, Shot, Table, rack, simulate
from server.rooms.drills import DrillScore, DrillSetup, DrillTries, made, scored
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


def lineup_room() -> Room:
    room = Room("r4", "practice", setup=DrillSetup(kind="lineup"))
    room.join("Ana")
    return room


def play(room: Room, place: tuple[float, float] | None, shot: Shot) -> None:
    """Play `shot` in `room` as the live room does (cue placed first when given)."""
    if place is not None:
        room.place_cue(0, *place)
    _, before = room.begin_shot(0)
    assert room.match is not None
    room.apply_shot(simulate(room.match.game.table, before, shot))
    room.end_shot()


MIDDLE = (TABLE.length / 2, TABLE.width / 2 + 0.3)  # above the line's middle ball
INTO_THE_SIDE = Shot(-math.pi / 2, 2.0)  # the middle ball straight into the side pocket
AWAY = Shot(math.pi / 2, 0.8)  # towards the other side rail, touching nothing


def test_a_lineup_is_three_balls_on_the_long_string_with_the_ball_in_hand() -> None:
    room = lineup_room()
    assert room.match is not None
    game = room.match.game
    objects = [b for b in game.balls.on_table_ids() if b != CUE]
    assert objects == [1, 2, 3]
    ys = {round(game.balls.position_of(b)[1], 9) for b in objects}
    assert ys == {round(TABLE.width / 2, 9)}
    assert game.ball_in_hand == ANYWHERE
    info = room.room_info().drill
    assert info is not None
    assert (info.kind, info.balls, info.score, info.tries, info.best) == ("lineup", 3, 0, 1, 0)


def test_a_lineup_run_goes_on_from_where_the_cue_ball_lies_until_a_miss() -> None:
    room = lineup_room()
    play(room, MIDDLE, INTO_THE_SIDE)
    assert room.drill == DrillScore(1)
    assert room.match is not None and room.match.game.ball_in_hand is None
    play(room, None, AWAY)
    assert room.drill == DrillScore(1, done=True)
    assert room.tries == DrillTries(1, best=1)
    assert room.match.game.ball_in_hand == ANYWHERE  # free practice once the run is over


def test_a_cleared_lineup_rack_brings_the_next_with_one_ball_more() -> None:
    room = lineup_room()
    assert room.match is not None
    game = room.match.game
    game.balls = BallSet.place({CUE: (0.3, 0.3), 2: (TABLE.length / 2, TABLE.width / 2)})
    play(room, MIDDLE, INTO_THE_SIDE)
    assert room.drill == DrillScore(1, racks=1)
    assert [b for b in game.balls.on_table_ids() if b != CUE] == [1, 2, 3, 4]
    assert game.ball_in_hand == ANYWHERE
    info = room.room_info().drill
    assert info is not None and info.balls == 4


def test_rerack_starts_another_try_keeping_the_best() -> None:
    room = lineup_room()
    room.rerack(0)  # nothing played yet: the same try, laid out again
    assert room.tries == DrillTries(1)
    play(room, MIDDLE, INTO_THE_SIDE)
    room.rerack(0)
    assert (room.drill, room.tries) == (DrillScore(), DrillTries(2, best=1))
    assert room.match is not None
    assert [b for b in room.match.game.balls.on_table_ids() if b != CUE] == [1, 2, 3]
    restored = room_from_snapshot(room_to_snapshot(room, None)).room
    assert restored.tries == DrillTries(2, best=1)


def test_rerack_on_a_ghost_table_racks_a_new_ghost_rack() -> None:
    room = Room("r5", "practice", setup=DrillSetup(kind="ghost"))
    room.join("Ana")
    assert room.match is not None
    first = room.match.game.balls.to_dict()
    room.drill = DrillScore(3, done=True)
    room.rerack(0)
    game = room.match.game
    assert sorted(b for b in game.balls.on_table_ids() if b != CUE) == list(range(1, 10))
    assert game.balls.to_dict() != first
    assert game.ball_in_hand == BEHIND_HEAD_STRING
    assert (room.drill, room.tries) == (DrillScore(), DrillTries(2))
