"""Pots that do not go straight from the object ball to the pocket: banks (the object ball
off one cushion), combinations (the cue ball sends one ball into another, which drops),
caroms (the object ball glances off another ball into the pocket) and billiards (the cue
ball glances off the ball it must hit first into the ball that drops).

Geometry only, like `geometry.pot_options`: where to aim, whether the paths are clear and a
rough chance to rank them by; the search simulates each with the engine, so the cushion's
real rebound and the throw between the balls decide what is played.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import replace

import numpy as np

from server.engine import CUE, BallSet, Table

from .geometry import (
    GEOMETRIC,
    MAX_CUT,
    ChanceModel,
    PotOption,
    clean_window,
    drop_chance,
    ghost_error,
    object_sigma,
    path_clear,
    pockets_of,
)

# The cushion sends a ball back with its normal speed times about this (the engine's
# e_cushion is 0.85; the friction of the nose and the spin move the rebound too), so a
# bank is aimed for each of these and the simulations pick the one that drops.
BANK_RESTITUTIONS = (0.55, 0.7, 0.85)
BANK_SIGMA = 0.02  # rad the cushion adds to the object ball's error (no two rebounds alike)
BANK_CLEAR_OF_POCKET = 0.12  # m: a bounce this near a pocket's mouth meets the jaws
MAX_COMBO_CUT = math.radians(50.0)  # thinner cuts of the second ball are not tried
MAX_LINK = 1.0  # m from the first ball to the second's ghost ball: longer is hopeless
MIN_COS_IN = 0.35  # the approach to a mouth must be at most about 70 degrees off square
# A carom's ball leaves the kiss along the tangent line when it slides and bends forward
# when it rolls (its path ends along 5 * tangent + 2 * share * incoming). A struck ball
# slides at first and rolls after about 12 v^2 / (49 mu g): 0.28 m at 1.5 m/s on the
# engine's cloth (mu 0.2), so the share is taken as the distance to the kiss over that.
CAROM_ROLL_DISTANCE = 0.28
MIN_KISS_CUT = math.radians(20.0)  # fuller, the ball stops on the kiss
MAX_KISS_CUT = math.radians(72.0)  # thinner, the smallest error turns it off the line
MAX_CAROM_LINK = 0.3  # m from the ball to the kiss
KISS_STEPS = 720  # contact points tried round the kissed ball before refining
MAX_BILLIARD_LINK = 0.6  # m the cue ball may travel from the first ball to the ball to pot
# A billiard's cue ball is struck harder than a carom's ball (it keeps only part of its
# speed at the glance), so it slides further before it rolls (0.5 m at 2 m/s, 1.1 m at
# 3 m/s): its rolling share at the glance is taken as this times a carom's. On 1,000 random
# tables the engine corrected 659 billiards' exact strokes into drops at 0.35, 329 at 1
# (`python -m bench.caroms --tables 1000 --seed 0 --kind billiard`).
BILLIARD_ROLL = 0.35


def _rows(balls: BallSet) -> tuple[list[int], np.ndarray, np.ndarray, int]:
    """(ball ids by row, positions, which are on the table, the cue ball's row)."""
    ids = balls.ids.tolist()
    return ids, balls.positions, balls.on_table, ids.index(CUE)


def _object_rows(ids: list[int], on: np.ndarray) -> dict[int, int]:
    """The row of each object ball on the table, by id (in the rows' order)."""
    return {b: row for row, b in enumerate(ids) if b != CUE and on[row]}


def _clear(
    positions: np.ndarray,
    on: np.ndarray,
    skip: tuple[int, int],
    a: np.ndarray,
    b: np.ndarray,
    r: float,
) -> bool:
    """Whether no ball on the table but the rows `skip` (the balls that travel the path)
    lies within a ball's width of the path a->b (`geometry.path_clear`)."""
    return bool(
        path_clear(float(a[0]), float(a[1]), float(b[0]), float(b[1]), positions, on, *skip, r)
    )


def _sigma(model: ChanceModel, aim_error: float, cut: float, extra: float) -> float:
    """The object ball's angle error under `model` (`geometry.object_sigma` with its aim
    scale, floor and cut term) for an unscaled aim error and a cut, plus `extra`."""
    return float(
        object_sigma(model.aim_scale * aim_error, math.sin(cut), model.floor, model.cut, extra)
    )


def _window(model: ChanceModel, mouth: float, cos_in: float, r: float, side: float) -> float:
    """The mouth's clean window under `model`, as `geometry.pot_options` has it."""
    return float(clean_window(mouth, cos_in, r, model.jaw)) - model.side * side


def _approach(
    table: Table, cue: np.ndarray, ball: np.ndarray, u: np.ndarray
) -> tuple[np.ndarray, np.ndarray, float, float] | None:
    """(ghost ball, cue ball to ghost ball, its length, cos of the cut) for sending `ball`
    along the unit vector `u`, or None when the ghost ball is off the bed or the cut is
    too thin."""
    r = table.ball_radius
    ghost = ball - 2 * r * u
    if not (r <= ghost[0] <= table.length - r and r <= ghost[1] <= table.width - r):
        return None
    to_ghost = ghost - cue
    d1 = float(np.linalg.norm(to_ghost))
    if d1 < 1e-6:
        return None
    cos_cut = float(to_ghost @ u) / d1
    if cos_cut <= math.cos(MAX_CUT):
        return None
    return ghost, to_ghost, d1, cos_cut


def _through(
    table: Table,
    positions: np.ndarray,
    on: np.ndarray,
    rows: tuple[tuple[int, int], tuple[int, int]],
    turn: np.ndarray,
    pocket: int,
    model: ChanceModel,
) -> tuple[np.ndarray, float, float, float] | None:
    """How the cue ball (row `rows[0][0]`) sends the ball in row `rows[0][1]` to `turn`
    (the bounce point of a bank, or its centre at the kiss of a carom) and on into
    `pocket`: (cue ball to ghost ball, its length, cos of the cut, the mouth's window
    under `model`), or None when the approach to the mouth is too steep, the ghost ball is
    off the bed, the cut is too thin or a path is blocked. The rows `rows[0]` travel the
    cue ball's way and `rows[1]` the ball's two legs."""
    r = table.ball_radius
    pk = pockets_of(table)
    cue, ball = positions[rows[0][0]], positions[rows[0][1]]
    aim = pk.aims[pocket]
    leg1, leg2 = turn - ball, aim - turn
    d_leg1, d_leg2 = float(np.linalg.norm(leg1)), float(np.linalg.norm(leg2))
    cos_in = float(leg2 @ pk.outward[pocket]) / d_leg2
    window = _window(model, pk.mouths[pocket], cos_in, r, pk.side[pocket])
    if cos_in <= MIN_COS_IN or window <= 0.003:
        return None
    approach = _approach(table, cue, ball, leg1 / d_leg1)
    if approach is None:
        return None
    ghost, to_ghost, d1, cos_cut = approach
    if not (
        _clear(positions, on, rows[0], cue, ghost, r)
        and _clear(positions, on, rows[1], ball, turn, r)
        and _clear(positions, on, rows[1], turn, aim, r)
    ):
        return None
    return to_ghost, d1, cos_cut, window


def bank_options(
    table: Table,
    balls: BallSet,
    targets: list[int],
    aim_sigma: float,
    model: ChanceModel = GEOMETRIC,
    restitutions: tuple[float, ...] = BANK_RESTITUTIONS,
) -> list[PotOption]:
    """One-cushion banks of the balls `targets`, best chance first: for each pocket and
    each cushion it is not on, the bounce point where a ball leaving the cushion with its
    normal speed times e (each of `restitutions`) runs into the pocket (the aims of one
    route share its `route` and its best chance, so they come out together). Rejected when a
    path (cue ball to ghost ball, object ball to cushion, cushion to pocket) is blocked,
    the bounce is near a pocket, the cut is too thin or the approach to the mouth too
    steep."""
    r = table.ball_radius
    pk = pockets_of(table)
    ids, positions, on, cue_row = _rows(balls)
    if not on[cue_row]:
        return []
    # Each cushion as the line the ball's centre bounces on: (axis, coordinate).
    lines = ((0, r), (0, table.length - r), (1, r), (1, table.width - r))
    out: list[PotOption] = []
    for target in targets:
        if target == CUE or target not in ids or not on[ids.index(target)]:
            continue
        row = ids.index(target)
        obj = positions[row]
        for p in range(len(pk.aims)):
            aim = pk.aims[p]
            for axis, c in lines:
                h1, h2 = abs(obj[axis] - c), abs(aim[axis] - c)
                if h1 < 2 * r or h2 < 0.1:  # frozen on it, or the pocket is on this cushion
                    continue
                along = 1 - axis
                aims: list[PotOption] = []
                for e in restitutions:
                    # The bounce point: tangential travel shares the run in the ratio of
                    # h1 to h2 / e (the normal speed leaves at e times what it came in at).
                    run = aim[along] - obj[along]
                    first = run / (1 + h2 / (e * h1))
                    bounce = np.empty(2)
                    bounce[axis], bounce[along] = c, obj[along] + first
                    if min(np.hypot(*(pk.aims - bounce).T)) < BANK_CLEAR_OF_POCKET:
                        continue
                    option = _bank(
                        table, positions, on, (cue_row, row), bounce, p, target, aim_sigma, model
                    )
                    if option is not None:
                        aims.append(option)
                # One chance for the route, so that its aims stay together when sorted.
                best = max((o.chance for o in aims), default=0.0)
                route = len(out)
                out.extend(replace(o, chance=best, route=route) for o in aims)
    out.sort(key=lambda o: -o.chance)
    return out


def _bank(
    table: Table,
    positions: np.ndarray,
    on: np.ndarray,
    rows: tuple[int, int],
    bounce: np.ndarray,
    pocket: int,
    target: int,
    aim_sigma: float,
    model: ChanceModel,
) -> PotOption | None:
    """The bank of the ball in row `rows[1]` off `bounce` into `pocket` (the cue ball in
    row `rows[0]`), or None when it cannot be played. Its chance is the direct pot's
    estimate over the whole path, with the cushion's scatter added."""
    r = table.ball_radius
    obj = positions[rows[1]]
    aim = pockets_of(table).aims[pocket]
    d_leg1 = float(np.linalg.norm(bounce - obj))
    d_leg2 = float(np.linalg.norm(aim - bounce))
    if d_leg1 < 1e-6 or d_leg2 < 1e-6:
        return None
    way = _through(table, positions, on, (rows, rows), bounce, pocket, model)
    if way is None:
        return None
    to_ghost, d1, cos_cut, window = way
    cut = math.acos(min(1.0, cos_cut))
    d2 = d_leg1 + d_leg2
    aim_error = ghost_error(d1, aim_sigma, cos_cut, r, 1.0)
    sigma = _sigma(model, aim_error, cut, BANK_SIGMA)
    return PotOption(
        target=target,
        pocket=pocket,
        angle=math.atan2(to_ghost[1], to_ghost[0]),
        chance=float(drop_chance(window, d2, sigma)),
        d1=d1,
        d2=d2,
        cut=cut,
        via="bank",
    )


def combo_options(
    table: Table,
    balls: BallSet,
    carriers: list[int],
    objects: list[int],
    aim_sigma: float,
    model: ChanceModel = GEOMETRIC,
) -> list[PotOption]:
    """Combinations, best chance first: the cue ball sends a ball of `carriers` (a legal
    first ball) into a ball of `objects`, which drops. Rejected when a path is blocked, a
    cut is too thin (the second under `MAX_COMBO_CUT`), the first ball is more than
    `MAX_LINK` from the second's ghost ball or the approach to the mouth is too steep.
    The chance carries the first ball's angle error through the second collision."""
    r = table.ball_radius
    ids, positions, on, cue_row = _rows(balls)
    if not on[cue_row]:
        return []
    cue = positions[cue_row]
    present = _object_rows(ids, on)
    out: list[PotOption] = []
    for second in objects:
        if second not in present:
            continue
        row_b = present[second]
        for p, d2, u_b, window in _pocket_ways(table, positions, on, row_b, cue_row, model):
            ghost_b = positions[row_b] - 2 * r * u_b
            for first in carriers:
                if first == second or first not in present:
                    continue
                option = _combo(
                    table, positions, on, cue_row, present[first], row_b, cue, ghost_b, u_b
                )
                if option is not None:
                    route = (second, p, first, "combo")
                    out.append(_relayed(route, option, window, d2, aim_sigma, model, r))
    out.sort(key=lambda o: -o.chance)
    return out


def _pocket_ways(
    table: Table,
    positions: np.ndarray,
    on: np.ndarray,
    row: int,
    cue_row: int,
    model: ChanceModel,
) -> Iterator[tuple[int, float, np.ndarray, float]]:
    """The pockets the ball in row `row` can be sent into, struck by another ball (a
    combination's second ball, a billiard's ball to pot): (pocket, distance to its aim
    point, unit direction there, the mouth's window under `model`), for each whose approach
    is not too steep and whose path is clear (of all but that ball and the cue ball)."""
    r = table.ball_radius
    pk = pockets_of(table)
    ball = positions[row]
    for p in range(len(pk.aims)):
        to_pocket = pk.aims[p] - ball
        d2 = float(np.linalg.norm(to_pocket))
        if d2 < 1e-6:
            continue
        u = to_pocket / d2
        cos_in = float(u @ pk.outward[p])
        window = _window(model, pk.mouths[p], cos_in, r, pk.side[p])
        if cos_in <= MIN_COS_IN or window <= 0.003:
            continue
        if _clear(positions, on, (cue_row, row), ball, pk.aims[p], r):
            yield p, d2, u, window


def _relayed(
    route: tuple[int, int, int, str],
    way: tuple[float, float, float, float, float],
    window: float,
    d2: float,
    aim_sigma: float,
    model: ChanceModel,
    r: float,
) -> PotOption:
    """A pot through two collisions, a combination or a billiard: `route` is (the ball to
    pot, the pocket, the first ball, `via`), `way` (cue ball to the first contact, the link
    to the second, the cut of each, the cue's direction). The first ball's angle error
    turns the path to the second collision, where it grows by the link over a ball's width."""
    target, pocket, carrier, via = route
    d1, link, cut_a, cut_b, angle = way
    error_a = ghost_error(d1, aim_sigma, math.cos(cut_a), r, 1.0)
    aim_error = ghost_error(link, error_a, math.cos(cut_b), r, 1.0)
    sigma = _sigma(model, aim_error, cut_b, 0.0)
    return PotOption(
        target=target,
        pocket=pocket,
        angle=angle,
        chance=float(drop_chance(window, d2, sigma)),
        d1=d1,
        d2=d2,
        cut=cut_a,
        via=via,
        carrier=carrier,
        link=link,
        link_cut=cut_b,
    )


def _combo(
    table: Table,
    positions: np.ndarray,
    on: np.ndarray,
    cue_row: int,
    row_a: int,
    row_b: int,
    cue: np.ndarray,
    ghost_b: np.ndarray,
    u_b: np.ndarray,
) -> tuple[float, float, float, float, float] | None:
    """(d1, link, cut on the first ball, cut on the second, cue angle) of the combination
    through row `row_a`, or None when it cannot be played."""
    r = table.ball_radius
    ball_a = positions[row_a]
    to_b = ghost_b - ball_a
    link = float(np.linalg.norm(to_b))
    if link < 1e-6 or link > MAX_LINK:
        return None
    u_a = to_b / link
    cos_b = float(u_a @ u_b)
    if cos_b <= math.cos(MAX_COMBO_CUT):
        return None
    approach = _approach(table, cue, ball_a, u_a)
    if approach is None:
        return None
    ghost_a, to_ghost, d1, cos_a = approach
    # The second ball counts on the cue ball's way (hit first, it is not a combination);
    # the cue ball does not on the first ball's (it has left its spot by then).
    if not (
        _clear(positions, on, (cue_row, row_a), cue, ghost_a, r)
        and _clear(positions, on, (row_a, row_b), ball_a, ghost_b, r)
    ):
        return None
    return (
        d1,
        link,
        math.acos(min(1.0, cos_a)),
        math.acos(min(1.0, cos_b)),
        math.atan2(to_ghost[1], to_ghost[0]),
    )


def carom_options(
    table: Table,
    balls: BallSet,
    targets: list[int],
    aim_sigma: float,
    model: ChanceModel = GEOMETRIC,
) -> list[PotOption]:
    """Caroms, best chance first: the cue ball sends a ball of `targets` into another ball
    (any but the cue ball), off which it glances into a pocket. For each kissed ball,
    pocket and side, the contact from which the ball's path after the kiss runs into the
    pocket (`CAROM_ROLL_DISTANCE`; the search then lets the engine correct the aim:
    `aiming.aim_carom`). Rejected when a path is blocked, the kiss is too full or
    too thin, the ball is more than `MAX_CAROM_LINK` from it or the approach to the mouth
    is too steep. The chance carries the ball's angle error through the kiss, as for a
    combination."""
    r = table.ball_radius
    pk = pockets_of(table)
    ids, positions, on, cue_row = _rows(balls)
    if not on[cue_row]:
        return []
    present = _object_rows(ids, on)
    out: list[PotOption] = []
    for target in targets:
        if target not in present:
            continue
        row = present[target]
        for kiss, row_k in present.items():
            gap = float(np.linalg.norm(positions[row_k] - positions[row]))
            if kiss == target or gap < 2.2 * r or gap > MAX_CAROM_LINK + 2 * r:
                continue
            roll = min(1.0, (gap - 2 * r) / CAROM_ROLL_DISTANCE)
            for p in range(len(pk.aims)):
                for contact in _kiss_points(positions[row], positions[row_k], pk.aims[p], r, roll):
                    rows = (cue_row, row, row_k)
                    option = _carom(
                        table, positions, on, rows, contact, (target, kiss, p), aim_sigma, model
                    )
                    if option is not None:
                        out.append(option)
    out.sort(key=lambda o: -o.chance)
    return out


def _kiss_points(
    ball: np.ndarray, kiss: np.ndarray, aim: np.ndarray, r: float, roll: float
) -> list[np.ndarray]:
    """The ball's centre at the kiss for each way `ball` can glance off `kiss` into `aim`
    with rolling share `roll`: the zeros, round the kissed ball, of the angle between the
    path after the kiss and the line to the pocket."""
    alpha = np.linspace(-math.pi, math.pi, KISS_STEPS, endpoint=False)
    outward = np.stack((np.cos(alpha), np.sin(alpha)), axis=1)
    contacts = kiss + 2 * r * outward
    incoming = contacts - ball
    incoming /= np.linalg.norm(incoming, axis=1)[:, None]
    normal = -outward  # from the contact to the kissed ball's centre
    cos_kiss = (incoming * normal).sum(axis=1)
    leaves = 5 * (incoming - cos_kiss[:, None] * normal) + 2 * roll * incoming
    to_aim = aim - contacts
    miss = leaves[:, 0] * to_aim[:, 1] - leaves[:, 1] * to_aim[:, 0]
    ok = (
        (cos_kiss > math.cos(MAX_KISS_CUT))
        & (cos_kiss < math.cos(MIN_KISS_CUT))
        & ((leaves * to_aim).sum(axis=1) > 0)
    )
    nxt = np.roll(np.arange(KISS_STEPS), -1)
    found = []
    for i in np.nonzero(ok & ok[nxt] & (np.sign(miss) != np.sign(miss[nxt])))[0]:
        j = nxt[i]
        share = miss[i] / (miss[i] - miss[j])
        a = alpha[i] + share * (2 * math.pi / KISS_STEPS)
        found.append(kiss + 2 * r * np.array([math.cos(a), math.sin(a)]))
    return found


def _carom(
    table: Table,
    positions: np.ndarray,
    on: np.ndarray,
    rows: tuple[int, int, int],
    contact: np.ndarray,
    route: tuple[int, int, int],
    aim_sigma: float,
    model: ChanceModel,
) -> PotOption | None:
    """The carom of the ball in row `rows[1]` off the ball in row `rows[2]` (the cue ball
    in row `rows[0]`), its centre at `contact` at the kiss, or None when it cannot be
    played; `route` is (that ball, the kissed ball, the pocket)."""
    r = table.ball_radius
    target, kiss_ball, pocket = route
    ball, kiss = positions[rows[1]], positions[rows[2]]
    to_kiss = contact - ball
    link = float(np.linalg.norm(to_kiss))
    d2 = float(np.linalg.norm(pockets_of(table).aims[pocket] - contact))
    if link < 1e-3 or link > MAX_CAROM_LINK or d2 < 1e-6:
        return None
    way = _through(table, positions, on, (rows[:2], rows[1:]), contact, pocket, model)
    if way is None:
        return None
    to_ghost, d1, cos_cut, window = way
    cos_kiss = float((to_kiss / link) @ (kiss - contact)) / (2 * r)
    # The ball's angle error moves the kiss's contact: the path after it turns by the
    # offset over a ball's width times the cosine of the kiss's cut.
    error = ghost_error(d1, aim_sigma, cos_cut, r, 1.0)
    kiss_cut = math.acos(min(1.0, cos_kiss))
    aim_error = ghost_error(link, error, cos_kiss, r, 1.0)
    return PotOption(
        target=target,
        pocket=pocket,
        angle=math.atan2(to_ghost[1], to_ghost[0]),
        chance=float(drop_chance(window, d2, _sigma(model, aim_error, kiss_cut, 0.0))),
        d1=d1,
        d2=d2,
        cut=math.acos(min(1.0, cos_cut)),
        via="carom",
        carrier=kiss_ball,
        link=link,
        link_cut=math.pi / 2 - kiss_cut,
    )


def billiard_options(
    table: Table,
    balls: BallSet,
    firsts: list[int],
    objects: list[int],
    aim_sigma: float,
    model: ChanceModel = GEOMETRIC,
) -> list[PotOption]:
    """Billiards, best chance first: the cue ball glances off a ball of `firsts` (a legal
    first ball) into a ball of `objects`, which drops; in 9-ball, off the lowest ball into
    the 9. For each first ball, ball to pot and pocket, the contact on the first ball from
    which the cue ball's path after the glance runs to the ghost ball of the ball to pot
    (`_kiss_points`, the cue ball bending forward by the share it rolls, `BILLIARD_ROLL`;
    the search then lets the engine correct the aim: `aiming.aim_carom`). Rejected when a
    path is blocked, the glance is too full or too thin, the cue ball would travel more
    than `MAX_BILLIARD_LINK` after it, the cut on the ball to pot is over `MAX_COMBO_CUT`
    or the approach to the mouth is too steep. The chance carries the cue ball's error
    through the glance and the link, as a combination's."""
    r = table.ball_radius
    ids, positions, on, cue_row = _rows(balls)
    if not on[cue_row]:
        return []
    cue = positions[cue_row]
    present = _object_rows(ids, on)
    out: list[PotOption] = []
    for first in firsts:
        if first not in present:
            continue
        row_a = present[first]
        to_first = float(np.linalg.norm(positions[row_a] - cue))
        roll = BILLIARD_ROLL * min(1.0, max(to_first - 2 * r, 0.0) / CAROM_ROLL_DISTANCE)
        for second in objects:
            if second == first or second not in present:
                continue
            row_b = present[second]
            for p, d2, u_b, window in _pocket_ways(table, positions, on, row_b, cue_row, model):
                ghost_b = positions[row_b] - 2 * r * u_b
                if not (r <= ghost_b[0] <= table.length - r and r <= ghost_b[1] <= table.width - r):
                    continue
                if np.linalg.norm(ghost_b - positions[row_a]) > MAX_BILLIARD_LINK + 2 * r:
                    continue
                for contact in _kiss_points(cue, positions[row_a], ghost_b, r, roll):
                    rows = (cue_row, row_a, row_b)
                    way = _billiard(table, positions, on, rows, contact, ghost_b, u_b)
                    if way is not None:
                        route = (second, p, first, "billiard")
                        out.append(_relayed(route, way, window, d2, aim_sigma, model, r))
    out.sort(key=lambda o: -o.chance)
    return out


def _billiard(
    table: Table,
    positions: np.ndarray,
    on: np.ndarray,
    rows: tuple[int, int, int],
    contact: np.ndarray,
    ghost_b: np.ndarray,
    u_b: np.ndarray,
) -> tuple[float, float, float, float, float] | None:
    """The cue ball (row `rows[0]`) glancing off the ball in row `rows[1]` with its centre
    at `contact`, on to `ghost_b` to send the ball in row `rows[2]` along `u_b`: (cue ball
    to contact, contact to ghost ball, cut on the first ball, cut on the second, the cue's
    direction), or None when it cannot be played."""
    r = table.ball_radius
    cue_row, row_a, row_b = rows
    cue, ball_a = positions[cue_row], positions[row_a]
    to_contact = contact - cue
    d1 = float(np.linalg.norm(to_contact))
    to_ghost = ghost_b - contact
    link = float(np.linalg.norm(to_ghost))
    if d1 < 1e-6 or link < 1e-3 or link > MAX_BILLIARD_LINK:
        return None
    cos_a = float(to_contact @ (ball_a - contact)) / (d1 * 2 * r)
    cos_b = float(to_ghost @ u_b) / link
    if cos_b <= math.cos(MAX_COMBO_CUT):
        return None
    # The first ball leaves along the line of centres, out of the cue ball's way.
    after = on.copy()
    after[row_a] = False
    if not (
        _clear(positions, on, (cue_row, row_a), cue, contact, r)
        and _clear(positions, after, (cue_row, row_b), contact, ghost_b, r)
    ):
        return None
    cut_a = math.acos(max(-1.0, min(1.0, cos_a)))
    cut_b = math.acos(max(-1.0, min(1.0, cos_b)))
    return d1, link, cut_a, cut_b, math.atan2(to_contact[1], to_contact[0])
