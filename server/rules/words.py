"""Sentences for players: ball lists, pocket names, foul labels."""

from __future__ import annotations

from collections.abc import Iterable

from server.engine import Table

SNOOKER_COLOURS = {16: "yellow", 17: "green", 18: "brown", 19: "blue", 20: "pink", 21: "black"}


def ball(ball_id: int) -> str:
    return "the cue ball" if ball_id == 0 else f"the {ball_id}"


def snooker_ball(ball_id: int) -> str:
    """'the cue ball', 'a red', 'the pink' (snooker's ids: `server.engine.rack`)."""
    if ball_id == 0:
        return "the cue ball"
    return f"the {SNOOKER_COLOURS[ball_id]}" if ball_id in SNOOKER_COLOURS else "a red"


def and_list(items: Iterable[str]) -> str:
    """'a', 'a and b', 'a, b and c'."""
    items = list(items)
    if len(items) <= 1:
        return "".join(items)
    return ", ".join(items[:-1]) + " and " + items[-1]


def balls(ball_ids: Iterable[int]) -> str:
    return and_list(ball(b) for b in ball_ids)


def pocket(table: Table, index: int) -> str:
    """'bottom left pocket' for index 0."""
    return table.pockets[index].name.replace("_", " ") + " pocket"


def capitalised(sentence: str) -> str:
    return sentence[:1].upper() + sentence[1:]
