"""Bodies of the accounts' routes: passwords, signing in, the lists of sessions and
passkeys, the passkey ceremonies and the merge question."""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, Field

from server.protocol.limits import MAX_NAME

from .inputs import StrictBody

PASSWORD_FIELD_MAX = 1024  # the policy's own bound (256) answers longer ones in words


class SetPassword(StrictBody):
    password: str = Field(max_length=PASSWORD_FIELD_MAX)
    old_password: str | None = Field(default=None, max_length=PASSWORD_FIELD_MAX)


class Login(StrictBody):
    name: str = Field(min_length=1, max_length=4 * MAX_NAME)
    password: str = Field(max_length=PASSWORD_FIELD_MAX)


class AccountState(BaseModel):
    name: str
    password: bool  # a password is set (changing it asks for the old one)


class SessionView(BaseModel):
    id: str  # names the session in this list (a prefix of its hash), opens nothing
    label: str  # "Firefox on Linux"
    created_at: float
    last_seen: float
    current: bool  # the session asking


class Sessions(BaseModel):
    sessions: list[SessionView]  # most recently seen first


class PasskeyView(BaseModel):
    id: str  # the credential id (base64url)
    label: str  # the device it was added on
    created_at: float
    last_used: float | None


class Passkeys(BaseModel):
    passkeys: list[PasskeyView]


class PasskeyAnswer(StrictBody):
    """What `navigator.credentials.create()` / `.get()` gave, as JSON (`toJSON()`)."""

    credential: dict[str, Any]


class CeremonyOptions(BaseModel):
    """The `publicKey` options for `navigator.credentials.create()` / `.get()`, as JSON
    (binary fields base64url)."""

    options: dict[str, Any]


class Guest(BaseModel):
    id: str
    name: str
    matches: int  # unranked matches it would bring


class MergeOffer(BaseModel):
    guest: Guest | None  # None: nothing to ask


class MergeAnswer(StrictBody):
    merge: bool


class Merged(BaseModel):
    moved: int  # matches now on the account
