"""Accounts' records: the account columns of a player, its sessions (the cookie's hash),
its passkeys, and the WebAuthn challenges waiting for an answer. Typed rows in and out;
what they mean (expiry, policy, the ceremonies) is `server.accounts`'.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from sqlalchemy import delete, select, update
from sqlalchemy.exc import IntegrityError

from .repository import Repository
from .schema import ceremonies, passkeys, player_seats, players, ranked_rooms, sessions


class NameTaken(Exception):
    """Another account has this name (after NFKC and casefolding)."""


@dataclass(frozen=True)
class AccountRecord:
    id: str
    name: str
    created_at: float
    name_key: str | None  # None: a guest
    password_hash: str | None
    account_at: float | None


@dataclass(frozen=True)
class SessionRecord:
    id_hash: str
    player_id: str
    label: str
    created_at: float
    last_seen: float


@dataclass(frozen=True)
class PasskeyRecord:
    credential_id: str
    player_id: str
    public_key: bytes
    sign_count: int
    label: str
    created_at: float
    last_used: float | None


@dataclass(frozen=True)
class CeremonyRecord:
    challenge: bytes
    player_id: str | None
    expires_at: float


_ACCOUNT = (
    players.c.id,
    players.c.name,
    players.c.created_at,
    players.c.name_key,
    players.c.password_hash,
    players.c.account_at,
)


def _account(row: Any) -> AccountRecord | None:
    if row is None:
        return None
    return AccountRecord(row[0], row[1], row[2], row[3], row[4], row[5])


class AccountRows:
    """Queries over the repository's connection (each method one transaction, or part of
    an enclosing `repo.transaction()`)."""

    def __init__(self, repo: Repository) -> None:
        self.repo = repo

    # ---- accounts ---------------------------------------------------------------------

    def account(self, player_id: str) -> AccountRecord | None:
        with self.repo.transaction(write=False) as conn:
            return _account(
                conn.execute(select(*_ACCOUNT).where(players.c.id == player_id)).first()
            )

    def account_named(self, name_key: str) -> AccountRecord | None:
        with self.repo.transaction(write=False) as conn:
            found = conn.execute(select(*_ACCOUNT).where(players.c.name_key == name_key)).first()
        return _account(found)

    def guest_by_secret(self, secret_hash: str) -> AccountRecord | None:
        with self.repo.transaction(write=False) as conn:
            found = conn.execute(
                select(*_ACCOUNT).where(
                    players.c.secret_hash == secret_hash, players.c.name_key.is_(None)
                )
            ).first()
        return _account(found)

    def claim(self, player_id: str, name_key: str, dead_secret_hash: str, at: float) -> None:
        """Make the guest an account (nothing changes if it is one): its name reserved by
        `name_key`, its guest cookie's hash replaced by one nobody holds. `NameTaken`."""
        query = (
            update(players)
            .where(players.c.id == player_id, players.c.name_key.is_(None))
            .values(name_key=name_key, secret_hash=dead_secret_hash, account_at=at)
        )
        self._unique_name(query)

    def rename_account(self, player_id: str, name: str, name_key: str) -> None:
        """An account's new name (`NameTaken` if another account has it)."""
        query = (
            update(players).where(players.c.id == player_id).values(name=name, name_key=name_key)
        )
        self._unique_name(query)

    def _unique_name(self, query: Any) -> None:
        try:
            with self.repo.transaction() as conn:
                conn.execute(query)
        except IntegrityError:
            raise NameTaken from None

    def set_password_hash(self, player_id: str, password_hash: str) -> None:
        with self.repo.transaction() as conn:
            conn.execute(
                update(players).where(players.c.id == player_id).values(password_hash=password_hash)
            )

    # ---- sessions ---------------------------------------------------------------------

    def add_session(self, record: SessionRecord) -> None:
        with self.repo.transaction() as conn:
            conn.execute(sessions.insert().values(**record.__dict__))

    def session(self, id_hash: str) -> SessionRecord | None:
        with self.repo.transaction(write=False) as conn:
            row = conn.execute(select(sessions).where(sessions.c.id_hash == id_hash)).first()
        return None if row is None else SessionRecord(*row)

    def touch_session(self, id_hash: str, at: float) -> None:
        with self.repo.transaction() as conn:
            conn.execute(update(sessions).where(sessions.c.id_hash == id_hash).values(last_seen=at))

    def sessions_of(self, player_id: str) -> list[SessionRecord]:
        with self.repo.transaction(write=False) as conn:
            rows = conn.execute(
                select(sessions)
                .where(sessions.c.player_id == player_id)
                .order_by(sessions.c.last_seen.desc())
            ).all()
        return [SessionRecord(*r) for r in rows]

    def delete_sessions(
        self, player_id: str, id_hash: str | None = None, seen_before: float | None = None
    ) -> int:
        """The player's sessions (one, with `id_hash`; or those idle since `seen_before`)."""
        query = delete(sessions).where(sessions.c.player_id == player_id)
        if id_hash is not None:
            query = query.where(sessions.c.id_hash == id_hash)
        if seen_before is not None:
            query = query.where(sessions.c.last_seen < seen_before)
        with self.repo.transaction() as conn:
            return int(conn.execute(query).rowcount)

    # ---- passkeys ---------------------------------------------------------------------

    def add_passkey(self, record: PasskeyRecord) -> None:
        with self.repo.transaction() as conn:
            conn.execute(passkeys.insert().values(**record.__dict__))

    def passkey(self, credential_id: str) -> PasskeyRecord | None:
        with self.repo.transaction(write=False) as conn:
            row = conn.execute(
                select(passkeys).where(passkeys.c.credential_id == credential_id)
            ).first()
        return None if row is None else PasskeyRecord(*row)

    def passkeys_of(self, player_id: str) -> list[PasskeyRecord]:
        with self.repo.transaction(write=False) as conn:
            rows = conn.execute(
                select(passkeys)
                .where(passkeys.c.player_id == player_id)
                .order_by(passkeys.c.created_at)
            ).all()
        return [PasskeyRecord(*r) for r in rows]

    def used_passkey(self, credential_id: str, sign_count: int, at: float) -> None:
        with self.repo.transaction() as conn:
            conn.execute(
                update(passkeys)
                .where(passkeys.c.credential_id == credential_id)
                .values(sign_count=sign_count, last_used=at)
            )

    def delete_passkey(self, player_id: str, credential_id: str) -> int:
        with self.repo.transaction() as conn:
            done = conn.execute(
                delete(passkeys).where(
                    passkeys.c.player_id == player_id, passkeys.c.credential_id == credential_id
                )
            )
        return int(done.rowcount)

    # ---- ceremonies -------------------------------------------------------------------

    def add_ceremony(self, id_hash: str, record: CeremonyRecord, now: float) -> None:
        with self.repo.transaction() as conn:
            conn.execute(delete(ceremonies).where(ceremonies.c.expires_at < now))
            conn.execute(ceremonies.insert().values(id_hash=id_hash, **record.__dict__))

    def take_ceremony(self, id_hash: str) -> CeremonyRecord | None:
        """The challenge of this ceremony, removed: each is answered once."""
        with self.repo.transaction() as conn:
            row = conn.execute(
                select(
                    ceremonies.c.challenge, ceremonies.c.player_id, ceremonies.c.expires_at
                ).where(ceremonies.c.id_hash == id_hash)
            ).first()
            if row is None:
                return None
            conn.execute(delete(ceremonies).where(ceremonies.c.id_hash == id_hash))
        return CeremonyRecord(bytes(row[0]), row[1], row[2])

    # ---- merging a guest ----------------------------------------------------------------

    def unranked_seats(self, player_id: str) -> int:
        with self.repo.transaction(write=False) as conn:
            return len(conn.execute(_unranked(player_id)).all())

    def move_unranked_seats(self, guest_id: str, account_id: str) -> int:
        """The guest's seats outside ranked rooms become the account's (a room where the
        account sat too keeps the account's seat); ratings and ranked results stay."""
        with self.repo.transaction() as conn:
            mine = set(
                conn.execute(
                    select(player_seats.c.room_id).where(player_seats.c.player_id == account_id)
                ).scalars()
            )
            rooms = [r for r in conn.execute(_unranked(guest_id)).scalars() if r not in mine]
            if rooms:
                conn.execute(
                    update(player_seats)
                    .where(player_seats.c.player_id == guest_id, player_seats.c.room_id.in_(rooms))
                    .values(player_id=account_id)
                )
        return len(rooms)


def _unranked(player_id: str) -> Any:
    ranked = select(ranked_rooms.c.room_id)
    return select(player_seats.c.room_id).where(
        player_seats.c.player_id == player_id, player_seats.c.room_id.not_in(ranked)
    )
