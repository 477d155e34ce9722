"""What the server's log may hold: no credentials, one line (not a traceback) for a
client's malformed frame, and a repeated error once with a count.

uvicorn logs every WebSocket handshake with its URL, and the seat token rides in the URL's
query: anyone who can read the log could sit down in any seat. A client sending invalid
UTF-8 in a text frame is closed with 1007 by uvicorn, which also logs a full traceback per
frame, so one client could fill the log. An outage repeats the same error (a Redis down: a
traceback about once a second per process) until it hides everything else: the same kind of
record is logged once per `REPEAT_WINDOW`, and the next one after it says how many were
held back.
"""

from __future__ import annotations

import logging
import re
import threading
import time
from collections.abc import Callable, Hashable
from dataclasses import dataclass

_TOKEN = re.compile(r"(token=)[^&\s\"']+")
REDACTED = "[redacted]"
_BAD_UTF8 = "Invalid UTF-8 sequence received from client."
REPEAT_WINDOW = 60.0  # s: a kind of record is logged at most once this often
MAX_KINDS = 1000  # kinds remembered at once (the oldest forgotten first)


def redact(text: str) -> str:
    return _TOKEN.sub(rf"\g<1>{REDACTED}", text)


class RedactTokens(logging.Filter):
    """Replace every `token=...` in a record's message and arguments."""

    def filter(self, record: logging.LogRecord) -> bool:
        if isinstance(record.msg, str):
            record.msg = redact(record.msg)
        if isinstance(record.args, tuple):
            record.args = tuple(redact(a) if isinstance(a, str) else a for a in record.args)
        return True


class OneLineForBadFrames(logging.Filter):
    """A client's invalid UTF-8 is the client's fault: log it as one warning line."""

    def filter(self, record: logging.LogRecord) -> bool:
        if record.getMessage() == _BAD_UTF8:
            record.exc_info = None
            record.exc_text = None
            record.levelno, record.levelname = logging.WARNING, "WARNING"
        return True


def kind_of(record: logging.LogRecord) -> Hashable:
    """What makes two records the same: logger, level, message template, the arguments but
    for numbers (a retry's delay, a count), and the exception's type and text."""
    args = record.args if isinstance(record.args, tuple) else ()
    words = tuple(str(a) for a in args if not isinstance(a, int | float))
    exc = record.exc_info[1] if record.exc_info else None
    error = None if exc is None else (type(exc).__name__, str(exc).split("\n", 1)[0])
    return (record.name, record.levelno, str(record.msg), words, error)


@dataclass
class _Seen:
    since: float  # when it was last let through
    held: int = 0  # copies held back since


class RepeatsOnce(logging.Filter):
    """Let a kind of warning or error (`kind_of`) through once per `window` seconds: the
    copies in between are counted, and the next one let through says how many there were
    (its traceback left out: the first one showed it)."""

    def __init__(
        self, window: float = REPEAT_WINDOW, clock: Callable[[], float] = time.monotonic
    ) -> None:
        super().__init__()
        self.window = window
        self.clock = clock
        self._seen: dict[Hashable, _Seen] = {}
        self._lock = threading.Lock()  # handlers log from any thread

    def filter(self, record: logging.LogRecord) -> bool:
        if record.levelno < logging.WARNING:
            return True  # information is not an error repeating (an access, a connection)
        kind, now = kind_of(record), self.clock()
        with self._lock:
            seen = self._seen.get(kind)
            if seen is not None and now - seen.since < self.window:
                seen.held += 1
                return False
            self._seen.pop(kind, None)
            self._seen[kind] = _Seen(now)
            if len(self._seen) > MAX_KINDS:
                del self._seen[next(iter(self._seen))]
        if seen is not None and seen.held:
            record.msg = (
                f"{record.msg} [and {seen.held} more like it in the last {now - seen.since:.0f} s]"
            )
            record.exc_info, record.exc_text = None, None
        return True


def install() -> None:
    """Put the filters on uvicorn's loggers (idempotent; after uvicorn set up logging)."""
    for name in ("uvicorn.error", "uvicorn.access"):
        logger = logging.getLogger(name)
        for kind in (RedactTokens, OneLineForBadFrames):
            if not any(isinstance(f, kind) for f in logger.filters):
                logger.addFilter(kind())


def hold_repeats() -> None:
    """Put `RepeatsOnce` on every handler the server's records reach: the root's and
    uvicorn's (idempotent; after `basicConfig` and uvicorn set up logging). The server's
    entry point does it, not the app: a test's log capture sees every record."""
    # A logger's filters see only its own records; a handler's see its children's too.
    for logger in (logging.getLogger(), logging.getLogger("uvicorn")):
        for handler in logger.handlers:
            if not any(isinstance(f, RepeatsOnce) for f in handler.filters):
                handler.addFilter(RepeatsOnce())
