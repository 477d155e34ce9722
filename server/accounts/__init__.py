"""Accounts: a guest player kept across devices by passkeys (WebAuthn, through
py_webauthn) and/or a password (argon2id), server-side sessions, sign-in limits, and
merging a device's other guest. The account is the guest's own row in `players`, so its
id, name, ratings and history stay. Used by `server.api`; uses `server.store` and
`server.players`' hashing. See docs/protocol.md ("Accounts")."""

from .attempts import SignInLimits
from .ceremonies import Ceremonies, PasskeyView
from .names import name_key
from .passkeys import PasskeyError, RelyingParty
from .passwords import Hasher, WeakPassword, check_password
from .service import Accounts, BadCredentials, GuestOffer, NameTaken, SessionView

__all__ = [
    "Accounts",
    "BadCredentials",
    "Ceremonies",
    "GuestOffer",
    "Hasher",
    "NameTaken",
    "PasskeyError",
    "PasskeyView",
    "RelyingParty",
    "SessionView",
    "SignInLimits",
    "WeakPassword",
    "check_password",
    "name_key",
]
