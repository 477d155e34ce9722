"""Playing a planned `Turn` on a `Game` through the rules' own actions, as a room would."""

from __future__ import annotations

from typing import Any, Protocol

from server.codec import from_data
from server.engine import Shot, ShotResult, Table, simulate
from server.rules import Game, Outcome

from .bot import Bot, NormalSource, Turn
from .geometry import best_chance, open_share
from .levels import LEVELS


class Executor(Protocol):
    def execute(self, shot: Shot, rng: NormalSource, table: Table | None = None) -> Shot: ...


def play_turn(
    game: Game,
    seat: int,
    turn: Turn,
    bot: Executor | None = None,
    rng: NormalSource | None = None,
) -> tuple[Outcome | None, ShotResult | None]:
    """Apply `turn` for `seat` to `game` (changing it): the decision, or the push out, the
    placement, the call and the shot (with `bot.execute(shot, rng)` when both are given).
    Returns the shot's outcome and result (None, None for a decision). Every step goes
    through the rules, so an illegal turn raises `IllegalActionError`."""
    if turn.decision is not None:
        game.decide(seat, turn.decision)
        return None, None
    if turn.shot is None:
        raise ValueError("the turn has neither a decision nor a shot")
    if turn.push_out:
        game.declare_push_out(seat)
    if turn.place is not None:
        game.place_cue(seat, *turn.place)
    if turn.call is not None and game.requires_call:
        game.call_pocket(seat, turn.call)
    if turn.nominate is not None:
        game.nominate(seat, turn.nominate)
    shot = turn.shot
    if bot is not None and rng is not None:
        shot = bot.execute(shot, rng, game.table)
    game.check_shot(seat)
    result = simulate(game.table, game.balls, shot)
    return game.apply(seat, result), result


def plan_data(level: str, seed: int, game: dict[str, Any], seat: int) -> Turn:
    """`Bot(level, seed).plan` of a game given as its data (`server.codec.to_data`): what a
    worker process runs for a room (the data pickles small; the plan is the same as on the
    room's own `Game`, since a plan depends only on the position, the level and the seed)."""
    return Bot(level, seed).plan(from_data(Game, game), seat)


def warm_up() -> None:
    """Load the compiled engine and the search's kernels (numba's cache) and plan once, so
    a worker's first real plan is as fast as any. The kernels are called outright: the
    break planned here need not reach them."""
    game = Game.new("eight_ball", ["a", "b"], seed=0)
    Bot(LEVELS[0]).plan(game, game.turn)
    targets = game.position().object_balls
    best_chance(game.table, game.balls, targets, Bot(LEVELS[-1]).level.aim)
    open_share(game.table, game.balls, targets)
