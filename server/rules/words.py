"""Sentences for players: ball lists, pocket names, foul labels."""

from __future__ import annotations

from collections.abc import Iterable

from server.engine import Table


def ball(ball_id: int) -> str:
    return "the cue ball" if ball_id == 0 else f"the {ball_id}"


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
