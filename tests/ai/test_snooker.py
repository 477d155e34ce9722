"""The computer plays legal snooker at every level: its break-off from the D, the ball on
first, the colour it pots nominated, a free ball taken; every turn goes through the rules'
own actions (`play_turn`), which refuse an illegal one."""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import replace

import numpy as np
import pytest

from server.ai import Bot
from server.ai.bot import HAND_FLOOR, RACK_BALLS, hand_budget
from server.ai.geometry import pot_options
from server.ai.levels import for_kind
from server.ai.play import play_turn
from server.ai.search import (
    EVENTS_PER_SIM,
    FEW_POTS,
    FINE_SPEED_FACTORS,
    FINE_TIPS,
    FREE_EVENTS,
    LATE_SPEED_FACTORS,
    LOOK_PAIRS,
    TIPS,
)
from server.engine import Shot, Table
from server.rules import Game
from server.rules.ruling import Ruling
from server.rules.snooker_score import COLOUR

from .conftest import set_table

SNOOKER = Table.snooker()
PINK = 20


@pytest.mark.parametrize("level", Bot.LEVELS)
def test_every_level_breaks_off_from_the_d_and_plays_the_ball_on(level: str) -> None:
    game = Game.new("snooker", ("Ana", "Computer"), breaker=1, seed=4)
    bot = Bot(level, seed=1)
    rng = np.random.default_rng(2)
    turn = bot.plan(game, 1)
    assert turn.place is not None and SNOOKER.in_d(*turn.place)
    out, _ = play_turn(game, 1, turn)
    assert out is not None
    # The break-off it means (played without its arm's error) is a fair stroke.
    assert not out.fouls, out.message
    for _ in range(3):  # and it goes on playing through the rules
        if game.over:
            break
        seat = game.decision.seat if game.decision else game.turn
        play_turn(game, seat, Bot(level, seed=seat).plan(game, seat), Bot(level), rng)


def _pink_on_the_lip() -> Game:
    """Only the pink near a corner pocket and the cue ball on its line, on a colour."""
    game = Game.new("snooker", ("Ana", "Computer"), seed=1)
    keep = {0: (0.55, 0.45), PINK: (0.2, 0.2)}
    balls = game.balls.with_only(keep)
    game.balls = balls
    game.ball_in_hand = None
    game.score = replace(game.score, on=COLOUR)  # type: ignore[arg-type]
    return game


def test_the_pro_pots_the_colour_it_nominates() -> None:
    game = _pink_on_the_lip()
    turn = Bot("pro", seed=3).plan(game, 0)
    assert turn.kind == "pot" and turn.target == PINK and turn.nominate == PINK
    out, _ = play_turn(game, 0, turn)
    assert out is not None and not out.fouls and game.points == (6, 0)


def test_the_computer_takes_a_free_ball() -> None:
    mid = SNOOKER.width / 2
    game = Game.new("snooker", ("Ana", "Computer"), seed=1)
    keep = {0: (1.0, mid), 1: (2.0, mid), 19: (1.5, mid), 21: SNOOKER.spots["black"]}
    balls = game.balls.with_only(keep)
    game.balls, game.ball_in_hand = balls, None
    angle = math.pi / 2  # straight at the side cushion: no ball hit
    from server.engine import Shot, simulate

    game.apply(0, simulate(game.table, game.balls, Shot(angle, 0.05)))
    assert game.decision is not None and game.decision.options[0] == "free_ball"
    turn = Bot("amateur", seed=1).plan(game, 1)
    assert turn.decision == "free_ball"


def test_show_me_a_shot_on_the_snooker_practice_table() -> None:
    # The practice table on snooker: one player, its 22 balls; the hint is the top level's
    # plan, played through the rules.
    game = Game.new("snooker_practice", ("Pia",), seed=2)
    assert game.table.style == "snooker" and len(game.balls) == 22
    turn = Bot("pro", seed=1).plan(game, 0)
    assert turn.shot is not None
    out, _ = play_turn(game, 0, turn)
    assert out is not None and not out.fouls and game.turn == 0


def test_ball_in_hand_on_a_fuller_table_than_a_pool_rack_searches_less() -> None:
    # The break-off's 22 balls make each simulation dearer: its turn spends a smaller
    # share of the budget (the plan-time goal); a pool table (16 balls at most) all of it.
    assert all(hand_budget(3900, n) == 3900 for n in range(RACK_BALLS + 1))
    assert hand_budget(3900, 21) == int(3900 * (16 / 21) ** 2) < 3900
    assert hand_budget(3900, 22) < hand_budget(3900, 21)
    assert hand_budget(550, 22) == 550 and hand_budget(3900, 40) == HAND_FLOOR


def _reds_spread() -> Game:
    """Mid-frame: eight reds spread over the middle of the table, the colours on their
    spots, the cue ball between them; a red is on."""
    game = Game.new("snooker", ("Ana", "Computer"), seed=1)
    reds = {k: (1.2 + 0.27 * k, 0.25 + 0.18 * ((3 * k) % 8)) for k in range(1, 9)}
    colours = {b: game.balls.position_of(b) for b in range(16, 22)}
    game.balls = game.balls.with_only({0: (1.6, 0.7), **reds, **colours})
    game.ball_in_hand = None
    game.breaking = False
    return game


def test_at_snooker_the_pro_searches_every_pots_position_finely() -> None:
    """A break runs for up to 36 pots, not a pool rack's 8: at snooker the pro gives every
    pot the finer strokes and searches the next shot on the late grid even with many pots
    on (`levels.for_kind`); the club keeps its usual strokes, and at pool the pro's level
    is what it was."""
    game = _reds_spread()
    pro, club = Bot("pro"), Bot("club")
    search = pro._search(game, 0)
    assert search.level.fine_pots and search.level.deep_next
    options = pot_options(SNOOKER, game.balls, search.targets(search.pos), search.plan_sigma())
    assert len(options) > FEW_POTS
    for bot, want in [
        (pro, len(FINE_SPEED_FACTORS) * len(FINE_TIPS)),
        (club, club.level.speeds * club.level.tips),
    ]:
        strokes = bot._search(game, 0).pot_candidates(game.balls, bot.level.pairs)
        per_pot = Counter((c.target, c.pocket) for c in strokes if c.via == "direct")
        assert set(per_pot.values()) == {want}, (bot.level.name, per_pot)
    before = search.sims
    search._next_shot(search.pos, Ruling(), game.balls)
    looked = min(len(options), LOOK_PAIRS)
    assert search.sims - before == looked * len(LATE_SPEED_FACTORS) * len(TIPS)
    for kind in ("eight_ball", "nine_ball", "three_cushion"):
        assert for_kind(pro.level, kind) == pro.level
    assert for_kind(club.level, "snooker") == club.level
    assert for_kind(pro.level, "snooker_practice") == for_kind(pro.level, "snooker")


def _red_behind_the_black() -> Game:
    """A red straight ahead of the cue ball with the black 20 cm ahead, in the way."""
    game = Game.new("snooker", ("Ana", "Computer"), seed=1)
    mid = SNOOKER.width / 2
    keep = {0: (1.0, mid), 21: (1.2, mid), 1: (2.0, mid)}
    balls = game.balls.with_only(keep)
    game.balls = balls
    game.ball_in_hand = None
    game.breaking = False
    return game


def test_at_snooker_no_level_jumps_but_the_pro_still_swerves(nine: Game) -> None:
    """A jump shot is a foul at snooker (WPBSA Section 2 "Jump Shot", 3.11): no level
    plans one there (`levels.for_kind`); swerves and masses stay. At 9-ball the same
    bot jumps a ball in the way (`test_jumps.py`)."""
    for name in Bot.LEVELS:
        assert not for_kind(Bot(name).level, "snooker").jumps
    game = _red_behind_the_black()
    search = Bot("pro")._search(game, 0)
    assert not search.level.jumps and search.level.masse
    assert search.jump_candidates(game.balls) == []
    assert search.curve_candidates(game.balls)
    pool = set_table(nine, {0: (0.6, 0.6), 2: (0.8, 0.6), 1: (1.6, 0.6), 9: (2.2, 1.0)})
    assert Bot("pro")._search(pool, 0).jump_candidates(pool.balls)


def test_a_turn_with_every_ball_still_on_searches_less_too() -> None:
    """After the break-off (played with the arm's error, a fixed draw), with all 22 balls
    on and the cue ball where it stopped, the pro's turn spends the same smaller share as
    a ball-in-hand turn would: each shot into the pack costs more (the plan-time goal).
    Given the whole budget, this turn spends 3,535 simulations."""
    game = Game.new("snooker", ("Ana", "Computer"), breaker=1, seed=117)
    bots = [Bot("pro", seed=234), Bot("pro", seed=235)]
    play_turn(game, 1, bots[1].plan(game, 1), bots[1], np.random.default_rng(117))
    assert game.ball_in_hand is None and len(game.balls.on_table_ids()) == 22
    share = hand_budget(bots[0].level.budget, 22)
    assert RACK_BALLS < 22 and share < bots[0].level.budget
    bots[0].plan(game, 0)
    assert share // 2 < bots[0].last_sims <= share


def test_a_cascade_in_the_pack_is_charged_by_its_events() -> None:
    """A shot into the pack after a seeded break-off sets off over a thousand contacts
    among touching reds: on a table fuller than a pool rack it costs the pro's search as
    many simulations as its events beyond `FREE_EVENTS`, and the budget counts as spent
    once reached; uncharged, it costs one."""
    game = Game.new("snooker", ("a", "b"), breaker=1, seed=195)
    pro = Bot("pro", seed=391)
    play_turn(game, 1, pro.plan(game, 1), pro, np.random.default_rng(195))
    assert len(game.balls.on_table_ids()) == 22 and game.ball_in_hand is None
    into_the_pack = Shot(0.6880164072447013, 1.8)
    for charged in (True, False):
        search = Bot("pro", seed=390)._search(game, game.turn)
        search.charge_events, search.limit = charged, 100
        _, result = search._simulate(game.balls, into_the_pack)
        events = len(result.rows)
        assert events > 1000
        want = 1 + (events - FREE_EVENTS) // EVENTS_PER_SIM if charged else 1
        assert search.sims == want and search.spent() == charged
