"""The one error a room action raises: a code for programs and a sentence for people."""

from __future__ import annotations


class ActionError(Exception):
    """The action was refused and nothing changed."""

    def __init__(self, code: str, message: str) -> None:
        super().__init__(message)
        self.code = code
        self.message = message
