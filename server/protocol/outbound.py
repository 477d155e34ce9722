"""What the server sends: every message a pydantic model, and the union a client parses.

Rooms build each message from its model (`text` encodes it). A shot's motion is the
exception: one binary WebSocket message packed by `protocol.motion` (docs/protocol.md,
`motion`); the replay route carries the same bytes in base64 in a `MotionMessage`.
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, TypeAdapter

from server.rules import Outcome

from .limits import PROTOCOL_VERSION, Limits

BallRowModel = tuple[int, int, int, int]  # [id, x_mm, y_mm, cel]
ResultCause = Literal["shot", "timeout", "concede", "forfeit"]


class ServerMessage(BaseModel):
    model_config = ConfigDict(extra="forbid")


class Sequenced(ServerMessage):
    """A message in the room's order: `seq` counts every one a room broadcast, so a client
    that sees a gap asks for a fresh `state` (`sync`). The room sets it when sending."""

    seq: int = 0


class PlayerInfo(ServerMessage):
    seat: int
    name: str
    connected: bool


class GraceInfo(ServerMessage):
    """An absent player's seat is kept this many more seconds. `left`: they had been at
    the table and dropped; false while a player seated for them (Play now) has not yet
    arrived, who has not left anything."""

    seat: int
    remaining: float
    left: bool = True


class ClockInfo(ServerMessage):
    seat: int
    remaining: float
    limit: float


class ShotInfo(ServerMessage):
    """The shot being streamed: a member joining now sees its tick `tick` of `ticks`."""

    id: int
    seat: int
    tick: int
    ticks: int


class ChatLine(ServerMessage):
    """One line of the room's chat, as the `chat` message carried it."""

    seat: int | None
    name: str
    text: str
    at: float


class DrillInfo(ServerMessage):
    """A drill's table (`server.rooms.drills`): a position (the analysed shot it comes
    from, the pro's chance there), a ghost 9-ball rack or a progressive line-up, and how
    it went so far."""

    kind: Literal["position", "ghost", "lineup"]
    match: int | None
    n: int | None
    par: float | None
    made: bool | None  # position: the first shot pocketed a ball without a foul (None: not yet)
    score: int  # position: 1 made, 0 missed; ghost: balls pocketed
    done: bool  # nothing more to score (the first shot played; the ghost won, or beaten)
    won: bool  # ghost: the rack cleared; lineup: the last rack cleared
    balls: int | None = None  # lineup: balls in the rack now
    tries: int = 1  # ghost, lineup: tries at this table (Rerack starts another)
    best: int = 0  # the most balls pocketed in one of them


class RoomInfo(ServerMessage):
    room_id: str
    game: str
    race_to: int
    shot_clock: float
    seats: int
    status: Literal["waiting", "playing", "finished"]
    players: list[PlayerInfo]
    spectators: int
    rematch: list[int]
    abandoned: bool = False
    drill: DrillInfo | None = None  # a practice table set up from an analysed shot


class Welcome(ServerMessage):
    """First message on a socket: who you are, the room's sequence number, the stream's
    rates and every limit the client needs."""

    type: Literal["welcome"] = "welcome"
    protocol: int = PROTOCOL_VERSION
    room_id: str
    seat: int | None
    role: Literal["player", "spectator"]
    name: str | None
    seq: int
    tick_hz: int
    frame_every: int
    frames_per_message: int = 1
    server_time: float
    limits: Limits


class MotionMessage(Sequenced):
    """A shot's binary `motion` message as a JSON line of a replay: `data` is its bytes in
    base64 (live, the room sends the bytes themselves, as a binary WebSocket message)."""

    type: Literal["motion"] = "motion"
    shot: int
    data: str


class ShotResultMessage(Sequenced):
    """What a shot (or a timeout, concession, forfeit: `shot` is null) decided."""

    type: Literal["shot_result"] = "shot_result"
    shot: int | None
    cause: ResultCause
    outcome: Outcome
    score: list[int]
    match_over: bool
    match_winner: int | None


class ReplayRef(ServerMessage):
    match: int
    n: int


class ReplayResultMessage(Sequenced):
    """The `shot_result` that closes a stored shot's replay: the outcome as judged then."""

    type: Literal["shot_result"] = "shot_result"
    shot: int
    cause: Literal["shot"] = "shot"
    outcome: Outcome
    replay: ReplayRef


class StateMessage(Sequenced):
    """Everything a client needs to draw the room now (after joining, a shot or a gap)."""

    type: Literal["state"] = "state"
    room: RoomInfo
    phase: Literal["waiting", "aiming", "rolling", "over"]
    table: dict[str, Any]
    balls: list[BallRowModel]
    shot: ShotInfo | None
    clock: ClockInfo | None
    grace: list[GraceInfo]
    match: dict[str, Any] | None
    chat: list[ChatLine] | None = None


class AimRelay(ServerMessage):
    """Another player's cue, relayed as it moves (droppable, no `seq`)."""

    type: Literal["aim"] = "aim"
    seat: int | None
    angle: float
    power: float
    tip: tuple[float, float]
    # The cue's elevation (rad); left out for a level cue, as before it existed.
    elevation: float = Field(default=0.0, exclude_if=lambda v: v == 0.0)
    # Ball in hand: where the cue ball is being dragged; left out of the message otherwise.
    cue: tuple[float, float] | None = Field(default=None, exclude_if=lambda v: v is None)


class ChatMessage(Sequenced):
    type: Literal["chat"] = "chat"
    seat: int | None
    name: str
    text: str
    at: float


class Presence(Sequenced):
    type: Literal["presence"] = "presence"
    players: list[PlayerInfo]
    spectators: int
    grace: list[GraceInfo]


class Pong(ServerMessage):
    type: Literal["pong"] = "pong"
    id: int | None
    server_time: float


class ErrorMessage(ServerMessage):
    """A refused message: nothing changed. `ref` is the refused message's type."""

    type: Literal["error"] = "error"
    code: str
    message: str
    ref: str | None = None


AnyServerMessage = Annotated[
    Welcome
    | ShotResultMessage
    | StateMessage
    | AimRelay
    | ChatMessage
    | Presence
    | Pong
    | ErrorMessage,
    Field(discriminator="type"),
]
AnyReplayMessage = Annotated[MotionMessage | ReplayResultMessage, Field(discriminator="type")]
server_messages: TypeAdapter[AnyServerMessage] = TypeAdapter(AnyServerMessage)
replay_messages: TypeAdapter[AnyReplayMessage] = TypeAdapter(AnyReplayMessage)


def text(message: ServerMessage, exclude: set[str] | None = None) -> str:
    """The message as compact JSON, fields in model order (`type` first)."""
    return message.model_dump_json(exclude=exclude)
