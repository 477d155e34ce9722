"""HTTP request and response bodies (they make the OpenAPI schema)."""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import BaseModel, Field, field_validator

from server.ai import LEVELS

from .inputs import Name, StrictBody

GameKind = Literal[
    "eight_ball",
    "nine_ball",
    "practice",
    "snooker",
    "snooker_practice",
    "three_cushion",
    "three_cushion_practice",
]


class CreateRoom(StrictBody):
    game: GameKind
    race_to: Annotated[int, Field(ge=1, le=15)] = 1
    shot_clock: (
        Annotated[float, Field(ge=0, le=600, description="seconds per shot; 0 = no clock")] | None
    ) = None
    listed: bool = Field(True, description="false: a private table, joined only by its link")
    opponent: str | None = Field(
        None, description=f"play the computer at this level: one of {', '.join(LEVELS)}"
    )
    ranked: bool = Field(
        False,
        description=(
            "rated when both players agree (8-ball/9-ball/snooker/three-cushion, two players,"
            " a profile)"
        ),
    )

    @field_validator("opponent")
    @classmethod
    def _level(cls, value: str | None) -> str | None:
        if value is not None and value not in LEVELS:
            raise ValueError(f"the computer plays at one of {', '.join(LEVELS)}")
        return value


class ComputerLevels(BaseModel):
    levels: list[str]  # weakest first


class RoomCreated(BaseModel):
    room_id: str
    game: GameKind
    race_to: int
    shot_clock: float
    seats: int
    listed: bool
    opponent: str | None  # the computer's level, when it plays the second seat
    ranked: bool = False  # rated when both players agree (see `JoinRoom.ranked`)
    url: str
    ws_url: str  # the room's WebSocket, on the server that plays it


class RoomSummary(BaseModel):
    room_id: str
    game: GameKind
    race_to: int
    shot_clock: float
    seats: int
    status: Literal["waiting", "playing", "finished"]
    players: list[str | None]
    spectators: int
    score: list[int] | None
    created_at: float
    ranked: bool = False  # a friends' table rated when both agree: join with `ranked: true`


class RoomList(BaseModel):
    rooms: list[RoomSummary]
    total: int  # listed rooms in all
    next: int | None  # offset of the next page; None on the last


class RoomDetail(RoomSummary):
    state: dict[str, Any]
    ws_url: str  # where to connect for this room now


class JoinRoom(StrictBody):
    # Left out: the player's profile name (their cookie's), the one name used everywhere.
    name: Name | None = None
    ranked: bool = Field(False, description="agree that a ranked table changes your rating")


class Joined(BaseModel):
    room_id: str
    seat: int
    token: str
    name: str
    ws_url: str  # where to connect with the token now


class Health(BaseModel):
    status: Literal["ok"]


class StreamStats(BaseModel):
    window: float
    frames: int  # frame messages sent in the window
    late_p50_ms: float | None  # behind the shot's schedule when sent
    late_p99_ms: float | None
    late_max_ms: float | None
    frames_sent: int  # since start
    frames_skipped: int  # since start: messages dropped for clients that were behind
    shots: int  # shots whose stream started in the window
    start_p50_ms: float | None  # from `shoot` to the start of the shot's stream
    start_p99_ms: float | None


class ServerStats(BaseModel):
    rooms: int
    rolling: int  # rooms with balls moving
    connections: int
    queued: int  # messages waiting in the members' outboxes
    stream: StreamStats


class ErrorBody(BaseModel):
    code: str
    message: str


class ErrorResponse(BaseModel):
    detail: ErrorBody
