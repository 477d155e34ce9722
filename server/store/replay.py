"""Replay a stored shot: simulate it again from its stored table and stream it like live.

The engine is deterministic and the stored floats are exact, so the replay is the original
shot bit for bit; the messages come from the same `plan_shot` as the live stream.
"""

from __future__ import annotations

import asyncio
from collections.abc import AsyncIterator

from server.engine import BallSet, Shot, ShotResult, Table, simulate
from server.rooms.stream import ShotPlan, encode, message_text, plan_shot

from .records import MatchRecord, ShotRecord


def resimulate(record: ShotRecord) -> ShotResult:
    shot = record.shot
    return simulate(Table(*record.table), BallSet.from_dict(record.balls),
                    Shot(shot["angle"], shot["speed"], (shot["tip"][0], shot["tip"][1])))


def replay_plan(record: ShotRecord, frame_every: int, frames_per_message: int = 1) -> ShotPlan:
    """The `frame` and `event` messages of the shot, as the live room sent them."""
    return plan_shot(resimulate(record), record.room_shot, frame_every, frames_per_message)


def result_message(record: ShotRecord, match: MatchRecord) -> dict:
    """The `shot_result` closing a replay: the outcome as it was judged then."""
    return {"type": "shot_result", "shot": record.room_shot, "cause": "shot",
            "outcome": record.outcome, "replay": {"match": match.id, "n": record.n}}


async def stream_replay(record: ShotRecord, match: MatchRecord, frame_every: int,
                        frames_per_message: int,
                        pace: float) -> AsyncIterator[str]:
    """NDJSON lines paced like the live stream (`pace` 2.0 plays twice as fast)."""
    plan = await asyncio.to_thread(replay_plan, record, frame_every, frames_per_message)
    loop = asyncio.get_running_loop()
    start = loop.time()
    seq = 0
    for timed in plan:
        delay = start + timed.at / pace - loop.time()
        if delay > 0:
            await asyncio.sleep(delay)
        seq += 1
        yield message_text(timed.kind, seq, timed.body) + "\n"
    seq += 1
    payload = result_message(record, match)
    yield encode({"type": "shot_result", "seq": seq,
                  **{k: v for k, v in payload.items() if k != "type"}}) + "\n"
