"""Practice's "Show me a shot": the strongest level's plan for the player's shot, as the
API returns it. It runs where the table is played (`server.api.owner` forwards it to the
room's owner in cluster mode), since the planner needs the live table."""

from __future__ import annotations

from typing import Any

from fastapi import HTTPException
from pydantic import BaseModel, Field

from server.config import Settings
from server.rooms import ActionError, LiveRoom
from server.rooms.computer import HINT_LEVEL, HintAsk
from server.rooms.computer import hint as plan_hint

from .inputs import StrictBody

# A call for a hint to the room's owner waits this long: a plan takes up to about 3 s of
# CPU, and the owner's planner processes may be busy with the computer's turns first.
CALL_TIMEOUT = 30.0
_STATUS = {
    "bad_token": 403,
    "not_practice": 409,
    "not_your_turn": 409,
    "hint_pending": 429,  # the table, the address or the player has a hint asked already
    "hints_busy": 429,  # the queue of hints waiting for the planners is full
    "planning_budget": 429,  # the address used its planning seconds of the minute
    "hint_timeout": 503,  # the planners stayed busy with the computer's turns
}


class HintRequest(StrictBody):
    token: str = Field(min_length=1, max_length=200, description="the seat's token")


class Hint(BaseModel):
    """The strongest level's plan for the shot: what it would play, not played."""

    level: str  # the level that planned it (the strongest)
    kind: str  # "pot", "safety", "kick", "break" or "push"
    place: tuple[float, float] | None  # where it would put the cue ball (ball in hand)
    call: int | None  # the pocket it would call (8-ball's 8)
    angle: float  # cue direction, radians
    speed: float  # cue-ball speed, m/s
    tip: tuple[float, float]  # (side, height) of the cue tip, fractions of the radius
    target: int | None  # the ball it pots (or plays at)
    pocket: int | None  # the pocket it plays for
    chance: float | None  # the share of its noisy trials that pocketed a ball legally
    via: str | None = None  # a pot's route: "direct", "bank" (off a cushion), "combo", "carom",
    # "billiard" (the cue ball glances off the first ball into the one it pots)
    elevation: float = 0.0  # the cue's elevation, radians (a jump, swerve or massé); 0 is left out


def hint_ask(settings: Settings, address: str | None, player: str | None) -> HintAsk:
    """Who asks (`requester` keys: the address, and the player when there is a profile),
    the queue's bounds and the address's planning budget from the settings."""
    requester: list[tuple[str, str]] = []
    budgeted: tuple[tuple[str, str], ...] = ()
    if address is not None:
        requester.append(("address", address))
        budgeted = (("address", address),)
    if player is not None:
        requester.append(("player", player))
    return HintAsk(
        tuple(requester), settings.hint_queue, settings.hint_wait, budgeted, settings.hint_budget
    )


async def hint_for(
    live: LiveRoom, token: str, settings: Settings, ask: HintAsk | None = None
) -> dict[str, Any]:
    """The `Hint` for the seat of `token` (planned off the event loop, after the rooms'
    computer turns); a refusal is raised as the HTTP error the endpoint answers with."""
    workers, starved = settings.computer_workers, settings.computer_starved
    try:
        turn = await plan_hint(
            live.room, token, workers, starved, ask or hint_ask(settings, None, None)
        )
    except ActionError as exc:
        raise HTTPException(
            _STATUS.get(exc.code, 409), {"code": exc.code, "message": exc.message}
        ) from None
    if turn.shot is None:  # a decision: practice has none, but say so plainly if it comes
        raise HTTPException(
            409, {"code": "not_your_turn", "message": "There is a decision to make, not a shot."}
        )
    raised = {"elevation": turn.shot.elevation} if turn.shot.elevation > 0.0 else {}
    return {
        "level": HINT_LEVEL,
        "kind": turn.kind or "pot",
        "place": turn.place,
        "call": turn.call,
        "nominate": turn.nominate,
        "angle": turn.shot.angle,
        "speed": turn.shot.speed,
        "tip": turn.shot.tip,
        "target": turn.target,
        "pocket": turn.pocket,
        "chance": turn.chance,
        "via": turn.via,
        **raised,
    }
