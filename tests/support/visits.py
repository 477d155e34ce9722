"""A ranked match played just far enough to be rated, over real sockets: each side has a
visit at the table, then the second concedes (the audit's farm, one round)."""

from __future__ import annotations

from typing import Any

import websockets

from .games import BREAK, EIGHT_BALL_GROUP_SHOT, EIGHT_BALL_PLACE, EIGHT_BALL_SCRATCH, shoot_message
from .live import greet, send, until


async def _open(url: str, token: str) -> Any:
    ws = await websockets.connect(f"{url}?token={token}")
    await greet(ws)
    return ws


async def visit_and_concede(url: str, breaker_token: str, other_token: str) -> dict:
    """Seat 0 breaks (`EIGHT_BALL`: legal) and scratches, seat 1 takes ball in hand and
    pots a ball, then concedes (a match is rated once each side has played); the final
    `state`. `url`: the room's socket (`ws_url`)."""
    breaker = await _open(url, breaker_token)
    other = await _open(url, other_token)
    place = {"type": "place_cue", "x": EIGHT_BALL_PLACE[0], "y": EIGHT_BALL_PLACE[1]}
    try:
        for shooter, message in (
            (breaker, shoot_message(BREAK)),
            (breaker, shoot_message(EIGHT_BALL_SCRATCH)),
            (other, place),
            (other, shoot_message(EIGHT_BALL_GROUP_SHOT)),
        ):
            await send(shooter, message)
            if message is place:
                await until(other, "state")
                continue
            await until(other, "shot_result")
            await until(other, "state")
        await send(other, {"type": "concede"})
        while not (state := (await until(breaker, "state"))[-1])["match"]["match_over"]:
            pass
        return state
    finally:
        await breaker.close()
        await other.close()
