"""Match analysis: how long a finished match waits for its analysis, and how the pro's own
shots are judged.

    python -m bench.analysis [--matches 5] [--pro-games 3] [--workers 1]

time to ready: `--matches` games of 8-ball (a race to 1) between an amateur (standing for
a person) and the club-level computer are stored as a room stores them; each is then asked
for through the server's queue (`AnalysisQueue.request`, the route's own call, with the
server's default settings: one idle-class planner process) and timed from that first
request until the stored analysis is served. Prints the median and the slowest (the
first includes starting the planner process).

pro judged: `--pro-games` games between two pro-level computers, stored as a room stores
a computer's shots (the stroke played and the plan it came from), read back and analysed
as the server does; prints the share of their shots judged best or good (the goal: at
least 90 %) and each verdict's count; then again as rows without the plan (stored before
it was kept) are judged: by the stroke as played.
"""

from __future__ import annotations

import argparse
import asyncio
import statistics
import tempfile
import time
from collections import Counter
from dataclasses import replace
from pathlib import Path

from server.ai.analysis import StoredShot, analyse_match
from server.ai.analysis.selfplay import self_play
from server.config import Settings
from server.engine import Table
from server.rooms.analyses import AnalysisQueue, stored_shot
from server.store import Database, Repository

KIND = "eight_ball"
PERSON, COMPUTER = "amateur", "club"
PROS = ("pro 0", "pro 1")
FIRST_SEED = 100


def store_match(
    repo: Repository,
    match_id: int,
    shots: list[StoredShot],
    players: tuple[str, str] = (f"{PERSON} (a person)", f"{COMPUTER} (the computer)"),
) -> None:
    """The match as a room records it (a computer's plan kept beside its stroke)."""
    repo.start_match(match_id, f"bench-{match_id}", KIND, list(players), 1)
    table = Table.pool("9ft").fields()
    for s in shots:
        repo.record_shot(
            match_id, s.n, s.game, s.seat, s.shot, table, s.balls, s.outcome, intended=s.intended
        )
    repo.finish_match(match_id, [1, 0], 0, "over")


async def time_to_ready(db: Database, settings: Settings, match_ids: list[int]) -> list[float]:
    queue = AnalysisQueue(db, settings)
    times = []
    try:
        for match_id in match_ids:
            start = time.perf_counter()
            answer = await queue.request(match_id)
            while answer.status == "pending":
                await queue.drained()
                answer = await queue.request(match_id)
            assert answer.status == "ready", answer
            times.append(time.perf_counter() - start)
    finally:
        await queue.close()
    return times


def bench_ready(matches: int, workers: int) -> None:
    games = [self_play(KIND, (PERSON, COMPUTER), FIRST_SEED + k) for k in range(matches)]
    with tempfile.TemporaryDirectory() as tmp:
        db = Database(Path(tmp) / "bench.db")
        try:
            for match_id, shots in enumerate(games, 1):
                db.run(lambda repo, i=match_id, s=shots: store_match(repo, i, s))
            settings = Settings(analysis_workers=workers)
            times = asyncio.run(time_to_ready(db, settings, list(range(1, matches + 1))))
        finally:
            db.close()
    shots = [len(g) for g in games]
    print(
        f"time to ready, {matches} matches of {KIND} race to 1 ({PERSON} vs the {COMPUTER}"
        f" computer, {min(shots)}-{max(shots)} shots): median {statistics.median(times):.1f} s,"
        f" slowest {max(times):.1f} s ({', '.join(f'{t:.1f}' for t in times)})"
    )


def stored_pro_games(games: int) -> list[list[StoredShot]]:
    """Pro-vs-pro games stored with their plans and read back as the analysis reads them."""
    played = [self_play(KIND, ("pro", "pro"), FIRST_SEED + 50 + k, True) for k in range(games)]
    with tempfile.TemporaryDirectory() as tmp:
        db = Database(Path(tmp) / "bench.db")
        try:
            for k, shots in enumerate(played):
                db.run(lambda repo, i=1000 + k, s=shots: store_match(repo, i, s, PROS))
            rows = [db.run(lambda repo, i=1000 + k: repo.shots(i)) for k in range(games)]
        finally:
            db.close()
    return [[stored_shot(r) for r in match] for match in rows]


def bench_pro(games: list[list[StoredShot]], intended: bool) -> None:
    verdicts: Counter[str] = Counter()
    for k, stored in enumerate(games):
        shots = stored if intended else [replace(s, intended=None) for s in stored]
        analysis = analyse_match(1000 + k, KIND, list(PROS), shots)
        verdicts.update(s.verdict for s in analysis.shots)
    total = sum(verdicts.values())
    share = (verdicts["best"] + verdicts["good"]) / max(total, 1)
    counts = ", ".join(f"{v} {verdicts[v]}" for v in ("best", "good", "mistake", "blunder"))
    strokes = (
        "as stored (the plan kept beside each stroke)"
        if intended
        else "without the plan (older rows: the planned stroke with the arm's error)"
    )
    print(
        f"pro vs pro, {len(games)} games, {total} shots, judged {strokes}:"
        f" best or good {100 * share:.0f} % ({counts})"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--matches", type=int, default=5)
    parser.add_argument("--pro-games", type=int, default=3)
    parser.add_argument("--workers", type=int, default=1)
    args = parser.parse_args()
    if args.matches:
        bench_ready(args.matches, args.workers)
    if args.pro_games:
        games = stored_pro_games(args.pro_games)
        bench_pro(games, intended=True)
        bench_pro(games, intended=False)


if __name__ == "__main__":
    main()
