"""Balls driven off the table (a jump or a hop that clears a rail).

WPA World Standardized Rules: General Rules, "cue ball scratch or off the table" (a cue
ball driven off the table is a scratch) and "balls driven off the table" (a foul; whether
the ball comes back is the game's rule); 8-ball, "loss of game" (driving the 8 off the
table loses, after the break); 9-ball, the 9 is spotted whenever it is not legally
pocketed, and other object balls stay down or off.
"""

from __future__ import annotations

import math

from server.engine import Shot, simulate, tip_seen_level
from server.rules import ANYWHERE, Game

from .helpers import TABLE, arrange, crafted, hit, off, pot, rail

FOUR_RAILS = [rail(2), rail(3), rail(4), rail(5)]


def nine_after_the_break(nine: Game) -> None:
    """Ana breaks legally and pockets nothing: Bob to shoot."""
    nine.apply(0, crafted(nine.balls, hit(0, 1), *FOUR_RAILS))
    assert nine.turn == 1


def eight_after_the_break(eight: Game) -> None:
    """Ana breaks and pockets the 1: an open table, Ana to shoot again."""
    eight.apply(0, crafted(eight.balls, hit(0, 1), rail(1), pot(1, 2)))
    assert eight.turn == 0


def test_nine_ball_object_ball_off_the_table_is_a_foul_and_stays_off(nine: Game) -> None:
    nine_after_the_break(nine)
    outcome = nine.apply(1, crafted(nine.balls, hit(0, 1), rail(1), off(3, 2)))
    assert [f.code for f in outcome.fouls] == ["ball_off_table"]
    assert outcome.fouls[0].message == "Bob drove the 3 off the table."
    assert outcome.message.startswith("Foul: ball off the table.")
    assert outcome.next_turn == 0 and outcome.ball_in_hand == ANYWHERE
    assert 3 not in nine.balls.on_table_ids() and outcome.spotted == ()
    assert outcome.pocketed == ()  # off the table is not pocketed


def test_nine_ball_the_nine_off_the_table_is_spotted(nine: Game) -> None:
    nine_after_the_break(nine)
    outcome = nine.apply(1, crafted(nine.balls, hit(0, 1), rail(1), off(9, 4)))
    assert [f.code for f in outcome.fouls] == ["ball_off_table"]
    assert not outcome.frame_over and outcome.spotted == (9,)
    assert 9 in nine.balls.on_table_ids()


def test_the_cue_ball_off_the_table_is_a_scratch(nine: Game) -> None:
    nine_after_the_break(nine)
    outcome = nine.apply(1, crafted(nine.balls, hit(0, 1), rail(1), off(0, 1)))
    assert [f.code for f in outcome.fouls] == ["scratch"]
    assert outcome.fouls[0].message == "Bob scratched: the cue ball left the table."
    assert outcome.ball_in_hand == ANYWHERE and outcome.pocketed == ()


def test_eight_ball_the_eight_off_the_table_loses(eight: Game) -> None:
    eight_after_the_break(eight)
    outcome = eight.apply(0, crafted(eight.balls, hit(0, 2), off(8, 3)))
    assert outcome.winner == 1 and outcome.frame_over
    assert outcome.reason == "Ana drove the 8 off the table."


def test_eight_ball_object_ball_off_the_table_is_a_foul_and_stays_off(eight: Game) -> None:
    eight_after_the_break(eight)
    outcome = eight.apply(0, crafted(eight.balls, hit(0, 2), rail(2), off(12, 3)))
    assert [f.code for f in outcome.fouls] == ["ball_off_table"]
    assert outcome.winner is None and outcome.ball_in_hand == ANYWHERE
    assert 12 not in eight.balls.on_table_ids()


def test_eight_ball_the_eight_off_the_table_on_the_break_is_spotted(eight: Game) -> None:
    outcome = eight.apply(0, crafted(eight.balls, hit(0, 1), rail(1), pot(2, 2), off(8, 4)))
    assert outcome.winner is None and outcome.spotted == (8,)
    assert [f.code for f in outcome.fouls] == ["ball_off_table"]
    assert 8 in eight.balls.on_table_ids() and outcome.ball_in_hand == ANYWHERE


def test_a_real_jump_off_the_table_is_judged_a_scratch(nine: Game) -> None:
    nine_after_the_break(nine)
    arrange(nine, {0: (1.0, 0.15), 1: (2.0, 1.0)})
    elevation = math.radians(45)
    shot = Shot(-math.pi / 2, 8.0, tip_seen_level((0.0, 0.0), elevation), elevation)
    outcome = nine.apply(1, simulate(TABLE, nine.balls, shot))
    assert [f.code for f in outcome.fouls] == ["no_contact", "scratch"]
    assert "left the table" in outcome.fouls[1].message
    assert outcome.ball_in_hand == ANYWHERE


def test_a_jump_over_a_ball_is_no_foul_at_nine_ball(nine: Game) -> None:
    # WPA General Rules: a jump with a raised cue is a legal stroke (snooker calls it a
    # foul: `test_snooker_jump.py`). The cue ball clears the 2, 20 cm ahead, onto the 1.
    nine_after_the_break(nine)
    arrange(nine, {0: (0.5, 0.6), 2: (0.7, 0.6), 1: (2.0, 0.6)})
    elevation = math.radians(40)
    shot = Shot(0.0, 5.0, tip_seen_level((0.0, 0.0), elevation), elevation)
    result = simulate(TABLE, nine.balls, shot)
    assert result.first_contact() == 1
    outcome = nine.apply(1, result)
    assert [f.code for f in outcome.fouls] == []
