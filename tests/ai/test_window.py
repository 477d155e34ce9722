"""The pro aims a pot at the middle of the directions in which the ball drops (the pocket's
window, found with the engine), not at the middle of the mouth."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from server.ai.aiming import aimed, departure, lone_ball, perturb, pocket_window, rolls_in
from server.ai.levels import BY_NAME, Level
from server.ai.search import Candidate, Search
from server.engine import simulate
from server.rules import Game
from server.rules.shotfacts import shot_facts

from .conftest import TABLE, R, pocket_aim, set_table

CORNER = 0  # bottom left
SPEED = 1.2  # m/s, the object ball's
STEP = math.radians(0.1)


def along_the_rail(eight: Game) -> tuple[Game, float]:
    """An object ball 1 m from the bottom-left corner, its centre 5 mm further off the
    bottom cushion than a frozen ball's, the cue ball 0.4 m behind it on the line to the
    middle of the mouth; and that line's direction."""
    px, py = pocket_aim(CORNER)
    obj = (R + 0.005 + 1.0, R + 0.005)
    line = math.atan2(py - obj[1], px - obj[0])
    back = 2 * R + 0.4
    cue = (obj[0] - back * math.cos(line), obj[1] - back * math.sin(line))
    game = set_table(eight, {0: cue, 1: obj, 9: (1.5, 0.9), 8: (2.0, 1.0)})
    return game, line


def test_the_window_edges_are_where_the_ball_stops_dropping(eight: Game) -> None:
    game, line = along_the_rail(eight)
    edges, used = pocket_window(TABLE, game.balls, 1, CORNER, SPEED, line)
    assert edges is not None and used > 4
    low, high = edges
    assert low < line < high
    alone = lone_ball(game.balls, 1)
    for edge, outward in ((low, -1.0), (high, 1.0)):
        assert rolls_in(TABLE, alone, edge - outward * STEP, SPEED, CORNER)
        assert not rolls_in(TABLE, alone, edge + outward * STEP, SPEED, CORNER)
    # Along the cushion the near point takes the ball a degree or so off the line, while
    # the far facing still turns it in several degrees off: the middle is not the mouth's.
    assert math.degrees(line - low) < 2.0 < math.degrees(high - line)
    assert math.degrees((low + high) / 2 - line) > 1.0


def test_a_ball_that_cannot_drop_has_no_window(eight: Game) -> None:
    game, line = along_the_rail(eight)
    blocked = set_table(eight, {**_places(game), 2: (R + 0.005 + 0.5, R + 0.005)})
    edges, used = pocket_window(TABLE, blocked.balls, 1, CORNER, SPEED, line)
    assert edges is None and used == 1


def _places(game: Game) -> dict[int, tuple[float, float]]:
    return {b: game.balls.position_of(b) for b in game.balls.on_table_ids()}


@pytest.mark.parametrize("windows", [True, False])
def test_the_aim_for_the_throw_sends_the_ball_at_the_middle_it_is_given(
    eight: Game, windows: bool
) -> None:
    game, line = along_the_rail(eight)
    level = replace(BY_NAME["pro"], windows=windows)
    cand, search = _aimed(game, line, level)
    leaves = departure(TABLE, game.balls, cand.shot, 1)
    assert leaves is not None
    want = line
    if windows:
        edges = next(iter(search.windows.values()))
        assert edges is not None
        want = (edges[0] + edges[1]) / 2
    assert abs(math.degrees(math.remainder(leaves - want, 2 * math.pi))) < 0.1


def test_aimed_at_the_windows_middle_the_pro_drops_more_of_its_noisy_strokes(
    eight: Game,
) -> None:
    game, line = along_the_rail(eight)
    pro = BY_NAME["pro"]
    draws = np.random.default_rng(1).standard_normal((300, 4))

    def drops(windows: bool) -> int:
        cand, _ = _aimed(game, line, replace(pro, windows=windows))
        runs = (simulate(TABLE, game.balls, perturb(cand.shot, row, pro)) for row in draws)
        return sum(1 in shot_facts(game.balls, run).pocketed for run in runs)

    mouth, window = drops(False), drops(True)
    assert window >= mouth + 6, (window, mouth)


def _aimed(game: Game, line: float, level: Level) -> tuple[Candidate, Search]:
    """The centre-ball stroke on the ghost-ball line whose object ball leaves at about
    `SPEED`, aimed by the search of `level` (`Search.allow_for_throw`)."""
    noise = np.zeros((1, 4))
    search = Search(TABLE, game.rules, game.position(), 0, level, noise, noise[:0])
    ox, oy = game.balls.position_of(1)
    gx, gy = ox - 2 * R * math.cos(line), oy - 2 * R * math.sin(line)
    cx, cy = game.balls.position_of(0)
    cand = Candidate(aimed(math.atan2(gy - cy, gx - cx), SPEED, 0.0, 0.0), None, "pot", 1, CORNER)
    search.allow_for_throw(game.balls, cand)
    return cand, search
