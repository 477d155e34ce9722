"""Replay a stored shot: stream what was shown live, paced like the live stream.

A shot stored with its motion replays exactly those messages, whatever engine is installed
now. An older row without motion is simulated again, but only by the engine version that
played it (the engine is deterministic and the stored floats exact, so that gives the
original bit for bit); a newer engine refuses rather than show a different shot.
"""

from __future__ import annotations

import asyncio
from collections.abc import AsyncIterator

from server.codec import from_data
from server.engine import ENGINE_VERSION, BallSet, Shot, ShotResult, Table, simulate
from server.protocol import message_text, plan_shot
from server.protocol.outbound import ReplayRef, ReplayResultMessage, text
from server.protocol.plan import motion_messages
from server.rules import Outcome
from server.store import MatchRecord, ShotRecord

# The engine that played the shots stored before engine versions were recorded (a literal:
# it must not follow ENGINE_VERSION when the physics changes).
FIRST_RECORDED_ENGINE = "1+343d34160186"


class EngineChanged(Exception):
    """The shot was played by another engine and its motion was not kept."""


def resimulate(record: ShotRecord) -> ShotResult:
    return simulate(
        from_data(Table, record.table),
        BallSet.from_dict(record.balls),
        from_data(Shot, record.shot),
    )


def replay_motion(
    record: ShotRecord, frame_every: int, frames_per_message: int = 1
) -> list[tuple[float, str, str]]:
    """The `frame` and `event` messages of the shot as (at, kind, body), as shown live."""
    if record.motion is not None:
        return motion_messages(record.motion)
    if (record.engine or FIRST_RECORDED_ENGINE) != ENGINE_VERSION:
        raise EngineChanged(
            f"shot {record.n} was played by engine {record.engine}; this "
            f"server runs {ENGINE_VERSION}"
        )
    plan = plan_shot(resimulate(record), record.room_shot, frame_every, frames_per_message)
    return [(timed.at, timed.kind, timed.body) for timed in plan]


def result_message(record: ShotRecord, match: MatchRecord, seq: int) -> ReplayResultMessage:
    """The `shot_result` closing a replay: the outcome as it was judged then."""
    return ReplayResultMessage(
        seq=seq,
        shot=record.room_shot,
        outcome=Outcome.from_dict(record.outcome),
        replay=ReplayRef(match=match.id, n=record.n),
    )


async def stream_replay(
    messages: list[tuple[float, str, str]], record: ShotRecord, match: MatchRecord, pace: float
) -> AsyncIterator[str]:
    """NDJSON lines paced like the live stream (`pace` 2.0 plays twice as fast)."""
    loop = asyncio.get_running_loop()
    start = loop.time()
    seq = 0
    for at, kind, body in messages:
        delay = start + at / pace - loop.time()
        if delay > 0:
            await asyncio.sleep(delay)
        seq += 1
        yield message_text(kind, seq, body) + "\n"
    yield text(result_message(record, match, seq + 1)) + "\n"
