"""What the store keeps, as typed records (rows come back as these, never as tuples)."""

from __future__ import annotations

from dataclasses import dataclass, field


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

    def to_dict(self) -> dict:
        winner_name = self.players[self.winner] if self.winner is not None else None
        return {"id": self.id, "room_id": self.room_id, "game": self.kind,
                "players": self.players, "race_to": self.race_to, "status": self.status,
                "score": self.score, "winner": self.winner, "winner_name": winner_name,
                "reason": self.reason, "started_at": self.started_at,
                "finished_at": self.finished_at, "games": self.games, "shots": self.shots}


@dataclass(frozen=True)
class GameRecord:
    match_id: int
    n: int
    winner: int | None
    reason: str | None
    cause: str
    score: list[int]
    finished_at: float

    def to_dict(self) -> dict:
        return {"n": self.n, "winner": self.winner, "reason": self.reason,
                "cause": self.cause, "score": self.score, "finished_at": self.finished_at}


@dataclass(frozen=True)
class ShotRecord:
    """One shot: enough to simulate it again bit for bit (`table`, `balls`, `shot`)."""

    match_id: int
    n: int
    room_shot: int
    game: int
    seat: int
    shot: dict  # {"angle": float, "speed": float, "tip": [side, height]}
    table: list[float]  # Table(*table)
    balls: dict  # BallSet.to_dict() before the shot
    outcome: dict  # Outcome.to_dict()
    played_at: float

    def to_dict(self) -> dict:
        return {"n": self.n, "shot_id": self.room_shot, "game": self.game, "seat": self.seat,
                "shot": self.shot, "table": self.table, "balls": self.balls,
                "outcome": self.outcome, "played_at": self.played_at,
                "replay": f"/api/matches/{self.match_id}/shots/{self.n}/replay"}


@dataclass(frozen=True)
class PendingShot:
    """A shot that was being played when the room was saved (replayed after a restart)."""

    id: int
    seat: int
    angle: float
    speed: float
    tip: tuple[float, float]


@dataclass
class RoomSnapshot:
    """A live room as saved after every shot: see `server.store.snapshot`."""

    room_id: str
    data: dict = field(repr=False)
    updated_at: float = 0.0
