"""The passkey endpoints without an authenticator (the browser tests run the whole
ceremony with Chromium's virtual one): the options asked for, the ceremony's cookie, an
answer that does not verify, each ceremony answered once, the list, and the last way in
kept."""

from __future__ import annotations

import base64

from fastapi.testclient import TestClient

from server.store.accounts import AccountRows, PasskeyRecord
from tests.accounts.device import Device

FAKE = {
    "id": "AAAA",
    "rawId": "AAAA",
    "type": "public-key",
    "response": {"clientDataJSON": "e30", "attestationObject": "oA", "authenticatorData": "AA"},
}


def b64url(text: str) -> str:
    return base64.urlsafe_b64encode(text.encode()).rstrip(b"=").decode()


def test_registration_options_ask_for_a_discoverable_credential(client: TestClient):
    ana = Device(client)
    me = ana.me()
    response = ana.call("POST", "/api/passkeys/register/options")
    assert response.status_code == 200, response.text
    options = response.json()["options"]
    assert options["rp"] == {"id": "testserver", "name": "Pool online"}
    assert options["user"]["id"] == b64url(me["id"])
    assert options["user"]["name"] == me["name"]
    assert options["authenticatorSelection"]["residentKey"] == "required"
    assert options["excludeCredentials"] == []
    cookie = " ".join(ana.set_cookies).lower()
    assert "pool_ceremony=" in cookie and "httponly" in cookie
    assert "samesite=strict" in cookie and "path=/api/passkeys" in cookie


def test_an_answer_that_does_not_verify_is_refused_and_the_ceremony_is_spent(
    client: TestClient,
):
    ana = Device(client)
    ana.call("POST", "/api/passkeys/register/options")
    ceremony = ana.jar["pool_ceremony"]
    refused = ana.call("POST", "/api/passkeys/register", json={"credential": FAKE})
    assert (refused.status_code, refused.json()["detail"]["code"]) == (400, "passkey_refused")
    assert ana.me()["account"] is False
    ana.jar["pool_ceremony"] = ceremony  # the same ceremony again
    again = ana.call("POST", "/api/passkeys/register", json={"credential": FAKE})
    assert again.status_code == 400
    none = Device(client).call("POST", "/api/passkeys/register", json={"credential": FAKE})
    assert none.status_code == 400


def test_signing_in_with_an_unknown_passkey_is_bad_credentials(client: TestClient):
    visitor = Device(client)
    options = visitor.call("POST", "/api/passkeys/login/options").json()["options"]
    assert options["rpId"] == "testserver" and options["allowCredentials"] == []
    answer = visitor.call("POST", "/api/passkeys/login", json={"credential": FAKE})
    assert (answer.status_code, answer.json()["detail"]["code"]) == (401, "bad_credentials")
    assert "pool_session" not in visitor.jar


def test_a_guest_whose_name_an_account_has_renames_first(client: TestClient):
    Device(client).claim("Ana")
    guest = Device(client)
    guest.rename("ANA")
    taken = guest.call("POST", "/api/passkeys/register/options")
    assert (taken.status_code, taken.json()["detail"]["code"]) == (409, "name_taken")


def test_the_list_of_passkeys_and_the_last_way_in(client: TestClient):
    ana = Device(client)
    player_id = ana.claim("Ana")["id"]
    store = client.app.state.store  # type: ignore[attr-defined]
    for n in (1, 2):
        key = PasskeyRecord(f"cred-{n}", player_id, b"k", 0, "Chrome on Linux", 10.0 + n, None)
        store.run(lambda repo, key=key: AccountRows(repo).add_passkey(key))
    listed = ana.call("GET", "/api/passkeys").json()["passkeys"]
    assert [(p["id"], p["label"]) for p in listed] == [
        ("cred-1", "Chrome on Linux"),
        ("cred-2", "Chrome on Linux"),
    ]
    assert ana.call("DELETE", "/api/passkeys/cred-1").status_code == 204
    assert ana.call("DELETE", "/api/passkeys/cred-1").status_code == 404
    store.run(
        lambda repo: repo.connection.exec_driver_sql(
            "UPDATE players SET password_hash = NULL WHERE id = ?", (player_id,)
        )
    )
    last = ana.call("DELETE", "/api/passkeys/cred-2")
    assert (last.status_code, last.json()["detail"]["code"]) == (409, "last_way_in")
    assert Device(client).call("GET", "/api/passkeys").status_code == 401
