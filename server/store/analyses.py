"""The analyses of finished matches: a queue in the store, so that in a cluster one process
analyses a match once, and the results kept for every later request.

A request adds a `queued` row (a repeat changes nothing). A process takes the oldest
queued row by turning it `running` under its name in one conditional update: of two
processes trying, one changes the row and the other finds it taken. A `running` row
claimed before the stale time (its process died) may be claimed again. Only the claimant
stores the result (`ready`) or the error (`failed`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from sqlalchemy import and_, func, or_, select, tuple_
from sqlalchemy.dialects import postgresql, sqlite

from .repository import Repository
from .schema import analyses

QUEUED, RUNNING, READY, FAILED = "queued", "running", "ready", "failed"
CLAIM_TRIES = 4  # rows tried when other processes take the first ones meanwhile


@dataclass(frozen=True)
class AnalysisRecord:
    match_id: int
    status: str  # queued | running | ready | failed
    requested_at: float
    claimed_by: str | None
    claimed_at: float | None
    result: str | None  # JSON (ready) or the error (failed)
    finished_at: float | None


class AnalysisRows:
    """Queries over the repository's connection (each method one transaction)."""

    def __init__(self, repo: Repository) -> None:
        self.repo = repo

    def request(self, match_id: int, now: float) -> AnalysisRecord:
        """The match's analysis, queued now unless it was asked for before."""
        insert = postgresql.insert if self.repo.dialect == "postgresql" else sqlite.insert
        row = {"match_id": match_id, "status": QUEUED, "requested_at": now}
        with self.repo.transaction() as conn:
            conn.execute(insert(analyses).values(**row).on_conflict_do_nothing())
            found = self.get(match_id)
        assert found is not None
        return found

    def get(self, match_id: int) -> AnalysisRecord | None:
        with self.repo.transaction(write=False) as conn:
            row = conn.execute(select(analyses).where(analyses.c.match_id == match_id)).first()
        return None if row is None else AnalysisRecord(*row)

    def results(self, match_ids: list[int]) -> dict[int, str]:
        """The stored results (JSON) of those of `match_ids` that are ready."""
        if not match_ids:
            return {}
        query = select(analyses.c.match_id, analyses.c.result).where(
            analyses.c.match_id.in_(match_ids), analyses.c.status == READY
        )
        with self.repo.transaction(write=False) as conn:
            return {int(r[0]): str(r[1]) for r in conn.execute(query)}

    def position(self, record: AnalysisRecord) -> int:
        """How many analyses are queued or running ahead of this queued one (0 when it is
        running)."""
        if record.status != QUEUED:
            return 0
        ahead = tuple_(analyses.c.requested_at, analyses.c.match_id) < (
            record.requested_at,
            record.match_id,
        )
        query = (
            select(func.count())
            .select_from(analyses)
            .where(
                analyses.c.status.in_([QUEUED, RUNNING]), or_(ahead, analyses.c.status == RUNNING)
            )
        )
        with self.repo.transaction(write=False) as conn:
            return int(conn.scalar(query) or 0)

    def waiting(self) -> int:
        """Analyses queued, not yet taken."""
        query = select(func.count()).select_from(analyses).where(analyses.c.status == QUEUED)
        with self.repo.transaction(write=False) as conn:
            return int(conn.scalar(query) or 0)

    def claim(self, owner: str, now: float, stale_before: float) -> int | None:
        """Take the oldest queued analysis (or one whose claimant went silent before
        `stale_before`) for `owner`; its match id, or None when there is none to take."""
        claimable = or_(
            analyses.c.status == QUEUED,
            and_(analyses.c.status == RUNNING, analyses.c.claimed_at < stale_before),
        )
        oldest = (
            select(analyses.c.match_id)
            .where(claimable)
            .order_by(analyses.c.requested_at, analyses.c.match_id)
            .limit(CLAIM_TRIES)
        )
        with self.repo.transaction() as conn:
            for match_id in conn.scalars(oldest).all():
                taken = conn.execute(
                    analyses.update()
                    .where(analyses.c.match_id == match_id, claimable)
                    .values(status=RUNNING, claimed_by=owner, claimed_at=now)
                )
                if taken.rowcount == 1:
                    return int(match_id)
        return None

    def finish(self, match_id: int, owner: str, result: str, now: float, ok: bool = True) -> bool:
        """Store the result (or, `ok` False, the error) of the claimant `owner`; False
        when another process holds the claim now (this one was taken for dead)."""
        values: dict[str, Any] = {"status": READY if ok else FAILED, "result": result}
        with self.repo.transaction() as conn:
            done = conn.execute(
                analyses.update()
                .where(
                    analyses.c.match_id == match_id,
                    analyses.c.status == RUNNING,
                    analyses.c.claimed_by == owner,
                )
                .values(**values, finished_at=now)
            )
        return bool(done.rowcount == 1)
