"""`Game`/`Match` through the codec (`to_data`/`from_data`, `to_dict`/`from_dict`): a stored
game comes back exactly and plays on the same.

The server saves rooms after every shot (restart recovery); these prove nothing is lost.
"""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from server.codec import from_data, from_json, to_data, to_json
from server.engine import BallSet, MotionState, Shot, Table, simulate
from server.rules import GAME_KINDS, Decision, Foul, Game, Match, Outcome, RuleOptions

from .helpers import TABLE
from .test_properties import act, check_possible


def through_json(data: dict) -> dict:
    return json.loads(json.dumps(data, allow_nan=False))


def same_balls(a: BallSet, b: BallSet) -> None:
    """Every array the same, bit for bit and dtype for dtype."""
    for f in dataclasses.fields(BallSet):
        x, y = getattr(a, f.name), getattr(b, f.name)
        assert (x.dtype, x.shape, x.tobytes()) == (y.dtype, y.shape, y.tobytes()), f.name


def same_game(a: Game, b: Game) -> None:
    """Field by field equal (the fields are the whole state), and shown the same."""
    assert set(vars(a)) == set(vars(b))  # nothing kept outside the stored fields
    for f in dataclasses.fields(Game):
        if f.name == "balls":
            same_balls(a.balls, b.balls)
        else:
            assert getattr(a, f.name) == getattr(b, f.name), f.name
    assert a.to_dict() == b.to_dict()
    assert a.public_state() == b.public_state()


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    kind=st.sampled_from(["eight_ball", "nine_ball", "practice"]),
    seed=st.integers(0, 5),
    data=st.data(),
)
def test_a_restored_game_is_identical_and_keeps_playing(kind, seed, data) -> None:
    players = ("Ana",) if kind == "practice" else ("Ana", "Bob")
    game = Game.new(kind, players, table=TABLE, seed=seed)
    for _ in range(30):
        if game.over:
            break
        restored = Game.from_dict(through_json(game.to_dict()))
        same_game(game, restored)
        game = restored  # play on from the stored copy
        act(data, game)
        check_possible(game)


SHOTS = [
    Shot(0.0, 9.0),
    Shot(0.3, 3.0, (0.1, 0.2)),
    Shot(2.5, 4.0),
    Shot(-1.2, 5.5),
    Shot(1.0, 2.0, (-0.2, 0.0)),
    Shot(math.pi, 6.0),
    Shot(0.7, 7.0),
    Shot(-2.8, 3.5),
]


def play(match: Match, restore_each_time: bool) -> tuple[Match, list[Outcome]]:
    outcomes = []
    for shot in SHOTS:
        if match.over:
            break
        if restore_each_time:
            match = Match.from_dict(through_json(match.to_dict()))
        game = match.game
        if game.decision is not None:
            game.decide(game.decision.seat, game.decision.options[0])
        seat = game.turn
        if not game.balls.on_table[game.balls.index(0)]:
            game.place_cue(seat, *TABLE.head_spot)
        if game.requires_call:
            game.call_pocket(seat, 0)
        game.check_shot(seat)
        outcomes.append(match.apply(seat, simulate(game.table, game.balls, shot)))
        if match.game.over and not match.over:
            match.next_game()
    return match, outcomes


def test_a_match_restored_before_every_shot_ends_exactly_like_one_never_stored() -> None:
    for kind in ("eight_ball", "nine_ball"):
        straight, outcomes = play(Match(kind, ("Ana", "Bob"), race_to=3, seed=4), False)
        stored, stored_outcomes = play(Match(kind, ("Ana", "Bob"), race_to=3, seed=4), True)
        assert outcomes == stored_outcomes
        assert len(outcomes) >= 4
        assert straight.to_dict() == stored.to_dict()
        assert set(vars(straight)) == set(vars(stored))
        same_game(straight.game, stored.game)


def test_match_round_trip_keeps_score_winner_and_rematch() -> None:
    match = Match("eight_ball", ("Ana", "Bob"), race_to=2, seed=9)
    match.concede(0)
    match.next_game()
    match.concede(0)
    assert match.over and match.winner == 1
    restored = Match.from_dict(through_json(match.to_dict()))
    assert restored.to_dict() == match.to_dict()
    assert restored.public_state() == match.public_state()
    assert (restored.score, restored.winner, restored.reason) == ([0, 2], 1, match.reason)
    restored.rematch()
    match.rematch()
    assert restored.to_dict() == match.to_dict() and restored.first_breaker == 1


def test_outcome_round_trip() -> None:
    match = Match("nine_ball", ("Ana", "Bob"), seed=1)
    outcome = match.timeout(0)
    assert outcome.fouls
    assert Outcome.from_dict(through_json(outcome.to_dict())) == outcome


# --- seeded positions straight through the codec ---------------------------------------
def random_balls(rng: np.random.Generator, balls: BallSet) -> BallSet:
    """Any bits at all in the float arrays, some balls pocketed in some pocket."""
    n = len(balls)
    pocketed = rng.random(n) < 0.4
    states = np.where(pocketed, MotionState.POCKETED, rng.integers(0, 4, n))
    return BallSet(
        ids=balls.ids.copy(),
        positions=rng.uniform(0, 2.5, (n, 2)) * rng.choice([1.0, 1e-300, 1 / 3], (n, 1)),
        velocities=rng.standard_normal((n, 2)),
        spins=rng.standard_normal((n, 3)) * 100,
        states=states.astype(np.int64),
        phases=rng.uniform(-1e6, 1e6, n),
        pockets=np.where(pocketed, rng.integers(0, 6, n), -1).astype(np.int64),
    )


def random_game(rng: np.random.Generator, kind: str | None = None) -> Game:
    kind = kind or str(rng.choice(GAME_KINDS))
    solo = kind in ("practice", "snooker_practice", "three_cushion_practice")
    players = ("Ana",) if solo else ("Ana", "Bob")
    table = Table.pool(str(rng.choice(["7ft", "8ft", "9ft"])))
    table = Table.snooker() if kind.startswith("snooker") else table
    table = Table.carom() if kind.startswith("three_cushion") else table
    options = RuleOptions(bool(rng.integers(2)))
    game = Game.new(kind, players, table=table, seed=int(rng.integers(1000)), options=options)
    seat = int(rng.integers(len(players)))
    pick = bool(rng.integers(2))
    decision = Decision(seat, ("shoot", "pass"), "Shoot or pass?") if pick else None
    last = Outcome(
        seat,
        (1, 0),
        (Foul("scratch", "Ana scratched."),),
        False,
        1 - seat,
        "anywhere",
        False,
        None,
        None,
        "Foul: scratch.",
        spotted=(9,),
        decision=decision,
    )
    return dataclasses.replace(
        game,
        balls=random_balls(rng, game.balls),
        racks=int(rng.integers(1, 4)),
        turn=seat,
        breaker=seat,
        breaking=bool(rng.integers(2)),
        ball_in_hand=str(rng.choice(["anywhere", "behind_head_string", ""])) or None,
        groups=None if solo or rng.integers(2) else {seat: "solids", 1 - seat: "stripes"},
        called_pocket=int(rng.integers(6)) if rng.integers(2) else None,
        decision=decision,
        pending="push_out" if decision else None,
        after_decision_bih="anywhere" if decision and rng.integers(2) else None,
        fouls_in_row=[int(v) for v in rng.integers(0, 3, len(players))],
        push_out_available=bool(rng.integers(2)),
        push_out_declared=bool(rng.integers(2)),
        over=pick,
        winner=seat if pick else None,
        reason="Ana pocketed the 9." if pick else None,
        last_outcome=last if rng.integers(2) else None,
        notice="Balls re-racked." if rng.integers(2) else None,
    )


def test_seeded_positions_survive_to_data_and_from_data_exactly() -> None:
    rng = np.random.default_rng(20240611)
    for _ in range(200):
        game = random_game(rng)
        same_game(from_data(Game, to_data(game)), game)
        same_game(from_json(Game, to_json(game)), game)
        same_game(Game.from_dict(through_json(game.to_dict())), game)


def test_seeded_matches_survive_the_codec_exactly() -> None:
    rng = np.random.default_rng(7)
    for k in range(40):
        kind = GAME_KINDS[k % 3]
        players = ("Ana",) if kind == "practice" else ("Ana", "Bob")
        table = None if k % 2 else TABLE
        match = Match(kind, players, race_to=1 + k % 4, seed=k, table=table)
        match.game = random_game(rng, kind)
        match.score = [int(v) for v in rng.integers(0, 3, len(players))]
        back = from_json(Match, to_json(match))
        assert to_data(back) == to_data(match) and back.table == table
        assert back.public_state() == match.public_state()
        same_game(back.game, match.game)


def test_stored_forms_from_before_the_codec_still_load() -> None:
    game = Game.new("eight_ball", ("Ana", "Bob"), table=Table.pool("8ft"), seed=3)
    data = game.to_dict()
    legacy_table = [2.34, 1.17, 0.028575, 0.114, 0.127]
    old = {**data, "table": legacy_table, "groups": [[0, "stripes"], [1, "solids"]]}
    loaded = Game.from_dict(old)
    assert loaded.table == Table(*legacy_table) and loaded.table.pockets == game.table.pockets
    assert loaded.groups == {0: "stripes", 1: "solids"}
    assert loaded.to_dict()["groups"] == {"0": "stripes", "1": "solids"}
    match = Match("nine_ball", ("Ana", "Bob"), table=TABLE)
    stored = {**match.to_dict(), "table": [2.54, 1.27]}
    assert Match.from_dict(stored).table == Table(2.54, 1.27)


def test_outcome_to_dict_is_the_shape_browsers_read() -> None:
    match = Match("nine_ball", ("Ana", "Bob"), seed=1, table=TABLE)
    data = match.timeout(0).to_dict()
    assert data == {
        "shooter": 0,
        "pocketed": [],
        "fouls": [{"code": "shot_clock", "message": "Ana ran out of time to shoot."}],
        "continues": False,
        "next_turn": 1,
        "ball_in_hand": "behind_head_string",
        "frame_over": False,
        "winner": None,
        "reason": None,
        "message": "Foul: time ran out. Bob breaks instead. Ball in hand behind the head "
        "string for Bob.",
        "spotted": [],
        "decision": None,
    }
    decision = Decision(1, ("shoot", "pass"), "Bob, shoot or pass?")
    assert decision.to_dict() == {
        "seat": 1,
        "options": ["shoot", "pass"],
        "prompt": decision.prompt,
    }
    assert Decision.from_dict(decision.to_dict()) == decision
