"""Store write throughput: shots per second on SQLite and on PostgreSQL.

    python -m bench.store [--shots 1000] [--runs 5] [--writers 1,4] [--backend both]
                          [--pg-fsync on]

A "shot" is what a room writes for one shot in cluster mode, each write fenced by the
room's epoch: `record_shot` (a break's balls, outcome and motion) and `save_room` twice
(the snapshot before the shot and after it). Writes go through `Database.write`, the
queue the server uses; a run is timed from the first write queued to the last one done.
`--writers N` runs N stores at once on their own rooms (N server processes; SQLite
serialises them on its file lock). PostgreSQL is a private server started here, durable
(fsync and synchronous commit on, as in production); SQLite is a WAL file with
`synchronous=NORMAL`, as the server opens it. Prints the median over `--runs` runs.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import threading
import time
from collections.abc import Callable
from pathlib import Path

from server.codec import encode
from server.config import Settings
from server.engine import Shot, Table, rack
from server.protocol.plan import motion_text
from server.rooms.prepare import prepare_shot
from server.store import Database, Repository

SHOTS_PER_MATCH = 40
FRAME_EVERY = Settings.model_fields["frame_every"].default  # the server's default


def payload() -> dict:
    """One break's records, of the sizes the server stores (the motion as the server
    stores it: `motion_text` of the break's plan, what was streamed)."""
    table = Table.pool("9ft")
    balls = rack("eight_ball", table, seed=1)
    _, plan = prepare_shot(table, balls, Shot(0.0, 9.0), 1, FRAME_EVERY)
    motion = motion_text(plan)
    fields = [table.length, table.width, table.ball_radius, table.corner_mouth, table.side_mouth]
    return {
        "shot": {"angle": 0.0, "speed": 9.0, "tip": [0.0, 0.0]},
        "table": fields,
        "balls": balls.to_dict(),
        "outcome": {"shooter": 0, "pocketed": [3, 9], "fouls": [], "message": "Ana breaks."},
        "motion": motion,
        "snapshot": encode({"balls": balls.to_dict(), "seats": ["x" * 900, "y" * 900]}),
    }


def writer(db: Database, rooms: list[str], shots: int, data: dict, epoch: int) -> None:
    """Queue every write for `shots` shots spread over `rooms`, then wait for the last."""
    ids = db.run(lambda r: r.reserve_match_ids(len(rooms)))
    for room, match_id in zip(rooms, ids, strict=True):
        db.run(lambda r, room=room: r.claim_room(room, epoch))
        db.run(
            lambda r, m=match_id, room=room: r.start_match(
                m, room, "eight_ball", ["A", "B"], 5, epoch=epoch
            )
        )
    last = None
    for n in range(shots):
        room, match_id = rooms[n % len(rooms)], ids[n % len(rooms)]

        def record(r: Repository, m: int = match_id, n: int = n) -> None:
            r.record_shot(
                m,
                n,
                1,
                n % 2,
                data["shot"],
                data["table"],
                data["balls"],
                data["outcome"],
                engine="bench",
                motion=data["motion"],
                epoch=epoch,
            )

        def save(r: Repository, room: str = room) -> None:
            r.save_room(room, data["snapshot"], epoch=epoch)

        db.write(save, "save room")
        db.write(record, "record shot")
        last = db.write(save, "save room")
    assert last is not None
    last.result()


def run_once(target: str | Path, writers: int, shots: int, data: dict) -> float:
    """Shots per second, all writers together."""
    stores = [Database(target) for _ in range(writers)]
    rooms = [
        [f"w{w}-room{i}" for i in range(shots // SHOTS_PER_MATCH or 1)] for w in range(writers)
    ]
    start = threading.Barrier(writers + 1)
    threads = [
        threading.Thread(
            target=lambda w=w: (start.wait(), writer(stores[w], rooms[w], shots, data, 1))
        )
        for w in range(writers)
    ]
    for t in threads:
        t.start()
    start.wait()
    began = time.perf_counter()
    for t in threads:
        t.join()
    elapsed = time.perf_counter() - began
    for store in stores:
        store.close()
    return writers * shots / elapsed


def measure(name: str, fresh: Callable[[], str | Path], args: argparse.Namespace) -> None:
    data = payload()
    for writers in args.writers:
        rates = [run_once(fresh(), writers, args.shots, data) for _ in range(args.runs)]
        print(
            f"{name:<20} writers={writers}  {statistics.median(rates):8.0f} shots/s "
            f"(median of {args.runs}: {', '.join(f'{r:.0f}' for r in rates)})"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--shots", type=int, default=1000, help="shots per writer and run")
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--writers", type=lambda s: [int(x) for x in s.split(",")], default=[1, 4])
    parser.add_argument("--backend", choices=["sqlite", "postgresql", "both"], default="both")
    parser.add_argument(
        "--pg-fsync",
        choices=["on", "off"],
        default="on",
        help="off: PostgreSQL without fsync, what its CPU alone allows (not for production)",
    )
    args = parser.parse_args()
    print("python -m bench.store " + " ".join(sys.argv[1:]))
    data = payload()
    balls, motion, snapshot = (
        len(encode(data["balls"])),
        len(data["motion"]),
        len(data["snapshot"]),
    )
    print(
        f"per shot: record_shot (balls {balls} B, motion {motion} B before zlib)"
        f" + 2 x save_room ({snapshot} B)"
    )
    if args.backend in ("sqlite", "both"):
        with tempfile.TemporaryDirectory(prefix="bench-store-") as folder:
            files = iter(range(1_000_000))
            measure("sqlite", lambda: Path(folder) / f"run{next(files)}.db", args)
    if args.backend in ("postgresql", "both"):
        from tests.support.postgres import running_postgres

        with running_postgres(durable=args.pg_fsync == "on") as server:
            measure(f"postgresql fsync={args.pg_fsync}", server.create_database, args)


if __name__ == "__main__":
    main()
