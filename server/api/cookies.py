"""The accounts' cookies: always HttpOnly (no script reads them), `Secure` when the page is
served over https (the request's scheme, or `POOL_PUBLIC_URL`'s), `SameSite=Lax` unless
said otherwise."""

from __future__ import annotations

from typing import Literal

from starlette.requests import Request
from starlette.responses import Response

from server.config import Settings

COOKIE_AGE = 400 * 86_400  # s: the longest browsers keep a cookie; the server decides expiry


def secure(request: Request, settings: Settings) -> bool:
    return request.url.scheme == "https" or (settings.public_url or "").startswith("https:")


def set_cookie(
    response: Response,
    request: Request,
    settings: Settings,
    name: str,
    value: str,
    *,
    path: str = "/",
    max_age: int = COOKIE_AGE,
    samesite: Literal["lax", "strict"] = "lax",
) -> None:
    response.set_cookie(
        name,
        value,
        max_age=max_age,
        path=path,
        httponly=True,
        samesite=samesite,
        secure=secure(request, settings),
    )


def clear_cookie(
    response: Response, request: Request, settings: Settings, name: str, path: str = "/"
) -> None:
    response.delete_cookie(
        name, path=path, httponly=True, samesite="lax", secure=secure(request, settings)
    )
