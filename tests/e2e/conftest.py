"""Fixtures for the browser tests: a real server on a free port and Debian's Chromium.

The server runs `server.app:create_app()` under uvicorn in a thread (127.0.0.1, port 0),
with shots paced twice as fast as real time so the break takes a few seconds to watch. Every
room gets the 8-ball rack of `tests.support.games.EIGHT_BALL`: the same game every run.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from pathlib import Path

import pytest
from playwright.sync_api import Browser, BrowserContext, Page, sync_playwright

from server.config import Settings
from server.engine import Shot, Table, rack, simulate
from tests.support.games import EIGHT_BALL
from tests.support.live import live_server
from tests.support.settings import UNLIMITED
from tests.support.tiers import needs

ARTIFACTS = Path(__file__).resolve().parents[2] / "artifacts"
CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking"]
E2E_SETTINGS = Settings(pace=2.0, **UNLIMITED)


@pytest.fixture(scope="package")
def base_url(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    """A live server; the engine is compiled first so the first shot does not wait for it."""
    table = Table.pool("9ft")
    simulate(table, rack("eight_ball", table), Shot(0.0, 1.0))
    settings = E2E_SETTINGS.replace(db_path=tmp_path_factory.mktemp("e2e") / "billiards.db")
    with live_server(settings, EIGHT_BALL) as address:
        yield f"http://{address}"


@pytest.fixture(scope="package")
def browser() -> Iterator[Browser]:
    """Package scope: Playwright's sync API keeps an event loop running in this thread
    while it is open, which would break `asyncio.run` in the tests that come after."""
    needs("browser")
    with sync_playwright() as p:
        b = p.chromium.launch(executable_path="/usr/bin/chromium", args=CHROMIUM_ARGS)
        yield b
        b.close()


@pytest.fixture
def new_page(browser: Browser) -> Iterator[Callable[..., Page]]:
    """Open a page in a fresh browser context (its own localStorage: another person)."""
    contexts: list[BrowserContext] = []
    errors: list[str] = []

    def open_page(**options: object) -> Page:
        ctx = browser.new_context(viewport={"width": 1200, "height": 720}, **options)
        contexts.append(ctx)
        page = ctx.new_page()
        page.on("pageerror", lambda e: errors.append(str(e)))
        return page

    yield open_page
    for ctx in contexts:
        ctx.close()
    assert errors == [], f"JavaScript errors in the page: {errors}"


@pytest.fixture(scope="session")
def artifacts() -> Path:
    ARTIFACTS.mkdir(exist_ok=True)
    return ARTIFACTS
