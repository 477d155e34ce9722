"""Guest pruning's cost: how long the store takes to delete the guests that never played,
on SQLite (the file the single server uses).

    python -m bench.guests [--guests 100000] [--played 10000]

Makes `--guests` profiles, `--played` of them with a seat taken (kept), then prunes as the
server's background task does (`GuestPruning`: statements of `BATCH` deletions until fewer
are left) and prints the time of the whole pruning and of one statement.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from server.ladder.guests import BATCH
from server.store import Database, Repository
from server.store.players import PlayerRows

MADE_AT = 1_000_000.0


def fill(db: Database, guests: int, played: int) -> None:
    def add(repo: Repository) -> None:
        rows = PlayerRows(repo)
        with repo.transaction():
            for i in range(guests):
                rows.add_player(f"g{i:07d}", f"Guest {i}", f"hash-{i}", MADE_AT)
            for i in range(played):
                rows.add_player_seat(f"g{i:07d}", f"room-{i}", 0, MADE_AT)

    db.run(add)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--guests", type=int, default=100_000)
    parser.add_argument("--played", type=int, default=10_000)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as scratch:
        db = Database(Path(scratch) / "pool.db")
        fill(db, args.guests, args.played)
        statements: list[float] = []
        pruned = 0
        started = time.perf_counter()
        while True:
            begun = time.perf_counter()
            deleted = db.run(lambda r: PlayerRows(r).prune_guests(MADE_AT + 1, set(), BATCH))
            statements.append(time.perf_counter() - begun)
            pruned += deleted
            if deleted < BATCH:
                break
        total = time.perf_counter() - started
        db.close()
    print(
        f"{pruned} of {args.guests} guests pruned ({args.played} kept: a seat) in {total:.2f} s,"
        f" {len(statements)} statements, the slowest {1000 * max(statements):.0f} ms"
        f" (median {1000 * sorted(statements)[len(statements) // 2]:.0f} ms)"
    )


if __name__ == "__main__":
    main()
