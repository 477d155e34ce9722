"""A game played by computer levels and kept as the history keeps it, for the analysis'
tests and benchmark (a room records the same rows: `server.rooms.recorder`)."""

from __future__ import annotations

import numpy as np

from server.codec import to_data
from server.engine import simulate
from server.rules import Game

from ..bot import Bot
from ..play import play_turn
from .rebuild import StoredShot

MAX_TURNS = 200  # a game that is not over by then is cut short


def self_play(
    kind: str, levels: tuple[str, str], seed: int, intended: bool = False
) -> list[StoredShot]:
    """One game of `kind`, seat 0 at `levels[0]` breaking; the rack, plans and errors all
    follow from `seed`. Each stroke is stored as its arm played it (as a room stores a
    computer's); with `intended`, the plan before the arm's error is kept beside it, and
    that is what the analysis judges (as a person's stroke is judged as sent)."""
    game = Game.new(kind, [f"{levels[0]} 0", f"{levels[1]} 1"], seed=seed)
    bots = [Bot(level, seed=seed + seat) for seat, level in enumerate(levels)]
    rng = np.random.default_rng(seed)
    shots: list[StoredShot] = []
    for _ in range(MAX_TURNS):
        if game.over:
            break
        seat = game.decision.seat if game.decision is not None else game.turn
        turn = bots[seat].plan(game, seat)
        if turn.decision is not None or turn.shot is None:
            play_turn(game, seat, turn)
            continue
        if turn.push_out:
            game.declare_push_out(seat)
        if turn.place is not None:
            game.place_cue(seat, *turn.place)
        if turn.call is not None and game.requires_call:
            game.call_pocket(seat, turn.call)
        stroke = bots[seat].execute(turn.shot, rng)
        before = game.balls.copy()
        outcome = game.apply(seat, simulate(game.table, before, stroke))
        shots.append(
            StoredShot(
                n=len(shots) + 1,
                game=1,
                seat=seat,
                shot=to_data(stroke),
                intended=to_data(turn.shot) if intended else None,
                table=game.table.fields(),
                balls=before.to_dict(),
                outcome=outcome.to_dict(),
            )
        )
    return shots
