"""A repeated error is logged once per window, then once with the count of its copies."""

from __future__ import annotations

import logging
from collections.abc import Iterator

import pytest

from server import logs
from server.logs import RepeatsOnce


class Clock:
    def __init__(self) -> None:
        self.now = 0.0

    def __call__(self) -> float:
        return self.now


class Kept(logging.Handler):
    def __init__(self) -> None:
        super().__init__()
        self.records: list[logging.LogRecord] = []

    def emit(self, record: logging.LogRecord) -> None:
        self.records.append(record)


@pytest.fixture
def clock() -> Clock:
    return Clock()


@pytest.fixture
def kept(clock: Clock) -> Iterator[Kept]:
    """A handler of the `server.test` logger, with the repeat filter on it (as `install`
    puts it on the root's): records of the logger's children reach it."""
    handler = Kept()
    handler.addFilter(RepeatsOnce(window=60.0, clock=clock))
    logger = logging.getLogger("server.test")
    logger.addHandler(handler)
    logger.setLevel(logging.INFO)
    try:
        yield handler
    finally:
        logger.removeHandler(handler)


def outage(log: logging.Logger) -> None:
    try:
        raise ConnectionError("Error 111 connecting to localhost:6379. Connection refused.")
    except ConnectionError:
        log.exception("cluster: heartbeat failed")


def test_an_outage_logs_its_traceback_once_then_a_count(kept: Kept, clock: Clock):
    log = logging.getLogger("server.test.cluster")
    for second in range(60):  # once a second for a minute
        clock.now = float(second)
        outage(log)
    assert len(kept.records) == 1 and kept.records[0].exc_info is not None
    clock.now = 61.0
    outage(log)
    assert len(kept.records) == 2
    summary = kept.records[1]
    assert summary.getMessage() == (
        "cluster: heartbeat failed [and 59 more like it in the last 61 s]"
    )
    assert summary.exc_info is None  # the first one showed it
    clock.now = 200.0
    outage(log)  # nothing held back since: logged as it is
    assert kept.records[2].getMessage() == "cluster: heartbeat failed"


def test_kinds_are_told_apart_but_not_by_their_numbers(kept: Kept):
    log = logging.getLogger("server.test.store")
    for delay in (0.05, 0.1, 0.2, 0.4):
        log.warning("store: %s; trying again in %.2f s", "connection refused", delay)
    log.warning("store: %s; trying again in %.2f s", "disk full", 0.05)
    log.warning("room %s not claimed", "abc")
    log.warning("room %s not claimed", "def")
    log.error("store: %s; trying again in %.2f s", "connection refused", 0.05)  # other level
    assert [r.getMessage() for r in kept.records] == [
        "store: connection refused; trying again in 0.05 s",
        "store: disk full; trying again in 0.05 s",
        "room abc not claimed",
        "room def not claimed",
        "store: connection refused; trying again in 0.05 s",
    ]


def test_information_is_never_held_back(kept: Kept):
    log = logging.getLogger("server.test.info")
    for _ in range(5):
        log.info("connection open")
    assert len(kept.records) == 5


def test_the_filter_goes_on_the_root_handlers_once(monkeypatch: pytest.MonkeyPatch):
    handler = Kept()
    root = logging.getLogger()
    monkeypatch.setattr(root, "handlers", [handler])
    monkeypatch.setattr(logging.getLogger("uvicorn"), "handlers", [])
    logs.hold_repeats()
    logs.hold_repeats()
    assert sum(isinstance(f, RepeatsOnce) for f in handler.filters) == 1
    log = logging.getLogger("server.test.installed")
    for _ in range(10):
        outage(log)
    assert len(handler.records) == 1
