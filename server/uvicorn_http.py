"""uvicorn's httptools HTTP protocol, without the reference cycle each WebSocket upgrade
leaves behind.

The protocol and its `httptools` parser reference each other (the parser calls back bound
methods of the protocol). uvicorn breaks that cycle when an HTTP connection is lost, but
not when the connection is handed to the WebSocket protocol: every WebSocket ever opened
then left its HTTP protocol, parser and transport (~28 objects) for the cyclic collector.
Spectators reconnecting in a loop (60 a second) made each pass of the young generation
free hundreds of them at once: 4-17 ms with the whole process stopped, and a player's shot
that started meanwhile waited for it (docs/performance.md, "Under attack"). Dropping the
parser once the upgrade is done lets reference counting free the lot as soon as the
socket closes.
"""

from __future__ import annotations

from uvicorn.protocols.http.httptools_impl import HttpToolsProtocol


class HttpProtocol(HttpToolsProtocol):
    def handle_websocket_upgrade(self) -> None:
        super().handle_websocket_upgrade()
        # The transport now talks to the WebSocket protocol; nothing calls this one again.
        self.parser = None  # type: ignore[assignment]
