"""Cross-site request forgery: a state-changing request (POST, PUT, PATCH, DELETE) from a
page of another site is refused with 403 `cross_site`, by its `Origin` (the rule of the
room socket's, `origin.py`) and its `Sec-Fetch-Site`. With the cookies' `SameSite=Lax`
(not sent with another site's POST) and bodies taken as JSON only (which a form cannot
send), a forged form neither reaches a player nor changes anything."""

from __future__ import annotations

from fastapi import HTTPException, Request

from .deps import ClusterDep, SettingsDep
from .origin import socket_allowed

UNSAFE = frozenset({"POST", "PUT", "PATCH", "DELETE"})
CROSS_SITE = {"code": "cross_site", "message": "Refused: this request came from another site."}


async def same_site(request: Request, settings: SettingsDep, cluster: ClusterDep) -> None:
    """A route dependency: nothing for reads; 403 for a write another site's page made."""
    if request.method not in UNSAFE:
        return
    if "origin" not in request.headers:  # not a browser, or one that says so instead
        if request.headers.get("sec-fetch-site") == "cross-site":
            raise HTTPException(403, CROSS_SITE)
        return
    if not await socket_allowed(request, settings, cluster):
        raise HTTPException(403, CROSS_SITE)
