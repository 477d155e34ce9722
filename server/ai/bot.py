"""`Bot`: the computer opponent. `plan` searches the turn, `execute` adds the level's error.

Pure: no I/O, no asyncio, no clock. A plan depends only on the game, the seat, the level and
the seed (its random draws are seeded from them), so the same position always gets the same
answer.
"""

from __future__ import annotations

import itertools
import math
import zlib
from dataclasses import dataclass, replace
from typing import Protocol

import numpy as np

from server.engine import BALL_RADIUS, CUE, BallSet, Shot, Table, rack_slots
from server.rules import BEHIND_HEAD_STRING, Game
from server.rules.outcome import IN_D
from server.rules.placement import can_place
from server.rules.position import Position
from server.rules.strategy import GameRules

from .aiming import clamp_shot, perturb
from .carom import CaromSearch, carom_level
from .geometry import best_chance, path_clear, pockets_of
from .levels import BY_NAME, LEVELS, Level, for_kind
from .search import Candidate, Search

HAND_DISTANCES = (0.18, 0.35, 0.6)  # m from the object ball to the cue ball
HAND_ANGLES = (0.0, -0.3, 0.3)  # radians off a straight-in line
# Ball in hand with no pot from any spot: spots round each legal ball with a clear line to
# it, for the safeties (ranked by a pot chance of 0 everywhere, the spots were arbitrary).
SAFETY_SPOT_DISTANCES = (0.3, 0.15, 0.5)  # m from the ball, the first tried first
SAFETY_SPOT_DIRECTIONS = 24
ACCEPT_ABOVE = 0.5  # take a table (push out, illegal break) with a pot at least this likely
SAY_POT_FROM = 0.5  # a safety or kick that pockets at least this often is reported as a pot
# A turn on a table with more balls than a pool rack (snooker's 22, the reds not yet
# split): each simulation costs more (more balls to collide, the pack), so the turn
# searches a smaller share of the budget, by (RACK_BALLS / balls on the table) squared:
# the break-off's and the first visits' plans fit the plan-time goal (docs/ai.md,
# "Snooker"). A pool table never has more, so its plans are
# unchanged. A budget of `HAND_FLOOR` or less is kept whole: the levels below the pro
# plan quickly anyway, and with half theirs the beginner's break-off found no fair hit.
RACK_BALLS = 16
HAND_FLOOR = 1000


@dataclass(frozen=True)
class BreakStroke:
    """A break: the cue ball on the head string `offset` m beside the long string, hit
    full on the head ball of the rack at `speed` m/s with the tip `height` above centre
    (a fraction of the radius; below centre draws)."""

    offset: float
    speed: float
    height: float = 0.0


# By rack, tuned with the engine under the top level's noise (`python -m bench.breaks`): in
# 8-ball the stroke that most often keeps the table with a pot to follow, in 9-ball the one
# that most often keeps it (whoever plays next may push out, so the pot to follow counts
# less).
BREAKS = {"eight_ball": BreakStroke(0.35, 10.0), "nine_ball": BreakStroke(0.35, 12.0)}


# A ball this near a rack slot has not moved since the rack (its seeded jitter is 0.025 mm).
RACKED_WITHIN = 0.5e-3  # m


def still_racked(rules: GameRules, balls: BallSet, table: Table) -> bool:
    """Every object ball still on its rack slot: the table waits for a break, even where
    the rules have none of their own (practice's fresh rack)."""
    slots = rack_slots(rules.rack, table)
    on = [balls.position_of(b) for b in balls.on_table_ids() if b != CUE]
    if len(on) != len(slots):
        return False
    return all(any(math.dist(slot, xy) <= RACKED_WITHIN for xy in on) for slot in slots)


def break_spot(table: Table, offset: float) -> tuple[float, float]:
    """Where a break's cue ball goes: just behind the head string, `offset` m to the side."""
    return (min(table.head_string, table.length) - 0.01, table.width / 2 + offset)


def head_ball(rules: GameRules, pos: Position, balls: BallSet, table: Table) -> int:
    """The ball a break hits: the only legal one (9-ball: the 1), else the one nearest the
    foot spot."""
    legal = rules.legal_targets(pos)
    if len(legal) == 1:
        return legal[0]
    on = set(balls.on_table_ids())
    targets = [t for t in (legal or pos.object_balls) if t in on] or [b for b in on if b != CUE]
    return min(targets, key=lambda t: math.dist(balls.position_of(t), table.foot_spot))


def break_shot(balls: BallSet, head: int, stroke: BreakStroke) -> Shot:
    """`stroke` played full on `head` from where the cue ball is."""
    (cx, cy), (hx, hy) = balls.position_of(CUE), balls.position_of(head)
    return clamp_shot(math.atan2(hy - cy, hx - cx), stroke.speed, 0.0, stroke.height)


class NormalSource(Protocol):
    def normal(self, loc: float = ..., scale: float = ...) -> float: ...


@dataclass(frozen=True)
class Turn:
    """What the computer does on its turn, in the order the room applies it.

    decision: an option of the pending `game.decision` (then nothing else is set).
    push_out: 9-ball, declare a push out before the shot. place: where to put the cue ball
    (ball in hand). call: the pocket called for the 8 (`game.requires_call`). nominate:
    snooker, the ball nominated (the colour on, the free ball) before the shot. shot: the
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
    nominate: int | None = None
    shot: Shot | None = None
    kind: str | None = None
    target: int | None = None
    pocket: int | None = None
    chance: float | None = None
    via: str | None = None


def level_at(level: Level, table: Table | None) -> Level:
    """`level` with its tip error in `table`'s balls' radii (a pool ball's when None)."""
    if table is not None and table.ball_radius != BALL_RADIUS:
        return carom_level(level, table)
    return level


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
    def execute(
        self, shot: Shot, rng: NormalSource | None = None, table: Table | None = None
    ) -> Shot:
        """`shot` as this level's arm plays it: normal errors on aim, speed and tip, the
        result clamped to a valid `Shot`. `rng`: a `numpy.random.Generator` (or anything
        with `normal()`); None plays the shot exactly. `table`: the tip's error is in its
        balls' radii (a carom ball is larger than a pool ball: the same millimetres are a
        smaller fraction of it)."""
        if rng is None:
            return shot
        noise = np.array([float(rng.normal(0.0, 1.0)) for _ in range(4)])
        return perturb(shot, noise, level_at(self.level, table))

    # --- planning ---------------------------------------------------------------------
    def plan(self, game: Game, seat: int) -> Turn:
        """The turn of `seat` in `game`; `game` is not changed."""
        if game.over:
            raise ValueError("the game is over")
        if game.decision is not None:
            if game.decision.seat != seat:
                raise ValueError("the pending decision is not this seat's")
            return Turn(decision=self._decide(game))
        if game.turn != seat:
            raise ValueError("it is not this seat's turn")
        if game.carom is not None:
            return self._carom(game, seat)
        search = self._search(game, seat)
        balls = game.balls
        on_table = len(balls.on_table_ids())
        search.limit = hand_budget(self.level.budget, on_table)
        # The levels with a budget of `HAND_FLOOR` or less plan quickly anyway.
        search.charge_events = on_table > RACK_BALLS and self.level.budget > HAND_FLOOR
        if game.ball_in_hand is not None:
            turn = self._with_hand(game, search, balls)
        elif not balls.on_table[balls.index(CUE)]:
            raise ValueError("the cue ball is off the table and there is no ball in hand")
        else:
            turn = self._from_here(game, search, balls, None)[1]
        self.last_sims = search.sims
        return _nominated(game, turn)

    def _rng(self, game: Game, seat: int) -> np.random.Generator:
        """The plan's random draws, seeded from the seed, the table, the seat and level."""
        level_index = LEVELS.index(self.level.name)
        digest = zlib.crc32(np.ascontiguousarray(game.balls.positions).tobytes())
        digest = zlib.crc32(np.ascontiguousarray(game.balls.states).tobytes(), digest)
        return np.random.default_rng([self.seed & 0xFFFFFFFF, digest, seat, level_index])

    def _carom(self, game: Game, seat: int) -> Turn:
        """Three-cushion: the engine's search of strokes (`carom.CaromSearch`)."""
        search = CaromSearch(
            game.table, game.balls, game.cue_ball, self.level, self._rng(game, seat)
        )
        legal = game.legal_targets()
        plan = search.plan(legal[0] if legal else None)
        self.last_sims = plan.sims
        kind = "safety" if plan.safety else "point"
        return Turn(shot=plan.shot, kind=kind, target=plan.first, chance=plan.chance)

    def _search(self, game: Game, seat: int) -> Search:
        rng = self._rng(game, seat)
        noise = rng.standard_normal((self.level.samples, 4))
        confirm = rng.standard_normal((self.level.confirm_samples, 4))
        pos = game.position()
        if not pos.breaking and still_racked(game.rules, game.balls, game.table):
            pos = replace(pos, breaking=True)  # a practice rack: the break is the shot
        level = for_kind(self.level, game.rules.kind)
        return Search(game.table, game.rules, pos, seat, level, noise, confirm)

    def _turn(self, cand: Candidate, place: tuple[float, float] | None, push: bool = False) -> Turn:
        kind, target, pocket = cand.kind, cand.target, cand.pocket
        via = cand.via if kind == "pot" else None
        if kind in ("safety", "kick") and cand.drop and cand.pot_rate >= SAY_POT_FROM:
            # A stroke of the safeties' or kicks' grid that pockets a ball most of the time
            # is a pot: the hint and the counts say so.
            kind = "pot"
            target, pocket, via = cand.drop
        return Turn(
            push_out=push,
            place=(float(place[0]), float(place[1])) if place is not None else None,
            call=cand.call,
            shot=cand.shot,
            kind=kind,
            target=target,
            pocket=pocket,
            chance=cand.pot_rate,
            via=via,
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
        share = hand_budget(self.level.budget, len(balls.on_table_ids())) // max(len(spots), 1)
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
        straight-in and gentle cut lines behind each ball's pots, then a grid. With no pot
        from any of them, those in turn with spots for a safety (`_safety_spots`)."""
        table = game.table
        r = table.ball_radius
        on = set(balls.on_table_ids())
        targets = search.targets(search.pos)
        spots: list[tuple[float, float]] = []
        for t in targets:
            if t in on:
                spots += _pot_line_spots(table, balls.position_of(t))
        xs = np.linspace(2 * r, table.length - 2 * r, 9)
        ys = np.linspace(2 * r, table.width - 2 * r, 5)
        if area == BEHIND_HEAD_STRING:
            xs = np.linspace(2 * r, table.head_string, 5)
        elif area == IN_D:  # snooker: the D's box, `can_place` keeps the D
            d = table.cut.d_radius
            xs = np.linspace(table.head_string - d, table.head_string, 6)
            ys = np.linspace(table.width / 2 - d, table.width / 2 + d, 9)
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
        quality = {
            s: best_chance(table, balls, targets, sigma, cue_xy=s, model=model) for s in legal
        }
        scored = sorted(legal, key=lambda s: -quality[s])
        if not scored or quality[scored[0]] <= 0.0:
            # No pot from any spot by the geometry: the first generated spots (behind the
            # balls on their blocked lines, where a simulation may still find a way) take
            # turns with spots that face a legal ball clear of the others.
            safe = self._safety_spots(game, balls, area, targets)
            scored = [s for pair in itertools.zip_longest(scored, safe) for s in pair if s]
        # Keep the best few spots, but not three on the same line.
        chosen: list[tuple[float, float]] = []
        for s in scored:
            if all(math.dist(s, c) > 0.1 for c in chosen):
                chosen.append(s)
            if len(chosen) >= max(self.level.placements, 1):
                break
        return chosen or legal[:1]

    def _safety_spots(
        self, game: Game, balls: BallSet, area: str | None, targets: list[int]
    ) -> list[tuple[float, float]]:
        """Legal spots round the legal balls from which the cue ball has a clear line to
        one of them, at the middle distance first, the balls and directions interleaved."""
        table = game.table
        ids = balls.ids.tolist()
        row = {b: i for i, b in enumerate(ids)}
        on = balls.on_table.copy()
        on[row[CUE]] = False  # the cue ball is in hand
        positions = balls.positions
        live = [(row[t], balls.position_of(t)) for t in targets if t in row and on[row[t]]]
        spots = []
        for d in SAFETY_SPOT_DISTANCES:
            for k in range(SAFETY_SPOT_DIRECTIONS):
                angle = 2 * math.pi * k / SAFETY_SPOT_DIRECTIONS
                for i, (ox, oy) in live:
                    x, y = ox + d * math.cos(angle), oy + d * math.sin(angle)
                    if not can_place(table, balls, area, x, y):
                        continue
                    if path_clear(x, y, ox, oy, positions, on, i, i, table.ball_radius):
                        spots.append((x, y))
        return spots

    # --- the break --------------------------------------------------------------------
    def _break_with_hand(
        self, game: Game, search: Search, balls: BallSet, area: str | None
    ) -> Turn:
        """The rack's tuned break (`BREAKS`) from its spot, or from the mirrored spot, or
        from the best ball-in-hand spot when both are taken."""
        offset = BREAKS[game.rules.rack].offset
        spots = [break_spot(game.table, dy) for dy in (offset, -offset)]
        spots = [xy for xy in spots if can_place(game.table, balls, area, *xy)]
        place = spots[0] if spots else self._hand_spots(game, search, balls, area)[0]
        return self._turn(self._break(search, balls.with_ball(CUE, place)), place)

    def _break(self, search: Search, balls: BallSet) -> Candidate:
        """The rack's tuned break from where the cue ball is, scored on a few noisy draws
        for the chance it reports."""
        head = head_ball(search.rules, search.pos, balls, search.table)
        shot = break_shot(balls, head, BREAKS[search.rules.rack])
        cand = Candidate(shot, None, "break", head)
        full = search.noise
        search.noise = full[: max(2, len(full) // 5)]
        try:
            search.score_noisy(balls, cand)
        finally:
            search.noise = full
        return cand

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
    def _decide(self, game: Game) -> str:
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
        if "play_again" in options:  # snooker, after the opponent's foul
            if "free_ball" in options or q >= ACCEPT_ABOVE:
                return options[0]  # the free ball if offered, else play on
            return "replace" if "replace" in options else "play_again"
        return options[0]


def hand_budget(budget: int, on_table: int) -> int:
    """The simulations a turn may spend with `on_table` balls on the table (the cue ball
    counted when the rules keep it there, as at the break-off): the whole
    budget up to a pool rack's `RACK_BALLS`, less beyond but not below `HAND_FLOOR`
    (their comment)."""
    if on_table <= RACK_BALLS:
        return budget
    return max(min(budget, HAND_FLOOR), int(budget * (RACK_BALLS / on_table) ** 2))


def _nominated(game: Game, turn: Turn) -> Turn:
    """Snooker: the turn with its target nominated when one may be (a colour after a red,
    a free ball); the search judged the stroke so, by the ball it hits first."""
    if turn.target is not None and turn.target in game.rules.nominations(game.position()):
        return replace(turn, nominate=turn.target)
    return turn


def _pot_line_spots(table: Table, ball: tuple[float, float]) -> list[tuple[float, float]]:
    """Cue-ball spots behind `ball` on its straight-in and gentle cut lines to each pocket."""
    r = table.ball_radius
    ox, oy = ball
    spots = []
    for aim_x, aim_y in pockets_of(table).aims:
        ux, uy = aim_x - ox, aim_y - oy
        n = math.hypot(ux, uy)
        if n < 1e-9:
            continue
        ux, uy = ux / n, uy / n
        for a in HAND_ANGLES:
            ca, sa = math.cos(a), math.sin(a)
            bx, by = -(ux * ca - uy * sa), -(ux * sa + uy * ca)
            for d in HAND_DISTANCES:
                spots.append((ox - 2 * r * ux + bx * d, oy - 2 * r * uy + by * d))
    return spots
