"""Replay a stored shot: the `motion` message that was shown live, then its result.

A shot stored with its motion replays exactly that, whatever engine is installed now (a
shot stored as `frame` and `event` messages, before the `motion` message, is converted).
An older row without motion is simulated again, but only by the engine version that
played it (the engine is deterministic and the stored floats exact, so that gives the
original bit for bit); a newer engine refuses rather than show a different shot.
"""

from __future__ import annotations

import asyncio
import base64
from collections.abc import AsyncIterator

from server.codec import from_data
from server.engine import ENGINE_VERSION, BallSet, Shot, ShotResult, Table, simulate
from server.protocol import plan_shot, trace
from server.protocol.motion import HEADER, TIME_UNIT, with_seq
from server.protocol.outbound import MotionMessage, ReplayRef, ReplayResultMessage, text
from server.protocol.plan import stored_motion
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


def replay_motion(record: ShotRecord, frame_every: int) -> bytes:
    """The shot's `motion` message, as shown live."""
    if record.motion is not None:
        return stored_motion(record.motion, record.room_shot)
    if (record.engine or FIRST_RECORDED_ENGINE) != ENGINE_VERSION:
        raise EngineChanged(
            f"shot {record.n} was played by engine {record.engine}; this "
            f"server runs {ENGINE_VERSION}"
        )
    table = from_data(Table, record.table)
    balls = BallSet.from_dict(record.balls)
    shot = from_data(Shot, record.shot)
    result = simulate(table, balls, shot)
    return plan_shot(result, trace(table, balls, shot), record.room_shot, frame_every).motion


def result_message(record: ShotRecord, match: MatchRecord, seq: int) -> ReplayResultMessage:
    """The `shot_result` closing a replay: the outcome as it was judged then."""
    return ReplayResultMessage(
        seq=seq,
        shot=record.room_shot,
        outcome=Outcome.from_dict(record.outcome),
        replay=ReplayRef(match=match.id, n=record.n),
    )


def duration_of(motion: bytes) -> float:
    """Seconds from the strike to the last tick, from the message's header."""
    micros: int = HEADER.unpack_from(motion)[4]
    return micros * TIME_UNIT


async def stream_replay(
    motion: bytes, record: ShotRecord, match: MatchRecord, pace: float
) -> AsyncIterator[str]:
    """NDJSON: the `motion` message at once (base64), then, when the shot has been played
    (`pace` 2: twice as fast), its `shot_result`."""
    data = base64.b64encode(with_seq(motion, 1)).decode("ascii")
    yield text(MotionMessage(seq=1, shot=record.room_shot, data=data)) + "\n"
    await asyncio.sleep(duration_of(motion) / pace)
    yield text(result_message(record, match, 2)) + "\n"
