"""Banks, combinations, caroms and billiards: found by geometry, judged by the engine,
played when nothing goes straight in (or when a combination or a billiard wins the game)."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from server.ai import Bot, play_turn
from server.ai.aiming import aim_carom, aimed, kiss_miss
from server.ai.geometry import pot_options, speed_for
from server.ai.indirect import bank_options, billiard_options, carom_options, combo_options
from server.ai.levels import BY_NAME
from server.ai.search import Search, route
from server.engine import simulate
from server.rules import Game
from server.rules.shotfacts import shot_facts

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
    """No straight pot on the 1. The banks the geometry finds go off one cushion (the long
    way into the top side pocket, 46 % under the pro's noise); the grid of safeties also
    finds a double off both long cushions into the bottom side pocket, 67 %, and the plan
    takes that, reported as the bank it is (not as a safety). Either way the 1 meets a
    cushion before it drops, with the exact stroke. Without the safeties the pro's best
    shot is the one-cushion bank."""
    game = set_table(eight, BANK_TABLE, groups=SOLIDS_STRIPES)
    no_safeties = replace(BY_NAME["pro"], safeties=False)
    noise = np.random.default_rng(1).standard_normal((no_safeties.samples, 4))
    search = Search(TABLE, game.rules, game.position(), 0, no_safeties, noise, noise[:0])
    bank = search.best_shot(game.balls)
    assert bank.kind == "pot" and bank.via == "bank" and bank.target == 1, bank
    turn = Bot("pro").plan(game, 0)
    assert turn.target == 1 and (turn.chance or 0.0) > 0.4, turn
    assert turn.kind == "pot" and turn.via == "bank", turn
    assert turn.shot is not None
    events = simulate(TABLE, game.balls, turn.shot).events
    kinds = [e.kind for e in events if 1 in e.ids]
    assert "cushion" in kinds and "pocket" in kinds
    assert kinds.index("cushion") < kinds.index("pocket")
    assert [e.target for e in events if e.kind == "pocket" and 1 in e.ids] == [turn.pocket]
    outcome, _ = play_turn(game, 0, turn)
    assert outcome is not None and 1 in outcome.pocketed and outcome.continues
    assert not outcome.fouls


def test_a_shots_route_is_read_from_its_events(eight: Game, nine: Game) -> None:
    """`route` names how a ball reached its pocket from the engine's events: what the turn
    reports when a stroke of the safeties' grid pockets a ball (a "bank": the test above)."""
    cue, one, nine_ball = _diagonal(0.95, 0.55, 0.3)
    straight = set_table(eight, {0: cue, 1: nine_ball, 8: (0.5, 0.3)}, groups=SOLIDS_STRIPES)
    combo = set_table(nine, {0: cue, 1: one, 9: nine_ball, 5: (0.5, 0.3)})
    for game, ball, via in ((straight, 1, "direct"), (combo, 9, "combo")):
        aim = math.atan2(nine_ball[1] - cue[1], nine_ball[0] - cue[0])
        result = simulate(TABLE, game.balls, aimed(aim, 2.0, 0.0, 0.0))
        facts = shot_facts(game.balls, result)
        assert ball in facts.pocketed and facts.pockets[ball] == 3
        assert route(result.events, ball, facts.first_contact) == via


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
    assert not [o for o in combo_options(TABLE, game.balls, [1], [9], SIGMA) if o.pocket == 0]


# The 1 with the 10 just to its left: the stripes and the 9 shut or thin its straight pots
# from the cue ball to its right, but the 1 glances off the 10 into the bottom left
# pocket (0).
CAROM_TABLE = {
    0: (0.591, 0.409),
    1: (0.493, 0.433),
    9: (0.455, 0.206),
    10: (0.364, 0.461),
    11: (0.689, 0.763),
    12: (0.422, 0.064),
    13: (0.07, 0.528),
    8: (0.114, 0.317),
}


def test_a_carom_route_is_found_and_a_ball_on_its_way_shuts_it(eight: Game) -> None:
    game = set_table(eight, CAROM_TABLE, groups=SOLIDS_STRIPES)
    assert not pot_options(TABLE, game.balls, [1], SIGMA)
    caroms = carom_options(TABLE, game.balls, [1], SIGMA)
    assert caroms[0].via == "carom" and caroms[0].target == 1 and caroms[0].carrier == 10
    assert caroms[0].pocket == 0
    # A stripe halfway from the 1 to the pocket shuts the route.
    (x, y), (px, py) = CAROM_TABLE[1], pocket_aim(0)
    blocker = {**CAROM_TABLE, 14: ((x + px) / 2, (y + py) / 2)}
    blocked = set_table(
        Game.new("eight_ball", ["ana", "bot"], seed=3), blocker, groups=SOLIDS_STRIPES
    )
    assert not [o for o in carom_options(TABLE, blocked.balls, [1], SIGMA) if o.pocket == 0]


def test_the_engine_corrects_a_caroms_aim(eight: Game) -> None:
    # The 1 travels 0.15 m to glance off the 9 into the bottom side pocket (1): it rolls
    # part of the way and the kiss throws it, so the geometry's aim is degrees off.
    table = {0: (1.927, 0.906), 1: (1.838, 0.644), 9: (1.811, 0.462)}
    game = set_table(eight, table, groups=SOLIDS_STRIPES)
    option = carom_options(TABLE, game.balls, [1], SIGMA)[0]
    assert option.pocket == 1 and option.carrier == 9
    shot = aimed(option.angle, 1.8 * speed_for(option), 0.0, 0.0)
    before = kiss_miss(TABLE, game.balls, shot, 1, option.pocket)
    corrected, used = aim_carom(TABLE, game.balls, shot, 1, option.pocket)
    after = kiss_miss(TABLE, game.balls, corrected, 1, option.pocket)
    assert before is not None and after is not None and 2 <= used <= 5
    assert abs(before) > math.radians(2.0) and abs(after) < math.radians(0.5)
    assert (corrected.speed, corrected.tip) == (shot.speed, shot.tip)
    pocketed = simulate(TABLE, game.balls, corrected).final
    assert not pocketed.on_table[pocketed.index(1)]


def test_with_only_a_carom_on_the_pro_plays_it_and_the_exact_stroke_drops(eight: Game) -> None:
    game = set_table(eight, CAROM_TABLE, groups=SOLIDS_STRIPES)
    turn = Bot("pro").plan(game, 0)
    assert turn.kind == "pot" and turn.via == "carom" and turn.target == 1, turn
    assert turn.shot is not None
    events = [e for e in simulate(TABLE, game.balls, turn.shot).events if 1 in e.ids]
    assert [set(e.ids) for e in events[:2]] == [{0, 1}, {1, 10}]  # the cue ball, then the kiss
    assert events[-1].kind == "pocket"
    outcome, _ = play_turn(game, 0, turn)
    assert outcome is not None and 1 in outcome.pocketed and outcome.continues
    assert not outcome.fouls


# 9-ball: the 1 near the bottom right pocket (2) with no pot from the cue ball, the 9 a
# ball's width off it; the cue ball can glance off the 1 into the 9 and drop it.
BILLIARD_TABLE = {0: (0.891, 0.93), 1: (1.89, 0.183), 9: (2.039, 0.2)}


def test_a_billiard_route_is_found_and_a_ball_on_its_way_shuts_it() -> None:
    game = set_table(Game.new("nine_ball", ["ana", "bot"], seed=1), BILLIARD_TABLE)
    assert not pot_options(TABLE, game.balls, [1], SIGMA)
    options = billiard_options(TABLE, game.balls, [1], [9], SIGMA)
    assert options and options[0].via == "billiard"
    assert (options[0].target, options[0].carrier, options[0].pocket) == (9, 1, 2)
    # A ball on the cue ball's way from the cue to the 1 shuts it.
    (cx, cy), (ox, oy) = BILLIARD_TABLE[0], BILLIARD_TABLE[1]
    blocker = {**BILLIARD_TABLE, 5: ((cx + ox) / 2, (cy + oy) / 2)}
    blocked = set_table(Game.new("nine_ball", ["ana", "bot"], seed=1), blocker)
    assert not billiard_options(TABLE, blocked.balls, [1], [9], SIGMA)


def test_the_engine_corrects_a_billiards_aim() -> None:
    """The cue ball bends as it rolls after the glance, and the glance throws it: the
    geometry's aim sends the 9 over a degree off the pocket's centre, the engine-corrected
    one within a tenth of that."""
    game = set_table(Game.new("nine_ball", ["ana", "bot"], seed=1), BILLIARD_TABLE)
    option = billiard_options(TABLE, game.balls, [1], [9], SIGMA)[0]
    shot = aimed(option.angle, 1.8 * speed_for(option), 0.0, 0.0)
    before = kiss_miss(TABLE, game.balls, shot, 9, option.pocket, first=1)
    corrected, used = aim_carom(TABLE, game.balls, shot, 9, option.pocket, first=1)
    after = kiss_miss(TABLE, game.balls, corrected, 9, option.pocket, first=1)
    assert before is not None and after is not None and 2 <= used <= 5
    assert abs(before) > math.radians(1.0) and abs(after) < 0.1 * abs(before)
    # Measured as a carom (the 9 struck first), the same stroke is no carom at all.
    assert kiss_miss(TABLE, game.balls, corrected, 9, option.pocket) is None
    final = simulate(TABLE, game.balls, corrected).final
    assert not final.on_table[final.index(9)] and final.on_table[final.index(0)]


def test_with_a_billiard_on_the_nine_the_pro_plays_it_and_wins() -> None:
    game = set_table(Game.new("nine_ball", ["ana", "bot"], seed=1), BILLIARD_TABLE)
    turn = Bot("pro").plan(game, 0)
    assert turn.kind == "pot" and turn.via == "billiard" and turn.target == 9, turn
    assert turn.shot is not None
    result = simulate(TABLE, game.balls, turn.shot)
    facts = shot_facts(game.balls, result)
    assert facts.first_contact == 1
    assert route(result.events, 9, facts.first_contact) == "billiard"
    outcome, _ = play_turn(game, 0, turn)
    assert outcome is not None and outcome.winner == 0 and 9 in outcome.pocketed
