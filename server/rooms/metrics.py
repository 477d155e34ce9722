"""How late the rooms send their frames: the server's own view of stream health.

Each room records, for every frame message it sends (a shot's `motion`), how far behind
the shot's schedule the send happened (loop time), and for every shot how long it took
from `shoot` to the start of its stream (simulating, planning, judging, and any wait for a
thread); `GET /api/stats` reports percentiles over a recent window. Measured on the server,
it separates a slow server from a slow network or client. Members' outboxes count the
messages they drop for a client that is behind (`skipped`): a slow network or client.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass, field
from typing import Any


def percentile(ordered: list[float], p: float) -> float:
    """Nearest-rank percentile of a sorted list (NaN when empty)."""
    if not ordered:
        return math.nan
    return ordered[min(len(ordered) - 1, round(p / 100 * (len(ordered) - 1)))]


@dataclass
class StreamMetrics:
    """Recent frame send lateness (bounded) and running totals."""

    capacity: int = 100_000
    frames_sent: int = 0
    # Messages dropped from a member's full outbox: aim relays first, then chat and
    # presence (a `motion` or any game message is never dropped: its client is closed).
    frames_skipped: int = 0
    _samples: deque[tuple[float, float]] = field(default_factory=deque)  # (time, late)
    _starts: deque[tuple[float, float]] = field(default_factory=deque)  # (time, seconds)

    def sent(self, now: float, late: float) -> None:
        self.frames_sent += 1
        if len(self._samples) >= self.capacity:
            self._samples.popleft()
        self._samples.append((now, max(0.0, late)))

    def skipped(self) -> None:
        """A member's outbox dropped a message: its client was behind."""
        self.frames_skipped += 1

    def shot_started(self, now: float, seconds: float) -> None:
        """A shot's stream began `seconds` after the room took the `shoot`."""
        if len(self._starts) >= self.capacity:
            self._starts.popleft()
        self._starts.append((now, seconds))

    def summary(self, now: float, window: float) -> dict[str, Any]:
        """Lateness of the frames sent in the last `window` seconds, in milliseconds."""
        late = sorted(v for t, v in self._samples if now - t <= window)
        starts = sorted(v for t, v in self._starts if now - t <= window)
        return {
            "window": window,
            "frames": len(late),
            "late_p50_ms": _ms(percentile(late, 50)),
            "late_p99_ms": _ms(percentile(late, 99)),
            "late_max_ms": _ms(late[-1] if late else math.nan),
            "frames_sent": self.frames_sent,
            "frames_skipped": self.frames_skipped,
            "shots": len(starts),
            "start_p50_ms": _ms(percentile(starts, 50)),
            "start_p99_ms": _ms(percentile(starts, 99)),
        }


def _ms(seconds: float) -> float | None:
    return None if math.isnan(seconds) else round(seconds * 1000.0, 3)
