"""What the server sends: every message a pydantic model, and the union a client parses.

Rooms build each message from its model (`text` encodes it). The hot `frame` and `event`
messages are the exception: a shot's are encoded once, off the event loop, by `plan` and the
compiled `frame_codec`; tests check those bytes against `FrameMessage` and `EventMessage`.
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, TypeAdapter

from server.rules import Outcome

from .limits import PROTOCOL_VERSION, Limits

BallRowModel = tuple[int, int, int, int]  # [id, x_mm, y_mm, cel]
SoundKind = Literal["strike", "ball", "cushion", "jaw", "pocket"]
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
    """A dropped player's seat is kept this many more seconds."""

    seat: int
    remaining: float


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


class AheadFrame(BaseModel):
    """A later tick sent early inside a `frame` message, to be shown at its own tick."""

    model_config = ConfigDict(extra="forbid")
    tick: int
    b: list[BallRowModel]
    last: bool | None = None


class FrameMessage(Sequenced):
    """One streamed tick: `b` holds [id, x_mm, y_mm, cel] for every ball on the table;
    `ahead` the next ticks of the stream, sent early (`frames_per_message` - 1 of them)."""

    type: Literal["frame"] = "frame"
    shot: int
    tick: int
    b: list[BallRowModel]
    ahead: list[AheadFrame] | None = None
    last: bool | None = None


class AlsoEvent(BaseModel):
    """A later sound of the same stretch of the shot, carried by an `event` message."""

    model_config = ConfigDict(extra="forbid")
    tick: int
    t: float
    kind: SoundKind
    ids: list[int]
    speed: float
    target: int


class EventMessage(Sequenced):
    """A sound; `also`: the ones that follow within one frame message's span, each to be
    played at its own `t`."""

    type: Literal["event"] = "event"
    shot: int
    tick: int
    t: float
    kind: SoundKind
    ids: list[int]
    speed: float
    target: int
    also: list[AlsoEvent] | None = None


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


class AimRelay(ServerMessage):
    """Another player's cue, relayed as it moves (droppable, no `seq`)."""

    type: Literal["aim"] = "aim"
    seat: int | None
    angle: float
    power: float
    tip: tuple[float, float]


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
    | FrameMessage
    | EventMessage
    | ShotResultMessage
    | StateMessage
    | AimRelay
    | ChatMessage
    | Presence
    | Pong
    | ErrorMessage,
    Field(discriminator="type"),
]
AnyReplayMessage = Annotated[
    FrameMessage | EventMessage | ReplayResultMessage, Field(discriminator="type")
]
server_messages: TypeAdapter[AnyServerMessage] = TypeAdapter(AnyServerMessage)
replay_messages: TypeAdapter[AnyReplayMessage] = TypeAdapter(AnyReplayMessage)


def text(message: ServerMessage, exclude: set[str] | None = None) -> str:
    """The message as compact JSON, fields in model order (`type` first)."""
    return message.model_dump_json(exclude=exclude)
