"""The facts a referee needs from a shot, read from the engine's events and final table.

A ball the engine put out of play is pocketed, or off the table (a jump that cleared a
rail: its pocket is `OFF_TABLE`); the cue ball off the table is a scratch (WPA General
Rules, "cue ball scratch or off the table").
The struck ball is the cue ball (0) unless told (carom: the striker's white or yellow).
Given the balls' radius, a played shot's facts also say which balls the cue ball jumped
over before its first contact (`jumps.passed_over`; a `Settled` shot cannot tell).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from server.engine import CUE, OFF_TABLE, BallSet, EventKind, MotionState, Settled, ShotResult
from server.engine.results import EVENT_CODES

from .jumps import passed_over

# Kind codes of `contacts()` (read once: a shot's facts are read for every simulated shot).
_BALL, _CUSHION, _JAW, _POCKET = (
    EVENT_CODES.index(kind)
    for kind in (EventKind.BALL, EventKind.CUSHION, EventKind.JAW, EventKind.POCKET)
)
_POCKETED = int(MotionState.POCKETED)  # a ball's state code once it dropped


@dataclass(frozen=True)
class ShotFacts:
    """What happened on one shot.

    first_contact: the first object ball the cue ball touched, or None.
    rail_after_contact: some ball reached a cushion (or a pocket point) after that contact.
    pocketed: object balls that dropped, in the order they dropped.
    pockets: pocket index (into `Table.pockets`) of each dropped ball, cue ball included.
    scratch: the cue ball dropped, or left the table.
    balls_to_rail: distinct object balls that reached a cushion (counts for a legal break).
    off_table: object balls that left the table (never in `pocketed`), in id order.
    cue_off_table: the cue ball left the table (a scratch).
    cue_path: what the struck ball met, in order: a ball's id, or -1 for a cushion (carom).
    final: the table at rest after the shot, before the rules re-spot anything (not a
    fact compared: the facts of a settled and a simulated shot are equal).
    jumped_over: object balls the cue ball passed over in the air before its first
    contact (WPBSA Jump Shot); read only from a simulated shot's frames, so not compared.
    """

    first_contact: int | None
    rail_after_contact: bool
    pocketed: tuple[int, ...]
    pockets: dict[int, int]
    scratch: bool
    balls_to_rail: frozenset[int]
    off_table: tuple[int, ...] = ()
    cue_off_table: bool = False
    cue_path: tuple[int, ...] = ()
    final: BallSet | None = field(default=None, compare=False, repr=False)
    jumped_over: tuple[int, ...] = field(default=(), compare=False)

    @property
    def any_pocketed(self) -> bool:
        return bool(self.pocketed)


def shot_facts(
    before: BallSet, result: ShotResult | Settled, cue: int = CUE, radius: float | None = None
) -> ShotFacts:
    """Facts of `result`, a shot played from the table `before` (its final table has
    `before`'s rows, as the engine keeps them). With the balls' `radius`, a `ShotResult`'s
    jumps are read too (`jumped_over`).

    Events give the order and the pockets; `result.final` is the authority on which balls
    dropped (a ball off in `final` but on in `before` dropped even if no event says so).
    """
    first_contact: int | None = None
    contact_seen = False
    rail_after_contact = False
    order: list[int] = []
    pockets: dict[int, int] = {}
    to_rail: set[int] = set()
    path: list[int] = []
    for code, ball, other, target in result.contacts():
        if code == _BALL:
            if ball == cue or other == cue:
                met = other if ball == cue else ball
                path.append(met)
                if not contact_seen:
                    first_contact = met
                    contact_seen = True
        elif code in (_CUSHION, _JAW):  # a pocket's point is a rail too
            if contact_seen:
                rail_after_contact = True
            if ball != cue:
                to_rail.add(ball)
            else:
                path.append(-1)
        elif code == _POCKET and ball not in pockets:
            order.append(ball)
            pockets[ball] = target
    final = result.final
    dropped, flown = _out_of_play(before, final)
    if dropped != pockets.keys():
        for ball in sorted(dropped - set(order)):
            order.append(ball)
            pockets[ball] = int(final.pockets[final.index(ball)])
        order = [b for b in order if b in dropped]
        pockets = {b: p for b, p in pockets.items() if b in dropped}
    return ShotFacts(
        first_contact=first_contact,
        rail_after_contact=rail_after_contact,
        pocketed=tuple(b for b in order if b != cue),
        pockets=pockets,
        scratch=cue in dropped or cue in flown,
        balls_to_rail=frozenset(to_rail),
        off_table=tuple(sorted(flown - {cue})),
        cue_off_table=cue in flown,
        cue_path=tuple(path),
        final=final,
        jumped_over=_jumped(before, result, cue, radius),
    )


def _jumped(
    before: BallSet, result: ShotResult | Settled, cue: int, radius: float | None
) -> tuple[int, ...]:
    if radius is None or not isinstance(result, ShotResult):
        return ()
    return passed_over(before, result, radius, cue)


def _out_of_play(before: BallSet, final: BallSet) -> tuple[set[int], set[int]]:
    """The balls the shot put out of play: those that dropped into a pocket, and those
    that left the table (pocket `OFF_TABLE`)."""
    gone = (before.states != _POCKETED) & (final.states == _POCKETED)
    if not gone.any():
        return set(), set()
    off = gone & (final.pockets == OFF_TABLE)
    return set(final.ids[gone & ~off].tolist()), set(final.ids[off].tolist())
