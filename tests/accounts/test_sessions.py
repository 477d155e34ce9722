"""Sessions through the API: rotated at each sign-in, ended by signing out (here, one from
the list, or everywhere: a stolen cookie with them) and by inactivity; a cross-site page
can neither rename nor sign out a player; a device's other guest merged on request."""

from __future__ import annotations

from fastapi.testclient import TestClient

from server.rooms.clock import ManualClock
from tests.accounts.device import GUEST, SESSION, Device
from tests.support.rooms import create_room

EVIL = {"Origin": "https://evil.example"}


def signed_in(client: TestClient, name: str = "Ana") -> tuple[Device, str]:
    device = Device(client)
    return device, device.claim(name)["id"]


def test_each_sign_in_rotates_the_session_and_ends_the_one_before(client: TestClient):
    phone, ana = signed_in(client)
    first = phone.jar[SESSION]
    assert phone.login("Ana").status_code == 204
    second = phone.jar[SESSION]
    assert second != first
    stale = Device(client, visit=False)
    stale.jar[SESSION] = first
    assert stale.me()["id"] != ana  # the replaced session opens nothing
    assert phone.me()["id"] == ana


def test_sign_out_ends_this_session_only(client: TestClient):
    phone, ana = signed_in(client)
    laptop = Device(client)
    laptop.login("Ana")
    cookie = phone.jar[SESSION]
    assert phone.call("POST", "/api/logout").status_code == 204
    assert SESSION not in phone.jar
    assert phone.me()["id"] != ana and phone.me()["account"] is False  # a new guest
    thief = Device(client, visit=False)
    thief.jar[SESSION] = cookie
    assert thief.me()["id"] != ana
    assert laptop.me()["id"] == ana


def test_a_stolen_cookie_stops_working_after_sign_out_everywhere(client: TestClient):
    phone, ana = signed_in(client)
    thief = Device(client, visit=False)
    thief.jar[SESSION] = phone.jar[SESSION]
    assert thief.me()["id"] == ana  # stolen: it works, until...
    assert phone.call("POST", "/api/logout/everywhere").status_code == 204
    assert thief.call("GET", "/api/account/sessions").status_code == 401
    assert thief.me()["id"] != ana
    assert phone.me()["id"] != ana
    assert phone.call("POST", "/api/logout/everywhere").status_code == 401


def test_the_list_of_sessions_and_revoking_one(client: TestClient, clock: ManualClock):
    phone, _ = signed_in(client)
    clock.advance(100)
    laptop = Device(client)
    laptop.login("Ana", headers={"User-Agent": "Mozilla/5.0 (X11; Linux x86_64) Firefox/133.0"})
    listed = laptop.call("GET", "/api/account/sessions").json()["sessions"]
    assert [(s["label"], s["current"]) for s in listed] == [
        ("Firefox on Linux", True),
        ("A browser", False),
    ]
    assert all(phone.jar[SESSION] not in s["id"] for s in listed)  # never the cookie
    other = listed[1]["id"]
    assert laptop.call("DELETE", f"/api/account/sessions/{other}").status_code == 204
    assert phone.me()["account"] is False
    assert laptop.call("DELETE", f"/api/account/sessions/{other}").status_code == 404
    assert len(laptop.call("GET", "/api/account/sessions").json()["sessions"]) == 1
    guest = Device(client)
    assert guest.call("GET", "/api/account/sessions").status_code == 401


def test_a_session_ends_after_the_idle_time(client: TestClient, clock: ManualClock, settings):
    phone, ana = signed_in(client)
    clock.advance(settings.session_idle - 1)
    assert phone.me()["id"] == ana  # used: the idle time starts again
    clock.advance(settings.session_idle - 1)
    assert phone.me()["id"] == ana
    clock.advance(settings.session_idle + 1)
    assert phone.me()["id"] != ana
    assert SESSION not in phone.jar  # the page drops the dead cookie


def test_a_cross_site_page_can_neither_rename_nor_sign_out(client: TestClient):
    phone, ana = signed_in(client)
    form = {"headers": {**EVIL, "Content-Type": "application/x-www-form-urlencoded"}}
    out = phone.call("POST", "/api/logout", content="", **form)
    assert (out.status_code, out.json()["detail"]["code"]) == (403, "cross_site")
    everywhere = phone.call("POST", "/api/logout/everywhere", **form)
    assert everywhere.status_code == 403
    renamed = phone.rename("Mallory", headers=EVIL)
    assert (renamed.status_code, renamed.json()["detail"]["code"]) == (403, "cross_site")
    no_origin = phone.call(
        "POST", "/api/logout", headers={"Sec-Fetch-Site": "cross-site"}, content=""
    )
    assert no_origin.status_code == 403
    assert phone.me()["id"] == ana and phone.me()["name"] == "Ana"
    forged = phone.call(
        "POST", "/api/login", json={"name": "Ana", "password": "x" * 8}, headers=EVIL
    )
    assert forged.status_code == 403  # nor sign the device in to another account
    plain = phone.call(
        "POST",
        "/api/login",
        content='{"name": "Ana", "password": "p"}',
        headers={"Content-Type": "text/plain"},
    )
    assert plain.status_code == 422  # a form's body is not read as JSON
    same = {"Origin": "http://testserver", "Sec-Fetch-Site": "same-origin"}
    assert phone.rename("Ana B", headers=same).status_code == 200
    assert phone.call("POST", "/api/logout", headers=same).status_code == 204


def test_a_guest_on_the_device_is_offered_and_merged(client: TestClient):
    Device(client).claim("Ana")
    laptop = Device(client)  # a guest who played a friendly game here
    room_id = create_room(client)
    assert laptop.call("POST", f"/api/rooms/{room_id}/join", json={}).status_code == 200
    guest_id = laptop.me()["id"]
    assert laptop.login("Ana").status_code == 204
    offer = laptop.call("GET", "/api/account/merge").json()["guest"]
    assert (offer["id"], offer["matches"]) == (guest_id, 1)
    merged = laptop.call("POST", "/api/account/merge", json={"merge": True})
    assert merged.json() == {"moved": 1}
    assert GUEST not in laptop.jar
    assert laptop.call("GET", "/api/account/merge").json() == {"guest": None}
    store = client.app.state.store  # type: ignore[attr-defined]
    seats = store.run(
        lambda repo: repo.connection.exec_driver_sql(
            "SELECT player_id FROM player_seats WHERE room_id = ?", (room_id,)
        ).all()
    )
    assert seats == [(laptop.me()["id"],)]


def test_declining_the_merge_leaves_the_guest_alone(client: TestClient):
    Device(client).claim("Ana")
    laptop = Device(client)
    room_id = create_room(client)
    laptop.call("POST", f"/api/rooms/{room_id}/join", json={})
    assert laptop.login("Ana").status_code == 204
    assert laptop.call("POST", "/api/account/merge", json={"merge": False}).json() == {"moved": 0}
    assert GUEST not in laptop.jar


def test_a_device_without_another_guest_is_asked_nothing(client: TestClient):
    Device(client).claim("Ana")
    fresh = Device(client)  # a guest, but one that never sat anywhere
    fresh.login("Ana")
    assert fresh.call("GET", "/api/account/merge").json() == {"guest": None}
