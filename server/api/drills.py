"""HTTP route for drills (`server.rooms.drills`): a practice table set up from an analysed
shot ("play this position again", the pro's chance there as the par), a ghost 9-ball
rack, or a progressive line-up."""

from __future__ import annotations

import json
import time
from typing import Annotated, Any, Literal

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
    kind: Literal["position", "ghost", "lineup"] = "position"
    match_id: Annotated[int, Field(ge=1, le=2**62)] | None = None  # position: the match
    n: Annotated[int, Field(ge=1, le=2**31)] | None = None  # position: the shot


class DrillCreated(RoomCreated):
    kind: Literal["position", "ghost", "lineup"]
    match_id: int | None
    n: int | None
    par: float | None  # position: the pro's chance from this table (its trials that pot)


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
    """A private practice table for a drill; join it next to play. `position`: the stored
    table before shot `n` of analysed match `match_id` (the same ball in hand or not);
    `ghost`: a 9-ball rack to clear against the ghost; `lineup`: balls in a line to clear,
    one more each rack, until a miss. Opened on the process asked.
    404 `unknown_shot`; 409 `analysis_not_ready` (ask for the analysis first)."""
    quotas.enforce("create", client)
    if body.kind == "position":
        setup = await _position(body, store)
    else:
        setup = DrillSetup(kind=body.kind)
    practice = CreateRoom(game="practice", listed=False)
    created = await owner.open_room(registry, cluster, practice, client, base, setup)
    room_id, now = created["room_id"], time.time()
    await store.call(
        lambda repo: DrillRows(repo).add(
            room_id, setup.kind, now, setup.match_id, setup.n, setup.par
        )
    )
    return {
        **created,
        "kind": setup.kind,
        "match_id": setup.match_id,
        "n": setup.n,
        "par": setup.par,
    }


async def _position(body: DrillAsk, store: Store) -> DrillSetup:
    """The setup of a position drill: the stored table, the analysis' ball in hand and par."""
    match_id, n = body.match_id, body.n
    if match_id is None or n is None:
        raise _refused(422, "position_needed", "A position drill needs match_id and n.")

    def load(repo: Repository) -> tuple[Any, Any]:
        return AnalysisRows(repo).get(match_id), repo.shot(match_id, n)

    analysis, shot = await store.call(load)
    if shot is None:
        raise _refused(404, "unknown_shot", "No such shot.")
    if analysis is None or analysis.status != READY or analysis.result is None:
        raise _refused(409, "analysis_not_ready", "Analyse the match first.")
    judged = next((s for s in json.loads(analysis.result)["shots"] if s["n"] == n), None)
    if judged is None:
        raise _refused(404, "unknown_shot", "That shot was not analysed.")
    par = float(judged["best"]["chance"])
    return DrillSetup(shot.balls, judged["ball_in_hand"], par, match_id, n)
