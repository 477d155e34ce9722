"""Bodies of the players' routes (profiles, the leaderboard, Play now)."""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel

from .inputs import Name, StrictBody

RankedGame = Literal["eight_ball", "nine_ball", "snooker", "three_cushion"]


class Rename(StrictBody):
    name: Name


class RatingView(BaseModel):
    game: RankedGame
    rating: float  # Glicko-2 rating as of now
    rd: float  # its deviation, grown with the days since the last ranked game
    conservative: float  # rating - 2 rd: what the leaderboard shows
    provisional: bool  # rd above 110: too few recent games to rank
    games: int  # ranked games
    wins: int


class RecentMatch(BaseModel):
    room_id: str
    match_id: int | None  # the match in the history (None if it was not recorded)
    game: RankedGame
    opponent: str
    opponent_id: str
    won: bool
    rating_before: float | None
    rating_after: float | None
    finished_at: float | None
    replay: str | None  # the page replaying it: /m/{match_id}


class PlayedMatch(BaseModel):
    match_id: int
    room_id: str
    game: str
    players: list[str]  # names, seat order
    seat: int  # the player's
    status: Literal["playing", "finished", "abandoned"]
    score: list[int]
    won: bool | None  # None: no winner (yet)
    started_at: float
    finished_at: float | None
    replay: str | None  # /m/{match_id}, once a shot was played
    accuracy: float | None = None  # 0-100 in the match's analysis; None: not analysed


class DrillBests(BaseModel):
    tries: int  # position drills played ("play this position again")
    made: int  # of them, a ball pocketed without a foul on the first shot
    best_run: int  # the most made in a row
    ghost_racks: int = 0  # ghost 9-ball racks played
    ghost_cleared: int = 0  # of them, cleared (the ghost beaten)
    ghost_best: int = 0  # the most balls pocketed in one
    lineup_runs: int = 0  # progressive line-up runs played
    lineup_best: int = 0  # the most balls pocketed in one


class Profile(BaseModel):
    id: str
    name: str
    me: bool  # the asking player's own profile
    account: bool  # kept by a passkey or password (signs in anywhere); false: a guest
    ratings: list[RatingView]  # one per ranked game
    recent: list[RecentMatch]  # ranked matches, newest first
    drills: DrillBests | None = None  # personal bests of the drills
    matches: list[PlayedMatch]  # every match in the player's seats, newest first


class Standing(BaseModel):
    rank: int | None  # None for a provisional player
    player_id: str
    name: str
    rating: float  # rating - 2 rd
    games: int


class Leaderboard(BaseModel):
    game: RankedGame
    ranked: list[Standing]
    provisional: list[Standing]


class PlayNow(StrictBody):
    game: RankedGame


class AssignedSeat(BaseModel):
    room_id: str
    seat: int
    token: str  # the seat token: keep it to connect (as from /join)
    url: str  # the table's page
    opponent: str
    ranked: bool  # false: against the computer


class PlayNowStatus(BaseModel):
    status: Literal["idle", "waiting", "matched"]
    game: RankedGame | None = None
    rating: float | None = None  # waiting: the rating paired on
    waited: float | None = None  # waiting: seconds in the queue
    window: float | None = None  # waiting: the rating difference accepted now
    computer: str | None = None  # the computer's level offered (or taken)
    room: AssignedSeat | None = None  # matched: where to play
