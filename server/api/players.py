"""Players over HTTP: the profile made on a first visit (a secret in an HttpOnly cookie),
renaming it, anyone's public profile, the leaderboard per game, and Play now (join the
queue, long-poll for the room, leave, take the computer instead). See docs/protocol.md,
"Players, Play now and the leaderboard"."""

from __future__ import annotations

from typing import Annotated, Any

from fastapi import APIRouter, Depends, HTTPException, Path, Query, Request, Response

from server.accounts import NameTaken
from server.ladder import PlayerData, matched
from server.players import (
    RANKED_KINDS,
    BadName,
    KindRating,
    Player,
    Waiting,
    check_name,
    default_name,
    new_player_id,
    new_secret,
    seat_key,
    secret_hash,
    standings,
)
from server.protocol.limits import MAX_NAME
from server.rooms import ActionError
from server.store.drills import DrillTry

from .csrf import same_site
from .deps import (
    AccountsDep,
    ClientId,
    Matchmaking,
    Players,
    Quotas,
    Registry,
    Secret,
    SettingsDep,
)
from .identity import COOKIE, DEVICE_COOKIE, SESSION_COOKIE, device_id
from .player_schemas import Leaderboard, PlayNow, PlayNowStatus, Profile, Rename
from .schemas import ErrorResponse

# A write another site's page makes is refused (403 `cross_site`, `csrf.py`).
router = APIRouter(tags=["players"], dependencies=[Depends(same_site)])
COOKIE_AGE = 400 * 86_400  # s: the longest browsers keep a cookie
RECENT = 20  # ranked matches on a profile
LEADERBOARD_MAX = 500
_ERRORS: dict[int | str, dict[str, Any]] = {
    401: {"model": ErrorResponse},
    404: {"model": ErrorResponse},
    409: {"model": ErrorResponse},
    429: {"model": ErrorResponse},
}
GameParam = Annotated[str, Path(pattern="^(eight_ball|nine_ball|snooker|three_cushion)$")]


async def known_player(secret: Secret, data: Players) -> Player:
    """The player of the cookie, else 401 `no_player` (the page makes one on load)."""
    player = None if secret is None else await data.by_secret(secret_hash(secret))
    if player is None:
        raise HTTPException(
            401, {"code": "no_player", "message": "No profile yet: load the page first."}
        )
    return player


Me = Annotated[Player, Depends(known_player)]


def _set_cookie(
    response: Response, request: Request, secret: str, secure: bool, name: str = COOKIE
) -> None:
    response.set_cookie(
        name,
        secret,
        max_age=COOKIE_AGE,
        path="/",
        httponly=True,
        samesite="lax",
        secure=secure or request.url.scheme == "https",
    )


def drill_bests(tries: list[DrillTry]) -> dict[str, int]:
    """The personal bests of the drills: position drills tried, made and the longest run
    made in a row; ghost 9-ball racks played, cleared and the most balls pocketed in one;
    line-up runs played and the most balls pocketed in one."""
    positions = [t.score == 1 for t in tries if t.kind == "position" and t.done]
    run = best = 0
    for made in positions:
        run = run + 1 if made else 0
        best = max(best, run)
    ghosts = [t for t in tries if t.kind == "ghost" and t.score is not None]
    lineups = [t for t in tries if t.kind == "lineup" and t.score is not None]
    return {
        "tries": len(positions),
        "made": sum(positions),
        "best_run": best,
        "ghost_racks": sum(t.tries for t in ghosts),
        "ghost_cleared": sum(t.cleared for t in ghosts),
        "ghost_best": max((t.score or 0 for t in ghosts), default=0),
        "lineup_runs": sum(t.tries for t in lineups),
        "lineup_best": max((t.score or 0 for t in lineups), default=0),
    }


async def _profile(data: PlayerData, player: Player, now: float, me: bool) -> dict[str, Any]:
    ratings = await data.ratings(player.id, RANKED_KINDS)
    recent = await data.recent(player.id, RECENT)
    played = await data.matches(player.id, RECENT)
    accuracy = await data.accuracies({m.match_id: m.seat for m in played})
    drills = drill_bests(await data.drills(player.id))
    shown = []
    for r in recent:
        seat = r.players.index(player.id)
        before = r.before[seat] if r.before else None
        after = r.after[seat] if r.after else None
        shown.append(
            {
                "room_id": r.room_id,
                "match_id": r.match_id,
                "game": r.kind,
                "opponent": r.names[1 - seat],
                "opponent_id": r.players[1 - seat],
                "won": r.winner == seat,
                "rating_before": None if before is None else before[0],
                "rating_after": None if after is None else after[0],
                "finished_at": r.finished_at,
                "replay": None if r.match_id is None else f"/m/{r.match_id}",
            }
        )
    return {
        "id": player.id,
        "name": player.name,
        "me": me,
        "account": player.account,
        "ratings": [_rating_view(k, now) for k in ratings.values()],
        "recent": shown,
        "drills": drills,
        "matches": [
            {
                "match_id": m.match_id,
                "room_id": m.room_id,
                "game": m.kind,
                "players": m.players,
                "seat": m.seat,
                "status": m.status,
                "score": m.score,
                "won": None if m.winner is None else m.winner == m.seat,
                "started_at": m.started_at,
                "finished_at": m.finished_at,
                "replay": f"/m/{m.match_id}" if m.shots > 0 else None,
                "accuracy": accuracy.get(m.match_id),
            }
            for m in played
        ],
    }


def _rating_view(k: KindRating, now: float) -> dict[str, Any]:
    current = k.at(now)
    return {
        "game": k.kind,
        "rating": round(current.rating, 2),
        "rd": round(current.rd, 2),
        "conservative": round(current.conservative, 2),
        "provisional": k.provisional(now),
        "games": k.games,
        "wins": k.wins,
    }


@router.get("/api/players/me", response_model=Profile, responses=_ERRORS)
async def my_profile(
    request: Request,
    response: Response,
    data: Players,
    settings: SettingsDep,
    quotas: Quotas,
    client: ClientId,
    registry: Registry,
    secret: Secret,
) -> dict[str, Any]:
    """The asking player's profile. On a first visit (no valid cookie) a player is made and
    its secret set in the `pool_player` cookie (HttpOnly, SameSite=Lax), and a browser
    without a `pool_device` cookie is given one then (kept across its profiles, for Play
    now). 429: this address made too many profiles within the rate window."""
    now = registry.clock.wall()
    player = None if secret is None else await data.by_secret(secret_hash(secret))
    if player is None:
        quotas.enforce("player", client)
        player_id = new_player_id()
        player = Player(player_id, default_name(player_id), now)
        secret = new_secret()
        await data.add(player, secret_hash(secret))
        secure = (settings.public_url or "").startswith("https:")
        _set_cookie(response, request, secret, secure)
        if device_id(request) is None:  # a browser keeps its device across its profiles
            _set_cookie(response, request, new_secret(), secure, DEVICE_COOKIE)
        if SESSION_COOKIE in request.cookies:  # a session ended (signed out elsewhere, idle)
            response.delete_cookie(SESSION_COOKIE, path="/", httponly=True, samesite="lax")
    return await _profile(data, player, now, me=True)


@router.patch("/api/players/me", response_model=Profile, responses=_ERRORS)
async def rename(
    body: Rename, me: Me, data: Players, accounts: AccountsDep, registry: Registry
) -> dict[str, Any]:
    """A new display name (the rule of a seat's name; 422 `bad_name`). Rooms already
    joined keep the name they were joined with. An account's name is its own: 409
    `name_taken` when another account has it (after NFKC and casefolding)."""
    try:
        name = check_name(body.name, MAX_NAME)
    except BadName as exc:
        raise HTTPException(422, {"code": "bad_name", "message": str(exc)}) from None
    if me.account:
        try:
            await accounts.rename(me.id, name)
        except NameTaken:
            detail = {"code": "name_taken", "message": "Another account has this name."}
            raise HTTPException(409, detail) from None
    else:
        await data.rename(me.id, name)
    renamed = Player(me.id, name, me.created_at, me.account)
    return await _profile(data, renamed, registry.clock.wall(), me=True)


@router.get("/api/players/{player_id}", response_model=Profile, responses=_ERRORS)
async def player_profile(
    player_id: Annotated[str, Path(max_length=32)], data: Players, registry: Registry
) -> dict[str, Any]:
    """Anyone's public profile: name, ratings, recent ranked matches (404 `unknown_player`)."""
    player = await data.get(player_id)
    if player is None:
        raise HTTPException(404, {"code": "unknown_player", "message": "No such player."})
    return await _profile(data, player, registry.clock.wall(), me=False)


@router.get("/api/leaderboard/{game}", response_model=Leaderboard)
async def leaderboard(
    game: GameParam,
    data: Players,
    registry: Registry,
    limit: Annotated[int, Query(ge=1, le=LEADERBOARD_MAX)] = 100,
) -> dict[str, Any]:
    """Ranked players by rating - 2 RD (highest first), provisional players apart."""
    rows = await data.rated(game)
    names = {k.player_id: name for k, name in rows}
    ranked, provisional = standings((k for k, _ in rows), registry.clock.wall())

    def view(standing: Any) -> dict[str, Any]:
        return {
            "rank": standing.rank,
            "player_id": standing.player_id,
            "name": names[standing.player_id],
            "rating": round(standing.rating, 2),
            "games": standing.games,
        }

    return {
        "game": game,
        "ranked": [view(s) for s in ranked[:limit]],
        "provisional": [view(s) for s in provisional[:limit]],
    }


def remember_seat(
    data: PlayerData, secret: str | None, room_id: str, seat: int, now: float
) -> None:
    """A seat taken through `POST /api/rooms/{room_id}/join`: with a profile's cookie
    (`secret`), the match played there goes on the profile (queued; the join does not wait
    for it)."""
    if secret is not None:
        data.seated(secret_hash(secret), room_id, seat, now)


# ---- Play now -----------------------------------------------------------------------------


@router.post("/api/playnow", response_model=PlayNowStatus, responses=_ERRORS)
async def play_now(
    request: Request,
    body: PlayNow,
    me: Me,
    secret: Secret,
    data: Players,
    registry: Registry,
    matches: Matchmaking,
    quotas: Quotas,
    client: ClientId,
    settings: SettingsDep,
) -> dict[str, Any]:
    """Queue for a ranked game of `game` at the player's rating; paired at once when
    someone suitable waits (`matched`), else `waiting`: long-poll `GET /api/playnow`.
    Pressing again keeps the player's one place. Never paired with a player asking from
    the same address or the same browser (`pool_device`). 429: too many joins and leaves."""
    quotas.enforce("queue", me.id)
    assert secret is not None  # `me` was found by it
    rating = (await data.ratings(me.id, (body.game,)))[body.game]
    # Read before queueing: `join` itself is one step on the loop (one entry a player).
    entry = Waiting(
        me.id,
        me.name,
        body.game,
        rating.at(registry.clock.wall()).rating,
        matches.now(),
        seat_key(secret),
        address=None if settings.playnow_same_address else client,
        device=device_id(request),
    )
    try:
        await matches.enqueue(entry)
    except ActionError as exc:
        raise HTTPException(503, {"code": exc.code, "message": exc.message}) from None
    return await matches.status(me.id)


@router.get("/api/playnow", response_model=PlayNowStatus, responses=_ERRORS)
async def play_now_status(
    me: Me,
    matches: Matchmaking,
    settings: SettingsDep,
    wait: Annotated[float, Query(ge=0, le=60, allow_inf_nan=False)] = 0.0,
) -> dict[str, Any]:
    """Where the player stands; with `wait`, held open (up to `wait` s, at most
    `POOL_PLAYNOW_POLL`) until that changes: paired, offered the computer, or out."""
    await matches.wait(me.id, min(wait, settings.playnow_poll))
    return await matches.status(me.id)


@router.delete("/api/playnow", response_model=PlayNowStatus, responses=_ERRORS)
async def leave_queue(me: Me, matches: Matchmaking, quotas: Quotas) -> dict[str, Any]:
    """Leave the queue (nothing happens if not in it)."""
    quotas.enforce("queue", me.id)
    await matches.dequeue(me.id)
    return await matches.status(me.id)


@router.post("/api/playnow/computer", response_model=PlayNowStatus, responses=_ERRORS)
async def play_the_computer(me: Me, secret: Secret, matches: Matchmaking) -> dict[str, Any]:
    """Take the offered computer (409 `not_offered` before the wait is over): a private
    room against the level nearest the player's rating, not rated."""
    assert secret is not None  # `me` was found by it
    try:
        assignment, level = await matches.take_computer(me.id, seat_key(secret))
    except ActionError as exc:
        code = 409 if exc.code == "not_offered" else 503
        raise HTTPException(code, {"code": exc.code, "message": exc.message}) from None
    return {**matched(assignment), "computer": level}
