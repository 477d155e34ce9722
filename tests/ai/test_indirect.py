"""Banks and combinations: found by geometry, judged by the engine, played when nothing goes
straight in (or when a combination wins the game)."""

from __future__ import annotations

import math

from server.ai import Bot, play_turn
from server.ai.indirect import bank_options, combo_options
from server.engine import simulate
from server.rules import Game

from .conftest import TABLE, pocket_aim, set_table

SOLIDS_STRIPES = {0: "solids", 1: "stripes"}
SIGMA = math.radians(0.125)
# The 1 near the bottom rail: the stripes shut its ways into the bottom side and bottom
# right pockets, and the cue ball (up and to the left) cannot cut it into any other; the
# way left is off the bottom cushion, across the table into the top side pocket (4).
BANK_TABLE = {0: (0.85, 0.75), 1: (1.0, 0.35), 9: (1.13, 0.18), 10: (1.6, 0.222), 8: (2.2, 1.0)}


def _diagonal(*distances: float) -> list[tuple[float, float]]:
    """Points on the line from the top right pocket's mouth to the table's centre."""
    px, py = pocket_aim(3)
    cx, cy = TABLE.length / 2, TABLE.width / 2
    d = math.hypot(cx - px, cy - py)
    return [(px + (cx - px) / d * k, py + (cy - py) / d * k) for k in distances]


def test_a_bank_route_is_found_and_a_ball_on_its_way_shuts_it(eight: Game) -> None:
    game = set_table(eight, BANK_TABLE, groups=SOLIDS_STRIPES)
    banks = bank_options(TABLE, game.balls, [1], SIGMA)
    side = [o for o in banks if o.pocket == 4]
    assert side and all(o.via == "bank" and o.target == 1 for o in side)
    assert all(o.d2 > math.dist(BANK_TABLE[1], pocket_aim(4)) for o in side)  # the long way
    # A stripe on the way back up from the cushion shuts the route.
    blocked = set_table(
        Game.new("eight_ball", ["ana", "bot"], seed=3),
        {**BANK_TABLE, 11: (1.12, 0.62)},
        groups=SOLIDS_STRIPES,
    )
    assert not [o for o in bank_options(TABLE, blocked.balls, [1], SIGMA) if o.pocket == 4]


def test_with_no_straight_pot_the_pro_banks_and_the_exact_stroke_drops(eight: Game) -> None:
    game = set_table(eight, BANK_TABLE, groups=SOLIDS_STRIPES)
    turn = Bot("pro").plan(game, 0)
    assert turn.kind == "pot" and turn.via == "bank" and turn.target == 1, turn
    assert turn.shot is not None
    events = simulate(TABLE, game.balls, turn.shot).events
    kinds = [e.kind for e in events if 1 in e.ids]
    assert "cushion" in kinds and "pocket" in kinds
    assert kinds.index("cushion") < kinds.index("pocket")
    outcome, _ = play_turn(game, 0, turn)
    assert outcome is not None and 1 in outcome.pocketed and outcome.continues
    assert not outcome.fouls


def test_a_combination_on_the_nine_wins_the_game(nine: Game) -> None:
    cue, one, nine_ball = _diagonal(0.95, 0.55, 0.3)
    game = set_table(nine, {0: cue, 1: one, 9: nine_ball, 5: (0.5, 0.3)})
    combos = combo_options(TABLE, game.balls, [1], [5, 9], SIGMA)
    assert combos[0].target == 9 and combos[0].carrier == 1 and combos[0].pocket == 3
    assert combos[0].chance > 0.9  # a short straight line
    turn = Bot("pro").plan(game, 0)
    assert turn.kind == "pot" and turn.via == "combo" and turn.target == 9, turn
    outcome, _ = play_turn(game, 0, turn)
    assert outcome is not None and not outcome.fouls
    assert game.over and game.winner == 0


def test_a_combination_needs_a_clear_way_between_the_balls(nine: Game) -> None:
    cue, one, nine_ball = _diagonal(1.1, 0.7, 0.3)
    between = _diagonal(0.5)[0]
    game = set_table(nine, {0: cue, 1: one, 9: nine_ball, 5: between})
    assert not [o for o in combo_options(TABLE, game.balls, [1], [9], SIGMA) if o.pocket == 3]
