"""Passwords: the policy (a minimum length, not one of the most common passwords, not the
name) and argon2id hashes with `argon2-cffi`'s recommended parameters (RFC 9106's
second choice), rehashed at sign-in when those change. The stored form is the library's
PHC string, e.g. `$argon2id$v=19$m=65536,t=3,p=4$<salt>$<hash>`: never the password.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

from argon2 import PasswordHasher
from argon2.exceptions import InvalidHashError, VerificationError, VerifyMismatchError

from .names import name_key

MIN_LENGTH = 8  # NIST SP 800-63B's minimum for a password the user chose
MAX_LENGTH = 256  # bounds the hashing work a request can ask for
COMMON_FILE = Path(__file__).with_name("common_passwords.txt")


class WeakPassword(ValueError):
    """A password the policy refuses; `code` says why (short, long, common, name)."""

    def __init__(self, code: str, message: str) -> None:
        super().__init__(message)
        self.code = code


@cache
def common_passwords() -> frozenset[str]:
    """The shipped list of the most used passwords, casefolded."""
    lines = COMMON_FILE.read_text(encoding="utf-8").splitlines()
    return frozenset(s.strip().casefold() for s in lines if s.strip() and not s.startswith("#"))


def check_password(password: str, name: str) -> None:
    """Refuse (`WeakPassword`) a password too short or long, too common, or the name."""
    if len(password) < MIN_LENGTH:
        raise WeakPassword("short", f"A password has at least {MIN_LENGTH} characters.")
    if len(password) > MAX_LENGTH:
        raise WeakPassword("long", f"A password has at most {MAX_LENGTH} characters.")
    if password.casefold() in common_passwords():
        raise WeakPassword("common", "That password is one of the most used: pick another.")
    if name_key(password) == name_key(name):
        raise WeakPassword("name", "The password cannot be the name.")


class Hasher:
    """argon2id with the library's defaults. Each hash or check takes tens of ms of CPU
    and 64 MiB: callers run it off the event loop."""

    def __init__(self, hasher: PasswordHasher | None = None) -> None:
        self._hasher = hasher or PasswordHasher()
        self._dummy: str | None = None

    @property
    def dummy(self) -> str:
        """Checked against when a name has no password, so that it is answered as slowly
        as a wrong password (no telling which names exist). Made on first use."""
        if self._dummy is None:
            self._dummy = self._hasher.hash("not a password anyone has")
        return self._dummy

    def hash(self, password: str) -> str:
        return self._hasher.hash(password)

    def verify(self, stored: str | None, password: str) -> bool:
        """Does `password` match `stored` (None: check the dummy, answer False)."""
        try:
            return self._hasher.verify(stored or self.dummy, password) and stored is not None
        except (VerifyMismatchError, VerificationError, InvalidHashError):
            return False

    def needs_rehash(self, stored: str) -> bool:
        return self._hasher.check_needs_rehash(stored)
