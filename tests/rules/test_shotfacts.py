"""Shot facts read from the engine's events and final table."""

from __future__ import annotations

import math
from dataclasses import replace

from server.engine import CUE, BallSet, Shot, Table, rack, settle, simulate, tip_seen_level
from server.rules.shotfacts import shot_facts

from .helpers import TABLE, crafted, hit, pot, rail, straight_in


def test_facts_of_a_real_pot() -> None:
    placement, shot = straight_in(3, pocket=0)
    balls = BallSet.place({**placement, 12: (1.8, 0.9)})
    result = simulate(TABLE, balls, shot)
    facts = shot_facts(balls, result)
    assert facts.first_contact == 3 == result.first_contact()
    assert facts.pocketed == (3,) and facts.pockets == {3: 0} and not facts.scratch


def test_a_rail_counts_only_after_the_first_contact() -> None:
    balls = BallSet.place({0: (0.5, 0.5), 1: (1.0, 0.5), 2: (1.5, 0.5)})
    before = shot_facts(balls, crafted(balls, rail(0), hit(0, 1)))
    after = shot_facts(balls, crafted(balls, rail(0), hit(0, 1), rail(1, 2)))
    assert not before.rail_after_contact and after.rail_after_contact
    assert after.first_contact == 1 and after.balls_to_rail == frozenset({1})


def test_distinct_balls_to_a_rail_and_the_cue_ball_pocket() -> None:
    balls = BallSet.place({0: (0.5, 0.5), 1: (1.0, 0.5), 2: (1.5, 0.5)})
    facts = shot_facts(
        balls, crafted(balls, hit(0, 1), rail(1), rail(1), rail(2), rail(0), pot(0, 4))
    )
    assert facts.balls_to_rail == frozenset({1, 2})
    assert facts.scratch and facts.pockets == {0: 4} and facts.pocketed == ()


def test_a_miss_has_no_contact() -> None:
    balls = BallSet.place({0: (0.5, 0.5), 1: (1.0, 1.0)})
    facts = shot_facts(balls, simulate(TABLE, balls, Shot(-1.2, 0.5)))
    assert facts.first_contact is None and facts.pocketed == ()


def test_settled_shots_give_the_facts_of_simulated_ones() -> None:
    """The search reads facts from `settle`'s rows (`Settled.contacts`), the room from
    `simulate`'s events: a break (many balls, rails, pockets), a pot, a scratch and a
    miss must read the same either way."""
    table = Table.pool("9ft")
    racked = rack("eight_ball", table, seed=3)
    cx, cy = racked.position_of(CUE)
    fx, fy = table.foot_spot
    placement, straight = straight_in(3, pocket=0)
    lone = BallSet.place(placement)
    shots = [
        (racked, Shot(math.atan2(fy - cy, fx - cx), 11.0)),
        (lone, straight),
        (lone, replace(straight, speed=4.0)),  # the cue ball scratches after the 3
        (lone, Shot(straight.angle + 1.0, 1.0)),
    ]
    seen = set()
    for balls, shot in shots:
        simulated, settled = simulate(table, balls, shot), settle(table, balls, shot)
        assert settled.contacts() == simulated.contacts()
        facts = shot_facts(balls, settled)
        assert facts == shot_facts(balls, simulated)
        seen.add((bool(facts.pocketed), facts.scratch, facts.first_contact is None))
    assert len(seen) >= 3  # the shots above do differ in what happened


def test_a_jump_over_a_ball_is_read_from_the_frames_and_not_from_a_settled_shot() -> None:
    """`jumped_over`: the balls the cue ball passed over before its first contact
    (`rules.jumps`). Only a simulated shot's frames tell; the facts stay equal."""
    table = Table.pool("9ft")
    balls = BallSet.place({0: (0.5, 0.6), 2: (0.7, 0.6), 1: (2.0, 0.6)})
    elevation = math.radians(40)
    shot = Shot(0.0, 5.0, tip_seen_level((0.0, 0.0), elevation), elevation)
    simulated = simulate(table, balls, shot)
    facts = shot_facts(balls, simulated, radius=table.ball_radius)
    assert facts.first_contact == 1 and facts.jumped_over == (2,)
    assert shot_facts(balls, simulated).jumped_over == ()  # no radius, no reading
    settled = shot_facts(balls, settle(table, balls, shot), radius=table.ball_radius)
    assert settled.jumped_over == () and settled == facts
    level = shot_facts(balls, simulate(table, balls, Shot(0.0, 5.0)), radius=table.ball_radius)
    assert level.first_contact == 2 and level.jumped_over == ()
