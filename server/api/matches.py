"""HTTP routes for the match history: recent matches, one match with its shots, and the
replay of a stored shot streamed like the live one (NDJSON, paced in real time)."""

from __future__ import annotations

import asyncio
from dataclasses import asdict
from typing import Annotated, Any, Literal

from fastapi import APIRouter, HTTPException, Query
from fastapi.responses import StreamingResponse
from pydantic import BaseModel

from server.codec import from_data
from server.engine import TICK_HZ, BallSet, Table
from server.protocol import BallRow, StreamRates, frame_rows
from server.protocol.limits import FRAMES_PER_MESSAGE
from server.rooms.replay import EngineChanged, replay_motion, stream_replay
from server.store import MatchRecord, Repository, ShotRecord

from .deps import SettingsDep, Store
from .inputs import RowId
from .schemas import ErrorResponse

router = APIRouter()
_NOT_FOUND: dict[int | str, dict[str, Any]] = {
    404: {"model": ErrorResponse},
    422: {"description": "Validation error"},
}


class MatchBase(BaseModel):
    id: int
    room_id: str
    game: str
    players: list[str]
    race_to: int
    status: Literal["playing", "finished", "abandoned"]
    score: list[int]
    winner: int | None
    winner_name: str | None
    reason: str | None
    started_at: float
    finished_at: float | None


class MatchSummary(MatchBase):
    games: int  # games (frames) finished
    shots: int


class MatchList(BaseModel):
    matches: list[MatchSummary]


class GameSummary(BaseModel):
    n: int
    winner: int | None
    reason: str | None
    cause: str
    score: list[int]
    finished_at: float


class StoredShot(BaseModel):
    n: int
    shot_id: int
    game: int
    seat: int
    shot: dict[str, Any]
    table: list[float]
    balls: dict[str, Any]
    outcome: dict[str, Any]
    played_at: float
    replay: str
    engine: str | None  # the engine version that played it (None: not recorded)
    # the computer's planned stroke before its arm's error, when kept (what the analysis
    # judges); None: `shot` is what was meant (a person's stroke as sent, or an older row)
    intended: dict[str, Any] | None = None
    b: list[list[int]]  # the balls on the table before it, as in `state`: [id, x_mm, y_mm, cel]


class MatchDetail(MatchBase):
    games: list[GameSummary]
    shots: list[StoredShot]
    # the table as `state.table` gives it (to draw a replay); None: no shot
    geometry: dict[str, Any] | None
    stream: StreamRates  # how a replay is streamed (tick rate and frames)


def _missing(what: str) -> HTTPException:
    return HTTPException(404, {"code": f"unknown_{what}", "message": f"No such {what}."})


@router.get("/api/matches", response_model=MatchList, tags=["history"])
async def recent_matches(
    store: Store,
    limit: Annotated[int, Query(ge=1, le=100)] = 20,
    status: Literal["playing", "finished", "abandoned"] | None = None,
    room: Annotated[str | None, Query(max_length=64)] = None,
) -> dict[str, Any]:
    """Matches newest first (finished, still being played, or abandoned); `room`: only
    that room's (its match and rematches, whatever their status)."""
    records = await store.call(lambda repo: repo.recent_matches(limit, status, room))
    return {"matches": [_match_row(r) for r in records]}


@router.get(
    "/api/matches/{match_id}", response_model=MatchDetail, responses=_NOT_FOUND, tags=["history"]
)
async def show_match(match_id: RowId, store: Store, settings: SettingsDep) -> dict[str, Any]:
    """One match: its games (frames) and every shot, with the table before it (exact)."""

    def load(repo: Repository) -> Any:
        match = repo.match(match_id)
        return None if match is None else (match, repo.games(match_id), repo.shots(match_id))

    found = await store.call(load)
    if found is None:
        raise _missing("match")
    match, games, shots = found
    rows = [_shot_row(s) for s in shots]
    geometry = from_data(Table, shots[0].table).to_dict() if shots else None
    games_rows = [{k: v for k, v in asdict(g).items() if k != "match_id"} for g in games]
    return {
        **_match_row(match),
        "games": games_rows,
        "shots": rows,
        "geometry": geometry,
        "stream": StreamRates(
            tick_hz=TICK_HZ,
            frame_every=settings.frame_every,
            frames_per_message=FRAMES_PER_MESSAGE,
        ),
    }


def _match_row(match: MatchRecord) -> dict[str, Any]:
    row = asdict(match)
    row["game"] = row.pop("kind")
    row["winner_name"] = match.players[match.winner] if match.winner is not None else None
    return row


def _shot_row(shot: ShotRecord) -> dict[str, Any]:
    return {
        "n": shot.n,
        "shot_id": shot.room_shot,
        "game": shot.game,
        "seat": shot.seat,
        "shot": shot.shot,
        "table": shot.table,
        "balls": shot.balls,
        "outcome": shot.outcome,
        "played_at": shot.played_at,
        "engine": shot.engine,
        "intended": shot.intended,
        "replay": f"/api/matches/{shot.match_id}/shots/{shot.n}/replay",
        "b": _resting_rows(shot.balls),
    }


def _resting_rows(balls: dict[str, Any]) -> list[BallRow]:
    """The stored balls (exact floats) in the stream's integer rows, cel from the roll."""
    state = BallSet.from_dict(balls)
    return frame_rows(state.ids, state.positions, state.cels(), state.on_table)


@router.get(
    "/api/matches/{match_id}/shots/{n}/replay",
    responses={
        **_NOT_FOUND,
        200: {
            "content": {"application/x-ndjson": {}},
            "description": "one JSON message a line, as on the room socket",
        },
    },
    response_class=StreamingResponse,
    tags=["history"],
)
async def replay_shot(
    match_id: RowId,
    n: RowId,
    store: Store,
    settings: SettingsDep,
    pace: Annotated[float, Query(ge=0.1, le=100, allow_inf_nan=False)] = 1.0,
) -> StreamingResponse:
    """Stored shot `n`'s `motion` message exactly as the room sent it live (base64 in a
    JSON line), then its `shot_result` once the shot has played (`pace` 2: twice as fast).
    Newline-delimited JSON. 409 `engine_changed`: an old shot whose motion was not kept,
    played by an engine other than this server's."""

    def load(repo: Repository) -> tuple[MatchRecord | None, ShotRecord | None]:
        return repo.match(match_id), repo.shot(match_id, n)

    match, shot = await store.call(load)
    if match is None:
        raise _missing("match")
    if shot is None:
        raise _missing("shot")
    try:
        motion = await asyncio.to_thread(replay_motion, shot, settings.frame_every)
    except EngineChanged as exc:
        raise HTTPException(409, {"code": "engine_changed", "message": str(exc)}) from None
    return StreamingResponse(
        stream_replay(motion, shot, match, pace), media_type="application/x-ndjson"
    )
