"""Every statement the repository runs, built once per dialect with bound parameters.

Why: SQLAlchemy caches the compiled SQL of a statement, but building a statement object and
its cache key on each call costs several times the SQLite write itself; built once, a call
only binds its values. Inserts and updates take their columns from the parameters passed.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache
from typing import Any

from sqlalchemy import BindParameter, bindparam, func, null, select
from sqlalchemy.dialects import postgresql, sqlite

from .schema import counters, games, matches, room_owners, rooms, shots


@dataclass(frozen=True)
class Statements:
    owner_epoch: Any  # locks the owner row: FOR UPDATE (SQLite: the write lock is held)
    read_epoch: Any
    add_owner: Any
    set_owner: Any
    prune_owners: Any
    match_room: Any
    last_match: Any
    counter: Any
    set_counter: Any
    add_match: Any
    set_match: Any
    finish_match: Any
    add_game: Any
    shot_n: Any
    last_shot: Any
    add_shot: Any
    save_room: Any
    delete_room: Any
    room: Any
    rooms: Any
    match: Any
    recent: Any
    recent_status: Any
    recent_room: Any
    games: Any
    shots: Any
    shot: Any


@cache
def statements(dialect: str) -> Statements:
    insert = postgresql.insert if dialect == "postgresql" else sqlite.insert
    room_id: BindParameter[str] = bindparam("key_room")
    match_id: BindParameter[int] = bindparam("key_match")
    save = insert(rooms)
    game_count = (
        select(func.count()).select_from(games).where(games.c.match_id == matches.c.id)
    ).scalar_subquery()
    shot_count = (
        select(func.count()).select_from(shots).where(shots.c.match_id == matches.c.id)
    ).scalar_subquery()
    with_counts = select(matches, game_count.label("games"), shot_count.label("shots"))
    newest = (matches.c.started_at.desc(), matches.c.id.desc())
    listed = [c for c in shots.c if c.name != "motion"]
    of_match = shots.c.match_id == match_id
    set_counter = insert(counters)
    return Statements(
        owner_epoch=select(room_owners.c.epoch, room_owners.c.owner)
        .where(room_owners.c.room_id == room_id)
        .with_for_update(),
        read_epoch=select(room_owners.c.epoch).where(room_owners.c.room_id == room_id),
        add_owner=insert(room_owners).on_conflict_do_nothing(index_elements=["room_id"]),
        set_owner=room_owners.update().where(room_owners.c.room_id == room_id),
        prune_owners=room_owners.delete().where(
            room_owners.c.claimed_at < bindparam("key_before"),
            room_owners.c.room_id.not_in(select(rooms.c.room_id)),
        ),
        match_room=select(matches.c.room_id).where(matches.c.id == match_id),
        last_match=select(func.coalesce(func.max(matches.c.id), 0)),
        counter=select(counters.c.value)
        .where(counters.c.name == bindparam("key_name"))
        .with_for_update(),
        set_counter=set_counter.on_conflict_do_update(
            index_elements=["name"], set_={"value": set_counter.excluded.value}
        ),
        add_match=insert(matches).on_conflict_do_nothing(index_elements=["id"]),
        set_match=matches.update().where(matches.c.id == match_id),
        finish_match=matches.update().where(
            matches.c.id == match_id, matches.c.status == "playing"
        ),
        add_game=insert(games).on_conflict_do_nothing(index_elements=["match_id", "n"]),
        shot_n=select(shots.c.n).where(of_match, shots.c.room_shot == bindparam("key_shot")),
        last_shot=select(func.coalesce(func.max(shots.c.n), 0)).where(of_match),
        add_shot=insert(shots).on_conflict_do_nothing(index_elements=["match_id", "room_shot"]),
        save_room=save.on_conflict_do_update(
            index_elements=["room_id"],
            set_={"snapshot": save.excluded.snapshot, "updated_at": save.excluded.updated_at},
        ),
        delete_room=rooms.delete().where(rooms.c.room_id == room_id),
        room=select(rooms).where(rooms.c.room_id == room_id),
        rooms=select(rooms).order_by(rooms.c.updated_at),
        match=with_counts.where(matches.c.id == match_id),
        recent=with_counts.order_by(*newest).limit(bindparam("key_limit")),
        recent_status=with_counts.where(matches.c.status == bindparam("key_status"))
        .order_by(*newest)
        .limit(bindparam("key_limit")),
        recent_room=with_counts.where(matches.c.room_id == room_id)
        .order_by(*newest)
        .limit(bindparam("key_limit")),
        games=select(games).where(games.c.match_id == match_id).order_by(games.c.n),
        shots=select(*listed, null().label("motion")).where(of_match).order_by(shots.c.n),
        shot=select(*listed, shots.c.motion).where(of_match, shots.c.n == bindparam("key_n")),
    )
