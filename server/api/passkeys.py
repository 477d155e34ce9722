"""Passkeys over HTTP: the WebAuthn ceremonies (options, then the browser's answer) for
adding a passkey (a guest adding one becomes an account) and for signing in with one
(discoverable: no name typed), and the account's list of passkeys. The relying party is
the host of `POOL_PUBLIC_URL` when set, else of the request. See docs/protocol.md,
"Accounts"."""

from __future__ import annotations

from dataclasses import asdict
from typing import Annotated, Any
from urllib.parse import urlsplit

from fastapi import APIRouter, Depends, HTTPException, Path, Request, Response

from server.accounts import NameTaken, PasskeyError, RelyingParty
from server.config import Settings

from .account_schemas import CeremonyOptions, PasskeyAnswer, Passkeys
from .accounts import BAD_CREDENTIALS, NAME_TAKEN, RATE_LIMITED, Account, sign_in_here
from .cookies import clear_cookie, set_cookie
from .csrf import same_site
from .deps import (
    AccountsDep,
    CeremoniesDep,
    ClientId,
    Registry,
    SettingsDep,
    SignInLimitsDep,
)
from .identity import COOKIE, cookie_secret
from .players import Me
from .schemas import ErrorResponse

router = APIRouter(tags=["accounts"], dependencies=[Depends(same_site)])
_ERRORS: dict[int | str, dict[str, Any]] = {
    code: {"model": ErrorResponse} for code in (400, 401, 403, 404, 409, 429)
}
CEREMONY_COOKIE = "pool_ceremony"
CEREMONY_PATH = "/api/passkeys"
CEREMONY_AGE = 300  # s, as the ceremony's record


def relying_party(request: Request, settings: Settings) -> RelyingParty:
    """Who the passkeys are for: the public address's host, else the request's."""
    if settings.public_url is not None:
        parts = urlsplit(settings.public_url)
        return RelyingParty(parts.hostname or "", f"{parts.scheme}://{parts.netloc}")
    host = request.headers.get("host", "")
    return RelyingParty(urlsplit(f"//{host}").hostname or "", f"{request.url.scheme}://{host}")


def _keep_ceremony(request: Request, response: Response, settings: Settings, cid: str) -> None:
    """The ceremony's id, for the answer only: `SameSite=Strict`, this path only."""
    set_cookie(
        response,
        request,
        settings,
        CEREMONY_COOKIE,
        cid,
        path=CEREMONY_PATH,
        max_age=CEREMONY_AGE,
        samesite="strict",
    )


@router.post("/api/passkeys/register/options", response_model=CeremonyOptions, responses=_ERRORS)
async def registration_options(
    request: Request,
    response: Response,
    me: Me,
    accounts: AccountsDep,
    ceremonies: CeremoniesDep,
    settings: SettingsDep,
    registry: Registry,
) -> dict[str, Any]:
    """Options for `navigator.credentials.create()` (a discoverable credential). A guest
    whose name another account has: 409 `name_taken` (rename first)."""
    if not me.account and not await accounts.name_free(me.id, me.name):
        raise HTTPException(409, NAME_TAKEN)
    rp = relying_party(request, settings)
    options, cid = await ceremonies.begin_registration(rp, me.id, me.name, registry.clock.wall())
    _keep_ceremony(request, response, settings, cid)
    return {"options": options}


@router.post("/api/passkeys/register", status_code=204, responses=_ERRORS)
async def register(
    body: PasskeyAnswer,
    request: Request,
    response: Response,
    me: Me,
    accounts: AccountsDep,
    ceremonies: CeremoniesDep,
    settings: SettingsDep,
    registry: Registry,
) -> None:
    """The browser's answer: the passkey is the player's (400 `passkey_refused` if it does
    not verify). A guest becomes an account, signed in on this device."""
    now, rp = registry.clock.wall(), relying_party(request, settings)
    cid = cookie_secret(request, CEREMONY_COOKIE)
    clear_cookie(response, request, settings, CEREMONY_COOKIE, CEREMONY_PATH)
    try:
        passkey = await ceremonies.check_registration(rp, cid, me.id, body.credential, now)
    except PasskeyError:
        raise HTTPException(400, _REFUSED) from None
    if not me.account:
        try:
            await accounts.claim(me.id, me.name, now)
        except NameTaken:
            raise HTTPException(409, NAME_TAKEN) from None
    await ceremonies.store(me.id, passkey, request.headers.get("user-agent"), now)
    if not me.account:
        clear_cookie(response, request, settings, COOKIE)
        await sign_in_here(request, response, accounts, settings, me.id, now)


_REFUSED = {"code": "passkey_refused", "message": "The passkey could not be verified."}


@router.post("/api/passkeys/login/options", response_model=CeremonyOptions, responses=_ERRORS)
async def sign_in_options(
    request: Request,
    response: Response,
    ceremonies: CeremoniesDep,
    limits: SignInLimitsDep,
    client: ClientId,
    settings: SettingsDep,
    registry: Registry,
) -> dict[str, Any]:
    """Options for `navigator.credentials.get()`: any passkey of this site may answer."""
    if not limits.allow_address(client):
        raise HTTPException(429, RATE_LIMITED)
    rp = relying_party(request, settings)
    options, cid = await ceremonies.begin_sign_in(rp, registry.clock.wall())
    _keep_ceremony(request, response, settings, cid)
    return {"options": options}


@router.post("/api/passkeys/login", status_code=204, responses=_ERRORS)
async def sign_in(
    body: PasskeyAnswer,
    request: Request,
    response: Response,
    accounts: AccountsDep,
    ceremonies: CeremoniesDep,
    settings: SettingsDep,
    registry: Registry,
) -> None:
    """The browser's answer: 204 and a new `pool_session` cookie, or 401
    `bad_credentials`."""
    now, rp = registry.clock.wall(), relying_party(request, settings)
    cid = cookie_secret(request, CEREMONY_COOKIE)
    clear_cookie(response, request, settings, CEREMONY_COOKIE, CEREMONY_PATH)
    try:
        player_id = await ceremonies.sign_in(rp, cid, body.credential, now)
    except PasskeyError:
        raise HTTPException(401, BAD_CREDENTIALS) from None
    await sign_in_here(request, response, accounts, settings, player_id, now)


@router.get("/api/passkeys", response_model=Passkeys, responses=_ERRORS)
async def passkeys(me: Account, ceremonies: CeremoniesDep) -> dict[str, Any]:
    return {"passkeys": [asdict(p) for p in await ceremonies.passkeys(me.id)]}


@router.delete("/api/passkeys/{passkey_id}", status_code=204, responses=_ERRORS)
async def delete_passkey(
    passkey_id: Annotated[str, Path(max_length=1400)],
    me: Account,
    accounts: AccountsDep,
    ceremonies: CeremoniesDep,
) -> None:
    """Remove a passkey (404 `unknown_passkey`); not the last way in (409 `last_way_in`:
    set a password first)."""
    record = await accounts.account(me.id)
    mine = [p.id for p in await ceremonies.passkeys(me.id)]
    if passkey_id not in mine:
        raise HTTPException(404, {"code": "unknown_passkey", "message": "No such passkey."})
    if len(mine) == 1 and (record is None or record.password_hash is None):
        detail = {"code": "last_way_in", "message": "Set a password before removing it."}
        raise HTTPException(409, detail)
    await ceremonies.delete(me.id, passkey_id)
