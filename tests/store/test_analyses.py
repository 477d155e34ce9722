"""The analyses' queue in the store: a request queues once, one claimant takes a match
(another finds it taken), a silent claim is taken over, and only the claimant stores the
result."""

from __future__ import annotations

from server.store import Database, Repository
from server.store.analyses import AnalysisRows


def _matches(repo: Repository, *ids: int) -> None:
    for match_id in ids:
        repo.start_match(match_id, f"r{match_id}", "eight_ball", ["a", "b"], 1)
        repo.finish_match(match_id, [1, 0], 0, "done")


def test_one_claimant_takes_each_match_in_order(db: Database) -> None:
    def run(repo: Repository) -> None:
        _matches(repo, 1, 2)
        rows = AnalysisRows(repo)
        second = rows.request(2, now=10.0)
        first = rows.request(1, now=20.0)
        assert rows.request(2, now=30.0) == second  # asked again: unchanged
        assert (rows.position(second), rows.position(first)) == (0, 1)
        assert rows.waiting() == 2
        assert rows.claim("p1", now=40.0, stale_before=0.0) == 2
        assert rows.claim("p2", now=41.0, stale_before=0.0) == 1
        assert rows.claim("p3", now=42.0, stale_before=0.0) is None
        assert rows.waiting() == 0

    db.run(run)


def test_a_silent_claim_is_taken_over_and_only_the_claimant_finishes(db: Database) -> None:
    def run(repo: Repository) -> None:
        _matches(repo, 5)
        rows = AnalysisRows(repo)
        rows.request(5, now=1.0)
        assert rows.claim("dead", now=2.0, stale_before=0.0) == 5
        assert rows.claim("alive", now=3.0, stale_before=1.0) is None  # not stale yet
        assert rows.claim("alive", now=700.0, stale_before=100.0) == 5
        assert not rows.finish(5, "dead", "{}", now=701.0)
        assert rows.finish(5, "alive", '{"shots": []}', now=702.0)
        found = rows.get(5)
        assert found is not None
        assert (found.status, found.result) == ("ready", '{"shots": []}')
        assert rows.results([5, 6]) == {5: '{"shots": []}'}

    db.run(run)
