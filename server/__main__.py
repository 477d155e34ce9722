"""`python -m server [--host H] [--port P]`: one uvicorn worker (rooms live in-process).

Several such processes share the rooms in cluster mode (`POOL_REDIS_URL`, docs/scaling.md):
on SIGTERM uvicorn runs the app's shutdown, which hands this process's rooms to the others
before it exits."""

from __future__ import annotations

import argparse
import faulthandler
import gc
import logging
import signal
from typing import Any

import uvicorn

from server import logs
from server.app import create_app
from server.config import Settings, SettingsError
from server.rooms.computer import warm_planners
from server.rooms.prepare import warm_up
from server.uvicorn_http import HttpProtocol


def uvicorn_config(
    app: Any, host: str, port: int, settings: Settings, **extra: Any
) -> uvicorn.Config:
    """WebSocket limits set explicitly (uvicorn's defaults are 16 MiB and 20 s/20 s).

    permessage-deflate (`POOL_WS_DEFLATE=1`, off by default): a break costs a client
    ~1.5 KB/s with it, ~7.0 KB/s without (`python -m bench.stream`), for ~45 % more server
    CPU at 200 rooms (docs/performance.md).
    """
    config = uvicorn.Config(
        app,
        host=host,
        port=port,
        ws_max_size=settings.max_message,
        ws_ping_interval=settings.ws_ping_interval,
        ws_ping_timeout=settings.ws_ping_timeout,
        ws_per_message_deflate=settings.ws_deflate,
        workers=1,
        proxy_headers=False,
        http=HttpProtocol,
        timeout_graceful_shutdown=settings.shutdown_wait,
        **extra,
    )
    logs.install()  # after uvicorn configured its loggers
    return config


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(prog="python -m server", description=__doc__)
    parser.add_argument("--host", default="127.0.0.1")
    parser.add_argument("--port", type=int, default=8000)
    parser.add_argument("--log-level", default="info")
    args = parser.parse_args(argv)
    logging.basicConfig(level=args.log_level.upper())
    try:
        settings = Settings.from_env()
    except SettingsError as exc:
        parser.error(str(exc))
    config = uvicorn_config(
        create_app(settings), args.host, args.port, settings, log_level=args.log_level
    )
    logs.hold_repeats()  # an outage's error once a minute with a count, not once a second
    warm_up(settings.frame_every)
    warm_planners(settings.computer_workers)  # the first hint need not wait for them
    # `kill -USR1 <pid>` prints every thread's stack to stderr: what a stuck process is doing.
    faulthandler.register(signal.SIGUSR1, all_threads=True)
    # Everything loaded so far (numba, numpy, pydantic, the app) lives as long as the
    # process: keep it out of the cyclic collector, whose full passes over it stalled every
    # room's stream for up to ~200 ms under load (docs/performance.md).
    gc.freeze()
    # Every message sent allocates a few short-lived containers (ASGI dicts): collect the
    # young generation less often, so full passes come seconds apart, not many a second.
    gc.set_threshold(20_000, 20, 20)
    uvicorn.Server(config).run()


if __name__ == "__main__":
    main()
