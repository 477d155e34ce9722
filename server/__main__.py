"""`python -m server [--host H] [--port P]`: one uvicorn worker (rooms live in-process)."""

from __future__ import annotations

import argparse
import logging

import uvicorn

from server.app import create_app
from server.config import Settings


def uvicorn_config(app: object, host: str, port: int, settings: Settings,
                   **extra: object) -> uvicorn.Config:
    """WebSocket limits set explicitly (uvicorn's defaults are 16 MiB and 20 s/20 s).

    permessage-deflate stays on: a break costs a client ~1.8 KB/s with it, ~7.6 KB/s
    without (`python -m bench.stream`).
    """
    return uvicorn.Config(app, host=host, port=port, ws_max_size=settings.max_message,
                          ws_ping_interval=settings.ws_ping_interval,
                          ws_ping_timeout=settings.ws_ping_timeout,
                          ws_per_message_deflate=True,
                          workers=1, proxy_headers=False, **extra)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(prog="python -m server", description=__doc__)
    parser.add_argument("--host", default="127.0.0.1")
    parser.add_argument("--port", type=int, default=8000)
    parser.add_argument("--log-level", default="info")
    args = parser.parse_args(argv)
    logging.basicConfig(level=args.log_level.upper())
    settings = Settings.from_env()
    config = uvicorn_config(create_app(settings), args.host, args.port, settings,
                            log_level=args.log_level)
    uvicorn.Server(config).run()


if __name__ == "__main__":
    main()
