"""The computer's levels: how well it executes (the noise `Bot.execute` applies) and how much
it searches (simulations per turn).

The top level executes with the noise of the computational-pool tournaments (FastFiz:
sigma aim 0.125 degrees, sigma speed 0.075 m/s, sigma tip offset 0.5 mm). Each level plans
under its own noise, so a weak level knows it misses long shots and plays easier ones.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from server.engine import BALL_RADIUS

from .geometry import FASTFIZ, FASTFIZ_TIP_MM, GEOMETRIC, ChanceModel


@dataclass(frozen=True)
class Level:
    """One level of play.

    aim_deg / speed / tip_mm: the standard deviations of the execution error (degrees, m/s,
    millimetres of tip offset on each axis); aim_deg is the whole error of the cue ball's
    line, the tip's error changes the spin, and speed is the cue's, as in FastFiz (the
    ball's speed strays by `aiming.strike_gain` times it, 1.3-1.6; `aiming.perturb`).
    pairs: (ball, pocket) pairs tried per turn; speeds / tips: stroke variants of each;
    refine: variants sampled under noise; samples: noisy simulations per refined variant;
    safeties: whether it plays safe on purpose (a level without them still finds a legal
    hit when it has no pot); placements: ball-in-hand spots searched in full; position:
    weight of the position left; confirm / confirm_samples: the best few variants sampled
    again on fresh draws; budget: simulations per turn at most (it bounds the plan time);
    lookahead: how many of the best pots get a simulated search of the next shot from the
    table they leave; calibrated: it ranks unsimulated pots with the chance model fitted
    to the engine; late_strokes: that search tries more strokes late in a rack
    (`search.LATE_BALLS`); windows: it aims a pot at the middle of the directions in
    which the ball drops, found with the engine (`aiming.pocket_window`), not at the
    middle of the mouth; jumps: when a legal ball's straight path is blocked, it also
    tries jumping the cue ball over the blocker (`search.JUMPS`) among its escapes;
    masse: when it is blocked (at any distance), it also tries curving the cue ball
    round the blocker with a raised cue and side spin (`search.CURVES`); fine_pots: every
    pot gets the finer strokes (`search.FINE_SPEED_FACTORS`), not only when few are on;
    deep_next: the next-shot search always tries the late grid (`search.LATE_SPEED_FACTORS`).
    The last two are set by `for_kind` (snooker), not by the table below, which also
    turns `jumps` off at snooker.
    """

    name: str
    aim_deg: float
    speed: float
    tip_mm: float
    pairs: int
    speeds: int
    tips: int
    refine: int
    samples: int
    safeties: bool
    placements: int
    position: float
    confirm: int = 0
    confirm_samples: int = 0
    budget: int = 1000
    lookahead: int = 0
    calibrated: bool = False
    late_strokes: bool = False
    windows: bool = False
    jumps: bool = False
    masse: bool = False
    fine_pots: bool = False
    deep_next: bool = False

    @property
    def chance_model(self) -> ChanceModel:
        """The pot-chance model it plans with: the one fitted to the engine under noise
        (scaled by this level's tip error) when `calibrated`, else the plain geometry."""
        if not self.calibrated:
            return GEOMETRIC
        k = self.tip_mm / FASTFIZ_TIP_MM
        return replace(FASTFIZ, floor=FASTFIZ.floor * k, cut=FASTFIZ.cut * k)

    @property
    def aim(self) -> float:
        """Aim sigma in radians."""
        return math.radians(self.aim_deg)

    @property
    def tip(self) -> float:
        """Tip sigma as a fraction of the ball radius (the unit of `Shot.tip`)."""
        return self.tip_mm * 1e-3 / BALL_RADIUS


# fmt: off
LEVEL_TABLE: tuple[Level, ...] = (
    Level("beginner", 1.5, 0.30, 3.0, 4, 2, 1, 3, 4, False, 1, 0.2, budget=200),
    Level("amateur", 0.7, 0.18, 2.0, 6, 3, 3, 4, 6, True, 2, 0.6, budget=350),
    Level("club", 0.35, 0.11, 1.0, 8, 3, 3, 6, 10, True, 3, 1.0, 2, 10, 550, 2),
    Level("pro", 0.125, 0.075, 0.5, 16, 4, 5, 16, 30, True, 3, 1.0, 4, 60, 3900, 14, True, True,
          windows=True, jumps=True, masse=True),
)
# fmt: on
LEVELS: tuple[str, ...] = tuple(level.name for level in LEVEL_TABLE)
BY_NAME: dict[str, Level] = {level.name: level for level in LEVEL_TABLE}


SNOOKER_KINDS = ("snooker", "snooker_practice")


def for_kind(level: Level, kind: str) -> Level:
    """`level` as it plays the game `kind`. A snooker break runs on for up to 36 pots, not a
    pool rack's 8 or 9, so the level that searches late-rack position (`late_strokes`)
    searches every pot's position so: the finer strokes on each pot and the late grid on
    the next shot: longer breaks in the pro's self-play (docs/ai.md, "Snooker"); a pool
    plan is unchanged.

    At snooker no level jumps: a jump shot is a foul there (WPBSA Section 2 "Jump Shot",
    3.11 Penalty Values; the referee calls it, `rules.jumps`), so the search does not
    spend simulations on strokes it would only reject. Swerves and masses stay: a
    raised cue that goes round a ball, not over it, is legal. The snooker practice table
    is planned the same way: its hints show what a frame allows."""
    if kind not in SNOOKER_KINDS:
        return level
    if level.late_strokes:
        level = replace(level, fine_pots=True, deep_next=True)
    return replace(level, jumps=False)
