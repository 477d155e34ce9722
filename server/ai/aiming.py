"""Strokes and their aims: a valid `Shot` near the wanted values, aimed against the squirt
of its side spin, perturbed by a level's execution error, and aims the engine corrects
(the throw of a cut; the path of a carom after its kiss), which the ghost-ball geometry
does not see.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import replace

import numpy as np

from server.engine import CUE, MAX_SPEED, MAX_TIP, BallSet, Event, Shot, Table, settle, simulate

from .geometry import pockets_of
from .levels import Level

THROW_STEP = math.radians(0.05)  # the aim step of the secant that allows for the throw
# An object ball thrown further off than this was not thrown (a kiss, a near miss): no
# correction. Bounded on the ball's error, not on the turn of the cue, which is larger the
# closer the cue ball is (from 0.1 m a 2.9-degree throw needs a turn of 1.45 degrees).
THROW_MAX = math.radians(5.0)
THROW_LOOK = 0.04  # s after the contact at which the object ball's direction is read
# The secant on a carom's aim (`aim_carom`): its first step, the engine shots it may take,
# the largest correction trusted and a miss small enough to stop at.
CAROM_NUDGE = math.radians(0.02)
CAROM_STEPS = 4
CAROM_MAX = math.radians(0.5)
CAROM_DONE = math.radians(0.2)
# The pocket's window (`pocket_window`): the outward steps that look for an edge, the
# furthest an edge is looked for, and the halvings of the last step (the edge to about
# 0.03 degrees of the object ball's direction).
WINDOW_STEP = math.radians(0.5)
WINDOW_REACH = math.radians(8.0)
WINDOW_HALVINGS = 4
# FastFiz's cue strike (Leckie and Greenspan's equation 1): its ball's mass over its cue's
# (163.01 g, 600 g).
FASTFIZ_MASS_RATIO = 163.01 / 600.0


def clamp_shot(angle: float, speed: float, side: float, height: float) -> Shot:
    """A valid `Shot` near the given values: speed within (0, MAX_SPEED], tip within MAX_TIP."""
    speed = min(max(speed, 0.05), MAX_SPEED)
    norm = math.hypot(side, height)
    if norm > MAX_TIP:
        k = MAX_TIP / norm * (1 - 1e-9)
        side, height = side * k, height * k
    return Shot(math.remainder(angle, 2 * math.pi), speed, (side, height))


def aimed(angle: float, speed: float, side: float, height: float) -> Shot:
    """A stroke whose cue ball leaves along `angle`: the aim turned against the squirt of
    its side spin (the ghost-ball line is where the cue ball must go, not the cue)."""
    shot = clamp_shot(angle, speed, side, height)
    return clamp_shot(angle - shot.squirt(), shot.speed, *shot.tip)


def strike_gain(side: float, height: float) -> float:
    """The cue ball's speed per unit of the cue's speed in FastFiz's strike, cue level:
    2 / (1 + m/M + 5/2 (a^2 + b^2) / R^2), 1.57 at centre ball and 1.27 with the tip
    0.35 R off it. FastFiz's speed error (sigma V) is the cue's: the ball's strays by
    sigma V times this."""
    return 2.0 / (1.0 + FASTFIZ_MASS_RATIO + 2.5 * (side * side + height * height))


def perturb(
    shot: Shot,
    noise: np.ndarray,
    level: Level,
    squirt: bool = False,
    cue_speed: bool = True,
) -> Shot:
    """`shot` with standard-normal errors `noise` (aim, speed, side, height) at `level`.

    As the level's arm plays it (`Bot.execute`), the aim sigma is the whole error of the
    cue ball's line: the tip's error changes the spin, and the cue is turned against the
    squirt of the tip it struck. That is the tournaments' noise as FastFiz plays it (its
    cue strike sends the ball along the cue whatever the tip: sigma aim 0.125 degrees is
    a 0.125-degree line); with the engine's squirt on top, the pro's 0.5 mm tip error
    turned the line by about 0.075 degrees more. `squirt=True` lets the tip's error turn
    the line too: the search plans so, a little more error than its arm has, which
    cleared more runouts than planning with the arm's own (docs/ai.md, "Levels").

    The speed sigma is the cue's, as FastFiz's is (`strike_gain`): the ball's speed
    strays by about 1.3-1.6 times it. `cue_speed=False` puts the sigma on the ball's
    speed itself (the benchmark's break, so that its layouts stay the seeds' layouts
    that every runout figure in docs/ai.md was measured on)."""
    side, height = shot.tip
    gain = strike_gain(side, height) if cue_speed else 1.0
    if shot.elevation > 0.0:
        # A jump: the tip stays where it meets the ball (an error there could be a miscue
        # the arm would not play); the line and the speed stray as on any stroke.
        jumped = clamp_shot(
            shot.angle + float(noise[0]) * level.aim,
            shot.speed + float(noise[1]) * level.speed * gain,
            0.0,
            0.0,
        )
        return replace(shot, angle=jumped.angle, speed=jumped.speed)
    played = clamp_shot(
        shot.angle + float(noise[0]) * level.aim,
        shot.speed + float(noise[1]) * level.speed * gain,
        side + float(noise[2]) * level.tip,
        height + float(noise[3]) * level.tip,
    )
    if not squirt:
        played = clamp_shot(
            played.angle + shot.squirt() - played.squirt(), played.speed, *played.tip
        )
    return played if shot.ball == played.ball else replace(played, ball=shot.ball)


# The object ball's speed and the direction of the mouth's middle -> the directions in which
# it drops, and the simulations that took (as `pocket_window`).
Window = Callable[[float, float], tuple[tuple[float, float] | None, int]]


def aim_for_throw(
    table: Table,
    balls: BallSet,
    shot: Shot,
    target: int,
    pocket: int,
    window: Window | None = None,
) -> tuple[Shot, int]:
    """`shot` with its aim turned so that the exact stroke sends `target` at the centre of
    `pocket`, and the simulations that took. The ghost-ball line ignores the throw of the
    collision (the friction between the balls turns the object ball 1-3 degrees towards
    the cue ball's path on a slow cut, in the engine as on a real table); under the pro's
    aim error that alone missed a 30-degree cut of 0.8 m a third of the time
    (`tests/ai/test_bot.py`). A secant of two engine shots finds the aim; speed
    and tip stay.

    The centre is the middle of the mouth, or with `window` the middle of the directions
    in which the ball drops: a ball that comes at a corner pocket along a cushion drops
    over a range of directions that lies mostly to one side of the mouth's middle
    (docs/ai.md, item 3 of "How the search works")."""
    ox, oy = balls.position_of(target)
    ax, ay = pockets_of(table).aims[pocket]
    want = math.atan2(ay - oy, ax - ox)
    left = leaving(table, balls, shot, target)
    if left is None:
        return shot, 1
    first, speed = left
    used = 1
    if window is not None:
        edges, looked = window(speed, want)
        used += looked
        if edges is not None:
            want = (edges[0] + edges[1]) / 2
    nudged = clamp_shot(shot.angle + THROW_STEP, shot.speed, *shot.tip)
    second = departure(table, balls, nudged, target)
    used += 1
    if second is None:
        return shot, used
    err = math.remainder(first - want, 2 * math.pi)
    slope = math.remainder(second - first, 2 * math.pi) / THROW_STEP
    if abs(slope) < 1.0:  # the object ball hardly follows the aim: not a clean hit
        return shot, used
    if abs(err) > THROW_MAX:
        return shot, used
    step = -err / slope
    return clamp_shot(shot.angle + step, shot.speed, *shot.tip), used


def pocket_window(
    table: Table, balls: BallSet, target: int, pocket: int, speed: float, toward: float
) -> tuple[tuple[float, float] | None, int]:
    """The directions (lowest, highest) in which `target`, sent off at `speed` with no spin
    (as a hit ball leaves), drops in `pocket`: the run of them around `toward`, each edge
    found by steps of `WINDOW_STEP` and then halvings; and the simulations that took. The
    engine rolls the ball alone among the other object balls (the cue ball that hit it is
    gone), so the jaws, the facings and a ball near the path all count. None when it does
    not drop along `toward`; an edge further than `WINDOW_REACH` is put there."""
    alone = lone_ball(balls, target)
    used = 1
    if not rolls_in(table, alone, toward, speed, pocket):
        return None, used
    edges = []
    for sign in (-1.0, 1.0):
        inside, outside = 0.0, WINDOW_REACH
        while inside + WINDOW_STEP <= WINDOW_REACH:
            used += 1
            if not rolls_in(table, alone, toward + sign * (inside + WINDOW_STEP), speed, pocket):
                outside = inside + WINDOW_STEP
                break
            inside += WINDOW_STEP
        else:
            edges.append(toward + sign * WINDOW_REACH)
            continue
        for _ in range(WINDOW_HALVINGS):
            middle = (inside + outside) / 2
            used += 1
            if rolls_in(table, alone, toward + sign * middle, speed, pocket):
                inside = middle
            else:
                outside = middle
        edges.append(toward + sign * (inside + outside) / 2)
    return (edges[0], edges[1]), used


def lone_ball(balls: BallSet, target: int) -> BallSet:
    """The table with the cue ball gone and, in `target`'s place, a ball the engine can
    send off (the cue ball's id: a `Shot` strikes only that)."""
    placement = {b: balls.position_of(b) for b in balls.on_table_ids() if b not in (CUE, target)}
    placement[CUE] = balls.position_of(target)
    return BallSet.place(placement)


def rolls_in(table: Table, alone: BallSet, angle: float, speed: float, pocket: int) -> bool:
    """The lone ball of `lone_ball`, sent along `angle` at `speed` with no spin, drops in
    `pocket`."""
    result = settle(table, alone, Shot(math.remainder(angle, 2 * math.pi), speed, (0.0, 0.0)))
    final = result.final
    return int(final.pockets[final.index(CUE)]) == pocket


def _first_hit(events: Sequence[Event], target: int) -> int | None:
    """The index of the shot's first collision between balls when it is the cue ball's
    with `target`, else None (another ball was hit first, or none)."""
    hit = next((k for k, e in enumerate(events) if e.kind == "ball"), None)
    if hit is None or set(events[hit].ids) != {CUE, target}:
        return None
    return hit


def departure(table: Table, balls: BallSet, shot: Shot, target: int) -> float | None:
    """The direction `target` leaves in when `shot` hits it first (from the engine's
    frames, so with the throw), or None when it is not the first ball hit or is stopped
    at once."""
    left = leaving(table, balls, shot, target)
    return None if left is None else left[0]


def leaving(table: Table, balls: BallSet, shot: Shot, target: int) -> tuple[float, float] | None:
    """The direction `target` leaves in when `shot` hits it first, and its speed then (from
    the engine's frames, `THROW_LOOK` after the contact at most), or None when it is not
    the first ball hit or is stopped at once."""
    result = simulate(table, balls, shot)
    hit = _first_hit(result.events, target)
    if hit is None:
        return None
    contact = result.events[hit]
    later = [e.time for e in result.events if e.time > contact.time and target in e.ids]
    until = min([*later, contact.time + THROW_LOOK])
    frames = result.frames
    k = min(int(until / frames.tick) - 1, len(frames) - 1)
    if k < 0 or (k + 1) * frames.tick <= contact.time:
        return None
    row = result.final.index(target)  # the rows of the frames are those of the set
    x, y = frames.positions[k, row]
    ox, oy = balls.position_of(target)
    travelled = math.hypot(x - ox, y - oy)
    if travelled < 1e-3:
        return None
    elapsed = (k + 1) * frames.tick - contact.time
    return math.atan2(y - oy, x - ox), travelled / elapsed


def aim_carom(
    table: Table, balls: BallSet, shot: Shot, target: int, pocket: int, first: int | None = None
) -> tuple[Shot, int]:
    """`shot` with its aim turned so that the exact stroke's carom sends `target` at the
    centre of `pocket`, and the simulations that took. After the kiss the ball bends
    forward as it rolls, by an amount that depends on the speed and the distance, and the
    kiss throws it: the geometry's aim missed most caroms without noise. A secant on
    where the ball goes after the kiss (`kiss_miss`), `CAROM_STEPS` engine shots at most;
    speed and tip stay, and the aim that missed least is kept. `first`: for a billiard, the
    ball the cue ball glances off into `target` (`kiss_miss`)."""
    miss = kiss_miss(table, balls, shot, target, pocket, first)
    if miss is None:
        return shot, 1
    best, best_miss, used = shot, abs(miss), 1
    a0, m0 = shot.angle, miss
    a1 = shot.angle + CAROM_NUDGE
    for _ in range(CAROM_STEPS):
        if abs(math.remainder(a1 - shot.angle, 2 * math.pi)) > CAROM_MAX:
            break
        trial = clamp_shot(a1, shot.speed, *shot.tip)
        m1 = kiss_miss(table, balls, trial, target, pocket, first)
        used += 1
        if m1 is None:
            break
        if abs(m1) < best_miss:
            best, best_miss = trial, abs(m1)
        if abs(m1) < CAROM_DONE or m1 == m0:
            break
        a0, m0, a1 = a1, m1, a1 - m1 * (a1 - a0) / (m1 - m0)
    return best, used


def kiss_miss(
    table: Table,
    balls: BallSet,
    shot: Shot,
    target: int,
    pocket: int,
    first: int | None = None,
) -> float | None:
    """How far (radians, seen from where `target` kissed another ball) its path then
    misses `pocket`'s aim point: where it is when it has come as far as the pocket, or
    when it next meets anything. None when the cue ball does not hit `target` first or
    `target` meets something else before its kiss. With `first` (a billiard) the cue ball
    must hit `first` first, and `target`'s kiss is the cue ball's, after that glance."""
    result = simulate(table, balls, shot)
    events = result.events
    hit = _first_hit(events, target if first is None else first)
    if hit is None:
        return None
    mine = [e for e in events[hit + 1 :] if target in e.ids]
    if not mine or mine[0].kind != "ball" or (CUE in mine[0].ids) != (first is not None):
        return None
    frames = result.frames
    row = result.final.index(target)  # the rows of the frames are those of the set
    start = min(max(int(mine[0].time / frames.tick), 0), len(frames) - 1)
    end = len(frames) - 1
    if len(mine) > 1:
        end = min(max(int(mine[1].time / frames.tick) - 1, start), end)
    path = frames.positions[start : end + 1, row]
    origin = path[0]
    aim = pockets_of(table).aims[pocket]
    reach = float(np.hypot(*(aim - origin)))
    far = np.nonzero(np.hypot(*(path - origin).T) >= reach)[0]
    x, y = path[far[0]] if len(far) else path[-1]
    if math.hypot(x - origin[0], y - origin[1]) < 1e-3:
        return None
    return math.remainder(
        math.atan2(y - origin[1], x - origin[0])
        - math.atan2(aim[1] - origin[1], aim[0] - origin[0]),
        2 * math.pi,
    )
