"""HTTP routes about the server itself: health, the bounds a client must respect, the
computer's levels, load and stream statistics."""

from __future__ import annotations

from typing import Annotated, Any

from fastapi import APIRouter, Query

from server.ai import LEVELS
from server.protocol import LIMITS, Limits

from .deps import Registry
from .schemas import ComputerLevels, Health, ServerStats

router = APIRouter(tags=["meta"])


@router.get("/health", response_model=Health)
async def health() -> dict[str, Any]:
    return {"status": "ok"}


@router.get("/api/limits", response_model=Limits)
async def limits() -> Limits:
    """Every bound a client's messages must respect (also in each socket's `welcome`)."""
    return LIMITS


@router.get("/api/computer", response_model=ComputerLevels)
async def computer_levels() -> dict[str, Any]:
    """The levels the computer opponent plays at, weakest first (`opponent` of a new room)."""
    return {"levels": list(LEVELS)}


@router.get("/api/stats", response_model=ServerStats)
async def server_stats(
    registry: Registry, window: Annotated[float, Query(gt=0, le=600, allow_inf_nan=False)] = 60.0
) -> dict[str, Any]:
    """Load and stream health: rooms, connections, messages waiting in outboxes, and how
    late frames left the server (percentiles over the last `window` seconds)."""
    return registry.stats(window)
