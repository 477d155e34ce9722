"""Snooker's rules, each test naming the WPBSA rule it checks as "WPBSA s.r" (Section s,
Rule r of the "Official Rules of the Games of Snooker and English Billiards", the edition
revised November 2019: Section 2 Definitions, Section 3 The Game, Section 4 The Players).
Shots are crafted results (`helpers.crafted`): the referee only reads which ball was hit
first and which dropped."""

from dataclasses import replace

import numpy as np
import pytest

from server.engine import Table
from server.rules import Game, IllegalActionError, Match
from server.rules.snooker_score import COLOUR, FrameScore, remaining, snookers_required
from server.rules.snooker_table import (
    edges_clear,
    open_path,
    respot_colours,
    snookered,
    spot_point,
)

from .helpers import crafted, hit, off, pot

SNOOKER = Table.snooker()
MID = SNOOKER.width / 2
YELLOW, GREEN, BROWN, BLUE, PINK, BLACK = 16, 17, 18, 19, 20, 21


def frame(placement: dict[int, tuple[float, float]], **score: object) -> Game:
    """A snooker frame with only the balls of `placement` on the table (at those
    points), Ana to play from where the cue ball lies, the score as given."""
    game = Game.new("snooker", ("Ana", "Ben"))
    balls = game.balls.with_only(placement)
    game.balls = balls
    game.ball_in_hand = None
    assert game.score is not None
    game.score = replace(game.score, **score)  # type: ignore[arg-type]
    return game


def spots(*colours: int) -> dict[int, tuple[float, float]]:
    names = {YELLOW: "yellow", GREEN: "green", BROWN: "brown", BLUE: "blue", PINK: "pink"}
    names[BLACK] = "black"
    return {c: SNOOKER.spots[names[c]] for c in colours}


ALL_COLOURS = spots(YELLOW, GREEN, BROWN, BLUE, PINK, BLACK)
CUE_IN_BAULK = {0: (0.6, MID + 0.1)}
RED_OPEN = {1: (2.0, 0.5), 2: (2.2, 1.3)}


def test_a_new_frame_is_the_wpbsa_table_and_the_cue_ball_in_hand_in_the_d():
    # WPBSA 3.2 Position of Balls, 3.5 Playing from In-hand, 2.9 In-hand.
    game = Game.new("snooker", ("Ana", "Ben"))
    assert game.table == Table.snooker() and game.table.ball_radius == 0.02625
    assert game.points == (0, 0)
    assert game.ball_in_hand == "in_d"
    assert game.can_place_cue(0.6, MID)
    assert not game.can_place_cue(0.8, MID)  # beyond the baulk line
    assert not game.can_place_cue(0.6, MID + 0.3)  # outside the D
    game.place_cue(0, 0.7, MID + 0.2)
    assert game.legal_targets() == list(range(1, 16))  # 2.11 Ball On: any red


def test_a_red_then_a_colour_score_and_the_colour_is_respotted():
    # WPBSA 3.3 Mode of Play (a red, then a colour while reds remain) and 3.7 Spotting
    # Colours (a colour potted while reds remain goes back on its own spot).
    game = frame({**CUE_IN_BAULK, **RED_OPEN, **ALL_COLOURS})
    out = game.apply(0, crafted(game.balls, hit(0, 1), pot(1, 2)))
    assert out.continues and game.points == (1, 0)
    assert game.score is not None and game.score.on == COLOUR
    game.nominate(0, PINK)
    out = game.apply(0, crafted(game.balls, hit(0, PINK), pot(PINK, 5)))
    assert game.points == (7, 0) and out.continues
    assert game.score.on == "red" and game.score.current_break == 7
    assert game.balls.position_of(PINK) == SNOOKER.spots["pink"]
    assert "the pink is spotted" in out.message.lower()


def test_without_a_nomination_the_colour_hit_first_is_the_nominated_one():
    # WPBSA 2.12 Nominated Ball: the server takes the obvious nomination.
    game = frame({**CUE_IN_BAULK, **RED_OPEN, **ALL_COLOURS}, on=COLOUR)
    game.apply(0, crafted(game.balls, hit(0, BLUE), pot(BLUE, 1)))
    assert game.points == (5, 0)


def test_only_a_colour_can_be_nominated_and_only_on_a_colour():
    # WPBSA 2.12 Nominated Ball.
    game = frame({**CUE_IN_BAULK, **RED_OPEN, **ALL_COLOURS})
    with pytest.raises(IllegalActionError):
        game.nominate(0, BLACK)  # on a red: nothing to nominate
    game.score = replace(game.score, on=COLOUR)  # type: ignore[arg-type]
    with pytest.raises(IllegalActionError):
        game.nominate(0, 1)
    game.nominate(0, BLACK)
    assert game.legal_targets() == [BLACK]


def test_the_colours_are_taken_in_order_once_the_reds_are_gone():
    # WPBSA 3.3 Mode of Play: after the last red and its colour, yellow to black; the
    # ball on stays down once potted.
    game = frame({**CUE_IN_BAULK, 1: (2.0, 0.5), **ALL_COLOURS})
    game.apply(0, crafted(game.balls, hit(0, 1), pot(1, 2)))
    game.apply(0, crafted(game.balls, hit(0, GREEN), pot(GREEN, 4)))
    assert game.score is not None and game.score.on == "yellow"
    assert game.balls.position_of(GREEN) == SNOOKER.spots["green"]  # the last red's colour
    game.apply(0, crafted(game.balls, hit(0, YELLOW), pot(YELLOW, 0)))
    assert game.score.on == "green" and game.points == (6, 0)
    assert YELLOW not in game.balls.on_table_ids()


def test_a_colour_goes_to_the_highest_free_spot_when_its_own_is_taken():
    # WPBSA 3.7 Spotting Colours: own spot, else the highest value spot available, else
    # as near its own spot as possible towards the top cushion.
    game = frame({0: SNOOKER.spots["pink"], **spots(BLUE, BROWN, GREEN, YELLOW)})
    balls = game.balls
    assert spot_point(SNOOKER, balls, PINK) == SNOOKER.spots["black"]  # the pink's own is taken
    balls = balls.with_ball(BLACK, (1.0, 0.2))  # the black spot is free now
    assert spot_point(SNOOKER, balls, PINK) == SNOOKER.spots["black"]
    full = frame({0: SNOOKER.spots["pink"], **ALL_COLOURS}).balls
    full = full.with_ball(PINK, (3.4, 0.2))  # every spot taken: the pink's by the cue
    x, y = spot_point(SNOOKER, full, PINK)
    assert y == MID and x > SNOOKER.spots["pink"][0]
    assert x - SNOOKER.spots["pink"][0] == pytest.approx(2 * SNOOKER.ball_radius, abs=2e-3)


def test_colours_with_their_own_spot_free_go_there_before_the_others_are_spotted():
    # WPBSA 3.7 Spotting Colours: a colour goes on its own spot when it is free; the
    # higher value takes precedence only among colours whose own spots are occupied.
    balls = frame({0: SNOOKER.spots["black"], **spots(YELLOW, GREEN, BROWN)}).balls
    back = respot_colours(SNOOKER, balls, (BLACK, PINK))
    assert back.position_of(PINK) == SNOOKER.spots["pink"]
    assert back.position_of(BLACK) == SNOOKER.spots["blue"]  # the highest spot left free


@pytest.mark.parametrize(
    ("events", "score", "value", "code"),
    [
        ((), {}, 4, "no_contact"),  # no ball hit: the ball on's value, at least 4
        ((hit(0, BLACK),), {}, 7, "wrong_ball_first"),  # a ball not on first: its value
        ((hit(0, 1), pot(PINK, 5)), {}, 6, "potted_not_on"),  # a ball not on potted
        ((hit(0, 1), pot(0, 0)), {}, 4, "in_off"),  # the cue ball potted
        ((hit(0, BLACK),), {"on": COLOUR, "nominated": BLUE}, 7, "wrong_ball_first"),
        ((hit(0, YELLOW),), {"on": COLOUR, "nominated": PINK}, 6, "wrong_ball_first"),
        ((), {"on": COLOUR}, 7, "no_contact"),  # after a red, no colour nominated: 7
        ((hit(0, 1),), {"on": COLOUR}, 7, "wrong_ball_first"),  # the same, a red first
    ],
)
def test_fouls_cost_the_value_of_the_ball_on_or_of_the_ball_involved_at_least_4(
    events, score, value, code
):
    # WPBSA 2.15 Infringements, Fouls and Penalties; 3.11 Penalty Values (seven points
    # for a foul after a red before a colour is nominated).
    game = frame({**CUE_IN_BAULK, **RED_OPEN, **ALL_COLOURS}, **score)
    out = game.apply(0, crafted(game.balls, *events))
    assert code in [f.code for f in out.fouls]
    assert game.points == (0, value)
    assert game.decision is not None and game.decision.seat == 1
    if code == "in_off":
        game.decide(1, "play")
        assert game.ball_in_hand == "in_d" and game.turn == 1


def test_after_a_foul_the_next_player_may_have_the_offender_play_again():
    # WPBSA 3.13 Play Again: after a foul the next player may play, or have the offender
    # play again.
    game = frame({**CUE_IN_BAULK, **RED_OPEN, **ALL_COLOURS})
    game.apply(0, crafted(game.balls, hit(0, BLACK)))
    assert game.decision is not None
    assert {"play", "play_again"} <= set(game.decision.options)
    game.decide(1, "play_again")
    assert game.turn == 0 and game.decision is None


SNOOKERED = {0: (1.0, MID), 1: (2.0, MID), BLUE: (1.5, MID), BLACK: SNOOKER.spots["black"]}


def test_snookered_is_no_ball_on_struck_at_both_extreme_edges():
    # WPBSA 2.17 Snookered.
    game = frame(SNOOKERED)
    assert snookered(SNOOKER, game.balls, [1])
    open_table = frame({**SNOOKERED, BLUE: (1.5, MID + 0.2)})
    assert not snookered(SNOOKER, open_table.balls, [1])


def test_snookered_asks_every_ball_on_for_both_extreme_edges():
    # WPBSA 2.17 Snookered: `snookered` (every ball on at once) is `edges_clear` asked of
    # each ball on, on tables with the balls scattered at random about a crowded middle.
    rng = np.random.default_rng(14)
    base = Game.new("snooker", ("Ana", "Ben")).balls
    ids = base.ids.tolist()
    found = 0
    for _ in range(300):
        balls = base.copy()
        for ball in ids:
            x = rng.uniform(0.5, SNOOKER.length - 0.5)
            balls = balls.with_ball(ball, (x, MID + rng.normal(0.0, 0.12)))
        on = [int(b) for b in rng.choice(ids[1:], size=int(rng.integers(1, 16)), replace=False)]
        each = not any(edges_clear(SNOOKER, balls, b, on) for b in on)
        assert snookered(SNOOKER, balls, on) == each
        found += each
    assert 10 < found < 290  # both answers were asked for


def test_a_foul_that_leaves_the_opponent_snookered_gives_a_free_ball():
    # WPBSA 3.12 Snookered After a Foul, 2.13 Free Ball: the nominated ball is a red;
    # potted, it scores as a red and is re-spotted.
    game = frame(SNOOKERED)
    out = game.apply(0, crafted(game.balls))  # no ball hit; Ana was snookered: no miss
    assert "miss" not in [f.code for f in out.fouls]
    assert game.decision is not None and game.decision.options[0] == "free_ball"
    assert "Free ball" in out.message
    game.decide(1, "free_ball")
    assert game.score is not None and game.score.free_ball
    assert BLUE in game.public_state()["nominations"]
    game.nominate(1, BLUE)
    out = game.apply(1, crafted(game.balls, hit(0, BLUE), pot(BLUE, 1)))
    assert not out.fouls and out.continues
    assert game.points == (0, 4 + 1)
    assert game.balls.position_of(BLUE) == SNOOKER.spots["blue"]
    assert game.score.on == COLOUR and not game.score.free_ball


def test_a_free_ball_is_any_ball_but_the_ball_on_and_a_foul_on_it_costs_the_ball_on():
    # WPBSA 2.13 Free Ball (a ball other than the ball on, nominated as the ball on),
    # 3.12 Snookered After a Foul (it acquires the value of the ball on), 3.11 Penalty
    # Values: hitting the free ball first is hitting the ball on, so going in-off after
    # it costs the ball on's value (4), not the free ball's.
    game = frame(SNOOKERED)
    game.apply(0, crafted(game.balls))  # Ana fouls: 4 to Ben, who is snookered
    game.decide(1, "free_ball")
    assert game.public_state()["nominations"] == [BLUE, BLACK]  # not the red on
    game.nominate(1, BLACK)
    out = game.apply(1, crafted(game.balls, hit(0, BLACK), pot(0, 2)))
    assert [f.code for f in out.fouls] == ["in_off"]
    assert game.points == (4, 4)


def test_a_foul_without_hitting_the_ball_on_when_not_snookered_is_a_miss():
    # WPBSA 3.14 Foul and a Miss: the balls may be replaced and the offender play again.
    game = frame({**CUE_IN_BAULK, **RED_OPEN, **ALL_COLOURS})
    before = game.balls.copy()
    moved = crafted(game.balls, hit(0, BLACK))
    moved.final.positions[moved.final.index(0)] = (3.0, 1.0)
    out = game.apply(0, moved)
    assert "miss" in [f.code for f in out.fouls]
    assert game.decision is not None and "replace" in game.decision.options
    game.decide(1, "replace")
    assert game.turn == 0
    assert game.balls.position_of(0) == before.position_of(0)


def test_no_miss_when_only_the_black_is_left_or_snookers_are_needed():
    # WPBSA 3.14(a)(i): not called when the striker needed penalty points before the
    # stroke; with only the black left the foul ends the frame (3.4).
    last = frame({**CUE_IN_BAULK, **spots(BLACK)}, on="black", points=(40, 40))
    out = last.apply(0, crafted(last.balls))
    assert "miss" not in [f.code for f in out.fouls]
    needs = frame({**CUE_IN_BAULK, **spots(PINK, BLACK)}, on="pink", points=(0, 60))
    out = needs.apply(0, crafted(needs.balls))
    assert "miss" not in [f.code for f in out.fouls]


PARTLY_HIDDEN = {**SNOOKERED, BLUE: (1.5, MID + 2 * SNOOKER.ball_radius)}


def test_a_miss_is_called_when_any_part_of_a_ball_on_is_open_but_counted_only_when_all_is():
    # WPBSA 3.14 Foul and a Miss: failing to hit a ball on with a clear path in a straight
    # line to any part of it is a miss; the count toward three asks for full-ball contact
    # (2.17: a ball on not struck at both extreme edges leaves the striker snookered).
    game = frame(PARTLY_HIDDEN)  # the blue hides one edge of the red, not the other
    assert snookered(SNOOKER, game.balls, [1]) and open_path(SNOOKER, game.balls, [1])
    out = game.apply(0, crafted(game.balls, hit(0, BLUE)))
    assert "miss" in [f.code for f in out.fouls]
    assert game.decision is not None and "replace" in game.decision.options
    assert game.score is not None and game.score.misses == (0, 0)
    hidden = frame(SNOOKERED)  # the red wholly hidden: the server judges no miss
    assert not open_path(SNOOKER, hidden.balls, [1])
    out = hidden.apply(0, crafted(hidden.balls, hit(0, BLUE)))
    assert "miss" not in [f.code for f in out.fouls]
    full = frame({**CUE_IN_BAULK, **RED_OPEN, **ALL_COLOURS})
    full.apply(0, crafted(full.balls, hit(0, BLACK)))
    assert full.score is not None and full.score.misses == (1, 0)


@pytest.mark.parametrize(
    ("points", "miss"),
    [
        ((0, 0), True),
        ((60, 0), False),  # the opponent needs penalty points before the stroke: (a)(i)
        ((0, 7), False),  # the striker needs them once the 7 are paid: (a)(i), after
        ((0, 13), False),  # the 13 on the table equal the difference: (a)(ii)
    ],
)
def test_no_miss_when_either_player_needs_penalty_points_before_or_after_the_stroke(points, miss):
    # WPBSA 3.14(a)(i), (ii): no miss when either player needed penalty points before or
    # after the stroke, or the points on the table equal the difference (the server
    # takes such a miss as not intended).
    game = frame({**CUE_IN_BAULK, **spots(PINK, BLACK)}, on="pink", points=points)
    out = game.apply(0, crafted(game.balls, hit(0, BLACK)))
    assert ("miss" in [f.code for f in out.fouls]) == miss


def test_a_failure_again_from_the_balls_replaced_is_a_miss_whatever_the_scores():
    # WPBSA 3.14: a further failure from the same position is a miss regardless of the
    # difference in scores, and the offender is warned that a third gives the frame away.
    game = frame({**CUE_IN_BAULK, **spots(PINK, BLACK)}, on="pink")
    game.apply(0, crafted(game.balls, hit(0, BLACK)))
    game.decide(1, "replace")
    out = game.apply(0, crafted(game.balls, hit(0, BLACK)))  # Ana 14 behind, 13 left
    assert "miss" in [f.code for f in out.fouls]
    assert game.score is not None and game.score.misses == (2, 0)
    assert "a third miss from the balls replaced gives Ben the frame" in out.message


def test_playing_again_from_where_the_balls_lie_starts_the_count_of_misses_again():
    # WPBSA 3.14: the failures counted toward three are from the same position (the balls
    # replaced); 3.13 Play Again from the position left starts afresh.
    game = frame({**CUE_IN_BAULK, **RED_OPEN, **ALL_COLOURS})
    game.apply(0, crafted(game.balls, hit(0, BLACK)))
    game.decide(1, "play_again")
    assert game.score is not None and game.score.misses == (0, 0)
    game.apply(0, crafted(game.balls, hit(0, BLACK)))
    assert game.score.misses == (1, 0) and not game.over


def test_three_misses_in_a_row_lose_the_frame():
    # WPBSA 3.14 Foul and a Miss: the third failure from the balls replaced, after a
    # warning, loses the frame.
    game = frame({**CUE_IN_BAULK, **RED_OPEN, **ALL_COLOURS})
    for k in range(3):
        out = game.apply(0, crafted(game.balls, hit(0, BLACK)))
        if k < 2:
            game.decide(1, "replace")
    assert out.frame_over and game.winner == 1


def test_misses_count_only_while_the_offender_plays_again_from_the_balls_replaced():
    # WPBSA 3.14: the run of misses ends when the next player plays a stroke.
    game = frame({**CUE_IN_BAULK, **RED_OPEN, **ALL_COLOURS})
    game.apply(0, crafted(game.balls, hit(0, BLACK)))
    game.decide(1, "replace")
    game.apply(0, crafted(game.balls, hit(0, BLACK)))
    assert game.score is not None and game.score.misses == (2, 0)
    game.decide(1, "play")
    game.apply(1, crafted(game.balls, hit(0, 1)))  # Ben plays a fair stroke
    assert game.score.misses == (0, 0)


def test_the_frame_ends_with_the_black_and_a_tie_respots_it():
    # WPBSA 3.4 End of Frame, Game or Match: the frame ends when the black is potted as
    # the last ball; with the scores equal the black is re-spotted, the next score or
    # foul ends it.
    won = frame({**CUE_IN_BAULK, **spots(BLACK)}, on="black", points=(50, 40))
    out = won.apply(0, crafted(won.balls, hit(0, BLACK), pot(BLACK, 3)))
    assert out.frame_over and won.winner == 0 and won.points == (57, 40)
    tied = frame({**CUE_IN_BAULK, **spots(BLACK)}, on="black", points=(40, 47))
    out = tied.apply(0, crafted(tied.balls, hit(0, BLACK), pot(BLACK, 3)))
    assert not out.frame_over and tied.points == (47, 47)
    assert tied.score is not None and tied.score.respotted_black
    assert tied.balls.position_of(BLACK) == SNOOKER.spots["black"]
    assert tied.turn == 1 and tied.ball_in_hand == "in_d"
    tied.place_cue(1, 0.6, MID)
    out = tied.apply(1, crafted(tied.balls, hit(0, BLACK)))  # no pot: play on
    assert not out.frame_over and tied.turn == 0
    out = tied.apply(0, crafted(tied.balls))  # a foul ends it
    assert out.frame_over and tied.winner == 1 and tied.points == (47, 54)


def test_a_player_may_concede_the_frame():
    # WPBSA 2.1 Frame (a): a frame ends by concession by a player during their turn.
    game = Game.new("snooker", ("Ana", "Ben"))
    out = game.resign(0, "Ana conceded the frame.")
    assert out.frame_over and game.winner == 1


def test_points_remaining_and_snookers_required():
    # WPBSA 3.1 Description (the values), 3.3 Mode of Play: 8 a red (with the black
    # after it) and the colours' 27.
    full = FrameScore.start(2)
    on = [0, *range(1, 22)]
    assert remaining(full, on) == 147
    fourteen = [0, *range(2, 22)]  # a red just potted: its colour (up to 7) to come
    assert remaining(replace(full, on=COLOUR), fourteen) == 8 * 14 + 7 + 27
    colours = [0, PINK, BLACK]
    behind = replace(full, on="pink", points=(30, 0))
    assert remaining(behind, colours) == 13
    assert snookers_required(behind, colours, 1) == 5  # 17 short: five penalties of 4
    assert snookers_required(behind, colours, 0) == 0


def test_a_match_is_best_of_n_frames():
    # WPBSA 2.2 Game: an agreed number of frames (the WPBSA's "match" is a number of
    # games); 3.1(g): the winner has the required number of frames; best of 3 is first to 2.
    match = Match("snooker", ("Ana", "Ben"), race_to=2)
    assert match.game.kind == "snooker" and match.game.table.style == "snooker"
    match.game.resign(1, "conceded")
    assert match.game.winner == 0


def test_a_snooker_frame_round_trips_through_its_stored_form():
    game = frame({**CUE_IN_BAULK, **RED_OPEN, **ALL_COLOURS})
    game.apply(0, crafted(game.balls, hit(0, BLACK)))
    back = Game.from_dict(game.to_dict())
    assert back.score == game.score and back.points == game.points
    assert back.decision == game.decision and back.table == game.table
    assert back.replaced is not None


def test_a_ball_forced_off_the_table_is_a_foul_colours_come_back_reds_stay_off():
    # WPBSA 2.14 Forced Off the Table, 3.11 Penalty Values (the value of the ball forced
    # off, at least 4), 3.7 Spotting Colours (a colour forced off the table is re-spotted;
    # a red is not).
    game = frame({**CUE_IN_BAULK, **RED_OPEN, **ALL_COLOURS})
    out = game.apply(0, crafted(game.balls, hit(0, 1), off(1, 2), off(PINK, 3)))
    assert [f.code for f in out.fouls] == ["ball_off_table"]
    assert out.fouls[0].message == "Ana forced a red and the pink off the table."
    assert game.points == (0, 6)
    assert 1 not in game.balls.on_table_ids() and 2 in game.balls.on_table_ids()
    assert game.balls.position_of(PINK) == SNOOKER.spots["pink"]


def test_the_cue_ball_forced_off_the_table_is_played_from_in_hand():
    # WPBSA 2.14 Forced Off the Table, 2.9 In-hand, 3.5 Playing from In-hand.
    game = frame({**CUE_IN_BAULK, **RED_OPEN, **ALL_COLOURS})
    out = game.apply(0, crafted(game.balls, hit(0, 1), off(0, 1)))
    assert [f.code for f in out.fouls] == ["scratch"]
    assert game.points == (0, 4)
    game.decide(1, "play")
    assert game.ball_in_hand == "in_d" and game.turn == 1
