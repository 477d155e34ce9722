"""Passkey ceremonies with their state in the store: each options request keeps its
challenge under the hash of a random ceremony id (the page holds the id in a short-lived
HttpOnly cookie), answered at most once and within `CEREMONY_TTL`; in the database, so any
process of a cluster can take the answer."""

from __future__ import annotations

import secrets
from dataclasses import dataclass
from typing import Any

from server.players import secret_hash
from server.store import Database
from server.store.accounts import AccountRows, CeremonyRecord, PasskeyRecord

from .passkeys import (
    NewPasskey,
    PasskeyError,
    RelyingParty,
    authentication_options,
    credential_id,
    registration_options,
    verify_authentication,
    verify_registration,
)
from .sessions import device_label

CEREMONY_TTL = 300.0  # s


@dataclass(frozen=True)
class PasskeyView:
    id: str  # the credential id (base64url): public, names it in the list
    label: str
    created_at: float
    last_used: float | None


class Ceremonies:
    def __init__(self, db: Database) -> None:
        self.db = db

    async def _begin(self, challenge: bytes, player_id: str | None, now: float) -> str:
        ceremony = secrets.token_urlsafe(32)
        record = CeremonyRecord(challenge, player_id, now + CEREMONY_TTL)
        await self.db.call(
            lambda repo: AccountRows(repo).add_ceremony(secret_hash(ceremony), record, now)
        )
        return ceremony

    async def _take(self, ceremony: str | None, now: float) -> CeremonyRecord:
        if ceremony is None:
            raise PasskeyError("no ceremony")
        found = await self.db.call(
            lambda repo: AccountRows(repo).take_ceremony(secret_hash(ceremony))
        )
        if found is None or found.expires_at < now:
            raise PasskeyError("no such ceremony, or too late")
        return found

    async def passkeys(self, player_id: str) -> list[PasskeyView]:
        rows = await self.db.call(lambda repo: AccountRows(repo).passkeys_of(player_id))
        return [PasskeyView(p.credential_id, p.label, p.created_at, p.last_used) for p in rows]

    async def delete(self, player_id: str, passkey: str) -> bool:
        done = await self.db.call(lambda repo: AccountRows(repo).delete_passkey(player_id, passkey))
        return done > 0

    # ---- adding a passkey -------------------------------------------------------------

    async def begin_registration(
        self, rp: RelyingParty, player_id: str, name: str, now: float
    ) -> tuple[dict[str, Any], str]:
        """(the options for `navigator.credentials.create()`, the ceremony id)."""
        existing = [p.id for p in await self.passkeys(player_id)]
        options, challenge = registration_options(rp, player_id, name, existing)
        return options, await self._begin(challenge, player_id, now)

    async def check_registration(
        self,
        rp: RelyingParty,
        ceremony: str | None,
        player_id: str,
        answer: dict[str, Any],
        now: float,
    ) -> NewPasskey:
        """The new passkey, verified against the ceremony this player began."""
        found = await self._take(ceremony, now)
        if found.player_id != player_id:
            raise PasskeyError("the ceremony is another player's")
        return verify_registration(rp, answer, found.challenge)

    async def store(
        self, player_id: str, passkey: NewPasskey, user_agent: str | None, now: float
    ) -> None:
        record = PasskeyRecord(
            passkey.credential_id,
            player_id,
            passkey.public_key,
            passkey.sign_count,
            device_label(user_agent),
            now,
            None,
        )
        await self.db.call(lambda repo: AccountRows(repo).add_passkey(record))

    # ---- signing in with one ----------------------------------------------------------

    async def begin_sign_in(self, rp: RelyingParty, now: float) -> tuple[dict[str, Any], str]:
        options, challenge = authentication_options(rp)
        return options, await self._begin(challenge, None, now)

    async def sign_in(
        self, rp: RelyingParty, ceremony: str | None, answer: dict[str, Any], now: float
    ) -> str:
        """The account whose passkey answered (`PasskeyError`)."""
        found = await self._take(ceremony, now)
        wanted = credential_id(answer)
        key = None
        if wanted is not None:
            key = await self.db.call(lambda repo: AccountRows(repo).passkey(wanted))
        if key is None:
            raise PasskeyError("unknown passkey")
        count = verify_authentication(rp, answer, found.challenge, key.public_key, key.sign_count)
        await self.db.call(
            lambda repo: AccountRows(repo).used_passkey(key.credential_id, count, now)
        )
        return key.player_id
