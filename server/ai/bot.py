"""`Bot`: the computer opponent. `plan` searches the turn, `execute` adds the level's error.

Pure: no I/O, no asyncio, no clock. A plan depends only on the game, the seat, the level and
the seed (its random draws are seeded from them), so the same position always gets the same
answer.
"""

from __future__ import annotations

import math
import zlib
from dataclasses import dataclass, replace
from typing import Protocol

import numpy as np

from server.engine import CUE, BallSet, Shot
from server.rules import BEHIND_HEAD_STRING, Game
from server.rules.placement import can_place

from .aiming import clamp_shot, perturb
from .geometry import best_chance, pockets_of
from .levels import BY_NAME, LEVELS, Level
from .search import Candidate, Search

BREAK_SPEEDS = (9.5, 11.5)
BREAK_TIPS = ((0.0, -0.2),)
BREAK_OFFSETS = (0.0, -0.22, 0.22)  # m either side of the long string
HAND_DISTANCES = (0.18, 0.35, 0.6)  # m from the object ball to the cue ball
HAND_ANGLES = (0.0, -0.3, 0.3)  # radians off a straight-in line
ACCEPT_ABOVE = 0.5  # take a table (push out, illegal break) with a pot at least this likely


class NormalSource(Protocol):
    def normal(self, loc: float = ..., scale: float = ...) -> float: ...


@dataclass(frozen=True)
class Turn:
    """What the computer does on its turn, in the order the room applies it.

    decision: an option of the pending `game.decision` (then nothing else is set).
    push_out: 9-ball, declare a push out before the shot. place: where to put the cue ball
    (ball in hand). call: the pocket called for the 8 (`game.requires_call`). shot: the
    stroke it intends (the room applies `Bot.execute` to it). target / pocket / chance /
    kind / via: what it is trying (for hints and logs): kind is "pot", "safety", "kick",
    "break" or "push"; a pot's via is "direct", "bank" (off a cushion), "combo" (the cue
    ball hits another ball into `target`) or "carom" (`target` glances off another ball
    into the pocket); chance is the share of its noisy trials that pocketed a ball legally.
    """

    decision: str | None = None
    push_out: bool = False
    place: tuple[float, float] | None = None
    call: int | None = None
    shot: Shot | None = None
    kind: str | None = None
    target: int | None = None
    pocket: int | None = None
    chance: float | None = None
    via: str | None = None


class Bot:
    """A computer player of one level (`Bot.LEVELS`, weakest first)."""

    LEVELS: tuple[str, ...] = LEVELS

    def __init__(self, level: str, seed: int = 0) -> None:
        if level not in BY_NAME:
            raise ValueError(f"unknown level {level!r}; choose one of {LEVELS}")
        self.level: Level = BY_NAME[level]
        self.seed = int(seed)
        self.last_sims = 0  # simulations run by the last `plan` (for benchmarks)

    @property
    def name(self) -> str:
        return self.level.name

    # --- execution --------------------------------------------------------------------
    def execute(self, shot: Shot, rng: NormalSource | None = None) -> Shot:
        """`shot` as this level's arm plays it: normal errors on aim, speed and tip, the
        result clamped to a valid `Shot`. `rng`: a `numpy.random.Generator` (or anything
        with `normal()`); None plays the shot exactly."""
        if rng is None:
            return shot
        noise = np.array([float(rng.normal(0.0, 1.0)) for _ in range(4)])
        return perturb(shot, noise, self.level)

    # --- planning ---------------------------------------------------------------------
    def plan(self, game: Game, seat: int) -> Turn:
        """The turn of `seat` in `game`; `game` is not changed."""
        if game.over:
            raise ValueError("the game is over")
        if game.decision is not None:
            if game.decision.seat != seat:
                raise ValueError("the pending decision is not this seat's")
            return Turn(decision=self._decide(game, seat))
        if game.turn != seat:
            raise ValueError("it is not this seat's turn")
        search = self._search(game, seat)
        search.limit = self.level.budget
        balls = game.balls
        if game.ball_in_hand is not None:
            turn = self._with_hand(game, search, balls)
        elif not balls.on_table[balls.index(CUE)]:
            raise ValueError("the cue ball is off the table and there is no ball in hand")
        else:
            turn = self._from_here(game, search, balls, None)[1]
        self.last_sims = search.sims
        return turn

    def _search(self, game: Game, seat: int) -> Search:
        level_index = LEVELS.index(self.level.name)
        digest = zlib.crc32(np.ascontiguousarray(game.balls.positions).tobytes())
        digest = zlib.crc32(np.ascontiguousarray(game.balls.states).tobytes(), digest)
        rng = np.random.default_rng([self.seed & 0xFFFFFFFF, digest, seat, level_index])
        noise = rng.standard_normal((self.level.samples, 4))
        confirm = rng.standard_normal((self.level.confirm_samples, 4))
        return Search(game.table, game.rules, game.position(), seat, self.level, noise, confirm)

    def _turn(self, cand: Candidate, place: tuple[float, float] | None, push: bool = False) -> Turn:
        return Turn(
            push_out=push,
            place=(float(place[0]), float(place[1])) if place is not None else None,
            call=cand.call,
            shot=cand.shot,
            kind=cand.kind,
            target=cand.target,
            pocket=cand.pocket,
            chance=cand.pot_rate,
            via=cand.via if cand.kind == "pot" else None,
        )

    def _from_here(
        self,
        game: Game,
        search: Search,
        balls: BallSet,
        place: tuple[float, float] | None,
        pairs: int | None = None,
    ) -> tuple[float, Turn]:
        """The best turn with the cue ball where `balls` has it, and its value."""
        if search.pos.breaking:
            cand = self._break(search, balls)
            return cand.value, self._turn(cand, place)
        best = search.best_shot(balls, pairs)
        if game.push_out_available and not search.pos.push_out_declared:
            push = self._push_out(search, balls)
            if push is not None and push.value > best.value:
                return push.value, self._turn(push, place, push=True)
        return best.value, self._turn(best, place)

    # --- ball in hand -----------------------------------------------------------------
    def _with_hand(self, game: Game, search: Search, balls: BallSet) -> Turn:
        area = game.ball_in_hand
        if search.pos.breaking:
            return self._break_with_hand(game, search, balls, area)
        spots = self._hand_spots(game, search, balls, area)
        best: tuple[float, Turn] | None = None
        pairs = max(2, self.level.pairs // 2)
        spots = spots[: self.level.placements]
        share = self.level.budget // max(len(spots), 1)
        for xy in spots:
            search.limit = search.sims + share
            placed = balls.with_ball(CUE, xy)
            value, turn = self._from_here(game, search, placed, xy, pairs)
            if best is None or value > best[0]:
                best = (value, turn)
        if best is None:  # pragma: no cover - _hand_spots always finds a spot
            raise ValueError("nowhere to put the cue ball")
        return best[1]

    def _hand_spots(
        self, game: Game, search: Search, balls: BallSet, area: str | None
    ) -> list[tuple[float, float]]:
        """Legal cue-ball spots, best first by the geometric chance of the shot from there:
        straight-in and gentle cut lines behind each ball's pots, then a grid."""
        table = game.table
        r = table.ball_radius
        pk = pockets_of(table)
        targets = search.targets(search.pos)
        on = set(balls.on_table_ids())
        spots: list[tuple[float, float]] = []
        for t in targets:
            if t not in on:
                continue
            ox, oy = balls.position_of(t)
            for p in range(len(pk.aims)):
                ux, uy = pk.aims[p][0] - ox, pk.aims[p][1] - oy
                n = math.hypot(ux, uy)
                if n < 1e-9:
                    continue
                ux, uy = ux / n, uy / n
                for a in HAND_ANGLES:
                    ca, sa = math.cos(a), math.sin(a)
                    bx, by = -(ux * ca - uy * sa), -(ux * sa + uy * ca)
                    for d in HAND_DISTANCES:
                        spots.append((ox - 2 * r * ux + bx * d, oy - 2 * r * uy + by * d))
        xs = np.linspace(2 * r, table.length - 2 * r, 9)
        ys = np.linspace(2 * r, table.width - 2 * r, 5)
        if area == BEHIND_HEAD_STRING:
            xs = np.linspace(2 * r, table.head_string, 5)
        spots += [(float(x), float(y)) for x in xs for y in ys]
        legal = [s for s in spots if can_place(table, balls, area, s[0], s[1])]
        if not legal:  # a crowded head: search finely
            fine = [
                (float(x), float(y))
                for x in np.linspace(
                    r, table.head_string if area == BEHIND_HEAD_STRING else table.length - r, 40
                )
                for y in np.linspace(r, table.width - r, 20)
            ]
            legal = [s for s in fine if can_place(table, balls, area, s[0], s[1])]
        sigma = self.level.aim
        model = self.level.chance_model

        def quality(xy: tuple[float, float]) -> float:
            return best_chance(table, balls, targets, sigma, cue_xy=xy, model=model)

        scored = sorted(legal, key=lambda s: -quality(s))
        # Keep the best few spots, but not three on the same line.
        chosen: list[tuple[float, float]] = []
        for s in scored:
            if all(math.dist(s, c) > 0.1 for c in chosen):
                chosen.append(s)
            if len(chosen) >= max(self.level.placements, 1):
                break
        return chosen or legal[:1]

    # --- the break --------------------------------------------------------------------
    def _break_with_hand(
        self, game: Game, search: Search, balls: BallSet, area: str | None
    ) -> Turn:
        table = game.table
        x = min(table.head_string, table.length) - 0.01
        spots = []
        for dy in BREAK_OFFSETS:
            xy = (x, table.width / 2 + dy)
            if can_place(table, balls, area, *xy):
                spots.append(xy)
        if not spots:
            spots = self._hand_spots(game, search, balls, area)[:1]
        best: tuple[float, Candidate, tuple[float, float]] | None = None
        for xy in spots:
            cand = self._break(search, balls.with_ball(CUE, xy))
            if best is None or cand.value > best[0]:
                best = (cand.value, cand, xy)
        assert best is not None
        return self._turn(best[1], best[2])

    def _break(self, search: Search, balls: BallSet) -> Candidate:
        """The break from where the cue ball is: a full hit on the head ball of the rack."""
        targets = search.targets(search.pos)
        on = set(balls.on_table_ids())
        targets = [t for t in targets if t in on] or [b for b in on if b != CUE]
        cue = balls.position_of(CUE)
        foot = search.table.foot_spot
        head = min(targets, key=lambda t: math.dist(balls.position_of(t), foot))
        if len(search.rules.legal_targets(search.pos)) == 1:
            head = search.rules.legal_targets(search.pos)[0]
        hx, hy = balls.position_of(head)
        angle = math.atan2(hy - cue[1], hx - cue[0])
        cands = [
            Candidate(clamp_shot(angle, speed, *tip), None, "break", head)
            for speed in BREAK_SPEEDS
            for tip in BREAK_TIPS
        ]
        samples = search.noise[: max(2, len(search.noise) // 5)]
        full = search.noise
        search.noise = samples
        try:
            for cand in cands:
                search.score_noisy(balls, cand)
        finally:
            search.noise = full
        cands.sort(key=lambda c: -c.value)
        return cands[0]

    # --- 9-ball push out --------------------------------------------------------------
    def _push_out(self, search: Search, balls: BallSet) -> Candidate | None:
        """A soft push that leaves a shot about as hard for either player to take."""
        if not self.level.safeties:
            return None
        pushed = replace(search.pos, push_out_declared=True)
        saved = search.pos
        search.pos = pushed
        try:
            cands = search.sweep_candidates(balls, (0.5, 1.0))
            for cand in cands:
                cand.kind = "push"
            chosen = search.refine(balls, cands, 2)
        finally:
            search.pos = saved
        return chosen[0] if chosen else None

    # --- decisions --------------------------------------------------------------------
    def _decide(self, game: Game, seat: int) -> str:
        decision = game.decision
        assert decision is not None
        options = decision.options
        pos = game.position()
        legal = game.rules.legal_targets(pos) or pos.object_balls
        q = best_chance(
            game.table, game.balls, legal, self.level.aim, model=self.level.chance_model
        )
        if "spot" in options:
            return "spot"  # keep the broken table (and the ball in hand, if offered)
        if "accept" in options:
            return "accept" if q >= ACCEPT_ABOVE else "rerack"
        if "shoot" in options and "pass" in options:
            return "shoot" if q >= ACCEPT_ABOVE else "pass"
        return options[0]
