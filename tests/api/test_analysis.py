"""`GET /api/matches/{id}/analysis`: 404 for an unknown match, 202 while queued, then 200
with every shot judged; the stored result is what a fresh analysis gives again; the pro's
own choice is best and a stroke away from every ball a blunder."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from server.codec import to_data
from server.config import Settings
from server.engine import Table
from server.rooms.analyses import AnalysisQueue
from server.store import Database
from tests.support.analysis import away_from_every_ball, club_game, pros_choice, store_match
from tests.support.rooms import app_with
from tests.support.settings import settings_in

MATCH_ID = 7


@pytest.fixture
def settings(tmp_path: Path) -> Settings:
    return settings_in(tmp_path, analysis_workers=0)


@pytest.fixture
def client(settings: Settings) -> Iterator[TestClient]:
    shots = list(club_game())[:4]
    shots[2] = pros_choice(MATCH_ID, shots, 3)
    shots[3] = away_from_every_ball(shots, 4)
    db = Database(settings.database)
    try:
        db.run(lambda repo: store_match(repo, MATCH_ID, shots, Table.pool("9ft")))
        db.run(lambda repo: repo.start_match(MATCH_ID + 1, "live", "eight_ball", ["a", "b"], 1))
    finally:
        db.close()
    with TestClient(app_with(settings)) as c:
        yield c


def queue_of(client: TestClient) -> AnalysisQueue:
    queue: AnalysisQueue = client.app.state.analyses  # type: ignore[attr-defined]
    return queue


def test_an_unknown_match_has_no_analysis_and_a_live_one_none_yet(client: TestClient) -> None:
    response = client.get("/api/matches/999/analysis")
    assert response.status_code == 404
    assert response.json()["detail"]["code"] == "unknown_match"
    response = client.get(f"/api/matches/{MATCH_ID + 1}/analysis")
    assert response.status_code == 409
    assert response.json()["detail"]["code"] == "match_playing"


def test_the_analysis_is_queued_then_served_from_the_store(client: TestClient) -> None:
    first = client.get(f"/api/matches/{MATCH_ID}/analysis")
    assert first.status_code == 202
    assert first.json() == {"status": "pending", "position": 0}
    queue = queue_of(client)
    client.portal.call(queue.drained)  # type: ignore[union-attr]
    ready = client.get(f"/api/matches/{MATCH_ID}/analysis")
    assert ready.status_code == 200
    body = ready.json()
    assert body["status"] == "ready"
    assert [p["seat"] for p in body["players"]] == [0, 1]
    assert all(p["accuracy"] is None or 0 <= p["accuracy"] <= 100 for p in body["players"])
    shots = body["shots"]
    assert [s["n"] for s in shots] == [1, 2, 3, 4]
    for shot in shots:
        assert shot["verdict"] in ("best", "good", "mistake", "blunder")
        assert set(shot["best"]) >= {"kind", "target", "pocket", "angle", "speed", "tip", "chance"}
    assert shots[2]["verdict"] == "best"
    assert shots[3]["verdict"] == "blunder"
    assert shots[3]["played_chance"] == 0.0
    # the same match analysed again gives the same figures
    again = client.portal.call(queue.analyse, MATCH_ID)  # type: ignore[union-attr]
    stored = {k: v for k, v in body.items() if k not in ("status", "thresholds")}
    assert to_data(again) == stored
    # served from the store: nothing is analysed a second time
    assert client.get(f"/api/matches/{MATCH_ID}/analysis").json() == body
    assert not queue.running


def test_a_rooms_matches_are_found_by_its_id(client: TestClient) -> None:
    """The table page finds the match it just finished by its room, for "Analyse"."""
    found = client.get(f"/api/matches?room=room-{MATCH_ID}&limit=1").json()["matches"]
    assert [m["id"] for m in found] == [MATCH_ID]
    assert client.get("/api/matches?room=elsewhere").json() == {"matches": []}


def test_an_analysed_shot_becomes_a_drill_on_its_stored_table(client: TestClient) -> None:
    """ "Play this position again": a private practice table with the stored table before
    the shot and the pro's chance there as the par; refused before the analysis."""
    ask = {"match_id": MATCH_ID, "n": 4}
    assert client.post("/api/drills", json=ask).json()["detail"]["code"] == "analysis_not_ready"
    client.get(f"/api/matches/{MATCH_ID}/analysis")
    client.portal.call(queue_of(client).drained)  # type: ignore[union-attr]
    analysis = client.get(f"/api/matches/{MATCH_ID}/analysis").json()
    unknown = client.post("/api/drills", json={"match_id": MATCH_ID, "n": 99})
    assert unknown.status_code == 404

    created = client.post("/api/drills", json=ask)
    assert created.status_code == 201
    drill = created.json()
    assert (drill["game"], drill["listed"], drill["kind"], drill["n"]) == (
        "practice",
        False,
        "position",
        4,
    )
    assert drill["par"] == analysis["shots"][3]["best"]["chance"]
    joined = client.post(f"/api/rooms/{drill['room_id']}/join", json={"name": "Ana"})
    assert joined.status_code == 200
    state = client.get(f"/api/rooms/{drill['room_id']}").json()["state"]
    assert state["room"]["drill"] == {
        "kind": "position",
        "match": MATCH_ID,
        "n": 4,
        "par": drill["par"],
        "made": None,
        "score": 0,
        "done": False,
        "won": False,
        "balls": None,
        "tries": 1,
        "best": 0,
    }
    stored = client.get(f"/api/matches/{MATCH_ID}").json()["shots"][3]["b"]
    assert sorted(map(tuple, state["balls"])) == sorted(map(tuple, stored))
