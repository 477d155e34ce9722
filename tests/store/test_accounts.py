"""Accounts' records on SQLite and PostgreSQL: a claimed guest keeps its row and its name
is unique among accounts after NFKC and casefolding, sessions find their player like a
guest's cookie does, passkeys and one-use ceremonies, and a guest's unranked seats moving
to an account."""

from __future__ import annotations

import pytest
from sqlalchemy import select

from server.accounts import name_key
from server.store import Database, Repository
from server.store.accounts import (
    AccountRows,
    CeremonyRecord,
    NameTaken,
    PasskeyRecord,
    SessionRecord,
)
from server.store.players import PlayerRows, RankedRecord
from server.store.schema import player_seats


def guests(repo: Repository, *names: str) -> None:
    for n, name in enumerate(names):
        PlayerRows(repo).add_player(f"p{n}", name, f"secret-{n}", 10.0 + n)


def test_a_claimed_guest_keeps_its_row_and_its_cookie_stops_working(db: Database) -> None:
    def run(repo: Repository) -> None:
        guests(repo, "Ana", "Ben")
        rows = AccountRows(repo)
        assert rows.guest_by_secret("secret-0") is not None
        rows.claim("p0", name_key("Ana"), "dead", 20.0)
        account = rows.account("p0")
        assert account is not None
        assert (account.id, account.name, account.created_at) == ("p0", "Ana", 10.0)
        assert (account.name_key, account.account_at, account.password_hash) == ("ana", 20.0, None)
        assert PlayerRows(repo).player_by_secret("secret-0") is None
        assert rows.guest_by_secret("dead") is None  # an account is no guest
        player = PlayerRows(repo).player("p0")
        assert player is not None and player.account
        ben = PlayerRows(repo).player("p1")
        assert ben is not None and not ben.account

    db.run(run)


@pytest.mark.parametrize("other", ["ana", "ANA", "\uff21na", " Ana "])
def test_account_names_are_unique_after_nfkc_and_casefolding(db: Database, other: str) -> None:
    def run(repo: Repository) -> None:
        guests(repo, "Ana", other, "Ana")  # guests may share a name
        rows = AccountRows(repo)
        rows.claim("p0", name_key("Ana"), "dead-0", 20.0)
        with pytest.raises(NameTaken):
            rows.claim("p1", name_key(other), "dead-1", 21.0)
        with pytest.raises(NameTaken):
            rows.claim("p2", name_key("Ana"), "dead-2", 21.0)
        assert rows.account("p1").name_key is None  # type: ignore[union-attr]
        rows.claim("p1", name_key("Cleo"), "dead-1", 21.0)
        with pytest.raises(NameTaken):
            rows.rename_account("p1", other, name_key(other))
        rows.rename_account("p1", "Dora", name_key("Dora"))
        assert rows.account_named("dora").name == "Dora"  # type: ignore[union-attr]

    db.run(run)


def test_a_session_finds_its_player_and_its_seats(db: Database) -> None:
    def run(repo: Repository) -> None:
        guests(repo, "Ana")
        rows = AccountRows(repo)
        rows.claim("p0", "ana", "dead", 20.0)
        rows.add_session(SessionRecord("s-hash", "p0", "Chrome on Linux", 30.0, 30.0))
        rows.add_session(SessionRecord("t-hash", "p0", "Firefox", 31.0, 35.0))
        found = PlayerRows(repo).player_by_secret("s-hash")
        assert found is not None and found.id == "p0" and found.account
        PlayerRows(repo).add_seat("s-hash", "room-a", 1, 40.0)
        PlayerRows(repo).add_seat("unknown", "room-b", 0, 40.0)
        assert [s.id_hash for s in rows.sessions_of("p0")] == ["t-hash", "s-hash"]
        rows.touch_session("s-hash", 50.0)
        assert rows.session("s-hash").last_seen == 50.0  # type: ignore[union-attr]
        assert rows.delete_sessions("p0", seen_before=40.0) == 1
        assert rows.delete_sessions("p0") == 1
        assert PlayerRows(repo).player_by_secret("s-hash") is None

        assert rows_of(repo, "p0") == ["room-a"]

    db.run(run)


def test_passkeys_and_ceremonies(db: Database) -> None:
    key = PasskeyRecord("cred-1", "p0", b"\x01\x02", 0, "Chrome on Linux", 30.0, None)

    def run(repo: Repository) -> None:
        guests(repo, "Ana")
        rows = AccountRows(repo)
        rows.add_passkey(key)
        assert rows.passkey("cred-1") == key
        rows.used_passkey("cred-1", 5, 40.0)
        assert rows.passkeys_of("p0")[0].sign_count == 5
        assert rows.delete_passkey("p1", "cred-1") == 0
        assert rows.delete_passkey("p0", "cred-1") == 1
        rows.add_ceremony("c-hash", CeremonyRecord(b"challenge", None, 100.0), 50.0)
        rows.add_ceremony("old", CeremonyRecord(b"x", "p0", 60.0), 50.0)
        rows.add_ceremony("new", CeremonyRecord(b"y", "p0", 200.0), 70.0)  # drops "old"
        assert rows.take_ceremony("c-hash") == CeremonyRecord(b"challenge", None, 100.0)
        assert rows.take_ceremony("c-hash") is None  # once
        assert rows.take_ceremony("old") is None

    db.run(run)


def test_a_guests_unranked_seats_move_to_an_account(db: Database) -> None:
    def run(repo: Repository) -> None:
        guests(repo, "Guest", "Ana", "Ben")
        players, rows = PlayerRows(repo), AccountRows(repo)
        for room in ("friendly", "ranked", "shared"):
            players.add_player_seat("p0", room, 0, 1.0)
        players.add_player_seat("p1", "shared", 1, 1.0)
        players.add_ranked(RankedRecord("ranked", "eight_ball", ("p0", "p2"), ("G", "B"), 1.0))
        assert rows.unranked_seats("p0") == 2
        assert rows.move_unranked_seats("p0", "p1") == 1
        assert set(rows_of(repo, "p1")) == {"friendly", "shared"}
        assert set(rows_of(repo, "p0")) == {"ranked", "shared"}

    db.run(run)


def rows_of(repo: Repository, player_id: str) -> list[str]:
    with repo.transaction(write=False) as conn:
        return list(
            conn.execute(
                select(player_seats.c.room_id).where(player_seats.c.player_id == player_id)
            ).scalars()
        )
