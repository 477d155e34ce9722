"""One browser for the accounts' tests: its own cookie jar (names to values; a cookie set
empty or with `Max-Age=0` is dropped), sent with each of its requests to a shared
TestClient, so several devices can ask one app."""

from __future__ import annotations

from http.cookies import SimpleCookie
from typing import Any

import httpx
from fastapi.testclient import TestClient

STRONG = "correct horse battery staple"
GUEST, SESSION = "pool_player", "pool_session"


class Device:
    def __init__(self, client: TestClient, *, visit: bool = True) -> None:
        self.client = client
        self.jar: dict[str, str] = {}
        self.set_cookies: list[str] = []  # the raw Set-Cookie headers of the last answer
        if visit:
            self.me()

    def call(self, method: str, url: str, **kwargs: Any) -> httpx.Response:
        headers = dict(kwargs.pop("headers", {}))
        if self.jar:
            headers["Cookie"] = "; ".join(f"{k}={v}" for k, v in self.jar.items())
        self.client.cookies.clear()
        response = self.client.request(method, url, headers=headers, **kwargs)
        self.client.cookies.clear()
        self.set_cookies = response.headers.get_list("set-cookie")
        for raw in self.set_cookies:
            parsed: SimpleCookie = SimpleCookie()
            parsed.load(raw)
            for name, morsel in parsed.items():
                if morsel.value in ("", '""') or morsel["max-age"] == "0":
                    self.jar.pop(name, None)
                else:
                    self.jar[name] = morsel.value
        return response

    def me(self) -> dict[str, Any]:
        response = self.call("GET", "/api/players/me")
        assert response.status_code == 200, response.text
        return response.json()

    def login(self, name: str, password: str = STRONG, **kwargs: Any) -> httpx.Response:
        body = {"name": name, "password": password}
        return self.call("POST", "/api/login", json=body, **kwargs)

    def set_password(self, password: str = STRONG, old: str | None = None) -> httpx.Response:
        body: dict[str, Any] = {"password": password}
        if old is not None:
            body["old_password"] = old
        return self.call("POST", "/api/account/password", json=body)

    def rename(self, name: str, **kwargs: Any) -> httpx.Response:
        return self.call("PATCH", "/api/players/me", json={"name": name}, **kwargs)

    def claim(self, name: str) -> dict[str, Any]:
        """Rename this device's guest and make it an account with a password."""
        assert self.rename(name).status_code == 200
        response = self.set_password()
        assert response.status_code == 204, response.text
        return self.me()
