"""Accounts over HTTP: setting or changing the password (a guest setting one becomes an
account), signing in with a name and password, signing out here or everywhere, the list
of signed-in sessions, and merging this device's other guest. Passkeys are in
`passkeys.py`. See docs/protocol.md, "Accounts"."""

from __future__ import annotations

from dataclasses import asdict
from typing import Annotated, Any

from fastapi import APIRouter, Depends, HTTPException, Path, Request, Response

from server.accounts import BadCredentials, NameTaken, WeakPassword, name_key
from server.players import Player

from .account_schemas import (
    AccountState,
    Login,
    MergeAnswer,
    Merged,
    MergeOffer,
    Sessions,
    SetPassword,
)
from .cookies import clear_cookie, set_cookie
from .csrf import same_site
from .deps import (
    AccountsDep,
    ClientId,
    Registry,
    Session,
    SettingsDep,
    SignInLimitsDep,
)
from .identity import COOKIE, SESSION_COOKIE, cookie_secret
from .players import Me
from .schemas import ErrorResponse

router = APIRouter(tags=["accounts"], dependencies=[Depends(same_site)])
_ERRORS: dict[int | str, dict[str, Any]] = {
    code: {"model": ErrorResponse} for code in (401, 403, 404, 409, 422, 429)
}
BAD_CREDENTIALS = {"code": "bad_credentials", "message": "Wrong name or password."}
RATE_LIMITED = {"code": "rate_limited", "message": "Too many attempts: wait a few minutes."}
NAME_TAKEN = {"code": "name_taken", "message": "An account has this name: rename first."}


async def signed_in(me: Me, session: Session) -> Player:
    """The account of this device's live session, else 401 `not_signed_in`."""
    if session is None or not me.account:
        raise HTTPException(401, {"code": "not_signed_in", "message": "Sign in first."})
    return me


Account = Annotated[Player, Depends(signed_in)]


async def sign_in_here(
    request: Request,
    response: Response,
    accounts: AccountsDep,
    settings: SettingsDep,
    player_id: str,
    now: float,
) -> None:
    """A new session for this device (its old one, if any, ends): the cookie rotates."""
    session = await accounts.start_session(
        player_id,
        request.headers.get("user-agent"),
        now,
        replacing=cookie_secret(request, SESSION_COOKIE),
    )
    set_cookie(response, request, settings, SESSION_COOKIE, session)


@router.post("/api/account/password", status_code=204, responses=_ERRORS)
async def set_password(
    body: SetPassword,
    request: Request,
    response: Response,
    me: Me,
    accounts: AccountsDep,
    limits: SignInLimitsDep,
    client: ClientId,
    settings: SettingsDep,
    registry: Registry,
) -> None:
    """Set a password (a guest becomes an account, signed in on this device; 409
    `name_taken` when another account has its name), or change it (`old_password`
    required: 401 `bad_credentials`; every other session ends). 422 `weak_password`."""
    record = await accounts.account(me.id)
    assert record is not None  # `me` was found
    key, now = name_key(me.name), registry.clock.wall()
    checked = record.password_hash is not None  # a change: the old password is checked
    if checked and not limits.reserve(client, key):
        raise HTTPException(429, RATE_LIMITED)
    failed = False
    try:
        async with limits.turn():
            claimed = await accounts.set_password(record, body.password, body.old_password, now)
    except BadCredentials:
        failed = True
        raise HTTPException(401, BAD_CREDENTIALS) from None
    except WeakPassword as exc:
        detail = {"code": "weak_password", "reason": exc.code, "message": str(exc)}
        raise HTTPException(422, detail) from None
    except NameTaken:
        raise HTTPException(409, NAME_TAKEN) from None
    finally:
        if checked:
            limits.release(client, key, failed)
    if claimed:
        clear_cookie(response, request, settings, COOKIE)  # the guest cookie opens nothing now
    else:
        await accounts.end_all(me.id)
    await sign_in_here(request, response, accounts, settings, me.id, now)


@router.post("/api/login", status_code=204, responses=_ERRORS)
async def login(
    body: Login,
    request: Request,
    response: Response,
    accounts: AccountsDep,
    limits: SignInLimitsDep,
    client: ClientId,
    settings: SettingsDep,
    registry: Registry,
) -> None:
    """Sign in with a name and password: 204 and a new `pool_session` cookie; 401
    `bad_credentials` (an unknown name and a wrong password alike); 429 `rate_limited`
    after too many failures from this address or at this name."""
    key = name_key(body.name)
    if not limits.reserve(client, key):
        raise HTTPException(429, RATE_LIMITED)
    failed = False
    try:
        async with limits.turn():
            player_id = await accounts.sign_in(body.name, body.password)
    except BadCredentials:
        failed = True
        raise HTTPException(401, BAD_CREDENTIALS) from None
    finally:
        limits.release(client, key, failed)
    await sign_in_here(request, response, accounts, settings, player_id, registry.clock.wall())


@router.post("/api/logout", status_code=204)
async def logout(
    request: Request, response: Response, accounts: AccountsDep, settings: SettingsDep
) -> None:
    """Sign out this device (its session ends; nothing happens without one)."""
    session = cookie_secret(request, SESSION_COOKIE)
    if session is not None:
        await accounts.end_session(session)
    clear_cookie(response, request, settings, SESSION_COOKIE)


@router.post("/api/logout/everywhere", status_code=204, responses=_ERRORS)
async def logout_everywhere(
    me: Account,
    request: Request,
    response: Response,
    accounts: AccountsDep,
    settings: SettingsDep,
) -> None:
    """Every session of the account ends, this one too (a stolen cookie with them)."""
    await accounts.end_all(me.id)
    clear_cookie(response, request, settings, SESSION_COOKIE)


@router.get("/api/account", response_model=AccountState, responses=_ERRORS)
async def account_state(me: Account, accounts: AccountsDep) -> dict[str, Any]:
    """The signed-in account: its name and whether a password is set."""
    record = await accounts.account(me.id)
    return {"name": me.name, "password": record is not None and record.password_hash is not None}


@router.get("/api/account/sessions", response_model=Sessions, responses=_ERRORS)
async def sessions(
    me: Account, session: Session, accounts: AccountsDep, registry: Registry
) -> dict[str, Any]:
    """The account's signed-in devices, most recently seen first."""
    views = await accounts.sessions(me.id, registry.clock.wall(), session)
    return {"sessions": [{**asdict(v), "id": v.handle} for v in views]}


@router.delete("/api/account/sessions/{session_id}", status_code=204, responses=_ERRORS)
async def revoke_session(
    session_id: Annotated[str, Path(max_length=64)], me: Account, accounts: AccountsDep
) -> None:
    """End one session of the list (404 `unknown_session`)."""
    if not await accounts.revoke(me.id, session_id):
        raise HTTPException(404, {"code": "unknown_session", "message": "No such session."})


@router.get("/api/account/merge", response_model=MergeOffer, responses=_ERRORS)
async def merge_offer(me: Account, request: Request, accounts: AccountsDep) -> dict[str, Any]:
    """This device's other guest (its `pool_player` cookie), when it has unranked matches
    the account could take: the page asks the player."""
    guest = cookie_secret(request)
    offer = None if guest is None else await accounts.merge_offer(guest, me.id)
    return {"guest": None if offer is None else asdict(offer)}


@router.post("/api/account/merge", response_model=Merged, responses=_ERRORS)
async def merge(
    body: MergeAnswer,
    me: Account,
    request: Request,
    response: Response,
    accounts: AccountsDep,
    settings: SettingsDep,
) -> dict[str, Any]:
    """The answer: `merge: true` moves the guest's unranked matches to the account
    (ratings and ranked results never move). Either way the device forgets the guest."""
    guest = cookie_secret(request)
    moved = await accounts.merge(guest, me.id) if body.merge and guest is not None else 0
    clear_cookie(response, request, settings, COOKIE)
    return {"moved": moved}
