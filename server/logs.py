"""What the server's log may hold: no credentials, and one line (not a traceback) for a
client's malformed frame.

uvicorn logs every WebSocket handshake with its URL, and the seat token rides in the URL's
query: anyone who can read the log could sit down in any seat. A client sending invalid
UTF-8 in a text frame is closed with 1007 by uvicorn, which also logs a full traceback per
frame, so one client could fill the log.
"""

from __future__ import annotations

import logging
import re

_TOKEN = re.compile(r"(token=)[^&\s\"']+")
REDACTED = "[redacted]"
_BAD_UTF8 = "Invalid UTF-8 sequence received from client."


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


def install() -> None:
    """Put the filters on uvicorn's loggers (idempotent; after uvicorn set up logging)."""
    for name in ("uvicorn.error", "uvicorn.access"):
        logger = logging.getLogger(name)
        for kind in (RedactTokens, OneLineForBadFrames):
            if not any(isinstance(f, kind) for f in logger.filters):
                logger.addFilter(kind())
