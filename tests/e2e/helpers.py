"""What the browser tests do with a page: the lobby's steps, real mouse input, reads of the
canvas pixels."""

from __future__ import annotations

import hashlib
import re
import time

import httpx
from playwright.sync_api import Error, Locator, Page

READY = "window.__pool && window.__pool.ready"
POLL_MS = 50
TABLE_PAGE = re.compile(r"/r/[A-Za-z0-9_-]+$")


def wait_for(page: Page, expression: str, arg: object = None, timeout: float = 30_000) -> None:
    """Wait until `expression` (or the function it is, called with `arg`) is truthy in the
    page. Playwright's `wait_for_function` evaluates strings inside the page, which the
    page's Content-Security-Policy (no eval) refuses; `evaluate` goes through the debugger
    protocol, so it is polled here instead."""
    deadline = time.monotonic() + timeout / 1000
    while not _evaluate(page, expression, arg):
        if time.monotonic() > deadline:
            raise TimeoutError(f"not true within {timeout:.0f} ms: {expression}")
        page.wait_for_timeout(POLL_MS)


def _evaluate(page: Page, expression: str, arg: object) -> object:
    """`page.evaluate`, false while the page is navigating (an action that opens another
    page, such as creating a room, destroys the context an evaluation ran in)."""
    try:
        return page.evaluate(expression, arg)
    except Error as exc:
        if "Execution context was destroyed" in exc.message:
            return False
        raise


def wait_ready(page: Page, phase: str | None = None, timeout: float = 30_000) -> None:
    cond = READY + (f" && window.__pool.state.phase === '{phase}'" if phase else "")
    wait_for(page, cond, timeout=timeout)


def create_table(page: Page) -> str:
    """Press the lobby's create button (the form filled in already) and wait until the new
    table's page waits for an opponent: the room's id."""
    page.get_by_test_id("create-room").click()
    page.wait_for_url(TABLE_PAGE)
    room_id = page.url.rsplit("/", 1)[1]
    wait_ready(page, "waiting")
    return room_id


def lobby_row(page: Page, room_id: str) -> Locator:
    """The lobby's row of the table `room_id` (with its join and watch buttons)."""
    return page.locator(f"li[data-room='{room_id}']")


def table_point(page: Page, x: float, y: float) -> tuple[float, float]:
    """Page coordinates (CSS px) of table point (x, y) metres."""
    box = page.get_by_test_id("table").bounding_box()
    sx, sy = page.evaluate("([x, y]) => window.__pool.toScreen(x, y)", [x, y])
    return box["x"] + sx, box["y"] + sy


def canvas_digest(page: Page, region: tuple[float, float, float, float] | None = None) -> str:
    """A hash of the canvas pixels (all, or a CSS-pixel box x, y, w, h of the canvas)."""
    data = page.evaluate(
        """(region) => {
          const c = document.querySelector('[data-testid=table]');
          const k = c.width / c.clientWidth;
          const [x, y, w, h] = region
            ? region.map((v) => Math.round(v * k)) : [0, 0, c.width, c.height];
          const px = c.getContext('2d').getImageData(x, y, Math.max(1, w), Math.max(1, h)).data;
          let a = 0, b = 0;
          for (let i = 0; i < px.length; i++) { a = (a + px[i]) % 65521; b = (b + a) % 65521; }
          return `${px.length}:${a}:${b}`;
        }""",
        list(region) if region else None,
    )
    return hashlib.sha1(data.encode()).hexdigest()


def aim_and_shoot(page: Page, target: tuple[float, float], pull_px: float = 160) -> None:
    """Aim at table point `target` with the mouse, press, pull back `pull_px`, release."""
    tx, ty = table_point(page, *target)
    cue = page.evaluate("window.__pool.balls.find((b) => b.id === 0)")
    cx, cy = table_point(page, cue["x"], cue["y"])
    dx, dy = tx - cx, ty - cy
    n = (dx * dx + dy * dy) ** 0.5
    page.mouse.move(tx - 30 * dx / n, ty - 30 * dy / n)
    page.mouse.move(tx, ty, steps=5)
    page.mouse.down()
    page.mouse.move(tx - pull_px * dx / n, ty - pull_px * dy / n, steps=10)
    page.mouse.up()


def create(server: str, **body: object) -> str:
    """A listed room made over HTTP (the lobby offers no 3 s clock); returns its id."""
    reply = httpx.post(f"{server}/api/rooms", json={"game": "eight_ball", **body}, timeout=20)
    reply.raise_for_status()
    return reply.json()["room_id"]


def sit(page: Page, server: str, room_id: str, name: str) -> None:
    """Open the room's link and take a seat through the join dialog."""
    page.goto(f"{server}/r/{room_id}")
    page.get_by_test_id("join-name").fill(name)
    page.get_by_test_id("join").click()
    wait_for(page, "window.__pool && window.__pool.state.me.role === 'player'")


def apex(page: Page) -> tuple[float, float]:
    """The rack's apex ball (on the foot spot): where a break aims."""
    foot = page.evaluate("window.__pool.state.table.foot_spot")
    ball = page.evaluate(
        "(fx) => window.__pool.balls.find((b) => b.id !== 0 && Math.abs(b.x - fx) < 0.01)", foot[0]
    )
    return ball["x"], ball["y"]
