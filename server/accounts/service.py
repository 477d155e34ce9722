"""Accounts as the routes use them: claiming a guest (its row, so id, name, ratings and
history stay), passwords, signing in and out, the sessions of an account, and merging a
device's other guest into it. No HTTP here: the routes turn these into cookies and
answers."""

from __future__ import annotations

import asyncio
import secrets
from dataclasses import dataclass

from server.players import secret_hash
from server.store import Database
from server.store.accounts import AccountRecord, AccountRows, NameTaken, SessionRecord

from .names import name_key
from .passwords import Hasher, check_password
from .sessions import TOUCH_EVERY, device_label, expired, handle, new_session


class BadCredentials(Exception):
    """No account has this name and password (which of the two is never said)."""


@dataclass(frozen=True)
class SessionView:
    handle: str
    label: str
    created_at: float
    last_seen: float
    current: bool


@dataclass(frozen=True)
class GuestOffer:
    """Another guest this device played as: its unranked matches can join the account."""

    id: str
    name: str
    matches: int


class Accounts:
    def __init__(self, db: Database, idle: float, hasher: Hasher | None = None) -> None:
        self.db = db
        self.idle = idle
        self.hasher = hasher or Hasher()

    async def account(self, player_id: str) -> AccountRecord | None:
        return await self.db.call(lambda repo: AccountRows(repo).account(player_id))

    # ---- sessions ---------------------------------------------------------------------

    async def session_player(self, secret: str, now: float) -> str | None:
        """The account a session cookie signs in, if the session is live (an idle one is
        removed); its last-seen time is kept at most `TOUCH_EVERY` s old."""
        id_hash = secret_hash(secret)
        found = await self.db.call(lambda repo: AccountRows(repo).session(id_hash))
        if found is None:
            return None
        if expired(found.last_seen, now, self.idle):
            await self.db.call(
                lambda repo: AccountRows(repo).delete_sessions(found.player_id, id_hash)
            )
            return None
        if now - found.last_seen > TOUCH_EVERY:
            self.db.write(lambda repo: AccountRows(repo).touch_session(id_hash, now), "touch")
        return found.player_id

    async def start_session(
        self, player_id: str, user_agent: str | None, now: float, replacing: str | None
    ) -> str:
        """A new session (its cookie's value): a sign-in always gets a new id, and the
        session the device had before (`replacing`) ends."""
        secret, id_hash = new_session()
        record = SessionRecord(id_hash, player_id, device_label(user_agent), now, now)

        def store(rows: AccountRows) -> None:
            with rows.repo.transaction():
                if replacing is not None:
                    old = rows.session(secret_hash(replacing))
                    if old is not None:
                        rows.delete_sessions(old.player_id, old.id_hash)
                rows.add_session(record)

        await self.db.call(lambda repo: store(AccountRows(repo)))
        return secret

    async def end_session(self, secret: str) -> None:
        id_hash = secret_hash(secret)

        def end(rows: AccountRows) -> None:
            found = rows.session(id_hash)
            if found is not None:
                rows.delete_sessions(found.player_id, id_hash)

        await self.db.call(lambda repo: end(AccountRows(repo)))

    async def end_all(self, player_id: str) -> int:
        """Sign out everywhere: every session of the account ends."""
        return await self.db.call(lambda repo: AccountRows(repo).delete_sessions(player_id))

    async def sessions(self, player_id: str, now: float, current: str | None) -> list[SessionView]:
        mine = None if current is None else secret_hash(current)

        def live(rows: AccountRows) -> list[SessionRecord]:
            rows.delete_sessions(player_id, seen_before=now - self.idle)
            return rows.sessions_of(player_id)

        found = await self.db.call(lambda repo: live(AccountRows(repo)))
        return [
            SessionView(handle(s.id_hash), s.label, s.created_at, s.last_seen, s.id_hash == mine)
            for s in found
        ]

    async def revoke(self, player_id: str, session: str) -> bool:
        """End the account's session named `session` (its handle in the list)."""

        def end(rows: AccountRows) -> bool:
            hit = [s for s in rows.sessions_of(player_id) if handle(s.id_hash) == session]
            return any(rows.delete_sessions(player_id, s.id_hash) for s in hit)

        return await self.db.call(lambda repo: end(AccountRows(repo)))

    # ---- names and passwords ----------------------------------------------------------

    async def name_free(self, player_id: str, name: str) -> bool:
        """May this player's account carry `name` (no other account has it)?"""
        key = name_key(name)
        found = await self.db.call(lambda repo: AccountRows(repo).account_named(key))
        return found is None or found.id == player_id

    async def claim(self, player_id: str, name: str, now: float) -> None:
        """The guest becomes an account (`NameTaken`); its guest cookie stops working."""
        dead = secret_hash(secrets.token_urlsafe(32))
        key = name_key(name)
        await self.db.call(lambda repo: AccountRows(repo).claim(player_id, key, dead, now))

    async def rename(self, player_id: str, name: str) -> None:
        """An account's new name (`NameTaken`)."""
        key = name_key(name)
        await self.db.call(lambda repo: AccountRows(repo).rename_account(player_id, name, key))

    async def set_password(
        self, record: AccountRecord, password: str, old: str | None, now: float
    ) -> bool:
        """Set the password (a guest is claimed: True), or change it: the old one is
        required (`BadCredentials`). `WeakPassword`, `NameTaken`."""
        known = record.password_hash
        if known is not None and (old is None or not await self._verify(known, old)):
            raise BadCredentials
        check_password(password, record.name)
        hashed = await asyncio.to_thread(self.hasher.hash, password)
        claiming = record.name_key is None
        dead = secret_hash(secrets.token_urlsafe(32))
        key = name_key(record.name)

        def store(rows: AccountRows) -> None:
            with rows.repo.transaction():
                if claiming:
                    rows.claim(record.id, key, dead, now)
                rows.set_password_hash(record.id, hashed)

        await self.db.call(lambda repo: store(AccountRows(repo)))
        return claiming

    async def sign_in(self, name: str, password: str) -> str:
        """The account of `name` and `password` (`BadCredentials`): an unknown name, an
        account without a password and a wrong password take the same time. A hash made
        with older parameters is replaced."""
        key = name_key(name)
        found = await self.db.call(lambda repo: AccountRows(repo).account_named(key))
        stored = None if found is None else found.password_hash
        if not await self._verify(stored, password) or found is None or stored is None:
            raise BadCredentials
        if self.hasher.needs_rehash(stored):
            fresh = await asyncio.to_thread(self.hasher.hash, password)
            await self.db.call(lambda repo: AccountRows(repo).set_password_hash(found.id, fresh))
        return found.id

    async def _verify(self, stored: str | None, password: str) -> bool:
        return await asyncio.to_thread(self.hasher.verify, stored, password)

    # ---- another guest on the device ---------------------------------------------------

    async def merge_offer(self, guest_secret: str, account_id: str) -> GuestOffer | None:
        """The guest of this device's guest cookie, if it is not the account and has
        unranked matches to bring."""
        found = await self.db.call(
            lambda repo: AccountRows(repo).guest_by_secret(secret_hash(guest_secret))
        )
        if found is None or found.id == account_id:
            return None
        count = await self.db.call(lambda repo: AccountRows(repo).unranked_seats(found.id))
        return GuestOffer(found.id, found.name, count) if count else None

    async def merge(self, guest_secret: str, account_id: str) -> int:
        """Move the guest's unranked matches to the account (ratings never move)."""
        offer = await self.merge_offer(guest_secret, account_id)
        if offer is None:
            return 0
        return await self.db.call(
            lambda repo: AccountRows(repo).move_unranked_seats(offer.id, account_id)
        )


__all__ = ["Accounts", "BadCredentials", "GuestOffer", "NameTaken", "SessionView"]
