"""Server settings: one frozen, validated object handed to the app, so tests can shrink every
clock and a typo in the environment stops the server with the variable's name.

Defaults are the production values. `Settings(...)` takes only what it is given;
`Settings.from_env()` reads `POOL_*` overrides (pydantic-settings), e.g. `POOL_GRACE=30`,
`POOL_ALLOWED_ORIGINS=https://a.example,https://b.example`, `POOL_DB_PATH=/data/pool.db`
(`BILLIARDS_DB` is still read as the database path's older name).
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from contextvars import ContextVar
from pathlib import Path
from typing import Annotated, Any

from limits import parse
from pydantic import AliasChoices, Field, ValidationError, field_validator, model_validator
from pydantic.fields import FieldInfo
from pydantic_settings import (
    BaseSettings,
    EnvSettingsSource,
    NoDecode,
    PydanticBaseSettingsSource,
    SettingsConfigDict,
)
from pydantic_settings.sources.utils import parse_env_vars
from typing_extensions import override

KIB = 1024
REPO_ROOT = Path(__file__).resolve().parent.parent
ENV_PREFIX = "POOL_"
_environment: ContextVar[Mapping[str, str] | None] = ContextVar("pool_environment", default=None)


# A WebSocket origin as a CSP source: scheme, host (its first label may be "*"), port.
SocketOrigin = Annotated[str, Field(pattern=r"^wss?://(\*\.)?[A-Za-z0-9.-]+(:[0-9]{1,5})?$")]


class SettingsError(ValueError):
    """A setting from the environment is missing its mark; the message names the variable."""


class _MappingEnvSource(EnvSettingsSource):
    """The environment source, reading a given mapping instead of `os.environ`."""

    def __init__(self, settings_cls: type[BaseSettings], env: Mapping[str, str]) -> None:
        self._mapping = env
        super().__init__(settings_cls)

    def _load_env_vars(self) -> Mapping[str, str | None]:
        return parse_env_vars(
            self._mapping, self.case_sensitive, self.env_ignore_empty, self.env_parse_none_str
        )


Seconds = Annotated[float, Field(ge=0.0, le=86_400.0)]
PositiveSeconds = Annotated[float, Field(gt=0.0, le=86_400.0)]


class Settings(BaseSettings):
    """Clocks in seconds, sizes in bytes or messages."""

    model_config = SettingsConfigDict(
        env_prefix=ENV_PREFIX, frozen=True, extra="forbid", populate_by_name=True
    )

    shot_clock: Annotated[float, Field(ge=0.0, le=600.0)] = 60.0  # a room may set its own
    min_shot_clock: Annotated[float, Field(gt=0.0, le=600.0)] = 5.0  # smallest non-zero clock
    max_shot_clock: Annotated[float, Field(gt=0.0, le=600.0)] = 600.0  # largest a room asks
    grace: Seconds = 60.0  # a dropped player keeps the seat this long
    idle_ttl: PositiveSeconds = 30 * 60.0  # a room nobody is connected to expires after this
    waiting_ttl: PositiveSeconds = 3 * 60.0  # ... or after this if nobody ever joined
    # A practice table is its one player's: once they left (nobody connected), it closes
    # after this (a reload is back well within it), no longer listed nor counted.
    practice_ttl: PositiveSeconds = 60.0
    sweep_interval: PositiveSeconds = 30.0
    max_rooms: Annotated[int, Field(ge=1, le=1_000_000)] = 2000
    # Per client (address): open rooms at once, and room creations and seat takings in a
    # moving window ("N/second|minute|hour", the `limits` library's notation).
    max_rooms_per_client: Annotated[int, Field(ge=1, le=1_000_000)] = 20
    room_create_rate: str = "30/minute"
    join_rate: str = "60/minute"
    # Spectator sockets opened per client (players, with their seat's token, are not
    # counted): a script reconnecting in a loop costs the event loop a handshake each time.
    watch_rate: str = "20/10 seconds"
    # A refused spectator handshake is answered this late: a script retrying in a loop then
    # costs the loop one refusal a second instead of hundreds.
    watch_refusal_delay: Annotated[float, Field(ge=0.0, le=60.0)] = 1.0

    # The engine ticks at a fixed 120 Hz; a shot's motion goes out whole at the strike, and
    # the room keeps every `frame_every`-th tick of it (where a late joiner's table starts).
    # (`POOL_FRAMES_PER_MESSAGE` is gone with the frame stream; like any `POOL_*` variable
    # that names no setting, it is ignored.)
    frame_every: Annotated[int, Field(ge=1, le=120)] = 6
    # Processes that simulate shots; 0 (default): threads of this process. On a 2-core
    # machine one worker process was slower under load (docs/performance.md).
    shot_workers: Annotated[int, Field(ge=0, le=64)] = 0
    pace: Annotated[float, Field(gt=0.0, le=1000.0)] = 1.0  # playback speed-up (tests)

    # The address players reach this server at (e.g. https://pool.example): the only
    # origin, with `allowed_origins`, that may open a room socket. Unset: the request's Host.
    public_url: Annotated[str, Field(pattern=r"^https?://[^/?#\s]+/?$")] | None = None
    allowed_origins: Annotated[tuple[str, ...], NoDecode] = ()  # beside same-origin; "*": any
    # More origins the page may open sockets to (its CSP's connect-src), e.g.
    # "wss://*.pool.example": a cluster's page then reaches a room moved to a process that
    # started after the page was served (else only the processes live then).
    socket_origins: Annotated[tuple[SocketOrigin, ...], NoDecode] = ()
    max_message: Annotated[int, Field(ge=256, le=1024 * KIB)] = 16 * KIB
    # An HTTP request body larger than this is refused (413) before it is read or parsed:
    # every body the API takes is a small JSON object.
    max_body_bytes: Annotated[int, Field(ge=1 * KIB, le=16 * 1024 * KIB)] = 64 * KIB
    send_queue: Annotated[int, Field(ge=4, le=100_000)] = 64  # messages waiting for a client
    # A client that cannot take what is queued for this long is dropped.
    send_timeout: PositiveSeconds = 5.0
    # On SIGTERM, how long uvicorn waits for open connections and their handlers to end
    # before it cancels them and runs the shutdown that hands the rooms over: a stuck
    # handler must not keep a deploy from draining (a stop is killed ~30 s after SIGTERM).
    shutdown_wait: Annotated[int, Field(ge=1, le=600)] = 10  # s (uvicorn takes whole seconds)
    rate_burst: Annotated[float, Field(ge=1.0, le=10_000.0)] = 40.0  # token bucket per socket
    rate_per_second: Annotated[float, Field(gt=0.0, le=10_000.0)] = 20.0
    # A spectator only chats and asks for a `sync`: a smaller budget, so a crowd sending as
    # fast as it may costs the event loop little (faster: closed 1008, as for players).
    spectator_rate_burst: Annotated[float, Field(ge=1.0, le=10_000.0)] = 10.0
    spectator_rate_per_second: Annotated[float, Field(gt=0.0, le=10_000.0)] = 2.0
    # Social traffic, so that no crowd can drown the players: presence at most once per
    # interval, chat credits per sender (spectators fewer), spectators per room.
    presence_interval: Annotated[float, Field(ge=0.0, le=60.0)] = 1.0
    player_chat_burst: Annotated[float, Field(ge=1.0, le=1000.0)] = 8.0
    player_chat_per_second: Annotated[float, Field(gt=0.0, le=100.0)] = 1.0
    spectator_chat_burst: Annotated[float, Field(ge=1.0, le=1000.0)] = 3.0
    spectator_chat_per_second: Annotated[float, Field(gt=0.0, le=100.0)] = 0.2
    crowd_chat_burst: Annotated[float, Field(ge=1.0, le=1000.0)] = 6.0  # all spectators
    crowd_chat_per_second: Annotated[float, Field(gt=0.0, le=1000.0)] = 1.0
    max_spectators: Annotated[int, Field(ge=0, le=100_000)] = 200
    # The computer opponent "thinks" at least this long before it shows a turn (at pace 1).
    computer_pause: Annotated[float, Field(ge=0.0, le=30.0)] = 1.0
    # Processes the computer opponent plans in (shared by every room; 0: a thread, which
    # holds the GIL the event loop needs for about half of each plan: docs/ai.md).
    computer_workers: Annotated[int, Field(ge=0, le=64)] = 1
    # A plan whose planner processes got almost no CPU this long (other work at normal
    # priority keeping every core busy: they run at the idle class) is planned in a
    # thread instead, so that the computer still moves.
    computer_starved: Annotated[float, Field(ge=0.5, le=600.0)] = 10.0
    # Practice hints share the planners behind the computer's turns (server/rooms/
    # planner_share.py): at most `hint_queue` wait (more: 429 hints_busy), each at most
    # `hint_wait` s (then 503 hint_timeout), one per table, address and player; an
    # address may use `hint_budget` s of planning in any minute (then 429 planning_budget).
    hint_queue: Annotated[int, Field(ge=0, le=1000)] = 8
    hint_wait: Annotated[float, Field(gt=0.0, le=120.0)] = 15.0
    hint_budget: Annotated[float, Field(gt=0.0, le=3600.0)] = 20.0
    # Match analyses (docs/ai.md, "Analysis"): asked for by the first GET of a finished
    # match's analysis, run in `analysis_workers` processes at the idle class (0: a
    # thread), at most `analysis_at_once` here at a time, each shot only while no computer
    # turn is being planned; at most `analysis_queue` wait in the store (more: 503
    # analysis_busy). `analysis_budget`: the pro's simulations per shot judged (its own
    # 3900 by default). A claim silent for `analysis_stale` s (its process died) is
    # taken over by another process.
    analysis_workers: Annotated[int, Field(ge=0, le=64)] = 1
    analysis_at_once: Annotated[int, Field(ge=1, le=64)] = 1
    analysis_queue: Annotated[int, Field(ge=1, le=100_000)] = 200
    analysis_budget: Annotated[int, Field(ge=50, le=20_000)] = 3900
    analysis_stale: Annotated[float, Field(ge=10.0, le=86_400.0)] = 600.0
    ws_ping_interval: PositiveSeconds = 20.0
    ws_ping_timeout: PositiveSeconds = 20.0
    # permessage-deflate: ~5x less bandwidth, but ~45 % more server CPU at 200 rooms, which
    # cost the lateness goal there (docs/performance.md); 6.6 KB/s a client without it.
    ws_deflate: bool = False

    web_dir: Path = REPO_ROOT / "web"
    db_path: Path = Field(
        default=Path("billiards.db"),
        validation_alias=AliasChoices("POOL_DB_PATH", "BILLIARDS_DB"),
    )

    # Cluster mode (docs/scaling.md): processes sharing one Redis for presence, room
    # ownership, the room list and messages; each needs its own `public_url`. A room's
    # owner renews its lease every `heartbeat` s; a lease not renewed for `lease_ttl` s
    # (a dead process) lets another process take the room over from the store.
    redis_url: Annotated[str, Field(pattern=r"^(rediss?|unix)://\S+$")] | None = None
    lease_ttl: Annotated[float, Field(ge=1.0, le=120.0)] = 8.0
    heartbeat: Annotated[float, Field(ge=0.1, le=30.0)] = 2.0
    rpc_timeout: Annotated[float, Field(gt=0.0, le=60.0)] = 5.0  # a call to another process
    # Every new room racked with this seed (tests of several processes, demos); unset:
    # a secret random rack each.
    rack_seed: Annotated[int, Field(ge=0, lt=2**31)] | None = None

    @model_validator(mode="after")
    def _shot_clocks(self) -> Settings:
        if self.min_shot_clock > self.max_shot_clock:
            raise ValueError("POOL_MIN_SHOT_CLOCK must be at most POOL_MAX_SHOT_CLOCK")
        if self.shot_clock > self.max_shot_clock:
            raise ValueError("POOL_SHOT_CLOCK must be at most POOL_MAX_SHOT_CLOCK")
        return self

    @model_validator(mode="after")
    def _cluster(self) -> Settings:
        if self.redis_url is not None and self.public_url is None:
            raise ValueError("POOL_REDIS_URL needs POOL_PUBLIC_URL (where clients reach this one)")
        if self.heartbeat * 2 > self.lease_ttl:
            raise ValueError("POOL_HEARTBEAT must be at most half of POOL_LEASE_TTL")
        return self

    @field_validator(
        "room_create_rate",
        "join_rate",
        "watch_rate",
        "queue_rate",
        "player_create_rate",
        "login_rate",
        "login_account_rate",
    )
    @classmethod
    def _rate(cls, value: str) -> str:
        try:
            parse(value)
        except ValueError:
            raise ValueError("a rate such as '30/minute'") from None
        return value

    @field_validator("allowed_origins", "socket_origins", mode="before")
    @classmethod
    def _comma_list(cls, value: Any) -> Any:
        if isinstance(value, str):
            return tuple(o.strip() for o in value.split(",") if o.strip())
        return value

    @classmethod
    @override
    def settings_customise_sources(
        cls,
        settings_cls: type[BaseSettings],
        init_settings: PydanticBaseSettingsSource,
        env_settings: PydanticBaseSettingsSource,
        dotenv_settings: PydanticBaseSettingsSource,
        file_secret_settings: PydanticBaseSettingsSource,
    ) -> tuple[PydanticBaseSettingsSource, ...]:
        """Only `from_env` reads the environment: `Settings(...)` in a test is exactly what
        it says, whatever the shell it runs in has set."""
        env = _environment.get()
        if env is None:
            return (init_settings,)
        return (init_settings, _MappingEnvSource(settings_cls, env))

    @classmethod
    def from_env(cls, env: Mapping[str, str] | None = None) -> Settings:
        """Defaults overridden by `POOL_*` variables (of `env`, else the process's);
        raises `SettingsError` naming each variable that is wrong."""
        token = _environment.set(os.environ if env is None else env)
        try:
            return cls()
        except ValidationError as exc:
            raise SettingsError(_explain(exc, os.environ if env is None else env)) from None
        finally:
            _environment.reset(token)

    def replace(self, **changes: Any) -> Settings:
        """A copy with `changes`, validated like the rest."""
        return type(self)(**{**self.model_dump(), **changes})

    # Players and Play now (docs/protocol.md, "Players, Play now and the leaderboard"). The
    # rating window of a queued player: `playnow_window` at once, `playnow_widen` more per
    # second of waiting, at most `playnow_window_max`; the computer is offered after
    # `playnow_computer_after` s alone. Per address: new profiles in a moving window; per
    # player: joining and leaving the queue.
    playnow_window: Annotated[float, Field(ge=0.0, le=3000.0)] = 100.0
    playnow_widen: Annotated[float, Field(ge=0.0, le=3000.0)] = 20.0
    playnow_window_max: Annotated[float, Field(ge=0.0, le=3000.0)] = 700.0
    playnow_computer_after: Annotated[float, Field(ge=0.0, le=600.0)] = 20.0
    playnow_race_to: Annotated[int, Field(ge=1, le=15)] = 1
    playnow_poll: Annotated[float, Field(gt=0.0, le=60.0)] = 25.0  # longest long-poll
    queue_rate: str = "20/minute"
    # Pair two players asking from one address (tests, a club on one connection); off: a
    # rating farmed by fresh profiles of one address conceding to each other.
    playnow_same_address: bool = False
    player_create_rate: str = "20/minute"
    # Guests (profiles made by a first visit) that never played (no seat, no rating) are
    # deleted `guest_ttl` s after they were made, checked every `guest_prune_every` s.
    guest_ttl: Annotated[float, Field(ge=60.0, le=400 * 86_400.0)] = 7 * 86_400.0
    guest_prune_every: Annotated[float, Field(ge=1.0, le=86_400.0)] = 3_600.0

    # Accounts (docs/protocol.md, "Accounts"): a session ends after this long unused;
    # sign-in attempts per address and per account name, in moving windows.
    session_idle: Annotated[float, Field(ge=60.0, le=400 * 86_400.0)] = 30 * 86_400.0
    login_rate: str = "20/10 minutes"
    login_account_rate: str = "5/10 minutes"

    # The shared history (docs/scaling.md, "Shared history"): PostgreSQL when set (psycopg
    # 3), e.g. `postgresql://pool:secret@db.internal:5432/pool`; else the SQLite `db_path`.
    database_url: str | None = Field(default=None, pattern=r"^postgres(ql)?(\+psycopg)?://\S+$")

    @property
    def database(self) -> Path | str:
        """Where the store is: the PostgreSQL URL when set, else the SQLite file."""
        return self.database_url or self.db_path


def env_names(name: str, field: FieldInfo) -> list[str]:
    """The environment variables that set field `name`."""
    alias = field.validation_alias
    if isinstance(alias, AliasChoices):
        return [str(c) for c in alias.choices if str(c).upper() == str(c)]
    return [f"{ENV_PREFIX}{name.upper()}"]


def _explain(exc: ValidationError, env: Mapping[str, str]) -> str:
    lines = []
    for error in exc.errors(include_url=False):
        name = str(error["loc"][0]) if error["loc"] else ""
        field = Settings.model_fields.get(name)
        names = env_names(name, field) if field is not None else [name]
        variable = next((n for n in names if n in env), names[0])
        shown = f"{variable}={env[variable]!r}" if variable in env else variable
        lines.append(f"{shown}: {error['msg']}")
    return "invalid settings: " + "; ".join(lines)
