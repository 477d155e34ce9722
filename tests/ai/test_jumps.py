"""The pro level's jumps: when the straight path to a legal ball is blocked by a ball near
the cue ball, it also tries jumping over it (`Search.jump_candidates`), and its arm plays
a jump as a jump (the elevation and tip kept, the line and speed straying)."""

from __future__ import annotations

import math

import numpy as np

from server.ai import Bot
from server.ai.aiming import perturb
from server.ai.levels import BY_NAME
from server.engine import Shot, simulate, tip_seen_level
from server.rules import Game
from server.rules.shotfacts import shot_facts

from .conftest import TABLE, set_table

# 9-ball: the 1 straight ahead of the cue ball, a blocker 20 cm ahead in the way.
BLOCKED = {0: (0.6, 0.6), 2: (0.8, 0.6), 1: (1.6, 0.6), 9: (2.2, 1.0)}
CLEAR = {0: (0.6, 0.6), 2: (0.8, 0.9), 1: (1.6, 0.6), 9: (2.2, 1.0)}


def test_a_blocked_ball_gets_jumps_that_hit_it_first(nine: Game) -> None:
    game = set_table(nine, BLOCKED)
    search = Bot("pro")._search(game, 0)
    jumps = search.jump_candidates(game.balls)
    assert jumps and all(c.shot.elevation > 0 and c.target == 1 for c in jumps)
    hits = []
    for cand in jumps:
        facts = shot_facts(game.balls, simulate(TABLE, game.balls, cand.shot))
        hits.append(facts.first_contact)
    assert hits.count(1) >= len(hits) // 2, hits  # most jumps clear the 2 and hit the 1
    level = simulate(TABLE, game.balls, Shot(0.0, 4.0))
    assert shot_facts(game.balls, level).first_contact == 2  # level, the 2 is hit first


def test_no_jump_when_the_path_is_clear_or_below_the_pro_level(nine: Game) -> None:
    game = set_table(nine, CLEAR)
    assert Bot("pro")._search(game, 0).jump_candidates(game.balls) == []
    game = set_table(nine, BLOCKED)
    assert Bot("club")._search(game, 0).jump_candidates(game.balls) == []


def test_the_arm_plays_a_jump_as_a_jump() -> None:
    elevation = math.radians(45)
    shot = Shot(0.3, 4.0, tip_seen_level((0.0, 0.0), elevation), elevation)
    played = perturb(shot, np.array([1.0, -1.0, 2.0, 2.0]), BY_NAME["pro"])
    assert played.elevation == shot.elevation and played.tip == shot.tip
    assert played.angle != shot.angle and played.speed != shot.speed


def test_the_pro_jumps_a_ball_that_hides_the_one(nine: Game) -> None:
    # Three balls across the line 18 cm ahead: no straight path, and a jump clears them.
    layout = {**BLOCKED, 2: (0.78, 0.6), 3: (0.78, 0.66), 4: (0.78, 0.54)}
    game = set_table(nine, layout)
    turn = Bot("pro").plan(game, 0)
    assert turn.shot is not None and turn.shot.elevation > 0
    facts = shot_facts(game.balls, simulate(TABLE, game.balls, turn.shot))
    assert facts.first_contact == 1
