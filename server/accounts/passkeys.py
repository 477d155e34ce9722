"""The WebAuthn ceremonies, through py_webauthn (no CBOR or COSE of our own): options for
the browser's `navigator.credentials.create()` / `.get()` and the checks of its answers.
Passkeys are discoverable credentials (resident keys), so signing in needs no name: the
authenticator offers the accounts it holds for this site."""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Any

from webauthn import (
    generate_authentication_options,
    generate_registration_options,
    options_to_json,
    verify_authentication_response,
    verify_registration_response,
)
from webauthn.helpers import base64url_to_bytes, bytes_to_base64url
from webauthn.helpers.exceptions import WebAuthnException
from webauthn.helpers.structs import (
    AuthenticatorSelectionCriteria,
    PublicKeyCredentialDescriptor,
    ResidentKeyRequirement,
    UserVerificationRequirement,
)

RP_NAME = "Pool online"
TIMEOUT_MS = 120_000


class PasskeyError(ValueError):
    """The browser's answer does not verify (wrong origin, challenge, signature, ...)."""


@dataclass(frozen=True)
class RelyingParty:
    """Who the passkeys are for: `id` is the host name, `origin` the page's origin."""

    id: str
    origin: str


@dataclass(frozen=True)
class NewPasskey:
    credential_id: str  # base64url
    public_key: bytes
    sign_count: int


def registration_options(
    rp: RelyingParty, player_id: str, name: str, existing: list[str]
) -> tuple[dict[str, Any], bytes]:
    """(the options as JSON for the page, the challenge to keep)."""
    options = generate_registration_options(
        rp_id=rp.id,
        rp_name=RP_NAME,
        user_id=player_id.encode(),
        user_name=name,
        user_display_name=name,
        timeout=TIMEOUT_MS,
        authenticator_selection=AuthenticatorSelectionCriteria(
            resident_key=ResidentKeyRequirement.REQUIRED,
            user_verification=UserVerificationRequirement.PREFERRED,
        ),
        exclude_credentials=[
            PublicKeyCredentialDescriptor(id=base64url_to_bytes(c)) for c in existing
        ],
    )
    return json.loads(options_to_json(options)), options.challenge


def verify_registration(
    rp: RelyingParty, credential: dict[str, Any], challenge: bytes
) -> NewPasskey:
    try:
        verified = verify_registration_response(
            credential=credential,
            expected_challenge=challenge,
            expected_rp_id=rp.id,
            expected_origin=rp.origin,
        )
    except (WebAuthnException, ValueError, KeyError, TypeError) as exc:
        raise PasskeyError(str(exc)) from None
    return NewPasskey(
        bytes_to_base64url(verified.credential_id),
        verified.credential_public_key,
        verified.sign_count,
    )


def authentication_options(rp: RelyingParty) -> tuple[dict[str, Any], bytes]:
    """Options without `allowCredentials`: any passkey of this site may answer."""
    options = generate_authentication_options(
        rp_id=rp.id, timeout=TIMEOUT_MS, user_verification=UserVerificationRequirement.PREFERRED
    )
    return json.loads(options_to_json(options)), options.challenge


def credential_id(credential: dict[str, Any]) -> str | None:
    """The credential's id as the page sent it (base64url), if it looks like one."""
    found = credential.get("rawId", credential.get("id"))
    return found if isinstance(found, str) and 0 < len(found) <= 1400 else None


def verify_authentication(
    rp: RelyingParty,
    credential: dict[str, Any],
    challenge: bytes,
    public_key: bytes,
    sign_count: int,
) -> int:
    """The authenticator's new signature count, once the answer verifies."""
    try:
        verified = verify_authentication_response(
            credential=credential,
            expected_challenge=challenge,
            expected_rp_id=rp.id,
            expected_origin=rp.origin,
            credential_public_key=public_key,
            credential_current_sign_count=sign_count,
        )
    except (WebAuthnException, ValueError, KeyError, TypeError) as exc:
        raise PasskeyError(str(exc)) from None
    return verified.new_sign_count
