"""HTTP route for a finished match's analysis: every shot against the pro level's best
choice (`server.ai.analysis`), queued on the first request and served from the store."""

from __future__ import annotations

import json
from typing import Any, Literal

from fastapi import APIRouter, HTTPException
from fastapi.responses import JSONResponse
from pydantic import BaseModel

from server.ai.analysis import BEST, GOOD, MISTAKE

from .deps import Analyses
from .inputs import RowId
from .schemas import ErrorResponse

router = APIRouter()


class BestShotOut(BaseModel):
    kind: str
    target: int | None
    pocket: int | None
    via: str | None
    call: int | None
    angle: float
    speed: float
    tip: tuple[float, float]
    place: tuple[float, float] | None  # where the pro puts the cue ball (ball in hand)
    chance: float  # share of the noisy draws that pocket a ball legally
    value: float  # -1 (lost) .. +1 (won): the position it leaves, over the draws


class ShotOut(BaseModel):
    n: int
    game: int
    seat: int
    verdict: Literal["best", "good", "mistake", "blunder"]
    loss: float  # winning chance given away against the best (0-1)
    played_chance: float
    played_value: float
    ball_in_hand: str | None
    push_out: bool
    best: BestShotOut


class PlayerOut(BaseModel):
    seat: int
    name: str
    accuracy: float | None  # 0-100; None: no shot of theirs
    best: int
    good: int
    mistakes: int
    blunders: int


class Thresholds(BaseModel):
    best: float
    good: float
    mistake: float


class AnalysisReady(BaseModel):
    status: Literal["ready"]
    match_id: int
    kind: str
    level: str
    players: list[PlayerOut]
    shots: list[ShotOut]
    turning_points: list[int]
    thresholds: Thresholds  # the largest loss of each verdict; above `mistake`: blunder


class AnalysisPending(BaseModel):
    status: Literal["pending"]
    position: int  # analyses ahead of this one (0: being analysed)


THRESHOLDS = {"best": BEST, "good": GOOD, "mistake": MISTAKE}
REFUSALS = {
    "unknown": (404, "unknown_match", "No such match."),
    "playing": (409, "match_playing", "The match is still being played."),
    "busy": (503, "analysis_busy", "Too many analyses are waiting; ask again later."),
    "failed": (500, "analysis_failed", "This match could not be analysed."),
}


@router.get(
    "/api/matches/{match_id}/analysis",
    response_model=AnalysisReady,
    responses={
        202: {"model": AnalysisPending, "description": "queued or being analysed"},
        404: {"model": ErrorResponse},
        409: {"model": ErrorResponse},
        503: {"model": ErrorResponse},
    },
    tags=["history"],
)
async def match_analysis(match_id: RowId, analyses: Analyses) -> Any:
    """The match's analysis: 200 once stored; 202 with the queue position while it waits
    or runs (the first request queues it). Ask again after a few seconds."""
    answer = await analyses.request(match_id)
    if answer.status == "pending":
        return JSONResponse({"status": "pending", "position": answer.position}, 202)
    if answer.status in REFUSALS:
        code, tag, message = REFUSALS[answer.status]
        raise HTTPException(code, {"code": tag, "message": message})
    assert answer.result is not None
    return {"status": "ready", **json.loads(answer.result), "thresholds": THRESHOLDS}
