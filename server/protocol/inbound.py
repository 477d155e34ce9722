"""What clients may send: intentions, each a pydantic model.

A discriminated union on `type`, validated straight from the raw text
(`parse_client_message`), strict about extra fields, bounds and NaN/inf: whatever reaches a
room is already well formed.
"""

from __future__ import annotations

import json
from typing import Annotated, Literal, get_args

from pydantic import BaseModel, ConfigDict, Field, TypeAdapter, ValidationError, model_validator

from server.engine import MAX_ELEVATION, MAX_SPEED, Miscue, check_stroke

from .limits import MAX_ANGLE, MAX_CHAT

# A point on the ball's face; which points the cue can strike depends on the elevation
# (`check_stroke`: |tip| <= max_tip for a level cue, higher on the ball for a raised one).
TipComponent = Annotated[float, Field(ge=-1.0, le=1.0)]
Tip = tuple[TipComponent, TipComponent]
Elevation = Annotated[float, Field(ge=0.0, le=MAX_ELEVATION)]
Angle = Annotated[float, Field(ge=-MAX_ANGLE, le=MAX_ANGLE)]
# The game (frame) of the match an action is meant for: `match.games_played` + 1. An action
# that names a game that is over (sent just before it ended) is refused as stale.
GameNumber = Annotated[int, Field(ge=1, le=1000)]


class ClientMessage(BaseModel):
    model_config = ConfigDict(extra="forbid", allow_inf_nan=False, strict=True, frozen=True)


class Shoot(ClientMessage):
    """Strike the cue ball: direction (rad), cue-ball speed (m/s), tip offset [side, height],
    the cue's elevation (rad; an old client leaves it out and plays level)."""

    type: Literal["shoot"]
    angle: Angle
    speed: Annotated[float, Field(gt=0.0, le=MAX_SPEED)]
    tip: Tip = (0.0, 0.0)
    elevation: Elevation = 0.0

    @model_validator(mode="after")
    def _tip_reachable(self) -> Shoot:
        check_stroke(self.tip, self.elevation)
        return self


Coordinate = Annotated[float, Field(ge=-10.0, le=10.0)]


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
    elevation: Elevation = 0.0
    # Ball in hand: where the cue ball is being dragged (metres), so the others see it move.
    cue: tuple[Coordinate, Coordinate] | None = None

    @model_validator(mode="after")
    def _tip_reachable(self) -> Aim:
        check_stroke(self.tip, self.elevation)
        return self


class Call(ClientMessage):
    """Call a pocket (index into the table's pockets) for the 8."""

    type: Literal["call"]
    pocket: Annotated[int, Field(ge=0, le=5)]


class Nominate(ClientMessage):
    """Snooker: nominate the colour on, or the free ball (a ball id from the state's
    `nominations`)."""

    type: Literal["nominate"]
    ball: Annotated[int, Field(ge=1, le=21)]


class Decide(ClientMessage):
    """Answer the pending rules decision with one of its options."""

    type: Literal["decide"]
    option: Annotated[str, Field(min_length=1, max_length=32)]
    game: GameNumber | None = None


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
    """Give up the current game (frame); `game`, when given, names it."""

    type: Literal["concede"]
    game: GameNumber | None = None


class Sync(ClientMessage):
    """Ask for a fresh `state` (after a sequence gap)."""

    type: Literal["sync"]


class Ping(ClientMessage):
    type: Literal["ping"]
    id: Annotated[int, Field(ge=0, le=2**53)] | None = None


AnyClientMessage = Annotated[
    Shoot
    | PlaceCue
    | Aim
    | Call
    | Nominate
    | Decide
    | PushOut
    | Rerack
    | Chat
    | Rematch
    | Concede
    | Sync
    | Ping,
    Field(discriminator="type"),
]
# Every `type` a client may send, read off the union itself.
CLIENT_TYPES = frozenset(
    get_args(model.model_fields["type"].annotation)[0]
    for model in get_args(get_args(AnyClientMessage)[0])
)
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
        if (
            kinds & {"json_invalid", "dict_type", "model_attributes_type", "model_type"}
            and not errors[0]["loc"][1:]
        ):
            raise BadMessage("bad_json", "The message must be a JSON object.") from None
        if kinds & {"union_tag_not_found", "union_tag_invalid"}:
            raise BadMessage(
                "unknown_type", "Unknown or missing message type; see docs/protocol.md."
            ) from None
        ref = _type_of(text)
        first = errors[0]
        error = first.get("ctx", {}).get("error")
        if isinstance(error, Miscue):
            raise BadMessage("miscue", str(error), ref) from None
        where = ".".join(str(p) for p in first["loc"][1:]) or "message"
        raise BadMessage("bad_message", f"{where}: {first['msg']}", ref) from None


def _type_of(text: str) -> str | None:
    try:
        value = json.loads(text).get("type")
    except (ValueError, AttributeError):
        return None
    return value if value in CLIENT_TYPES else None
