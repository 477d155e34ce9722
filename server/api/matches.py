"""HTTP routes for the match history (issue 7): recent matches, one match with its shots,
and the replay of a stored shot streamed like the live one (NDJSON, paced in real time)."""

from __future__ import annotations

from typing import Annotated, Literal

from fastapi import APIRouter, HTTPException, Query, Request
from fastapi.responses import StreamingResponse
from pydantic import BaseModel

from server.engine import BallSet, Table
from server.rooms.stream import BallRow, frame_rows
from server.store import Database
from server.store.replay import stream_replay

from .schemas import ErrorResponse

router = APIRouter()
_NOT_FOUND = {404: {"model": ErrorResponse}, 422: {"description": "Validation error"}}


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
    shot: dict
    table: list[float]
    balls: dict
    outcome: dict
    played_at: float
    replay: str
    b: list[list[int]]  # the balls on the table before it, as in `state`: [id, x_mm, y_mm, cel]


class MatchDetail(MatchBase):
    games: list[GameSummary]
    shots: list[StoredShot]
    geometry: dict | None  # the table as `state.table` gives it (to draw a replay); None: no shot


def _db(request: Request) -> Database:
    return request.app.state.store


def _missing(what: str) -> HTTPException:
    return HTTPException(404, {"code": f"unknown_{what}", "message": f"No such {what}."})


@router.get("/api/matches", response_model=MatchList, tags=["history"])
async def recent_matches(request: Request,
                         limit: Annotated[int, Query(ge=1, le=100)] = 20,
                         status: Literal["playing", "finished", "abandoned"] | None = None
                         ) -> dict:
    """Matches newest first (finished, still being played, or abandoned)."""
    records = await _db(request).call(lambda repo: repo.recent_matches(limit, status))
    return {"matches": [r.to_dict() for r in records]}


@router.get("/api/matches/{match_id}", response_model=MatchDetail, responses=_NOT_FOUND,
            tags=["history"])
async def show_match(match_id: int, request: Request) -> dict:
    """One match: its games (frames) and every shot, with the table before it (exact)."""
    def load(repo):
        match = repo.match(match_id)
        return None if match is None else (match, repo.games(match_id), repo.shots(match_id))

    found = await _db(request).call(load)
    if found is None:
        raise _missing("match")
    match, games, shots = found
    rows = [s.to_dict() for s in shots]
    for row in rows:
        row["b"] = _resting_rows(row["balls"])
    geometry = Table(*rows[0]["table"]).to_dict() if rows else None
    return {**match.to_dict(), "games": [g.to_dict() for g in games], "shots": rows,
            "geometry": geometry}


def _resting_rows(balls: dict) -> list[BallRow]:
    """The stored balls (exact floats) in the stream's integer rows, cel from the roll."""
    state = BallSet.from_dict(balls)
    return frame_rows(state.ids, state.positions, state.cels(), state.on_table)


@router.get("/api/matches/{match_id}/shots/{n}/replay", responses={
    **_NOT_FOUND, 200: {"content": {"application/x-ndjson": {}},
                        "description": "one JSON message a line, as on the room socket"}},
            response_class=StreamingResponse, tags=["history"])
async def replay_shot(match_id: int, n: int, request: Request,
                      pace: Annotated[float, Query(gt=0, le=100, allow_inf_nan=False)] = 1.0
                      ) -> StreamingResponse:
    """Simulate stored shot `n` again and stream its `frame` and `event` messages exactly as
    the room sent them live (same format, same timing; `pace` 2 plays twice as fast), then
    its `shot_result`. Newline-delimited JSON."""
    def load(repo):
        return repo.match(match_id), repo.shot(match_id, n)

    match, shot = await _db(request).call(load)
    if match is None:
        raise _missing("match")
    if shot is None:
        raise _missing("shot")
    settings = request.app.state.settings
    return StreamingResponse(stream_replay(shot, match, settings.frame_every,
                                           settings.frames_per_message, pace),
                             media_type="application/x-ndjson")
