"""Named errors, in the spirit of python-chess's `IllegalMoveError`: the room turns them into
clear replies to a client, and the game is left exactly as it was."""

from __future__ import annotations


class RulesError(Exception):
    """Base class: `code` is a short snake_case tag for programs, `message` a sentence."""

    def __init__(self, code: str, message: str) -> None:
        super().__init__(message)
        self.code = code
        self.message = message


class IllegalActionError(RulesError):
    """The action is not allowed now; nothing changed.

    Codes: "not_your_turn", "game_over", "illegal_placement", "no_ball_in_hand",
    "cue_ball_off_table", "call_required", "call_not_needed", "bad_pocket",
    "decision_pending", "no_decision", "bad_option", "push_out_not_allowed",
    "game_not_over", "match_over", "practice_only", "not_in_practice", "bad_result".
    """
