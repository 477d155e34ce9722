"""What the store keeps, as typed records (rows come back as these, never as tuples)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any


@dataclass(frozen=True)
class MatchRecord:
    id: int
    room_id: str
    kind: str
    players: list[str]
    race_to: int
    status: str  # "playing" | "finished" | "abandoned"
    score: list[int]
    winner: int | None
    reason: str | None
    started_at: float
    finished_at: float | None
    games: int = 0  # games finished
    shots: int = 0


@dataclass(frozen=True)
class GameRecord:
    match_id: int
    n: int
    winner: int | None
    reason: str | None
    cause: str
    score: list[int]
    finished_at: float


@dataclass(frozen=True)
class ShotRecord:
    """One shot: the table before it, the stroke, the judged outcome and what was shown."""

    match_id: int
    n: int
    room_shot: int
    game: int
    seat: int
    shot: dict[str, Any]  # {"angle": float, "speed": float, "tip": [side, height]}
    table: list[float | str]  # Table.from_fields(table): the numbers, then a style but pool
    balls: dict[str, Any]  # BallSet.to_dict() before the shot
    outcome: dict[str, Any]  # Outcome.to_dict()
    played_at: float
    engine: str | None = None  # ENGINE_VERSION that played it (None: before versions)
    motion: str | None = None  # the streamed messages (`protocol.plan.motion_text`)
    # The stroke meant, when it differs from `shot` (a computer's plan before its arm's
    # error); None: `shot` is what the player meant (a person's, as sent)
    intended: dict[str, Any] | None = None


@dataclass(frozen=True)
class PendingShot:
    """A shot that was being played when the room was saved (replayed after a restart)."""

    id: int
    seat: int
    angle: float
    speed: float
    tip: tuple[float, float]
    elevation: float = 0.0  # a room saved before elevation existed played level shots


@dataclass
class RoomSnapshot:
    """A live room as saved after every shot: see `server.rooms.snapshot`."""

    room_id: str
    data: dict[str, Any] = field(repr=False)
    updated_at: float = 0.0
