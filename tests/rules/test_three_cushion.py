"""Three-cushion's rules, each test naming the UMB article it checks ("World Rules of Carom
Billiard": Art. 23 Starting position, cue-ball; Art. 24 Cannon; Art. 27 Balls in contact
with each other; Art. 29 End of the match; Art. 41 Fouls; Art. 83 Three cushions). Shots
are crafted results: the referee only reads what the cue ball met, in order."""

from dataclasses import replace

import numpy as np
import pytest

from server.engine import (
    OFF_TABLE,
    BallSet,
    Event,
    FrameSequence,
    MotionState,
    Shot,
    ShotResult,
    Table,
    simulate,
)
from server.engine.rack import RED, WHITE, YELLOW
from server.rules import Game, IllegalActionError
from server.rules.carom_score import CaromScore, cushions_before_second, is_point

CAROM = Table.carom()
C = -1  # a cushion in a cue ball's path


def crafted(before: BallSet, struck: int, *path: int) -> ShotResult:
    """A result in which `struck` meets, in order, the balls and cushions (-1) of `path`."""
    events = [Event(0.0, "strike", (struck,), 2.0)]
    for k, what in enumerate(path):
        t = 0.01 * (k + 1)
        if what == C:
            events.append(Event(t, "cushion", (struck,), 1.0, k % 4))
        else:
            events.append(Event(t, "ball", (struck, what), 1.0))
    n = len(before)
    frames = FrameSequence(
        1 / 120, np.empty((0, n, 2)), np.empty((0, n), dtype=np.int64), np.empty((0, n), dtype=bool)
    )
    return ShotResult(before.ids.copy(), frames, events, before.copy())


def game(**score: object) -> Game:
    """A game past its opening stroke (unless told), Ana on the white, Ben on the yellow."""
    g = Game.new("three_cushion", ("Ana", "Ben"))
    assert g.carom is not None
    g.carom = replace(g.carom, **{"opening": False, **score})  # type: ignore[arg-type]
    return g


def play(g: Game, *path: int) -> None:
    g.apply(g.turn, crafted(g.balls, g.cue_ball, *path))


@pytest.mark.parametrize(
    ("path", "point"),
    [
        ((RED, C, C, C, YELLOW), True),  # the first ball, three cushions, the second
        ((C, C, C, RED, YELLOW), True),  # three cushions first
        ((C, RED, C, C, YELLOW), True),  # in any order with the first ball
        ((C, C, RED, C, YELLOW, C), True),
        ((RED, C, C, YELLOW, C), False),  # the third cushion after the second ball
        ((RED, C, C, C), False),  # one ball only
        ((C, C, C, C, C), False),
        ((RED, YELLOW, C, C, C), False),
        ((YELLOW, C, C, C, RED), True),  # the other cue ball first is no foul
        ((RED, C, RED, C, C, YELLOW), True),  # the first ball met twice is still the first
    ],
)
def test_the_point_both_balls_and_three_cushions_before_the_second(path, point):
    # UMB Art. 83 Three cushions (one cushion counted each time it is met).
    assert is_point(path, WHITE) is point
    assert is_point(tuple(WHITE if b == YELLOW else b for b in path), YELLOW) is point


def test_the_cushions_counted_are_those_before_the_second_ball():
    assert cushions_before_second((C, RED, C, C, YELLOW, C), WHITE) == 3
    assert cushions_before_second((C, RED, C), WHITE) == 2


def test_the_opening_position_and_the_white_for_the_opener():
    # UMB Art. 23 Starting position, cue-ball.
    g = Game.new("three_cushion", ("Ana", "Ben"))
    assert g.table == CAROM and g.table.pockets == ()
    assert g.balls.position_of(RED) == CAROM.spots["foot"]
    assert g.balls.position_of(YELLOW) == CAROM.spots["head"]
    assert g.balls.position_of(WHITE) == CAROM.spots["break_right"]
    assert g.ball_in_hand is None
    assert g.cue_ball == WHITE and g.legal_targets() == [RED]
    assert g.points == (0, 0)
    other = Game.new("three_cushion", ("Ana", "Ben"), breaker=1)
    assert other.turn == 1 and other.cue_ball == WHITE
    assert other.carom is not None and other.carom.cue_ball(0) == YELLOW


def test_the_opening_stroke_must_hit_the_red_first():
    # UMB Art. 23: the starting cannon is played by direct attack on the red ball.
    g = Game.new("three_cushion", ("Ana", "Ben"))
    play(g, C, RED, C, C, YELLOW)
    assert g.turn == 1 and g.points == (0, 0)
    assert g.last_outcome is not None and g.last_outcome.fouls[0].code == "opening"
    g = Game.new("three_cushion", ("Ana", "Ben"))
    play(g, YELLOW, C, C, C, RED)
    assert g.last_outcome is not None and g.last_outcome.fouls[0].code == "opening"
    g = Game.new("three_cushion", ("Ana", "Ben"))
    play(g, RED, C, C, C, YELLOW)
    assert g.points == (1, 0) and g.turn == 0 and g.legal_targets() == []


def test_a_point_continues_the_inning_and_a_miss_ends_it():
    # UMB Art. 24 Cannon: the striker plays on while scoring; the inning ends at a miss.
    g = game()
    play(g, RED, C, C, C, YELLOW)
    play(g, C, C, C, RED, YELLOW)
    assert g.points == (2, 0) and g.turn == 0
    assert g.last_outcome is not None and g.last_outcome.continues
    play(g, RED, C, YELLOW)
    assert g.turn == 1 and g.cue_ball == YELLOW
    assert g.carom is not None
    assert g.carom.innings == (1, 1) and g.carom.high_run == (2, 0) and g.carom.run == 0
    play(g, WHITE, C, C, C, RED)  # Ben's yellow: the white first is no foul
    assert g.points == (2, 1) and g.turn == 1
    play(g, C)
    assert g.turn == 0 and g.carom.innings == (2, 1)
    board = g.public_state()["carom"]
    assert board["points"] == [2, 1] and board["innings"] == [2, 1]
    assert board["average"] == [1.0, 1.0] and board["high_run"] == [2, 1]
    assert board["cue_balls"] == [WHITE, YELLOW]


def test_the_striker_strikes_only_their_own_cue_ball():
    # UMB Art. 41 Fouls (playing the wrong ball): the server never lets it happen.
    g = game()
    with pytest.raises(IllegalActionError) as err:
        g.apply(0, crafted(g.balls, YELLOW, RED))
    assert err.value.code == "wrong_cue_ball"


def test_running_out_of_time_is_a_foul_that_ends_the_inning():
    # UMB Art. 41 Fouls.
    g = game()
    out = g.timeout(0)
    assert out.fouls[0].code == "shot_clock" and g.turn == 1 and g.points == (0, 0)


def test_the_race_is_won_at_the_distance():
    # UMB Art. 29 End of the match.
    g = game(race_to=2)
    play(g, RED, C, C, C, YELLOW)
    assert not g.over
    play(g, RED, C, C, C, YELLOW)
    assert g.over and g.winner == 0


def test_with_equal_innings_the_other_player_has_a_last_inning():
    # UMB Art. 29 End of the match: equalizing inning.
    g = game(race_to=2, equal_innings=True)
    play(g, RED, C, C, C, YELLOW)
    play(g, RED, C, C, C, YELLOW)
    assert not g.over and g.turn == 1 and g.carom is not None and g.carom.last_inning
    play(g, WHITE, C, C, C, RED)
    play(g, C)  # Ben ends short: Ana wins
    assert g.over and g.winner == 0
    g = game(race_to=1, equal_innings=True)
    play(g, RED, C, C, C, YELLOW)
    play(g, WHITE, C, C, C, RED)  # level: play on
    assert not g.over
    play(g, WHITE, C, C, C, RED)  # Ben passes in his last inning
    assert g.over and g.winner == 1


def test_level_after_equal_innings_plays_on_a_pair_at_a_time():
    # UMB Art. 29 (the UMB's penalty shots left out: another inning each).
    g = game(race_to=1, equal_innings=True)
    play(g, RED, C, C, C, YELLOW)
    play(g, WHITE, C, C, C, RED)
    play(g, C)  # Ben misses, level at 1-1
    assert not g.over and g.turn == 0
    play(g, RED, C, C, C, YELLOW)  # Ana's extra inning
    play(g, C)
    play(g, C)  # Ben misses: Ana leads after the pair
    assert g.over and g.winner == 0


def test_balls_touching_after_the_stroke_are_set_up_as_at_the_opening():
    # UMB Art. 27 Balls in contact with each other.
    g = game()
    r = CAROM.ball_radius
    g.balls = BallSet.place({WHITE: (1.0, 0.5), YELLOW: (1.5, 0.5 + 2 * r), RED: (1.5, 0.5)})
    play(g, C)  # Ana misses; Ben's yellow lies against the red
    assert g.turn == 1
    assert g.balls.position_of(YELLOW) == CAROM.spots["break_right"]
    assert g.balls.position_of(WHITE) == CAROM.spots["head"]
    assert g.balls.position_of(RED) == CAROM.spots["foot"]


def test_a_real_stroke_is_judged_from_the_engine_and_stored():
    g = Game.new("three_cushion", ("Ana", "Ben"))
    x, y = g.balls.position_of(WHITE)
    rx, ry = g.balls.position_of(RED)
    shot = Shot(float(np.arctan2(ry - y, rx - x)), 3.0, ball=WHITE)
    g.apply(0, simulate(g.table, g.balls, shot))
    assert g.carom is not None and not g.carom.opening
    again = Game.from_dict(g.to_dict())
    assert again.carom == g.carom and again.table == CAROM
    assert "carom" not in Game.new("nine_ball", ("Ana", "Ben")).to_dict()


def test_a_new_score_starts_the_openers_first_inning():
    assert CaromScore.start(1).innings == (0, 1)


def test_practice_counts_points_and_innings_alone_and_never_ends():
    g = Game.new("three_cushion_practice", ("Pia",))
    assert g.table == CAROM and g.cue_ball == WHITE and g.points == (0,)
    assert g.legal_targets() == [RED]
    play(g, YELLOW, C, C, C, RED)  # the opening not on the red: said, not a foul
    assert g.turn == 0 and g.last_outcome is not None and not g.last_outcome.fouls
    assert "did not hit the red first" in g.last_outcome.message
    assert g.carom is not None and g.carom.innings == (2,)
    play(g, RED, C, C, C, YELLOW)
    play(g, C, C, C, YELLOW, RED)
    assert g.points == (2,) and g.carom.high_run == (2,) and not g.over
    g.rerack()
    assert g.points == (0,) and g.balls.position_of(RED) == CAROM.spots["foot"]


def test_a_ball_off_the_table_is_a_foul_and_the_balls_are_set_up_again():
    # UMB Art. 28 Balls bounding out of the billiard: a foul, no point even with the
    # cannon made; the inning ends.
    g = game()
    result = crafted(g.balls, WHITE, RED, C, C, C, YELLOW)
    row = result.final.index(RED)
    result.final.states[row] = MotionState.POCKETED
    result.final.pockets[row] = OFF_TABLE
    result.events.append(Event(0.1, "off_table", (RED,), 3.0, 1))
    out = g.apply(0, result)
    assert [f.code for f in out.fouls] == ["ball_off_table"]
    assert out.fouls[0].message == "Ana drove the red off the table."
    assert g.points == (0, 0) and g.turn == 1 and g.cue_ball == YELLOW
    assert g.balls.position_of(YELLOW) == CAROM.spots["break_right"]
    assert g.balls.position_of(WHITE) == CAROM.spots["head"]
    assert g.balls.position_of(RED) == CAROM.spots["foot"]
    assert sorted(g.balls.on_table_ids()) == [WHITE, YELLOW, RED]
