"""Each kind of game's strategy, judged from hand-made frozen positions."""

from __future__ import annotations

import dataclasses

import pytest

from server.rules import ANYWHERE, BEHIND_HEAD_STRING, GAME_KINDS, Game, RuleOptions
from server.rules.eight_ball import EightBallRules
from server.rules.kinds import RULES, rules_for
from server.rules.nine_ball import NineBallRules
from server.rules.position import Position
from server.rules.practice import PracticeRules
from server.rules.shotfacts import ShotFacts

from .helpers import TABLE, crafted, hit, pot

EIGHT = rules_for("eight_ball")
NINE = rules_for("nine_ball")
PRACTICE = rules_for("practice")
ALL = tuple(range(16))


def position(
    on_table: tuple[int, ...] = ALL,
    players: tuple[str, ...] = ("Ana", "Bob"),
    **state: object,
) -> Position:
    return Position(players, TABLE, RuleOptions(), on_table, **state)


def facts(
    first: int | None = None,
    pocketed: tuple[int, ...] = (),
    scratch: bool = False,
    rail: bool = True,
) -> ShotFacts:
    return ShotFacts(first, rail, pocketed, {b: 0 for b in pocketed}, scratch, frozenset())


# --- lookup ----------------------------------------------------------------------------
def test_one_strategy_per_kind_looked_up_by_its_kind() -> None:
    assert GAME_KINDS == (
        "eight_ball",
        "nine_ball",
        "practice",
        "snooker",
        "snooker_practice",
        "three_cushion",
        "three_cushion_practice",
    )
    for kind in GAME_KINDS:
        assert rules_for(kind).kind == kind and RULES[kind] is rules_for(kind)
    assert (type(EIGHT), type(NINE), type(PRACTICE)) == (
        EightBallRules,
        NineBallRules,
        PracticeRules,
    )
    with pytest.raises(ValueError, match="unknown game 'four_ball'"):
        rules_for("four_ball")
    with pytest.raises(ValueError, match="unknown game"):
        Game.new("four_ball", ("Ana", "Bob"))


@pytest.mark.parametrize(
    ("rules", "seats", "rack", "breaks", "opening", "at_will", "spot"),
    [
        (EIGHT, 2, "eight_ball", True, BEHIND_HEAD_STRING, False, (8,)),
        (NINE, 2, "nine_ball", True, BEHIND_HEAD_STRING, False, ()),
        (PRACTICE, 1, "eight_ball", False, ANYWHERE, True, ()),
    ],
)
def test_what_each_kind_sets_up(rules, seats, rack, breaks, opening, at_will, spot) -> None:
    assert (rules.seats, rules.rack, rules.breaks) == (seats, rack, breaks)
    assert (rules.opening_ball_in_hand, rules.rerack_at_will, rules.spot_choice) == (
        opening,
        at_will,
        spot,
    )
    players = ("Ana", "Bob")[:seats]
    game = Game.new(rules.kind, players, table=TABLE)
    assert game.rules is rules and game.breaking == breaks
    assert game.ball_in_hand == opening and len(game.balls) == (10 if rack == "nine_ball" else 16)


# --- legal targets ---------------------------------------------------------------------
def test_eight_ball_legal_targets() -> None:
    assert EIGHT.legal_targets(position(turn=0)) == [1, 2, 3, 4, 5, 6, 7, 9, 10, 11, 12, 13, 14, 15]
    groups = ("stripes", "solids")
    assert EIGHT.legal_targets(position((0, 3, 5, 8, 12), turn=0, groups=groups)) == [12]
    assert EIGHT.legal_targets(position((0, 3, 5, 8, 12), turn=1, groups=groups)) == [3, 5]
    assert EIGHT.legal_targets(position((0, 3, 8), turn=0, groups=groups)) == [8]
    assert EIGHT.legal_targets(position((0, 8), turn=1)) == [8]  # open table, groups gone
    assert EIGHT.legal_targets(position((0,), turn=1)) == []


def test_nine_ball_legal_targets() -> None:
    assert NINE.legal_targets(position((0, 3, 5, 9), turn=1)) == [3]
    pushing = position((0, 3, 5, 9), turn=1, push_out_declared=True)
    assert NINE.legal_targets(pushing) == [3, 5, 9]
    assert NINE.legal_targets(position((0,), turn=0)) == []


def test_practice_has_no_legal_targets_anything_goes() -> None:
    assert PRACTICE.legal_targets(position(players=("Ana",), turn=0)) == []


# --- balls left and calls --------------------------------------------------------------
def test_balls_left() -> None:
    on = (0, 2, 7, 8, 10)
    assert EIGHT.balls_left(position(on, turn=0)) is None  # open table
    assert EIGHT.balls_left(position(on, turn=0, groups=("solids", "stripes"))) == [[2, 7], [10]]
    assert NINE.balls_left(position((0, 4, 9), turn=0)) == [[4, 9], [4, 9]]
    assert PRACTICE.balls_left(position(on, players=("Ana",), turn=0)) is None


def test_only_eight_ball_calls_a_pocket_and_never_on_the_break() -> None:
    on_the_eight = position((0, 8, 9), turn=0, groups=("solids", "stripes"))
    assert EIGHT.requires_call(on_the_eight)
    assert not EIGHT.requires_call(dataclasses.replace(on_the_eight, breaking=True))
    assert not EIGHT.requires_call(dataclasses.replace(on_the_eight, turn=1))
    assert not NINE.requires_call(position((0, 9), turn=0))
    assert not PRACTICE.requires_call(position((0, 8), players=("Ana",), turn=0))


# --- the shot clock --------------------------------------------------------------------
@pytest.mark.parametrize("rules", [EIGHT, NINE])
def test_timeout_is_a_foul_with_ball_in_hand_anywhere(rules) -> None:
    r = rules.timeout(position(turn=1, fouls_in_row=(0, 0)))
    assert [f.code for f in r.fouls] == ["shot_clock"] and r.fouls[0].message.startswith("Bob")
    assert r.ball_in_hand == ANYWHERE and r.break_passes_to is None and r.winner is None


@pytest.mark.parametrize("rules", [EIGHT, NINE])
def test_timeout_on_the_break_passes_the_break(rules) -> None:
    r = rules.timeout(position(turn=0, breaking=True, fouls_in_row=(2, 0)))
    assert [f.code for f in r.fouls] == ["shot_clock"] and r.winner is None
    assert r.break_passes_to == 1 and r.ball_in_hand == BEHIND_HEAD_STRING
    assert r.notes == ["Bob breaks instead."]


def test_a_third_foul_on_the_clock_loses_only_in_nine_ball() -> None:
    on_two = position(turn=0, fouls_in_row=(2, 0))
    lost = NINE.timeout(on_two)
    assert lost.winner == 1 and lost.reason == "Ana fouled three times in a row."
    assert EIGHT.timeout(on_two).winner is None
    assert NINE.timeout(dataclasses.replace(on_two, fouls_in_row=(1, 0))).winner is None


def test_practice_timeout_is_no_foul() -> None:
    r = PRACTICE.timeout(position(players=("Ana",), turn=0))
    assert r.fouls == [] and r.continues and r.ball_in_hand == ANYWHERE
    assert r.notes == ["Time ran out."]


# --- counting fouls --------------------------------------------------------------------
def test_nine_ball_counts_fouls_in_a_row_per_seat() -> None:
    assert NINE.count_fouls([0, 1], 1, fouled=True) == [0, 2]
    assert NINE.count_fouls([2, 1], 0, fouled=False) == [0, 1]
    assert NINE.foul_warning([0, 2], 1, "Bob") == (
        "Bob is on two fouls: a third foul in a row loses."
    )
    assert NINE.foul_warning([0, 1], 1, "Bob") is None
    assert NINE.foul_warning([0, 3], 1, "Bob") is None


@pytest.mark.parametrize("rules", [EIGHT, PRACTICE])
def test_eight_ball_and_practice_count_nothing(rules) -> None:
    assert rules.count_fouls([0, 2], 1, fouled=True) == [0, 2]
    assert rules.count_fouls([1], 0, fouled=False) == [1]
    assert rules.foul_warning([0, 2], 1, "Bob") is None


def test_the_third_foul_loses_the_same_way_on_a_shot_and_on_the_clock() -> None:
    on_two = position((0, 1, 2, 9), turn=1, fouls_in_row=(0, 2))
    shot = NINE.judge(on_two, facts(first=2))  # wrong ball first
    clock = NINE.timeout(on_two)
    assert (
        (shot.winner, shot.reason)
        == (clock.winner, clock.reason)
        == (
            0,
            "Bob fouled three times in a row.",
        )
    )
    push = NINE.judge(dataclasses.replace(on_two, push_out_declared=True), facts(scratch=True))
    assert push.winner == 0 and push.decision is None and push.pending is None


# --- judging ---------------------------------------------------------------------------
def test_a_judge_reads_only_its_position() -> None:
    pos = position((0, 1, 2, 9), turn=0, fouls_in_row=(1, 0))
    shot = facts(first=1, pocketed=(2,))
    first = NINE.judge(pos, shot)
    assert first == NINE.judge(pos, shot) and first.continues and first.fouls == []
    with pytest.raises(dataclasses.FrozenInstanceError):
        pos.turn = 1


def test_practice_judge_has_no_fouls_and_says_when_the_table_is_cleared() -> None:
    solo = ("Ana",)
    r = PRACTICE.judge(position((0, 4, 6), players=solo, turn=0), facts(pocketed=(4,)))
    assert r.fouls == [] and r.continues and r.notes == []
    r = PRACTICE.judge(position((0, 4), players=solo, turn=0), facts(pocketed=(4,), scratch=True))
    assert r.notes == [
        "The cue ball went in: place it anywhere.",
        "Table cleared. Rerack to play again.",
    ]


def test_game_position_is_the_frozen_state_the_rules_read(eight: Game) -> None:
    eight.apply(0, crafted(eight.balls, hit(0, 1), pot(1, 2)))
    eight.apply(0, crafted(eight.balls, hit(0, 10), pot(10, 3)))
    pos = eight.position()
    assert pos.groups == ("stripes", "solids") and pos.turn == 0 and not pos.breaking
    assert pos.on_table == tuple(eight.balls.on_table_ids()) and 10 not in pos.on_table
    assert pos.fouls_in_row == (0, 0) and pos.players == ("Ana", "Bob")
    assert eight.legal_targets() == EIGHT.legal_targets(pos) == [9, 11, 12, 13, 14, 15]
