"""What any client can do over HTTP, bounded: per-client room and seat limits, private
tables, a paginated room list, security headers, only the client's own files served."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from server.app import create_app
from server.config import Settings


@pytest.fixture
def settings(tmp_path: Path) -> Settings:
    web = tmp_path / "web"
    (web / "js").mkdir(parents=True)
    (web / "index.html").write_text("<!doctype html><title>pool</title><p>lobby</p>")
    (web / "style.css").write_text("body { margin: 0 }")
    (web / "js" / "main.js").write_text("export const ok = true;\n")
    (web / "package.json").write_text("{}")
    (web / "tests").mkdir()
    (web / "tests" / "a.test.mjs").write_text("// test")
    return Settings(
        web_dir=web,
        db_path=tmp_path / "pool.db",
        max_rooms_per_client=5,
        room_create_rate="8/minute",
        join_rate="6/minute",
    )


@pytest.fixture
def client(settings: Settings) -> Iterator[TestClient]:
    with TestClient(create_app(settings)) as c:
        yield c


def other_client(client: TestClient, address: str) -> TestClient:
    """The same app seen from another address (TestClient lets us name the peer)."""
    other = TestClient(client.app, client=(address, 50000))
    return other


def test_one_client_cannot_take_every_room(client: TestClient):
    codes = [client.post("/api/rooms", json={"game": "eight_ball"}).status_code for _ in range(50)]
    assert codes[:5] == [201] * 5
    assert set(codes[5:]) == {429}  # five open at once, then the rate window
    body = client.post("/api/rooms", json={"game": "eight_ball"}).json()
    assert body["detail"]["code"] in ("too_many_rooms_open", "rate_limited")
    assert (
        other_client(client, "10.1.2.3").post("/api/rooms", json={"game": "nine_ball"}).status_code
        == 201
    )


def test_seats_are_rate_limited_per_client(client: TestClient):
    rooms = [
        other_client(client, f"10.0.0.{i}")
        .post("/api/rooms", json={"game": "practice"})
        .json()["room_id"]
        for i in range(8)
    ]
    codes = [client.post(f"/api/rooms/{r}/join", json={"name": "Bot"}).status_code for r in rooms]
    assert codes == [200] * 6 + [429] * 2


def test_private_tables_are_not_listed_but_open_by_link(client: TestClient):
    public = client.post("/api/rooms", json={"game": "eight_ball"}).json()
    private = client.post("/api/rooms", json={"game": "eight_ball", "listed": False}).json()
    assert (public["listed"], private["listed"]) == (True, False)
    listed = client.get("/api/rooms").json()
    assert [r["room_id"] for r in listed["rooms"]] == [public["room_id"]]
    assert client.get(f"/api/rooms/{private['room_id']}").status_code == 200
    joined = client.post(f"/api/rooms/{private['room_id']}/join", json={"name": "Ana"})
    assert joined.status_code == 200


def test_the_room_list_comes_in_pages_newest_first(client: TestClient):
    made = [
        other_client(client, f"10.0.1.{i}")
        .post("/api/rooms", json={"game": "nine_ball"})
        .json()["room_id"]
        for i in range(7)
    ]
    first = client.get("/api/rooms?limit=3").json()
    second = client.get("/api/rooms?limit=3&offset=3").json()
    last = client.get("/api/rooms?limit=3&offset=6").json()
    ids = [r["room_id"] for page in (first, second, last) for r in page["rooms"]]
    assert ids == made[::-1]
    assert (first["total"], first["next"], second["next"], last["next"]) == (7, 3, 6, None)
    assert client.get("/api/rooms?limit=1000").status_code == 422


def test_pages_carry_security_headers_and_only_the_client_is_served(client: TestClient):
    page = client.get("/")
    csp = page.headers["content-security-policy"]
    assert "script-src 'self'" in csp and "frame-ancestors 'none'" in csp
    assert "'unsafe-inline'" not in csp
    assert page.headers["x-content-type-options"] == "nosniff"
    assert page.headers["referrer-policy"] == "same-origin"
    assert client.get("/js/main.js").text.startswith("export")
    assert client.get("/style.css").headers["content-type"].startswith("text/css")
    for hidden in ("/package.json", "/tests/a.test.mjs", "/docs", "/redoc"):
        assert client.get(hidden).status_code == 404, hidden
    assert client.get("/openapi.json").status_code == 200
    assert client.get("/api/rooms").headers["x-content-type-options"] == "nosniff"


def test_the_page_may_open_sockets_to_the_configured_origins(
    client: TestClient, settings: Settings
):
    """`socket_origins` (e.g. every server of a cluster behind one domain) join the CSP's
    connect-src; without them the page connects to its own server only."""
    assert "connect-src 'self';" in client.get("/").headers["content-security-policy"]
    wider = settings.replace(socket_origins=("wss://*.pool.example", "ws://10.0.0.7:8000"))
    with TestClient(create_app(wider)) as other:
        csp = other.get("/").headers["content-security-policy"]
    assert "connect-src 'self' ws://10.0.0.7:8000 wss://*.pool.example;" in csp


def test_a_replay_cannot_be_held_open_at_a_crawl(client: TestClient):
    assert client.get("/api/matches/1/shots/1/replay?pace=1e-9").status_code == 422
