"""Server settings: one frozen object handed to the app, so tests can shrink every clock.

Defaults are the production values; `Settings.from_env()` reads `POOL_*` overrides.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field, replace
from pathlib import Path

KIB = 1024
REPO_ROOT = Path(__file__).resolve().parent.parent


@dataclass(frozen=True)
class Settings:
    """Clocks in seconds, sizes in bytes or messages."""

    shot_clock: float = 60.0  # default per room; a room may set its own
    min_shot_clock: float = 5.0  # smallest non-zero clock a room may ask for
    max_shot_clock: float = 600.0
    grace: float = 60.0  # a dropped player keeps the seat this long
    idle_ttl: float = 30 * 60.0  # a room nobody is connected to expires after this
    waiting_ttl: float = 10 * 60.0  # ... or after this if nobody ever joined
    sweep_interval: float = 30.0
    max_rooms: int = 2000

    tick_hz: int = 120  # the engine's tick (DEFAULT_TICK = 1/120)
    frame_every: int = 6  # send every 6th tick: 20 frames/s (see docs/protocol.md)
    frames_per_message: int = 4  # ... in 5 `frame` messages/s, each with 3 frames ahead
    # Processes that simulate shots; 0 (default): threads of this process. On this 2-core
    # machine one worker process was slower under load (docs/performance.md).
    shot_workers: int = 0
    pace: float = 1.0  # playback speed-up (tests only; 1.0 is real time)

    allowed_origins: tuple[str, ...] = ()  # beside same-origin; "*" allows any
    max_message: int = 16 * KIB
    send_queue: int = 64  # messages waiting for one client
    send_timeout: float = 5.0  # a client that cannot take what is queued in this long is dropped
    rate_burst: float = 40.0  # token bucket per connection: burst ...
    rate_per_second: float = 20.0  # ... and sustained messages per second
    ws_ping_interval: float = 20.0
    # permessage-deflate: ~5x less bandwidth, but ~45 % more server CPU at 200 rooms, which
    # cost the lateness goal there (docs/performance.md); 6.6 KB/s a client without it
    ws_deflate: bool = False
    ws_ping_timeout: float = 20.0

    web_dir: Path = field(default=REPO_ROOT / "web")

    @classmethod
    def from_env(cls, env: dict[str, str] | None = None) -> Settings:
        """Defaults overridden by `POOL_SHOT_CLOCK`, `POOL_GRACE`, `POOL_ALLOWED_ORIGINS`..."""
        env = dict(os.environ if env is None else env)
        base = cls()
        changes: dict[str, object] = {}
        for name, value in vars(base).items():
            raw = env.get(f"POOL_{name.upper()}")
            if raw is None:
                continue
            if isinstance(value, bool):
                changes[name] = raw.strip().lower() in ("1", "true", "yes", "on")
            elif isinstance(value, tuple):
                changes[name] = tuple(o.strip() for o in raw.split(",") if o.strip())
            elif isinstance(value, Path):
                changes[name] = Path(raw)
            else:
                changes[name] = type(value)(raw)
        return replace(base, **changes)

    @property
    def tick(self) -> float:
        return 1.0 / self.tick_hz
