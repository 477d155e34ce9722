"""The shot search: candidate strokes simulated with the engine, without and then with the
level's execution noise, each outcome judged by the game's own rules and scored by what it
leaves (the best next shot for whoever plays next).

Values are on one scale, from -1 (the game is lost) to +1 (won): keeping the table scores
by the chance of the next pot, giving it up scores against the opponent's best chance, a
foul gives the opponent ball in hand.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Iterable
from dataclasses import dataclass, field, replace

import numpy as np

from server.engine import CUE, MAX_SPEED, BallSet, Settled, Shot, Table, settle, tip_seen_level
from server.engine.results import Event
from server.rules.position import Position
from server.rules.ruling import Ruling
from server.rules.shotfacts import ShotFacts, shot_facts
from server.rules.strategy import GameRules

from .aiming import aim_carom, aim_for_throw, aimed, clamp_shot, perturb, pocket_window
from .geometry import (
    MIN_AIM_SIGMA,
    PotOption,
    best_chance,
    open_share,
    pot_options,
    speed_for,
)
from .indirect import bank_options, billiard_options, carom_options, combo_options
from .levels import Level

WIN, LOSS = 1.0, -1.0
WindowKey = tuple[int, int, int, bytes]  # target, pocket, speed step, the object balls
FOUL = -0.6  # the opponent has ball in hand
KEEP_BASE, KEEP_SCALE = 0.15, 0.8  # value of keeping the table: base + scale * next chance
GIVE_BASE, GIVE_SCALE = -0.1, 0.6  # value of giving it up: base - scale * opponent chance
OPEN_WEIGHT = 0.45  # share of the position score given to how open the own balls are
PROGRESS = 0.03  # per own ball pocketed
SAFETY_BELOW = 0.3
SAFETY_SHARE = 0.3  # of a turn's simulations kept for safeties and kicks
SAFETY_LOOKS = 3  # best safeties that pocket sometimes, searched a shot ahead like the pots
LOOK_PAIRS, LOOK_SPEEDS, LOOK_TIPS = 4, 2, 3  # the next-shot search of the lookahead
LOOK_LEAVES = 3  # leaves searched per looked-ahead pot: the exact one and two noisy ones
GIVE_UP = GIVE_BASE - GIVE_SCALE * 0.4  # the table given up to a 40 % shot: a missed next
# pot, or a leave with no next pot while the safeties are not known yet
SAFE_LATER = 0.1  # a safety played after a pot, above one played now (a ball fewer to pot)
LOOK_SIMS = (
    LOOK_PAIRS * LOOK_SPEEDS * LOOK_TIPS + 1
)  # look for a safety when the best pot is worth less than this
TIPS = ((0.0, 0.0), (0.0, 0.35), (0.0, -0.35), (0.3, 0.15), (-0.3, 0.15))
SPEED_FACTORS = (1.25, 1.8, 3.0, 4.6)
# With few pots on (late in a rack, or a table with few open balls) the budget would go
# mostly unspent: each pot gets finer strokes, for the exact position a runout needs.
FEW_POTS = 4
FINE_SPEED_FACTORS = (1.1, 1.4, 1.8, 2.4, 3.0, 3.8, 4.6)
FINE_TIPS = (*TIPS, (0.0, 0.18), (0.0, -0.18), (0.3, -0.15), (-0.3, -0.15))
# Late in a rack (this many balls or fewer to pot before the game ball, and few pots on)
# the next-shot search of a level with `late_strokes` tries more strokes on each pot: the
# position for the last balls is where the racks are lost (docs/ai.md, "Current figures"),
# and there the budget goes partly unspent. Its six speeds reach softer and firmer than
# four (1.25-3.0) did: 18 more racks of 600 cleared.
LATE_BALLS = 2
LATE_SPEED_FACTORS = (1.1, 1.4, 1.8, 2.4, 3.0, 3.8)
LATE_LOOK_SIMS = LOOK_PAIRS * len(LATE_SPEED_FACTORS) * len(TIPS)  # what that search may take
# Safeties: hits on a legal ball from full to thin (a fraction of the widest offset that
# still hits it), soft to firm, with centre ball, draw and follow. Where the cue ball stops
# is what hides it, so draw and follow.
SAFETY_FRACTIONS = (-0.9, -0.6, -0.3, 0.0, 0.3, 0.6, 0.9)
SAFETY_SPEEDS = (0.7, 1.1, 1.6, 2.6)
SAFETY_HEIGHTS = (0.0, -0.35, 0.35)
KICK_SPEEDS = (1.5, 2.6, 4.0)
# Jumps over a ball in the way (the pro level): the cue raised so (degrees) at these speeds,
# its axis through the ball's centre. The engine clears a ball 15 cm ahead at 45 degrees
# and 4-5 m/s, one 20-25 cm ahead from 35 degrees (docs/engine.md).
JUMPS = ((40.0, 4.0), (40.0, 5.0), (45.0, 4.0), (45.0, 5.0))
JUMP_REACH = (0.1, 0.35)  # m from the cue ball to the blocker: nearer or further, no jump
# Swerves and masses round a ball in the way (the pro level, any distance): the cue raised
# so (degrees) at these speeds, struck `CURVE_SIDE` along the cue to one side and aimed
# off the blocked line to the other, so the curve comes back to the ball. The engine
# curves a 15-degree swerve about 5 cm over 1 m and a 60-degree masse at 2 m/s 58 cm
# (docs/engine.md): a swerve slips by a ball far ahead, a masse bends round a near one.
CURVES = ((20.0, 1.5), (20.0, 4.5), (35.0, 3.5), (60.0, 2.5), (60.0, 3.5))
CURVE_SIDE = 0.45  # of the radius, along the cue
CURVE_AIMS = (1.0, 1.6, 2.4, 3.5)  # times the turn off the line that just passes the blocker
KICK_OFFSETS = (-2.0, -0.8, 0.0, 0.8, 2.0)  # degrees off the mirror-image line
SWEEP_SPEEDS = (1.6, 3.2)
SWEEP_ANGLES = 40
# Banks, combinations, caroms and billiards (`indirect`), for the levels that look ahead
# when few pots are on (`FEW_POTS`): the best routes of each, and the speeds tried on each
# (a bank's route comes with an aim per restitution; billiards take the caroms' speeds).
BANK_ROUTES, COMBOS, CAROMS, BILLIARDS = 2, 2, 2, 2
BANK_SPEED_FACTORS = (1.25, 1.8, 2.6)
COMBO_SPEED_FACTORS = (1.25, 1.8, 3.0)
CAROM_SPEED_FACTORS = (1.25, 1.8, 2.6)
WINDOW_SPEED_STEP = 0.25  # m/s: a pocket's window is found once per step of the ball's speed
# On a table fuller than a pool rack (snooker's reds not yet split) a shot into the pack
# may take thousands of contacts among touching balls: such a simulation costs as many as
# its events beyond `FREE_EVENTS`, `EVENTS_PER_SIM` each (a simulation of 22 balls takes
# about 0.6 ms, an event of a packed cascade about 0.15 ms), and sampling stops once the
# budget is spent (`Search.charge_events`). One pot into the pack ran 2,054 simulations
# in 12 s of CPU without it (docs/ai.md, "Snooker"). No pool table has more balls than
# its rack, so no pool plan is charged.
FREE_EVENTS, EVENTS_PER_SIM = 300, 5


def _strokes(
    option: PotOption,
    needs_call: bool,
    speeds: tuple[float, ...],
    tips: tuple[tuple[float, float], ...],
) -> list[Candidate]:
    """A pot's strokes: each speed (times the speed that just reaches the pocket) with
    each tip, the pocket called when the rules want a call."""
    base = speed_for(option)
    return [
        Candidate(
            aimed(option.angle, min(base * factor, 0.85 * MAX_SPEED), side, height),
            option.pocket if needs_call else None,
            "pot",
            option.target,
            option.pocket,
            option.chance,
            via=option.via,
        )
        for factor in speeds
        for side, height in tips
    ]


def _object_balls(balls: BallSet) -> bytes:
    """The object balls' places, as a key: what a pocket's window depends on."""
    keep = (balls.ids != CUE) & balls.on_table
    return np.ascontiguousarray(balls.positions[keep]).tobytes()


def route(events: list[Event], ball: int, first_contact: int | None) -> str:
    """How `ball` reached its pocket, by the shot's events (`PotOption.via`'s names):
    when the cue ball hit another ball first, "billiard" if the cue ball then hit `ball`
    and "combo" if another ball did; "bank" when `ball` met a cushion before it dropped,
    "carom" when it met another object ball, else "direct"."""
    if first_contact != ball:
        hit = next((e for e in events if e.kind == "ball" and ball in e.ids), None)
        return "billiard" if hit is not None and CUE in hit.ids else "combo"
    via = "direct"
    for event in events:
        if ball not in event.ids:
            continue
        if event.kind == "pocket":
            break
        if event.kind == "cushion":
            via = "bank"
        elif event.kind == "ball" and CUE not in event.ids and via == "direct":
            via = "carom"
    return via


@dataclass
class Candidate:
    """A stroke being considered. value0: its score without noise; value: with noise."""

    shot: Shot
    call: int | None
    kind: str  # "pot", "safety", "kick", "break", "push"
    target: int | None = None
    pocket: int | None = None
    prior: float = 0.0
    via: str = "direct"  # a pot's route: "direct", "bank", "combo", "carom" or "billiard"
    value0: float = -math.inf
    value: float = -math.inf
    pot_rate: float = 0.0
    # Lookahead: the value before the next shot was searched, and for each leave searched
    # (value of the leave, value of the best next pot there or -inf when there is none).
    base: float = 0.0
    leaves: list[tuple[float, float]] = field(default_factory=list)
    # A safety or kick whose exact stroke pockets a ball legally: (ball, pocket, route).
    drop: tuple[int, int, str] | None = None

    def revalue(self, floor: float) -> None:
        """The value with `floor` for a leave whose best next pot is worth less (what
        playing safe from there is worth)."""
        if self.leaves:
            gain = sum(max(nxt, floor) - v for v, nxt in self.leaves) / len(self.leaves)
            self.value = self.base + self.pot_rate * gain


@dataclass
class Search:
    """One turn's search: the position the shot is played from and the level's budget."""

    table: Table
    rules: GameRules
    pos: Position
    seat: int
    level: Level
    noise: np.ndarray  # (samples, 4) standard normals, shared by every candidate
    confirm_noise: np.ndarray  # fresh draws for the second look at the best few
    sims: int = 0
    limit: int = 1 << 30  # simulations allowed up to now (the level's budget per turn)
    windows: dict[WindowKey, tuple[float, float] | None] = field(default_factory=dict)
    charge_events: bool = False  # a packed table: a long cascade costs more (`FREE_EVENTS`)

    # --- targets and values -----------------------------------------------------------
    def targets(self, pos: Position) -> list[int]:
        legal = self.rules.legal_targets(pos)
        return legal if legal else pos.object_balls

    def plan_sigma(self) -> float:
        return self.level.aim

    def chance_for(self, pos: Position, balls: BallSet) -> float:
        return best_chance(self.table, balls, self.targets(pos), self.plan_sigma())

    def after(self, pos: Position, ruling: Ruling, final: BallSet, turn: int) -> Position:
        groups = pos.groups
        if ruling.groups:
            groups = tuple(ruling.groups[s] for s in range(len(pos.players)))
        return replace(
            pos,
            on_table=tuple(final.on_table_ids()),
            turn=turn,
            breaking=False,
            groups=groups,
            called_pocket=None,
            push_out_declared=False,
            score=ruling.score if ruling.score is not None else pos.score,
            balls=final,
        )

    def outcome(
        self, pos: Position, before: BallSet, shot: Shot
    ) -> tuple[float, bool, Ruling, BallSet]:
        """Simulate `shot` from `before` played in `pos`: (value, pocketed legally, ruling,
        table after)."""
        facts, result = self._simulate(before, shot)
        ruling, final = self._judge(pos, facts, result.final)
        return (
            self.value_of(pos, ruling, final, facts.pocketed),
            self._made(ruling, facts.pocketed),
            ruling,
            final,
        )

    def _simulate(self, before: BallSet, shot: Shot) -> tuple[ShotFacts, Settled]:
        """One engine shot, counted against the budget: (its facts, the settled shot)."""
        self.sims += 1
        result = settle(self.table, before, shot)
        if self.charge_events:
            self.sims += max(0, len(result.rows) - FREE_EVENTS) // EVENTS_PER_SIM
        return shot_facts(before, result), result

    def spent(self) -> bool:
        """The budget is gone on a table whose simulations are charged by their events;
        elsewhere the stages size themselves to the budget beforehand."""
        return self.charge_events and self.sims >= self.limit

    def _judge(self, pos: Position, facts: ShotFacts, final: BallSet) -> tuple[Ruling, BallSet]:
        """The rules' ruling on a simulated shot and the table after it (balls re-spotted)."""
        ruling = self.rules.judge(pos, facts)
        if ruling.spot:
            final = self.rules.respot(self.table, final, ruling.spot)
        return ruling, final

    def _made(self, ruling: Ruling, pocketed: tuple[int, ...]) -> bool:
        if ruling.winner is not None:
            return ruling.winner == self.seat
        return bool(pocketed) and not ruling.fouls and ruling.continues

    def value_of(
        self, pos: Position, ruling: Ruling, final: BallSet, pocketed: Iterable[int]
    ) -> float:
        me = self.seat
        level = self.level
        if ruling.winner is not None:
            return WIN if ruling.winner == me else LOSS
        if ruling.decision is not None:
            if ruling.pending == "push_out":
                nxt = self.after(pos, ruling, final, ruling.decision.seat)
                q = self.chance_for(nxt, final)
                return -0.05 - 0.8 * abs(q - 0.5)
            return KEEP_BASE if ruling.decision.seat == me else FOUL
        if ruling.fouls:
            worse = 0.15 * (pos.fouls_in_row[me] if pos.fouls_in_row else 0)
            return FOUL - min(worse, 0.3)
        solo = len(pos.players) == 1
        if ruling.continues or solo:
            nxt = self.after(pos, ruling, final, me)
            q = self.chance_for(nxt, final)
            mine = set(self.targets(pos))
            progress = PROGRESS * sum(1 for b in pocketed if b in mine)
            if ruling.score is not None and pos.score is not None:  # snooker: by the points
                progress = PROGRESS * (ruling.score.points[me] - pos.score.points[me])
            w = level.position
            spread = open_share(self.table, final, self.targets(nxt))
            quality = (1 - OPEN_WEIGHT) * q + OPEN_WEIGHT * spread
            keep = KEEP_BASE + KEEP_SCALE * (w * quality + (1 - w) * 0.5) + progress
            if solo and not ruling.continues:
                return keep - 0.3
            return keep
        other = 1 - me
        if not level.safeties:
            return GIVE_BASE - GIVE_SCALE * 0.5
        nxt = self.after(pos, ruling, final, other)
        q_opp = self.chance_for(nxt, final)
        return GIVE_BASE - GIVE_SCALE * q_opp

    # --- evaluation -------------------------------------------------------------------
    def noisy(self, shot: Shot, row: np.ndarray) -> Shot:
        """`shot` under the draws `row` as the search plans it: the level's error with the
        tip's error turning the line by its squirt as well (`perturb`), a little more
        than the arm's own; planned so, the pro cleared more runouts (docs/ai.md,
        "Levels")."""
        return perturb(shot, row, self.level, squirt=True)

    def pos_for(self, cand: Candidate) -> Position:
        return replace(self.pos, called_pocket=cand.call) if cand.call is not None else self.pos

    def score0(self, balls: BallSet, cand: Candidate) -> None:
        """The stroke's value without noise. A safety or kick on the 8 that drops it in
        another pocket than the one called would lose: it calls that pocket instead. A
        safety or kick that pockets a ball legally records the ball, pocket and route
        (`Candidate.drop`), so that the turn can say it is a pot."""
        pos = self.pos_for(cand)
        facts, result = self._simulate(balls, cand.shot)
        stopped = result.final
        ruling, final = self._judge(pos, facts, stopped)
        cand.value0 = self.value_of(pos, ruling, final, facts.pocketed)
        if cand.value0 == LOSS and cand.kind != "pot" and cand.call is not None:
            dropped = [facts.pockets[t] for t in self.targets(pos) if t in facts.pockets]
            if dropped and dropped[0] != cand.call:
                cand.call = dropped[0]  # the same stroke, judged with that call
                pos = self.pos_for(cand)
                ruling, final = self._judge(pos, facts, stopped)
                cand.value0 = self.value_of(pos, ruling, final, facts.pocketed)
        if cand.kind != "pot" and facts.pocketed and self._made(ruling, facts.pocketed):
            ball = facts.pocketed[0]
            cand.drop = (ball, facts.pockets[ball], route(result.events, ball, facts.first_contact))

    def score_noisy(self, balls: BallSet, cand: Candidate) -> None:
        pos = self.pos_for(cand)
        total, made, n = 0.0, 0, 0
        for row in self.noise:
            if self.spent():
                break
            value, ok, _, _ = self.outcome(pos, balls, self.noisy(cand.shot, row))
            total += value
            made += ok
            n += 1
        if n == 0 and len(self.noise):  # not sampled: below every candidate that was
            cand.value, cand.pot_rate = -math.inf, 0.0
            return
        n = max(n, 1)
        cand.value, cand.pot_rate = total / n, made / n

    def refine(self, balls: BallSet, cands: list[Candidate], keep: int) -> list[Candidate]:
        """Score every candidate without noise, then the best `keep` under noise; never past
        `limit` simulations (candidates come best first; when no noisy sample fits, the best
        zero-noise candidate stands, valued as it scored)."""
        room = self.limit - self.sims
        if room <= 0 or not cands:
            return []
        cands = cands[: min(room, max(keep, room // 2))]
        for k, cand in enumerate(cands):
            if k and self.spent():
                cands = cands[:k]
                break
            self.score0(balls, cand)
        cands.sort(key=lambda c: -(c.value0 + 0.5 * c.prior))
        room = self.limit - self.sims
        keep = min(keep, room // max(len(self.noise), 1))
        if keep <= 0:
            best = cands[0]
            best.value = best.value0
            return [best]
        chosen = cands[:keep]
        if self.limit - self.sims >= keep * (len(self.noise) + 2):
            for cand in chosen:
                self.allow_for_throw(balls, cand)
            # The windows' simulations (`Search.window`) may leave room for fewer.
            chosen = chosen[: max(1, (self.limit - self.sims) // max(len(self.noise), 1))]
        for cand in chosen:
            self.score_noisy(balls, cand)
        chosen.sort(key=lambda c: -c.value)
        if chosen[0].value == -math.inf:  # the budget went before any was sampled
            chosen[0].value = chosen[0].value0
        room = self.limit - self.sims
        n_confirm = min(self.level.confirm, len(chosen))
        if n_confirm > 1 and room >= len(self.confirm_noise) * n_confirm:
            # The best few again on fresh draws: the first scores favour lucky candidates.
            first = self.noise
            self.noise = self.confirm_noise
            try:
                for cand in chosen[:n_confirm]:
                    before, rate = cand.value, cand.pot_rate
                    self.score_noisy(balls, cand)
                    n0, n1 = len(first), len(self.confirm_noise)
                    cand.value = (before * n0 + cand.value * n1) / (n0 + n1)
                    cand.pot_rate = (rate * n0 + cand.pot_rate * n1) / (n0 + n1)
            finally:
                self.noise = first
            head = sorted(chosen[:n_confirm], key=lambda c: -c.value)
            chosen = head + chosen[n_confirm:]
        if self.level.lookahead and chosen and chosen[0].kind == "pot":
            # Only the looked-ahead pots compete first: the search of the next shot is
            # stricter than the quick estimate, so an unsearched pot would win by default.
            looked = [c for c in chosen[: self.level.lookahead] if self.look_ahead(balls, c)]
            rest = [c for c in chosen if not any(c is x for x in looked)]
            chosen = sorted(looked, key=lambda c: -c.value) + rest
        return chosen

    def allow_for_throw(self, balls: BallSet, cand: Candidate) -> None:
        """Turn a pot's aim for the throw (`aim_for_throw`); its simulations count against
        the budget."""
        direct = cand.kind == "pot" and cand.via == "direct"
        if not direct or cand.target is None or cand.pocket is None:
            return
        window = None
        if self.level.windows:
            window = functools.partial(self.window, balls, cand.target, cand.pocket)
        cand.shot, used = aim_for_throw(
            self.table, balls, cand.shot, cand.target, cand.pocket, window
        )
        self.sims += used

    def window(
        self, balls: BallSet, target: int, pocket: int, speed: float, toward: float
    ) -> tuple[tuple[float, float] | None, int]:
        """`pocket_window` for `target` leaving at about `speed` (to `WINDOW_SPEED_STEP`),
        and the simulations that took. Kept for the turn: the window does not depend on
        the cue ball (it is gone), so a pot's strokes of about one speed, and the same pot
        from every ball-in-hand spot, share it."""
        step = max(round(speed / WINDOW_SPEED_STEP), 1)
        key = (target, pocket, step, _object_balls(balls))
        if key in self.windows:
            return self.windows[key], 0
        found, used = pocket_window(
            self.table, balls, target, pocket, step * WINDOW_SPEED_STEP, toward
        )
        self.windows[key] = found
        return found, used

    def look_ahead(self, balls: BallSet, cand: Candidate) -> bool:
        """Replace the quick estimate of the position a pot leaves by a search of the next
        shot from the tables the shot leaves: without noise and on the first
        `LOOK_LEAVES - 1` noisy draws (a leave that only works when the speed is exact
        is worth less), averaged over those that pocket. When none of those pockets (a
        safety that pockets on some draws, not with the exact stroke), the next draws are
        tried until one does: otherwise its pots would keep the quick estimate and
        outrank the pots searched. False when the budget allowed no search."""
        pos = self.pos_for(cand)
        searched = False
        cand.base, cand.leaves = cand.value, []
        for k, row in enumerate([None, *self.noise]):  # the exact stroke, then the draws
            if self.limit - self.sims < LOOK_SIMS or (k >= LOOK_LEAVES and cand.leaves):
                break
            searched = True
            shot = cand.shot if row is None else self.noisy(cand.shot, row)
            value, made, ruling, final = self.outcome(pos, balls, shot)
            if not made or ruling.winner is not None:
                continue
            cand.leaves.append((value, self._next_shot(pos, ruling, final)))
        cand.revalue(GIVE_UP)
        return searched

    def _next_shot(self, pos: Position, ruling: Ruling, final: BallSet) -> float:
        """The value of the best next pot from `final` (simulated without noise, weighted by
        its chance), -inf when there is none."""
        nxt = self.after(pos, ruling, final, self.seat)
        model = self.level.chance_model
        sigma = self.plan_sigma() if model.floor else max(self.plan_sigma(), MIN_AIM_SIGMA)
        options = pot_options(self.table, final, self.targets(nxt), sigma, model=model)
        speeds, tips = SPEED_FACTORS[:LOOK_SPEEDS], TIPS[:LOOK_TIPS]
        late = self.level.late_strokes and (
            self.level.deep_next or (len(options) <= FEW_POTS and self._late(nxt))
        )
        if late and self.limit - self.sims >= LATE_LOOK_SIMS:
            speeds, tips = LATE_SPEED_FACTORS, TIPS
        options = options[:LOOK_PAIRS]
        needs_call = self.rules.requires_call(nxt)
        best = -math.inf
        for option in options:
            base = speed_for(option)
            for factor in speeds:
                for side, height in tips:
                    speed = min(base * factor, 0.85 * MAX_SPEED)
                    shot = aimed(option.angle, speed, side, height)
                    after = replace(nxt, called_pocket=option.pocket) if needs_call else nxt
                    saved, self.seat = self.seat, nxt.turn
                    try:
                        v, ok, _, _ = self.outcome(after, final, shot)
                    finally:
                        self.seat = saved
                    est = option.chance * v + (1 - option.chance) * GIVE_UP if ok else -math.inf
                    best = max(best, est)
        return best

    def _late(self, pos: Position) -> bool:
        """At most `LATE_BALLS` balls left to pot before the game ball (the 8 once the
        groups are chosen; in 9-ball the 9)."""
        left = self.rules.balls_left(pos)
        if left is None:
            return False
        before_game_ball = len(left[pos.turn]) - (1 if self.rules.kind == "nine_ball" else 0)
        return before_game_ball <= LATE_BALLS

    # --- candidates -------------------------------------------------------------------
    def pot_candidates(self, balls: BallSet, pairs: int) -> list[Candidate]:
        options = pot_options(self.table, balls, self.targets(self.pos), self.plan_sigma())
        needs_call = self.rules.requires_call(self.pos)
        fine = self.level.lookahead > 0 and (self.level.fine_pots or len(options) <= FEW_POTS)
        out = []
        for option in options[:pairs]:
            out.extend(self._variants(option, needs_call, fine))
        if fine:  # few pots on: the banks, combinations and caroms may be the best of them
            out.extend(self.indirect_candidates(balls, needs_call))
        return out

    def indirect_candidates(self, balls: BallSet, needs_call: bool) -> list[Candidate]:
        """The best banks, combinations, caroms and billiards, a few strokes each (centre
        ball, and follow for a combination); the simulations judge them like any pot. In
        9-ball a combination or a billiard may drop any ball (the lowest is hit first), in
        8-ball only the shooter's own. A carom's or billiard's aim is corrected with the
        engine (`aim_carom`), whose simulations count against the budget."""
        targets = self.targets(self.pos)
        sigma = self.plan_sigma()
        banks = bank_options(self.table, balls, targets, sigma)
        # Banks come best first, the aims of a route together.
        routes = set(list(dict.fromkeys(o.route for o in banks))[:BANK_ROUTES])
        objects = self.pos.object_balls if self.rules.kind == "nine_ball" else targets
        combos = combo_options(self.table, balls, targets, objects, sigma)[:COMBOS]
        out = []
        for option in [o for o in banks if o.route in routes] + combos:
            if option.via == "bank":
                out.extend(_strokes(option, needs_call, BANK_SPEED_FACTORS, TIPS[:1]))
            else:
                out.extend(_strokes(option, needs_call, COMBO_SPEED_FACTORS, TIPS[:2]))
        caroms = carom_options(self.table, balls, targets, sigma)[:CAROMS]
        billiards = billiard_options(self.table, balls, targets, objects, sigma)[:BILLIARDS]
        for option in caroms + billiards:
            for cand in _strokes(option, needs_call, CAROM_SPEED_FACTORS, TIPS[:1]):
                cand.shot, used = aim_carom(
                    self.table,
                    balls,
                    cand.shot,
                    option.target,
                    option.pocket,
                    option.carrier if option.via == "billiard" else None,
                )
                self.sims += used
                out.append(cand)
        return out

    def _variants(self, option: PotOption, needs_call: bool, fine: bool) -> list[Candidate]:
        """The strokes tried on one pot: the level's speeds and tips, or the finer set."""
        if fine:
            return _strokes(option, needs_call, FINE_SPEED_FACTORS, FINE_TIPS)
        speeds, tips = SPEED_FACTORS[: self.level.speeds], TIPS[: self.level.tips]
        return _strokes(option, needs_call, speeds, tips)

    def safety_candidates(self, balls: BallSet) -> list[Candidate]:
        """Hits on each of the four nearest legal balls, full to thin, soft to firm, with
        centre ball, draw and follow."""
        cue = np.array(balls.position_of(CUE))
        r = self.table.ball_radius
        call = self.default_call(balls)
        out = []
        on = set(balls.on_table_ids())
        targets = [t for t in self.targets(self.pos) if t in on]
        targets.sort(key=lambda t: float(np.linalg.norm(np.array(balls.position_of(t)) - cue)))
        for t in targets[:4]:
            obj = np.array(balls.position_of(t))
            dx, dy = obj - cue
            dist = max(math.hypot(dx, dy), 2 * r + 1e-6)
            direct = math.atan2(dy, dx)
            for frac in SAFETY_FRACTIONS:
                offset = math.asin(max(-1.0, min(1.0, frac * 2 * r / dist)))
                for speed in SAFETY_SPEEDS:
                    for height in SAFETY_HEIGHTS:
                        shot = clamp_shot(direct + offset, speed, 0.0, height)
                        out.append(Candidate(shot, call, "safety", t))
        return out

    def kick_candidates(self, balls: BallSet) -> list[Candidate]:
        """Kicks: aim at the mirror images of each legal ball in one cushion, and in two
        (round a corner), with small corrections for the cushion's loss of pace."""
        table = self.table
        r = table.ball_radius
        lo_x, hi_x, lo_y, hi_y = r, table.length - r, r, table.width - r
        cx, cy = balls.position_of(CUE)
        call = self.default_call(balls)
        on = set(balls.on_table_ids())
        targets = [t for t in self.targets(self.pos) if t in on]
        targets.sort(key=lambda t: math.dist(balls.position_of(t), (cx, cy)))
        out = []
        for t in targets[:3]:
            ox, oy = balls.position_of(t)
            mx = (2 * lo_x - ox, 2 * hi_x - ox)
            my = (2 * lo_y - oy, 2 * hi_y - oy)
            images = [(x, oy, 1) for x in mx] + [(ox, y, 1) for y in my]
            images += [(x, y, 2) for x in mx for y in my]
            for ix, iy, rails in images:
                direct = math.atan2(iy - cy, ix - cx)
                offsets = KICK_OFFSETS if rails == 1 else KICK_OFFSETS[1:-1]
                speeds = KICK_SPEEDS if rails == 1 else KICK_SPEEDS[1:]
                for off in offsets:
                    for speed in speeds:
                        shot = clamp_shot(direct + math.radians(off), speed, 0.0, 0.0)
                        out.append(Candidate(shot, call, "kick", t))
        return out

    def escape_candidates(self, balls: BallSet) -> list[Candidate]:
        """The kicks and, at a level that jumps, the jumps, swerves and masses: judged
        side by side."""
        kicks = self.kick_candidates(balls)
        return kicks + self.jump_candidates(balls) + self.curve_candidates(balls)

    def jump_candidates(self, balls: BallSet) -> list[Candidate]:
        """Jumps at the nearest legal balls whose straight path from the cue ball is
        blocked by a ball within `JUMP_REACH` of it: straight at the ball's centre, the cue
        raised and struck as `JUMPS` says; the simulations judge them like kicks."""
        if not self.level.jumps:
            return []
        r = self.table.ball_radius
        cx, cy = balls.position_of(CUE)
        call = self.default_call(balls)
        on = set(balls.on_table_ids())
        targets = [t for t in self.targets(self.pos) if t in on]
        targets.sort(key=lambda t: math.dist(balls.position_of(t), (cx, cy)))
        out = []
        for t in targets[:3]:
            tx, ty = balls.position_of(t)
            if not _blocked_near(balls, (cx, cy), (tx, ty), t, r):
                continue
            for degrees, speed in JUMPS:
                elevation = math.radians(degrees)
                tip = tip_seen_level((0.0, 0.0), elevation)
                shot = Shot(math.atan2(ty - cy, tx - cx), speed, tip, elevation)
                out.append(Candidate(shot, call, "kick", t))
        return out

    def curve_candidates(self, balls: BallSet) -> list[Candidate]:
        """Swerves and masses at the two nearest legal balls whose straight path from the
        cue ball is blocked (by a ball at any distance): for each side of the nearest
        blocker, aimed `CURVE_AIMS` times the turn that passes it on that side, with side
        spin that curves back (right spin curves right), raised and struck as `CURVES`
        says; the simulations judge them like kicks."""
        if not self.level.masse:
            return []
        r = self.table.ball_radius
        cue = balls.position_of(CUE)
        call = self.default_call(balls)
        on = set(balls.on_table_ids())
        targets = [t for t in self.targets(self.pos) if t in on]
        targets.sort(key=lambda t: math.dist(balls.position_of(t), cue))
        out = []
        for t in targets[:2]:
            target = balls.position_of(t)
            blockers = _in_the_way(balls, cue, target, t, r)
            if not blockers:
                continue
            along, across = min(blockers)
            direct = math.atan2(target[1] - cue[1], target[0] - cue[0])
            for left in (1.0, -1.0):  # pass the blocker on the left (+) or the right
                turn = math.atan2(2 * r + left * across, along)
                for degrees, speed in CURVES:
                    elevation = math.radians(degrees)
                    tip = tip_seen_level((left * CURVE_SIDE, 0.0), elevation)
                    for factor in CURVE_AIMS:
                        angle = direct + left * turn * factor
                        out.append(Candidate(Shot(angle, speed, tip, elevation), call, "kick", t))
        return out

    def sweep_candidates(
        self, balls: BallSet, speeds: tuple[float, ...] = SWEEP_SPEEDS
    ) -> list[Candidate]:
        """A sweep of directions all round the cue ball (the last resort, and push outs)."""
        call = self.default_call(balls)
        out = []
        for k in range(SWEEP_ANGLES):
            angle = 2 * math.pi * k / SWEEP_ANGLES
            for speed in speeds:
                out.append(Candidate(clamp_shot(angle, speed, 0.0, 0.0), call, "kick"))
        return out

    def default_call(self, balls: BallSet) -> int | None:
        """The pocket to call when the shot played is not a pot (the 8's easiest pocket)."""
        if not self.rules.requires_call(self.pos):
            return None
        options = pot_options(self.table, balls, self.targets(self.pos), self.plan_sigma())
        if options:
            return options[0].pocket
        eight = [t for t in self.targets(self.pos) if t in balls.on_table_ids()]
        if not eight:
            return 0
        x, y = balls.position_of(eight[0])
        centres = [p.center for p in self.table.pockets]
        return min(range(len(centres)), key=lambda i: math.dist(centres[i], (x, y)))

    # --- the turn ---------------------------------------------------------------------
    def best_shot(self, balls: BallSet, pairs: int | None = None) -> Candidate:
        """The best stroke from `balls` (cue ball where it is), within `limit` simulations:
        the pots may spend all but `SAFETY_SHARE` of them, the safeties the rest."""
        level = self.level
        pairs = level.pairs if pairs is None else pairs
        end = self.limit
        if level.safeties:
            self.limit = self.sims + int((end - self.sims) * (1 - SAFETY_SHARE))
        try:
            chosen = self.refine(balls, self.pot_candidates(balls, pairs), level.refine)
        finally:
            self.limit = end
        best = chosen[0] if chosen else None
        keep = max(2, level.refine // 2) if level.safeties else 1
        if best is None or (level.safeties and best.value < SAFETY_BELOW):
            safe = self.refine(balls, self.safety_candidates(balls), keep)
            for more in (self.escape_candidates, self.sweep_candidates):
                if safe and safe[0].value > FOUL + 0.2:
                    break
                safe = sorted(safe + self.refine(balls, more(balls), keep), key=lambda c: -c.value)
            if level.lookahead and best is not None and best.kind == "pot":
                # A safety that sometimes pockets was valued by the quick estimate of what
                # it leaves; the pots by the search of the next shot: compare like with like.
                # The best few are searched, then the best left while it is one unsearched.
                looked = [c for c in safe[:SAFETY_LOOKS] if c.pot_rate > 0]
                for cand in looked:
                    self.look_ahead(balls, cand)
                safe.sort(key=lambda c: -c.value)
                while safe and safe[0].pot_rate > 0 and not any(safe[0] is c for c in looked):
                    looked.append(safe[0])
                    if not self.look_ahead(balls, safe[0]):
                        break
                    safe.sort(key=lambda c: -c.value)
                best = self.pot_then_safe(chosen, safe) or best
            if safe and (best is None or safe[0].value > best.value):
                best = safe[0]
        return best if best is not None else self.fallback(balls)

    def pot_then_safe(self, pots: list[Candidate], safe: list[Candidate]) -> Candidate | None:
        """The best pot once a leave with no next pot is valued as the safety played from
        there: about what a safety now is worth (a pure safety is worth at most
        `GIVE_BASE`), plus a ball fewer left to pot. Without this the search preferred a
        safety now to a sure pot followed by the same safety. When every safety searched
        pockets sometimes (a ball near a pocket), the best of them stands in."""
        pure = [c.value for c in safe if c.pot_rate == 0] or [c.value for c in safe[:1]]
        if not pure:
            return None
        floor = max(GIVE_UP, min(pure[0], GIVE_BASE) + SAFE_LATER)
        for cand in pots + safe:
            cand.revalue(floor)
        safe.sort(key=lambda c: -c.value)
        return max((c for c in pots if c.leaves), key=lambda c: c.value, default=None)

    def fallback(self, balls: BallSet) -> Candidate:
        """A firm hit straight at the nearest legal ball, unsimulated: what is left when the
        budget allowed no simulation at all."""
        cx, cy = balls.position_of(CUE)
        on = set(balls.on_table_ids())
        targets = [t for t in self.targets(self.pos) if t in on] or [b for b in on if b != CUE]
        near = min(targets, key=lambda t: math.dist(balls.position_of(t), (cx, cy)))
        nx, ny = balls.position_of(near)
        shot = clamp_shot(math.atan2(ny - cy, nx - cx), 2.0, 0.0, 0.0)
        return Candidate(shot, self.default_call(balls), "safety", near)


def _in_the_way(
    balls: BallSet, cue: tuple[float, float], target: tuple[float, float], ball: int, r: float
) -> list[tuple[float, float]]:
    """The balls on the straight path from the cue ball to `ball`: each as (along, across),
    its centre's distance down the line and to the left of it (m)."""
    dx, dy = target[0] - cue[0], target[1] - cue[1]
    length = math.hypot(dx, dy)
    out = []
    for other in balls.on_table_ids():
        if other in (CUE, ball):
            continue
        ox, oy = balls.position_of(other)
        along = ((ox - cue[0]) * dx + (oy - cue[1]) * dy) / length
        across = (dx * (oy - cue[1]) - dy * (ox - cue[0])) / length
        past = max(along - (length - 2 * r), 0.0)  # beyond where the cue ball meets `ball`
        if along > 0.0 and past * past + across * across < 4 * r * r:
            out.append((along, across))
    return out


def _blocked_near(
    balls: BallSet, cue: tuple[float, float], target: tuple[float, float], ball: int, r: float
) -> bool:
    """Is the straight path from the cue ball to `ball` blocked, by a ball whose centre is
    within `JUMP_REACH` of the cue ball's (one a jump can clear)?"""
    for other in balls.on_table_ids():
        if other in (CUE, ball):
            continue
        ox, oy = balls.position_of(other)
        dx, dy = target[0] - cue[0], target[1] - cue[1]
        length = math.hypot(dx, dy)
        along = ((ox - cue[0]) * dx + (oy - cue[1]) * dy) / length
        across = abs((ox - cue[0]) * dy - (oy - cue[1]) * dx) / length
        if JUMP_REACH[0] <= along <= min(JUMP_REACH[1], length - 2 * r) and across < 2 * r:
            return True
    return False
