"""Matches stored by the code before the codec load, look the same and play on the same.

Each file in `data/` was written by `Match.to_dict()` at commit 18f42e5 (hand-written
`to_dict`/`from_dict`): the stored match, its public state, a script of actions played on
from there, what each action returned and showed, and the match at the end. Saved rooms in
existing databases hold exactly this form.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from server.codec import from_data, to_data
from server.rules import Game, Match, Outcome

from .helpers import crafted, hit, pot, rail

DATA = Path(__file__).parent / "data"
FIXTURES = sorted(DATA.glob("*.json"))
EVENTS = {"hit": hit, "rail": rail, "pot": pot}


def run(match: Match, action: list[Any]) -> Outcome | None:
    """One scripted action, as the fixture script names it."""
    do, *args = action
    game = match.game
    if do == "shoot":
        seat, events = args
        return match.apply(seat, crafted(game.balls, *(EVENTS[e[0]](*e[1:]) for e in events)))
    if do == "timeout":
        return match.timeout(args[0])
    if do == "concede":
        return match.concede(args[0])
    actions = {
        "place": game.place_cue,
        "call": game.call_pocket,
        "decide": game.decide,
        "push_out": game.declare_push_out,
        "rerack": game.rerack,
        "next_game": match.next_game,
    }
    actions[do](*args)
    return None


def without_balls(state: dict[str, Any]) -> dict[str, Any]:
    return {k: v for k, v in state.items() if k != "balls"}


def tables_as_lists(data: Any) -> Any:
    """`data` with every stored table in the list form the old code wrote."""
    if isinstance(data, dict):
        if set(data) == {"length", "width", "ball_radius", "corner_mouth", "side_mouth"}:
            return [
                data[k] for k in ("length", "width", "ball_radius", "corner_mouth", "side_mouth")
            ]
        return {k: tables_as_lists(v) for k, v in data.items()}
    if isinstance(data, list):
        return [tables_as_lists(v) for v in data]
    return data


def groups_as_pairs(game: dict[str, Any]) -> dict[str, Any]:
    groups = game["groups"]
    pairs = sorted([int(s), g] for s, g in groups.items()) if groups is not None else None
    return {**game, "groups": pairs}


def old_form(match: dict[str, Any]) -> dict[str, Any]:
    """A stored match as the old code would have written it."""
    data = tables_as_lists(match)
    return {**data, "game": groups_as_pairs(data["game"])}


@pytest.fixture(params=FIXTURES, ids=lambda p: p.stem)
def fixture(request: pytest.FixtureRequest) -> dict[str, Any]:
    data: dict[str, Any] = json.loads(request.param.read_text())
    return data


def test_every_kind_and_state_has_a_fixture() -> None:
    stored = [json.loads(p.read_text())["match"] for p in FIXTURES]
    assert {m["kind"] for m in stored} == {"eight_ball", "nine_ball", "practice"}
    games = [m["game"] for m in stored]
    assert any(g["decision"] and g["pending"] == "push_out" for g in games)
    assert any(g["decision"] and g["after_decision_bih"] == "anywhere" for g in games)
    assert any(g["push_out_declared"] and max(g["fouls_in_row"]) == 2 for g in games)
    assert any(g["groups"] for g in games) and any(m["table"] is None for m in stored)


def test_an_old_match_loads_with_the_same_public_state(fixture: dict[str, Any]) -> None:
    match = Match.from_dict(fixture["match"])
    assert match.public_state() == fixture["state"]
    assert Game.from_dict(fixture["match"]["game"]).public_state() == match.game.public_state()


def test_an_old_match_plays_on_exactly_as_it_did(fixture: dict[str, Any]) -> None:
    match = Match.from_dict(fixture["match"])
    for action, then in zip(fixture["actions"], fixture["after"], strict=True):
        outcome = run(match, action)
        assert (outcome.to_dict() if outcome else None) == then["outcome"], action
        assert without_balls(match.public_state()) == then["state"], action
    assert match.public_state() == fixture["final_state"]
    assert match.to_dict() == Match.from_dict(fixture["final"]).to_dict()


def test_the_stored_form_changed_only_in_how_tables_and_groups_are_written(
    fixture: dict[str, Any],
) -> None:
    match = Match.from_dict(fixture["match"])
    assert old_form(to_data(match)) == fixture["match"]
    for action in fixture["actions"]:
        run(match, action)
    assert old_form(match.to_dict()) == fixture["final"]


def test_a_loaded_old_match_survives_the_codec_round_trip(fixture: dict[str, Any]) -> None:
    match = Match.from_dict(fixture["match"])
    again = from_data(Match, json.loads(json.dumps(to_data(match))))
    assert to_data(again) == to_data(match)
    assert again.public_state() == fixture["state"]
