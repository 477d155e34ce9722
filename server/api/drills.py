"""HTTP route for drills: a practice table set up from an analysed shot ("play this
position again"), with the pro's chance there as the par."""

from __future__ import annotations

import json
import time
from typing import Annotated, Any

from fastapi import APIRouter, HTTPException, status
from pydantic import Field

from server.rooms.drills import DrillSetup
from server.store import Repository
from server.store.analyses import READY, AnalysisRows
from server.store.drills import DrillRows

from . import owner
from .deps import BaseUrl, ClientId, ClusterDep, Quotas, Registry, Store
from .inputs import StrictBody
from .schemas import CreateRoom, ErrorResponse, RoomCreated

router = APIRouter()


class DrillAsk(StrictBody):
    match_id: Annotated[int, Field(ge=1, le=2**62)]
    n: Annotated[int, Field(ge=1, le=2**31)]


class DrillCreated(RoomCreated):
    match_id: int
    n: int
    par: float  # the pro's chance from this table (share of its noisy trials that pot)


def _refused(code: int, tag: str, message: str) -> HTTPException:
    return HTTPException(code, {"code": tag, "message": message})


@router.post(
    "/api/drills",
    status_code=status.HTTP_201_CREATED,
    response_model=DrillCreated,
    responses={
        404: {"model": ErrorResponse},
        409: {"model": ErrorResponse},
        429: {"model": ErrorResponse},
        503: {"model": ErrorResponse},
    },
    tags=["history"],
)
async def create_drill(
    body: DrillAsk,
    registry: Registry,
    store: Store,
    quotas: Quotas,
    client: ClientId,
    cluster: ClusterDep,
    base: BaseUrl,
) -> dict[str, Any]:
    """A private practice table with the stored table before shot `n` of an analysed match
    (the same ball in hand or not); join it next to play. Opened on the process asked.
    404 `unknown_shot`; 409 `analysis_not_ready` (ask for the analysis first)."""
    quotas.enforce("create", client)

    def load(repo: Repository) -> tuple[Any, Any]:
        return AnalysisRows(repo).get(body.match_id), repo.shot(body.match_id, body.n)

    analysis, shot = await store.call(load)
    if shot is None:
        raise _refused(404, "unknown_shot", "No such shot.")
    if analysis is None or analysis.status != READY or analysis.result is None:
        raise _refused(409, "analysis_not_ready", "Analyse the match first.")
    judged = next((s for s in json.loads(analysis.result)["shots"] if s["n"] == body.n), None)
    if judged is None:
        raise _refused(404, "unknown_shot", "That shot was not analysed.")
    par = float(judged["best"]["chance"])
    setup = DrillSetup(shot.balls, judged["ball_in_hand"], par, body.match_id, body.n)
    practice = CreateRoom(game="practice", listed=False)
    created = await owner.open_room(registry, cluster, practice, client, base, setup)
    room_id = created["room_id"]
    await store.call(
        lambda repo: DrillRows(repo).add(room_id, body.match_id, body.n, par, time.time())
    )
    return {**created, "match_id": body.match_id, "n": body.n, "par": par}
