"""`origin_allowed`: which pages may open a room socket (cross-site WebSocket hijacking)."""

from __future__ import annotations

import pytest

from server.api.origin import origin_allowed

HOST = "pool.example:8000"


@pytest.mark.parametrize(
    "origin",
    [
        "http://pool.example:8000",
        "https://pool.example:8000",
        "http://POOL.example:8000",
    ],
)
def test_the_same_origin_as_the_host_is_allowed(origin: str) -> None:
    assert origin_allowed(origin, HOST, ())
    assert origin_allowed(origin, " Pool.Example:8000 ", ())


@pytest.mark.parametrize(
    "origin",
    [
        "http://pool.example",  # another port
        "http://pool.example:8001",
        "http://evil.example:8000",
        "http://pool.example:8000.evil.example",
        "ws://pool.example:8000",  # not a page's scheme
        "file://pool.example:8000",
        "null",  # a sandboxed or local page
        "",
    ],
)
def test_other_origins_are_refused(origin: str) -> None:
    assert not origin_allowed(origin, HOST, ())


def test_no_host_header_allows_only_listed_origins() -> None:
    assert not origin_allowed("http://pool.example:8000", None, ())
    assert origin_allowed("http://pool.example:8000", None, ("http://pool.example:8000",))


def test_listed_origins_are_allowed_with_or_without_a_trailing_slash() -> None:
    allowed = ("https://a.example", "https://b.example/")
    assert origin_allowed("https://a.example", HOST, allowed)
    assert origin_allowed("https://a.example/", HOST, allowed)
    assert origin_allowed("https://b.example", HOST, allowed)
    assert not origin_allowed("http://a.example", HOST, allowed)  # the scheme counts
    assert not origin_allowed("https://a.example:444", HOST, allowed)  # and the port
    assert not origin_allowed("https://c.example", HOST, allowed)


def test_a_star_allows_any_origin() -> None:
    assert origin_allowed("https://anything.example", HOST, ("*",))
    assert origin_allowed("null", HOST, ("https://a.example", "*"))


def test_no_origin_header_is_not_a_browser_and_is_allowed() -> None:
    assert origin_allowed(None, HOST, ())
    assert origin_allowed(None, None, ())
