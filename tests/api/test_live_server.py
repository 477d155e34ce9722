"""A real uvicorn on a free port, real sockets, real-time pacing, the `websockets` client.

Covers what TestClient cannot: uvicorn's own 1009 on a big frame, the handshake refusal as
a browser sees it (HTTP 403), a player dropping mid-shot and reconnecting, wall-clock pacing.
"""

from __future__ import annotations

import asyncio
import time

import pytest
import websockets
from websockets.exceptions import ConnectionClosed, InvalidStatus

from tests.support.games import (
    BREAK_MESSAGE,
    EIGHT_BALL_BREAK_BALL,
    EIGHT_BALL_SCRATCH,
    shoot_message,
)
from tests.support.live import greet, http, live_server, recv, send, until
from tests.support.rooms import create_room, seated_room

pytestmark = pytest.mark.timeout(120)


async def play(address: str, room_id: str, tokens: list[str]) -> None:
    """The 8-ball game of `games.EIGHT_BALL`: the break pockets a ball, Ana plays again and
    scratches."""
    url = f"ws://{address}/ws/rooms/{room_id}"
    with pytest.raises(InvalidStatus) as refused:  # a foreign page is refused at handshake
        async with websockets.connect(f"{url}?token={tokens[0]}", origin="http://evil.example"):
            pass
    assert refused.value.response.status_code == 403

    a = await websockets.connect(f"{url}?token={tokens[0]}", origin=f"http://{address}")
    b = await websockets.connect(f"{url}?token={tokens[1]}")
    s = await websockets.connect(url)
    try:
        for ws in (a, b, s):
            await greet(ws)
        await until(a, "presence")
        await until(a, "presence")
        await until(b, "presence")

        # the break: its motion at the strike, its result when it has been shown in real
        # time; Ben drops mid-shot and comes back
        await send(a, BREAK_MESSAGE)
        motion = await recv(b)
        strike_seen = time.monotonic()
        assert motion["type"] == "motion" and motion["sounds"][0]["kind"] == "strike"
        await asyncio.sleep(0.6)
        await b.close()
        b = await websockets.connect(f"{url}?token={tokens[1]}")
        welcome, state = await greet(b)
        assert welcome["seat"] == 1
        assert state["phase"] == "rolling" and state["shot"]["tick"] >= 60
        resumed = await until(b, "state")
        assert resumed[0] == motion  # the same motion, to play on from `shot.tick`
        assert [m["type"] for m in resumed[1:]] == ["shot_result", "state"]
        assert resumed[-2]["outcome"]["pocketed"] == [EIGHT_BALL_BREAK_BALL]
        watched = time.monotonic() - strike_seen
        assert watched >= 0.95 * motion["duration"]  # the result once the shot is shown

        spectator_view = await until(s, "state")
        player_view = await until(a, "state")
        assert spectator_view[-1]["match"] == player_view[-1]["match"] == resumed[-1]["match"]
        assert sum(m["type"] == "shot_result" for m in player_view) == 1

        # Ana again: her shot touches nothing and the cue ball drops, Ben has ball in hand
        assert resumed[-1]["match"]["turn"] == 0
        await send(a, shoot_message(EIGHT_BALL_SCRATCH))
        second = await until(s, "state")
        result = next(m for m in second if m["type"] == "shot_result")
        assert result["shot"] == 2 and result["outcome"]["shooter"] == 0
        assert [f["code"] for f in result["outcome"]["fouls"]] == ["no_contact", "scratch"]
        assert second[-1]["match"]["turn"] == 1
        assert second[-1]["match"]["ball_in_hand"] == "anywhere"

        # a frame over 16 KiB: uvicorn closes with 1009
        await send(a, {"type": "chat", "text": "x" * (20 * 1024)})
        with pytest.raises(ConnectionClosed) as closed:
            while True:
                await recv(a)
        assert closed.value.rcvd is not None and closed.value.rcvd.code == 1009
    finally:
        for ws in (a, b, s):
            await ws.close()


@pytest.mark.slow  # many seconds: not in scripts/test --quick
def test_real_server_plays_shots_with_reconnection_mid_shot(settings):
    with live_server(settings.replace(pace=1.0)) as address, http(address) as client:
        room_id, ta, tb = seated_room(client)
        asyncio.run(play(address, room_id, [ta, tb]))


async def spectate_offering_deflate(address: str, room_id: str) -> tuple[str | None, dict]:
    """A spectator that offers permessage-deflate, as browsers do: the extensions the server
    accepted, and the `state` it then read."""
    async with websockets.connect(
        f"ws://{address}/ws/rooms/{room_id}", compression="deflate"
    ) as ws:
        _, state = await greet(ws)
        return ws.response.headers.get("Sec-WebSocket-Extensions"), state


@pytest.mark.parametrize("deflate", [False, True])
def test_permessage_deflate_is_accepted_only_when_enabled(settings, deflate):
    with live_server(settings.replace(ws_deflate=deflate)) as address, http(address) as client:
        room_id = create_room(client, "practice")
        extensions, state = asyncio.run(spectate_offering_deflate(address, room_id))
    assert ("permessage-deflate" in (extensions or "")) is deflate
    assert state["room"]["game"] == "practice"
    assert state["table"]["length"] == pytest.approx(2.54)
