"""Ranked tables made for friends, over HTTP: the refusals of a table that cannot be ranked
and of a join without the player's agreement. The tables themselves are
`server.ladder.RankedTables`: rated only when both players agree.

The creator agrees by opening the table with `ranked: true`; each player who sits down
agrees again with `ranked: true` on their join (the join dialog says the rating will
change). A join without that agreement, or without a profile, is refused and seats nobody.
One process only: in cluster mode a ranked table is refused.
"""

from __future__ import annotations

from fastapi import HTTPException

from server.cluster import Cluster
from server.ladder import PlayerData
from server.players import Player, secret_hash
from server.rules import PRACTICE_KINDS

NEEDS_AGREEMENT = {
    "code": "ranked_needs_agreement",
    "message": "This table is ranked: join with ranked true (and a profile) to agree that "
    "your rating will change.",
}


def check_create(
    game: str, opponent: str | None, cluster: Cluster | None, player: Player | None
) -> None:
    """Refuse a ranked table that cannot be one (422 `bad_ranked`), one asked for without a
    profile (401 `no_player`) or in cluster mode (409 `ranked_unavailable`)."""
    if game in PRACTICE_KINDS or opponent is not None:
        raise HTTPException(
            422,
            {
                "code": "bad_ranked",
                "message": "Only 8-ball and 9-ball between two players can be ranked.",
            },
        )
    if player is None:
        raise HTTPException(
            401, {"code": "no_player", "message": "No profile yet: load the page first."}
        )
    if cluster is not None:
        raise HTTPException(
            409,
            {"code": "ranked_unavailable", "message": "Ranked tables are made by Play now here."},
        )


async def asking_player(secret: str | None, data: PlayerData) -> Player | None:
    """The player of the request's cookie `secret`, if any."""
    if secret is None:
        return None
    return await data.by_secret(secret_hash(secret))
