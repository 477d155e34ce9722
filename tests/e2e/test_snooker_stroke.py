"""The newcomer's sighting (`snooker_stroke`), which the snooker frame in the browser relies
on, checked on the engine and the rules without a browser: a pot it chooses goes in, a
ball on in plain view is hit first, a ball hidden behind another is reached off a cushion,
and a cue ball in hand is put where the rules accept it (WPBSA 3.4, the D)."""

from __future__ import annotations

import math

from server.engine import CUE, BallSet, Shot, Table, simulate
from server.rules.game import Game
from server.rules.shotfacts import shot_facts

from .snooker_stroke import Layout, choose, cushions, place_in_d

TABLE = Table.snooker()
LAYOUT = Layout.of(TABLE.to_dict())
RED, PINK, BLUE = 1, 20, 19


def play(placement: dict[int, tuple[float, float]], on: list[int], attempt: int = 0):
    balls = BallSet.place(placement)
    others = {b: p for b, p in placement.items() if b != CUE}
    stroke = choose(LAYOUT, placement[CUE], others, on, attempt)
    result = simulate(TABLE, balls, Shot(stroke.angle, stroke.speed))
    return stroke, shot_facts(balls, result, CUE)


def test_a_red_straight_at_a_corner_pocket_is_potted():
    stroke, facts = play({CUE: (2.6, 1.1), RED: (3.1, 1.45)}, on=[RED])
    assert stroke.kind == "pot"
    assert facts.first_contact == RED and RED in facts.pocketed and not facts.scratch


def test_with_no_pot_on_the_ball_on_in_plain_view_is_hit_first():
    # The red sits on the middle of the top cushion, away from both side pockets' lines.
    stroke, facts = play({CUE: (1.0, 0.4), RED: (1.2, LAYOUT.width - 0.03)}, on=[RED])
    assert stroke.kind in ("pot", "hit")
    assert facts.first_contact == RED


def test_a_red_hidden_behind_the_blue_is_reached_off_a_cushion():
    placement = {CUE: (1.2, 0.889), BLUE: (1.5, 0.889), RED: (1.8, 0.889)}
    others = {b: p for b, p in placement.items() if b != CUE}
    kicks = cushions(LAYOUT, placement[CUE], others, [RED])
    assert kicks, "a one-cushion path to the red"
    stroke, facts = play(placement, on=[RED])
    assert stroke.kind == "cushion" and facts.first_contact == RED


def test_a_repeated_table_gets_another_stroke():
    placement = {CUE: (1.2, 0.889), BLUE: (1.5, 0.889), RED: (1.8, 0.889)}
    others = {b: p for b, p in placement.items() if b != CUE}
    first = choose(LAYOUT, placement[CUE], others, [RED], attempt=0)
    second = choose(LAYOUT, placement[CUE], others, [RED], attempt=1)
    assert not math.isclose(first.angle, second.angle)


def test_the_cue_ball_in_hand_goes_where_the_rules_accept_it():
    game = Game.new("snooker", ["Ana", "Ben"], seed=3)
    balls = {b: game.balls.position_of(b) for b in game.balls.on_table_ids() if b != CUE}
    x, y = place_in_d(LAYOUT, balls, game.legal_targets())
    assert game.can_place_cue(x, y)
    game.place_cue(0, x, y)
