"""Property: random legal action sequences never leave a game in an impossible state."""

from __future__ import annotations

import json

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from server.engine import MotionState
from server.rules import Game, IllegalActionError
from server.rules.eight_ball import SOLIDS, STRIPES

from .helpers import TABLE, crafted, hit, pot, rail

STEPS = 60


def random_shot(data, game: Game):
    """A crafted result from the current table: usually a legal first contact, some rails,
    some balls (the cue ball too) dropped in random pockets; the 8 and the 9 drop less
    often, so that games last long enough to reach their later rules."""
    objects = [b for b in game.balls.on_table_ids() if b != 0]
    on = [*objects, 0] if 0 in game.balls.on_table_ids() else objects  # cue last: rarer
    legal = game.legal_targets() or objects
    events = []
    choice = data.draw(st.integers(0, 9))  # hypothesis favours 0: make it the legal case
    if objects and choice < 9:
        pool = legal if choice < 7 else objects
        events.append(hit(0, data.draw(st.sampled_from(pool))))
    for ball in data.draw(st.lists(st.sampled_from(on), min_size=1, max_size=5)):
        events.append(rail(ball))
    dropped = data.draw(st.lists(st.sampled_from(on), max_size=3, unique=True))
    if data.draw(st.integers(0, 9)) < 9:
        dropped = [b for b in dropped if b not in (8, 9) or len(objects) == 1]
    for ball in dropped:
        events.append(pot(ball, data.draw(st.integers(0, 5))))
    return crafted(game.balls, *events)


def act(data, game: Game) -> None:
    """One legal action for whoever must act now."""
    if game.decision is not None:
        d = game.decision
        game.decide(d.seat, data.draw(st.sampled_from(d.options)))
        return
    seat = game.turn
    if data.draw(st.integers(0, 19)) == 0:
        game.timeout(seat)
        return
    if game.ball_in_hand:
        for _ in range(5):
            x = data.draw(st.floats(0, TABLE.length))
            y = data.draw(st.floats(0, TABLE.width))
            if game.can_place_cue(x, y):
                game.place_cue(seat, x, y)
                break
        else:
            if not game.balls.on_table[game.balls.index(0)]:
                game.place_cue(seat, *_free_spot(game))
    if game.requires_call:
        game.call_pocket(seat, data.draw(st.integers(0, 5)))
    if game.push_out_available and data.draw(st.booleans()):
        game.declare_push_out(seat)
    game.check_shot(seat)
    outcome = game.apply(seat, random_shot(data, game))
    for ball in outcome.pocketed:
        if ball not in outcome.spotted and ball != 0:
            assert ball not in game.balls.on_table_ids()


def _free_spot(game: Game) -> tuple[float, float]:
    for x in np.linspace(0.1, TABLE.length - 0.1, 25):
        for y in np.linspace(0.1, TABLE.width - 0.1, 12):
            if game.can_place_cue(float(x), float(y)):
                return float(x), float(y)
    raise AssertionError("no free spot for the cue ball")


def check_possible(game: Game) -> None:
    balls = game.balls
    pocketed = balls.states == MotionState.POCKETED
    assert np.array_equal(pocketed, balls.pockets >= 0)  # pocketed xor on the table
    on = balls.on_table
    pos = balls.positions[on]
    r = TABLE.ball_radius
    assert all(TABLE.contains(float(x), float(y), margin=-1e-9) for x, y in pos)
    if len(pos) > 1:
        d = np.linalg.norm(pos[:, None, :] - pos[None, :, :], axis=2)
        d[np.diag_indices(len(pos))] = np.inf
        assert d.min() >= 2 * r - 1e-9
    seats = range(len(game.players))
    assert game.turn in seats
    if game.decision is not None:
        assert game.decision.seat in seats and game.decision.seat == game.turn
    state = game.public_state()
    json.dumps(state)
    left = set(balls.on_table_ids())
    if game.kind == "eight_ball":
        if game.over:
            assert not (left & SOLIDS and left & STRIPES and 8 in left)
        if game.requires_call:
            assert game.groups is None or not left & (
                SOLIDS if game.groups[game.turn] == "solids" else STRIPES
            )
    if game.kind == "nine_ball" and game.over:
        assert 9 not in left or max(game.fouls_in_row) >= 3
    if game.kind == "practice":
        assert not game.over and game.turn == 0


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    kind=st.sampled_from(["eight_ball", "nine_ball", "practice"]),
    seed=st.integers(0, 5),
    data=st.data(),
)
def test_random_legal_actions_never_reach_an_impossible_state(kind, seed, data) -> None:
    players = ("Ana",) if kind == "practice" else ("Ana", "Bob")
    game = Game.new(kind, players, table=TABLE, seed=seed)
    check_possible(game)
    for _ in range(STEPS):
        if game.over:
            break
        try:
            act(data, game)
        except IllegalActionError as err:  # only a legal action may be refused if none fits
            raise AssertionError(f"a legal action was refused: {err.code}") from err
        check_possible(game)
