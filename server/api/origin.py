"""Cross-site WebSocket hijacking guard: which `Origin` may open a room socket."""

from __future__ import annotations

from urllib.parse import urlsplit

from starlette.requests import HTTPConnection

from server.cluster import Cluster
from server.config import Settings

_DEFAULT_PORTS = {"http": 80, "https": 443}


def normalised(url: str) -> tuple[str, str, int] | None:
    """(scheme, host, port) of an http(s) origin or URL, else None."""
    try:
        parts = urlsplit(url.strip())
        port = parts.port
    except ValueError:
        return None
    if parts.scheme not in _DEFAULT_PORTS or not parts.hostname:
        return None
    return parts.scheme, parts.hostname.lower(), port or _DEFAULT_PORTS[parts.scheme]


def origin_allowed(
    origin: str | None,
    host: str | None,
    allowed: tuple[str, ...],
    public_url: str | None = None,
) -> bool:
    """Listed in `allowed` ("*" = any), or the server's own origin: `public_url` (scheme,
    host and port) when it is configured, which a DNS-rebinding page cannot match; else,
    for a server that does not know its address, the same host and port as `Host`.
    No Origin: not a browser."""
    if origin is None:
        return True
    if "*" in allowed or origin.rstrip("/") in {a.rstrip("/") for a in allowed}:
        return True
    mine = normalised(origin)
    if mine is None:
        return False
    if public_url is not None:
        return mine == normalised(public_url)
    if host is None:
        return False
    return urlsplit(origin).netloc.lower() == host.strip().lower()


async def socket_allowed(conn: HTTPConnection, settings: Settings, cluster: Cluster | None) -> bool:
    """May the page that opens this socket do so: its Origin is allowed here, or (cluster
    mode) it is a page served by any live server of the cluster."""
    origin, host = conn.headers.get("origin"), conn.headers.get("host")
    if origin_allowed(origin, host, settings.allowed_origins, settings.public_url):
        return True
    if cluster is None:
        return False
    peers = (*settings.allowed_origins, *await cluster.fresh_origins())
    return origin_allowed(origin, host, peers, settings.public_url)
