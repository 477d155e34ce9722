"""Room options that change the rules."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class RuleOptions:
    """Choices a room makes when it is created.

    break_scratch_behind_head_string: 8-ball only. The current WPA rules give ball in hand
        anywhere after a scratch on the break; older editions and many leagues restrict it
        to behind the head string.
    """

    break_scratch_behind_head_string: bool = False


DEFAULT_OPTIONS = RuleOptions()
