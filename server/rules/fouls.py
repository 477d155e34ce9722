"""The fouls, each a code for programs and a sentence for people."""

from __future__ import annotations

from .outcome import Foul
from .words import and_list, ball, snooker_ball

LABELS = {
    "scratch": "scratch",
    "no_contact": "no ball hit",
    "wrong_ball_first": "wrong ball first",
    "no_rail": "no rail after contact",
    "illegal_break": "illegal break",
    "shot_clock": "time ran out",
    "ball_off_table": "ball off the table",
    "in_off": "in-off",
    "potted_not_on": "a ball not on potted",
    "miss": "a miss",
    "jump_shot": "a jump shot",
}


def label(foul: Foul) -> str:
    """Short words for the outcome line 'Foul: scratch.'."""
    return LABELS.get(foul.code, foul.code.replace("_", " "))


def scratch(name: str, off_table: bool = False) -> Foul:
    """The cue ball pocketed, or driven off the table (WPA General Rules: both scratches)."""
    if off_table:
        return Foul("scratch", f"{name} scratched: the cue ball left the table.")
    return Foul("scratch", f"{name} scratched: the cue ball went into a pocket.")


def ball_off_table(name: str, off: tuple[int, ...]) -> Foul:
    """An object ball driven off the table (WPA General Rules, "balls driven off the
    table": a foul; whether it comes back is the game's rule)."""
    words = ", ".join(ball(b) for b in off)
    return Foul("ball_off_table", f"{name} drove {words} off the table.")


def no_contact(name: str) -> Foul:
    return Foul("no_contact", f"{name}'s cue ball did not touch any object ball.")


def wrong_ball_first(name: str, hit: int, expected: str) -> Foul:
    return Foul(
        "wrong_ball_first", f"{name} hit {ball(hit)} first; the first ball hit must be {expected}."
    )


def no_rail(name: str) -> Foul:
    return Foul(
        "no_rail", f"After {name}'s cue ball hit a ball, no ball was pocketed or reached a rail."
    )


def illegal_break(name: str, to_rail: int) -> Foul:
    return Foul(
        "illegal_break",
        f"{name}'s break pocketed no ball and drove only {to_rail} object "
        f"ball{'s' if to_rail != 1 else ''} to a rail (four are needed).",
    )


def shot_clock(name: str) -> Foul:
    return Foul("shot_clock", f"{name} ran out of time to shoot.")


# Snooker (WPBSA 2.15 Infringements, Fouls and Penalties; 3.11 Penalty Values; 3.14 Foul
# and a Miss).
def no_ball_hit(name: str) -> Foul:
    return Foul("no_contact", f"{name}'s cue ball did not touch any ball.")


def snooker_wrong_first(name: str, hit: int, expected: str) -> Foul:
    return Foul(
        "wrong_ball_first", f"{name} hit {snooker_ball(hit)} first; the ball on was {expected}."
    )


def potted_not_on(name: str, potted: list[int]) -> Foul:
    said = and_list(snooker_ball(b) for b in potted)
    return Foul("potted_not_on", f"{name} potted {said}, not a ball on.")


def in_off(name: str) -> Foul:
    return Foul("in_off", f"{name}'s cue ball went into a pocket (in-off).")


def miss(name: str) -> Foul:
    return Foul("miss", f"{name} did not hit the ball on, open to a straight stroke: a miss.")


def jump_shot(name: str, over: tuple[int, ...]) -> Foul:
    """WPBSA Section 2 "Jump Shot" (the cue ball passed over an object ball before its
    first contact), a foul under 3.11 Penalty Values."""
    said = and_list(snooker_ball(b) for b in over)
    return Foul("jump_shot", f"{name}'s cue ball jumped over {said}: a jump shot.")
