"""A player's Glicko-2 rating in one game kind, over time: provisional while the deviation
is high, the deviation growing while the player does not play, and the update of a ranked
match's two players.

Rating period: a ranked match is rated when it ends, as a period of its own (lichess does
the same); between games the deviation grows by Glickman's step 6 once per
`RATING_PERIOD` (fractions count), up to the starting 350.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field, replace

from .glicko2 import Rating, idle, rate

RANKED_KINDS: tuple[str, ...] = ("eight_ball", "nine_ball", "snooker", "three_cushion")
RATING_PERIOD = 86_400.0  # s: one day, the period of the deviation's growth
PROVISIONAL_RD = 110.0  # a rating is provisional while its deviation is above this
# The farm rule (docs/rules.md, "Ratings"): a ranked result moves a player's rating only
# when the opponent had at least this many rated games in the kind before it (about the
# games a new player needs before the deviation falls below `PROVISIONAL_RD`).
COUNTED_GAMES = 10

# The computer's levels on the same scale. Estimated from the ladder measured in docs/ai.md
# (8-ball, the levels as they were when these were set: amateur beat beginner 81.7 % of 60 games,
# club beat amateur 83.3 % of 60, pro beat club 85.0 % of 40), each share turned into a
# rating gap by the logistic curve Glicko uses (400 log10(p / (1 - p)): 260, 279 and 301
# points), anchored with the amateur at 1500, the rating every new player starts at.
# Re-measure the ladder when the levels change, and these with it.
COMPUTER_RATINGS: dict[str, float] = {
    "beginner": 1240.0,
    "amateur": 1500.0,
    "club": 1779.0,
    "pro": 2080.0,
}


@dataclass(frozen=True)
class KindRating:
    """`player_id`'s rating in `kind` as of `rated_at` (wall time of the last rated game;
    None: never rated), with the games and wins rated so far."""

    player_id: str
    kind: str
    rating: Rating = field(default_factory=Rating)
    games: int = 0
    wins: int = 0
    rated_at: float | None = None

    def at(self, now: float) -> Rating:
        """The rating as of `now`: the deviation grown over the periods since the last game."""
        if self.rated_at is None:
            return self.rating
        return idle(self.rating, max(0.0, now - self.rated_at) / RATING_PERIOD)

    def provisional(self, now: float) -> bool:
        return self.at(now).rd > PROVISIONAL_RD


def rate_match(
    first: KindRating, second: KindRating, first_won: bool, now: float
) -> tuple[KindRating, KindRating]:
    """Both players after a ranked match: each rated against the other's rating as it was
    before the match, a rating period of one game."""
    a, b = first.at(now), second.at(now)
    score = 1.0 if first_won else 0.0
    new_a = rate(a, [(b, score)])
    new_b = rate(b, [(a, 1.0 - score)])
    return (
        replace(
            first, rating=new_a, games=first.games + 1, wins=first.wins + first_won, rated_at=now
        ),
        replace(
            second,
            rating=new_b,
            games=second.games + 1,
            wins=second.wins + (not first_won),
            rated_at=now,
        ),
    )


def counts(opponent: KindRating) -> bool:
    """Whether a result against `opponent` may move the other player's rating: only once
    the opponent has `COUNTED_GAMES` rated games (fresh profiles are free to make)."""
    return opponent.games >= COUNTED_GAMES


def rate_ranked(
    first: KindRating, second: KindRating, first_won: bool, now: float
) -> tuple[KindRating, KindRating]:
    """A ranked match as the ladder rates it: `rate_match` (Glicko-2 untouched), except that
    a player whose opponent does not `count` yet keeps the rating (rating, deviation and
    volatility as of `now`); the game and the win are counted either way. So a profile made
    to lose moves nobody, and a newcomer moves only against players with a record."""
    new_first, new_second = rate_match(first, second, first_won, now)
    if not counts(second):
        new_first = replace(new_first, rating=first.at(now))
    if not counts(first):
        new_second = replace(new_second, rating=second.at(now))
    return new_first, new_second


def nearest_level(rating: float) -> str:
    """The computer's level whose rating is nearest `rating` (the weaker one on a tie)."""
    return min(COMPUTER_RATINGS, key=lambda level: abs(COMPUTER_RATINGS[level] - rating))


@dataclass(frozen=True)
class Standing:
    rank: int | None  # None: provisional, listed apart
    player_id: str
    rating: float  # conservative: rating - 2 RD
    games: int


def standings(ratings: Iterable[KindRating], now: float) -> tuple[list[Standing], list[Standing]]:
    """The leaderboard: established players ranked by their conservative rating (rating -
    2 RD, as of `now`), highest first; provisional ones apart, in the same order, unranked.
    Ties go to more games, then the player id (a stable order)."""
    rows = [(r, r.at(now)) for r in ratings if r.games > 0]
    rows.sort(key=lambda row: (-row[1].conservative, -row[0].games, row[0].player_id))
    ranked: list[Standing] = []
    provisional: list[Standing] = []
    for kind_rating, current in rows:
        if current.rd > PROVISIONAL_RD:
            provisional.append(
                Standing(None, kind_rating.player_id, current.conservative, kind_rating.games)
            )
        else:
            ranked.append(
                Standing(
                    len(ranked) + 1, kind_rating.player_id, current.conservative, kind_rating.games
                )
            )
    return ranked, provisional
