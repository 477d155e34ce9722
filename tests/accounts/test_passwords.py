"""Passwords through the API: a guest claimed by a password keeps its id, name and ratings
and signs in on another device; the cookies; wrong and unknown answered alike (401) and
limited (429); the policy; changing needs the old one; argon2id at rest, rehashed when the
parameters change; account names unique after NFKC and casefolding."""

from __future__ import annotations

import asyncio

import httpx
import pytest
from argon2 import PasswordHasher
from fastapi.testclient import TestClient

from server.accounts import Hasher
from server.store.accounts import AccountRows
from tests.accounts.device import GUEST, SESSION, STRONG, Device
from tests.support.rooms import app_with

BAD = {"detail": {"code": "bad_credentials", "message": "Wrong name or password."}}


def stored_hash(client: TestClient, player_id: str) -> str | None:
    store = client.app.state.store  # type: ignore[attr-defined]
    record = store.run(lambda repo: AccountRows(repo).account(player_id))
    return record.password_hash


def test_a_guest_with_a_password_signs_in_on_another_device_as_itself(client: TestClient):
    phone = Device(client)
    phone.rename("Ana")
    assert phone.set_password().status_code == 204
    cookies = " ".join(phone.set_cookies).lower()
    guest = phone.me()
    assert phone.call("GET", "/api/account").json() == {"name": "Ana", "password": True}
    assert f"{SESSION}=" in cookies and "httponly" in cookies and "samesite=lax" in cookies
    assert GUEST not in phone.jar  # the guest cookie is gone: it opens nothing now
    assert guest["account"] is True and guest["name"] == "Ana"
    laptop = Device(client)
    assert laptop.me()["account"] is False and laptop.me()["id"] != guest["id"]
    assert laptop.call("GET", "/api/account").status_code == 401  # a guest has none
    assert laptop.login("ana", STRONG).status_code == 204
    there = laptop.me()
    assert (there["id"], there["name"], there["ratings"]) == (
        guest["id"],
        "Ana",
        guest["ratings"],
    )
    assert there["account"] is True


def test_the_password_is_stored_as_an_argon2id_string(client: TestClient):
    ana = Device(client)
    player_id = ana.claim("Ana")["id"]
    stored = stored_hash(client, player_id)
    assert stored is not None and stored.startswith("$argon2id$v=19$m=65536,t=3,p=4$")
    assert STRONG not in stored


def test_an_old_guest_cookie_is_a_stranger_after_the_claim(client: TestClient):
    ana = Device(client)
    guest_secret = ana.jar[GUEST]
    player_id = ana.claim("Ana")["id"]
    thief = Device(client, visit=False)
    thief.jar[GUEST] = guest_secret
    assert thief.me()["id"] != player_id


def test_wrong_and_unknown_are_answered_alike_then_limited(client: TestClient):
    Device(client).claim("Ana")
    other = Device(client)
    wrong = other.login("Ana", "not the password")
    unknown = other.login("Nobody", "not the password")
    assert (wrong.status_code, wrong.json()) == (401, BAD)
    assert (unknown.status_code, unknown.json()) == (401, BAD)
    answers = [other.login("Ana", f"guess number {n}").status_code for n in range(5)]
    assert answers == [401, 401, 401, 401, 429]  # 5 failures per name per window
    assert other.login("Ana", STRONG).status_code == 429  # even the right one, for now
    assert other.login("Nobody", "x" * 8).status_code == 401  # other names are not limited
    assert SESSION not in other.jar


def test_an_unknown_name_costs_a_hash_check_too(client: TestClient):
    """The same work for an unknown name as for a wrong password: the dummy hash is
    checked (the time itself is not asserted: it is the same function on the same
    input size)."""
    checked: list[str] = []
    hasher = client.app.state.accounts.hasher  # type: ignore[attr-defined]
    real = hasher.verify

    def spy(stored: str | None, password: str) -> bool:
        checked.append("dummy" if stored is None else "stored")
        return real(stored, password)

    hasher.verify = spy
    Device(client).claim("Ana")
    other = Device(client)
    other.login("Nobody", "some password")
    other.login("Ana", "some password")
    assert checked == ["dummy", "stored"]


def test_the_address_is_limited_across_names(client: TestClient, settings):
    client.app.state.sign_in_limits = type(client.app.state.sign_in_limits)(  # type: ignore[attr-defined]
        "3/minute", settings.login_account_rate
    )
    other = Device(client)
    answers = [other.login(f"Name {n}", "some password").status_code for n in range(4)]
    assert answers == [401, 401, 401, 429]


@pytest.mark.parametrize(
    ("password", "reason"),
    [("short", "short"), ("password123", "common"), ("Qwertyuiop", "common"), ("x" * 300, "long")],
)
def test_weak_passwords_are_refused(client: TestClient, password: str, reason: str):
    ana = Device(client)
    response = ana.set_password(password)
    assert response.status_code == 422
    assert response.json()["detail"]["code"] == "weak_password"
    assert response.json()["detail"]["reason"] == reason
    assert ana.me()["account"] is False


def test_the_name_is_no_password(client: TestClient):
    ana = Device(client)
    ana.rename("Ana Banana")
    assert ana.set_password("ana banana").json()["detail"]["reason"] == "name"


def test_changing_needs_the_old_password_and_ends_the_other_sessions(client: TestClient):
    phone = Device(client)
    phone.claim("Ana")
    laptop = Device(client)
    assert laptop.login("Ana").status_code == 204
    assert phone.set_password("a new long passphrase").status_code == 401  # no old one
    wrong = phone.set_password("a new long passphrase", old="not it at all")
    assert (wrong.status_code, wrong.json()) == (401, BAD)
    before = phone.jar[SESSION]
    assert phone.set_password("a new long passphrase", old=STRONG).status_code == 204
    assert phone.jar[SESSION] != before  # rotated
    assert phone.me()["account"] is True
    assert laptop.me()["account"] is False  # signed out there
    assert laptop.login("Ana", STRONG).status_code == 401
    assert laptop.login("Ana", "a new long passphrase").status_code == 204


def test_a_hash_of_older_parameters_is_replaced_at_sign_in(client: TestClient):
    ana = Device(client)
    player_id = ana.claim("Ana")["id"]
    weak = Hasher(PasswordHasher(time_cost=1, memory_cost=8192, parallelism=1))
    old = weak.hash(STRONG)
    store = client.app.state.store  # type: ignore[attr-defined]
    store.run(lambda repo: AccountRows(repo).set_password_hash(player_id, old))
    assert Device(client).login("Ana").status_code == 204
    stored = stored_hash(client, player_id)
    assert stored != old and stored is not None
    assert stored.startswith("$argon2id$v=19$m=65536,t=3,p=4$")
    assert Device(client).login("Ana").status_code == 204  # the new hash checks


@pytest.mark.parametrize("other", ["ana", "ANA", "\uff21\uff4e\uff41", " Ana"])
def test_account_names_are_unique_after_nfkc_and_casefolding(client: TestClient, other: str):
    Device(client).claim("Ana")
    guest = Device(client)
    assert guest.rename(other).status_code == 200  # guests may share a name
    taken = guest.set_password()
    assert (taken.status_code, taken.json()["detail"]["code"]) == (409, "name_taken")
    assert guest.me()["account"] is False
    ben = Device(client)
    ben.claim("Ben")
    renamed = ben.rename(other)
    assert (renamed.status_code, renamed.json()["detail"]["code"]) == (409, "name_taken")
    assert ben.rename("Benedict").status_code == 200
    assert Device(client).login("benedict").status_code == 204  # signs in by the new name


def test_a_burst_of_guesses_sent_together_is_limited_like_one_after_another(settings):
    """Attempts sent at once queue for their turn, so each sees the failures before it:
    no more than the limit reach the hashing."""

    async def burst() -> list[int]:
        app = app_with(settings.replace(login_rate="3/minute"))
        async with app.router.lifespan_context(app):
            transport = httpx.ASGITransport(app=app)
            async with httpx.AsyncClient(transport=transport, base_url="http://test") as http:
                answers = await asyncio.gather(
                    *(
                        http.post("/api/login", json={"name": f"N{n}", "password": "guess"})
                        for n in range(8)
                    )
                )
        return sorted(a.status_code for a in answers)

    assert asyncio.run(burst()) == [401, 401, 401, 429, 429, 429, 429, 429]
