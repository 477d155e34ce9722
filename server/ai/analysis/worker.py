"""One shot of a stored match judged at a time, for a process that analyses in steps (the
server's analysis queue hands the planners back between shots). The games rebuilt for a
match are kept for its next shots, so a match is played forward once, not once a shot."""

from __future__ import annotations

from .judge import ShotVerdict, judge_shot
from .rebuild import Before, StoredShot, positions

KEPT = 2  # matches whose rebuilt games a process keeps
_rebuilt: dict[int, list[Before]] = {}


def judge_nth(
    match_id: int,
    kind: str,
    players: list[str],
    shots: list[StoredShot],
    k: int,
    budget: int | None = None,
) -> ShotVerdict:
    """`judge_shot` of `shots[k]` (from 0), the games before each shot rebuilt once."""
    found = _rebuilt.get(match_id)
    if found is None or len(found) != len(shots):
        while len(_rebuilt) >= KEPT:
            _rebuilt.pop(next(iter(_rebuilt)))
        found = _rebuilt[match_id] = list(positions(kind, players, shots))
    return judge_shot(match_id, found[k], budget)
