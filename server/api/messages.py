"""Every WebSocket message as a pydantic model: client intentions in, room news out.

Client messages are a discriminated union on `type`, validated straight from the raw text
(`parse_client_message`), strict about extra fields, bounds and NaN/inf. Server messages
are models too (the protocol doc is written from them); the hot `frame` is built as a plain
dict by `server.rooms.stream` with the same shape as `FrameMessage`.
"""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field, TypeAdapter, ValidationError, model_validator

from server.engine import MAX_SPEED, MAX_TIP

PROTOCOL_VERSION = 1
MAX_ANGLE = 10.0  # radians; any direction fits in [-pi, pi], this only bounds junk
MAX_CHAT = 200

TipComponent = Annotated[float, Field(ge=-MAX_TIP, le=MAX_TIP)]
Tip = tuple[TipComponent, TipComponent]
Angle = Annotated[float, Field(ge=-MAX_ANGLE, le=MAX_ANGLE)]


class ClientMessage(BaseModel):
    model_config = ConfigDict(extra="forbid", allow_inf_nan=False, strict=False,
                              frozen=True)


def _check_tip(tip: tuple[float, float]) -> None:
    if math.hypot(*tip) > MAX_TIP + 1e-12:
        raise ValueError(f"tip offset must be within {MAX_TIP} of the radius")


class Shoot(ClientMessage):
    """Strike the cue ball: direction (rad), cue-ball speed (m/s), tip offset [side, height]."""

    type: Literal["shoot"]
    angle: Angle
    speed: Annotated[float, Field(gt=0.0, le=MAX_SPEED)]
    tip: Tip = (0.0, 0.0)

    @model_validator(mode="after")
    def _tip_in_circle(self) -> Shoot:
        _check_tip(self.tip)
        return self


class PlaceCue(ClientMessage):
    """Ball in hand: put the cue ball at (x, y) metres."""

    type: Literal["place_cue"]
    x: Annotated[float, Field(ge=-10.0, le=10.0)]
    y: Annotated[float, Field(ge=-10.0, le=10.0)]


class Aim(ClientMessage):
    """Where the cue points and how far it is drawn back; relayed to the room."""

    type: Literal["aim"]
    angle: Angle
    power: Annotated[float, Field(ge=0.0, le=1.0)]
    tip: Tip = (0.0, 0.0)

    @model_validator(mode="after")
    def _tip_in_circle(self) -> Aim:
        _check_tip(self.tip)
        return self


class Call(ClientMessage):
    """Call a pocket (index into the table's pockets) for the 8."""

    type: Literal["call"]
    pocket: Annotated[int, Field(ge=0, le=5)]


class Decide(ClientMessage):
    """Answer the pending rules decision with one of its options."""

    type: Literal["decide"]
    option: Annotated[str, Field(min_length=1, max_length=32)]


class PushOut(ClientMessage):
    """9-ball: the next shot is a push out."""

    type: Literal["push_out"]


class Rerack(ClientMessage):
    """Practice: rack the balls again."""

    type: Literal["rerack"]


class Chat(ClientMessage):
    type: Literal["chat"]
    text: Annotated[str, Field(min_length=1, max_length=MAX_CHAT)]


class Rematch(ClientMessage):
    type: Literal["rematch"]


class Concede(ClientMessage):
    type: Literal["concede"]


class Sync(ClientMessage):
    """Ask for a fresh `state` (after a sequence gap)."""

    type: Literal["sync"]


class Ping(ClientMessage):
    type: Literal["ping"]
    id: Annotated[int, Field(ge=0, le=2**53)] | None = None


AnyClientMessage = Annotated[
    Shoot | PlaceCue | Aim | Call | Decide | PushOut | Rerack | Chat | Rematch | Concede
    | Sync | Ping,
    Field(discriminator="type"),
]
CLIENT_TYPES = frozenset(
    ("shoot", "place_cue", "aim", "call", "decide", "push_out", "rerack", "chat", "rematch",
     "concede", "sync", "ping"))
_client_adapter: TypeAdapter[AnyClientMessage] = TypeAdapter(AnyClientMessage)


class BadMessage(Exception):
    """A message that cannot be understood: `code` for the client, `ref` its type if known."""

    def __init__(self, code: str, message: str, ref: str | None = None) -> None:
        super().__init__(message)
        self.code = code
        self.message = message
        self.ref = ref


def parse_client_message(text: str) -> AnyClientMessage:
    """Validate one raw text frame; raises `BadMessage` with a code and a readable reason."""
    try:
        return _client_adapter.validate_json(text)
    except ValidationError as exc:
        errors = exc.errors(include_url=False)
        kinds = {e["type"] for e in errors}
        if kinds & {"json_invalid", "dict_type", "model_attributes_type", "model_type"} \
                and not errors[0]["loc"][1:]:
            raise BadMessage("bad_json", "The message must be a JSON object.") from None
        if kinds & {"union_tag_not_found", "union_tag_invalid"}:
            raise BadMessage("unknown_type", "Unknown or missing message type; see "
                             "docs/protocol.md.") from None
        ref = _type_of(text)
        first = errors[0]
        where = ".".join(str(p) for p in first["loc"][1:]) or "message"
        raise BadMessage("bad_message", f"{where}: {first['msg']}", ref) from None


def _type_of(text: str) -> str | None:
    import json

    try:
        value = json.loads(text).get("type")
    except (ValueError, AttributeError):
        return None
    return value if value in CLIENT_TYPES else None


# ---- server -> client -------------------------------------------------------------------

class ServerMessage(BaseModel):
    model_config = ConfigDict(extra="forbid")


class PlayerInfo(ServerMessage):
    seat: int
    name: str
    connected: bool


class GraceInfo(ServerMessage):
    seat: int
    remaining: float


class Welcome(ServerMessage):
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


class AheadFrame(BaseModel):
    """A later tick sent early inside a `frame` message, to be shown at its own tick."""

    model_config = ConfigDict(extra="forbid")
    tick: int
    b: list[tuple[int, int, int, int]]


class FrameMessage(ServerMessage):
    """One streamed tick: `b` holds [id, x_mm, y_mm, cel] for every ball on the table;
    `ahead` the next ticks of the stream, sent early (`frames_per_message` - 1 of them)."""

    type: Literal["frame"] = "frame"
    seq: int
    shot: int
    tick: int
    b: list[tuple[int, int, int, int]]
    ahead: list[AheadFrame] | None = None
    last: bool | None = None


SoundKind = Literal["strike", "ball", "cushion", "jaw", "pocket"]


class AlsoEvent(BaseModel):
    """A later sound of the same stretch of the shot, carried by an `event` message."""

    model_config = ConfigDict(extra="forbid")
    tick: int
    t: float
    kind: SoundKind
    ids: list[int]
    speed: float
    target: int


class EventMessage(ServerMessage):
    """A sound; `also`: the ones that follow within one frame message's span, each to be
    played at its own `t`."""

    type: Literal["event"] = "event"
    seq: int
    shot: int
    tick: int
    t: float
    kind: SoundKind
    ids: list[int]
    speed: float
    target: int
    also: list[AlsoEvent] | None = None


class ShotResultMessage(ServerMessage):
    type: Literal["shot_result"] = "shot_result"
    seq: int
    shot: int | None
    cause: Literal["shot", "timeout", "concede", "forfeit"]
    outcome: dict
    score: list[int]
    match_over: bool
    match_winner: int | None


class StateMessage(ServerMessage):
    type: Literal["state"] = "state"
    seq: int
    room: dict
    phase: Literal["waiting", "aiming", "rolling", "over"]
    table: dict
    balls: list[tuple[int, int, int, int]]
    shot: dict | None
    clock: dict | None
    grace: list[GraceInfo]
    match: dict | None


class AimRelay(ServerMessage):
    type: Literal["aim"] = "aim"
    seat: int
    angle: float
    power: float
    tip: tuple[float, float]


class ChatMessage(ServerMessage):
    type: Literal["chat"] = "chat"
    seq: int
    seat: int | None
    name: str
    text: str
    at: float


class Presence(ServerMessage):
    type: Literal["presence"] = "presence"
    seq: int
    players: list[PlayerInfo]
    spectators: int
    grace: list[GraceInfo]


class Pong(ServerMessage):
    type: Literal["pong"] = "pong"
    id: int | None
    server_time: float


class ErrorMessage(ServerMessage):
    type: Literal["error"] = "error"
    code: str
    message: str
    ref: str | None = None
