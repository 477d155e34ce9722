"""A room as a synchronous state machine: seats, the match and what is shown now.

No I/O and no clocks of its own (times are passed in): `LiveRoom` drives it from the event
loop and sends what it returns. Every refused action raises `ActionError` and changes
nothing; rules refusals keep the rules' own codes.
"""

from __future__ import annotations

import functools
import secrets
from collections import deque
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any, Literal

from server.codec import encode
from server.engine import BallSet, Shot, ShotResult, Table
from server.protocol import BallRow, StreamFrames, Timed, frame_rows
from server.protocol.limits import MAX_NAME
from server.protocol.outbound import (
    ChatLine,
    ChatMessage,
    ClockInfo,
    DrillInfo,
    GraceInfo,
    PlayerInfo,
    RoomInfo,
    ShotInfo,
    StateMessage,
)
from server.rules import GAME_KINDS, Match, Outcome, RulesError
from server.rules.kinds import rules_for

from .drills import RACKED, DrillScore, DrillSetup, DrillTries, after_shot, scored, set_up
from .errors import ActionError
from .tokens import hash_token, new_token, token_matches

Phase = Literal["waiting", "aiming", "rolling", "over"]
WAITING: Phase = "waiting"
AIMING: Phase = "aiming"
ROLLING: Phase = "rolling"
OVER: Phase = "over"
CHAT_KEPT = 50  # chat lines a (re)connecting member is shown
FIRST_BREAK_FACTOR = 4.0  # the room's first break: this many shot clocks to play it


@functools.lru_cache(maxsize=8)
def _table_dict(table: Table) -> dict[str, Any]:
    """A table never changes: its geometry goes into every `state`, built once. (The
    encoder only reads it.)"""
    return table.to_dict()


@functools.lru_cache(maxsize=8)
def _table_json(table: Table) -> str:
    return encode(_table_dict(table))


@dataclass
class Seat:
    name: str
    token_hash: str
    connected: bool = False
    seen: bool = False  # connected at least once (a player who leaves has been here)


@dataclass
class ShotInProgress:
    """The shot being streamed: what a member joining now is shown."""

    id: int
    seat: int
    match_before: dict[str, Any]  # the match as it was when the shot was struck
    before: list[BallRow]  # the table when it was struck
    ticks: int = 0  # last tick of the shot (0 while it is being simulated)
    tick: int = 0  # the tick shown now
    outcome: Outcome | None = None
    shown: tuple[StreamFrames, int] | None = None  # the frame shown now
    # The stroke meant when it differs from the one struck (the computer's plan before its
    # arm's error), kept with the shot for the analysis; None: the one struck
    intended: Shot | None = None

    @property
    def balls(self) -> list[BallRow]:
        """The table as shown now (rows built on demand: only a joining member needs them)."""
        if self.shown is None:
            return self.before
        frames, j = self.shown
        return frames.rows(j)


@dataclass
class Room:
    """One table: `game` kind, seats (one for practice), the match once every seat is taken."""

    room_id: str
    game: str
    race_to: int = 1
    shot_clock: float = 60.0
    seed: int = field(default_factory=lambda: secrets.randbelow(2**31))
    created_at: float = 0.0
    listed: bool = True  # False: a private table, reached only through its link
    computer: dict[int, str] = field(default_factory=dict)  # seat -> level it plays at
    setup: DrillSetup | None = None  # a drill: the table it starts from (practice only)
    drill: DrillScore = field(default_factory=DrillScore)  # how the drill's try went so far
    tries: DrillTries = field(default_factory=DrillTries)  # and the room's tries of it
    seats: list[Seat | None] = field(init=False)
    match: Match | None = field(default=None, init=False)
    shot: ShotInProgress | None = field(default=None, init=False)
    shots_played: int = field(default=0, init=False)
    # Shots each seat has struck: a ranked match is rated only once every seat has had a
    # visit at the table (a concession before that is a farm, not a game).
    shots_by_seat: list[int] = field(init=False)
    rematch_votes: set[int] = field(default_factory=set, init=False)
    spectators: int = field(default=0, init=False)
    # Both players left and none came back: the match stopped, nobody won it.
    abandoned: bool = field(default=False, init=False)
    chat: deque[ChatLine] = field(default_factory=lambda: deque(maxlen=CHAT_KEPT), init=False)

    def __post_init__(self) -> None:
        if self.game not in GAME_KINDS:
            raise ValueError(f"unknown game {self.game!r}")
        self.seats = [None] if self.practice else [None, None]
        self.shots_by_seat = [0] * len(self.seats)
        if self.practice:
            self.shot_clock = 0.0
            self.race_to = 1

    # ---- seats -----------------------------------------------------------------------

    @property
    def practice(self) -> bool:
        return rules_for(self.game).seats == 1

    def join(self, name: str, token: str | None = None) -> tuple[int, str]:
        """Take the first free seat; returns (seat, token). Starts the match when full.
        `token`: the seat's token when the caller made it (a player's own, see
        `server.players.seat_token`); else a new random one."""
        clean = name.strip()
        if not 1 <= len(clean) <= MAX_NAME or not clean.isprintable():
            raise ActionError("bad_name", f"A name is 1 to {MAX_NAME} printable characters.")
        free = next((i for i, s in enumerate(self.seats) if s is None), None)
        if free is None:
            raise ActionError(
                "room_full",
                "Both seats are taken."
                if len(self.seats) == 2
                else "This practice table has one seat and it is taken.",
            )
        token = token or new_token()
        self.seats[free] = Seat(clean, hash_token(token))
        self._start_when_full()
        return free, token

    def _start_when_full(self) -> None:
        if all(self.seats):
            self.match = Match(self.game, self.player_names(), race_to=self.race_to, seed=self.seed)
            if self.setup is not None:
                set_up(self.match, self.setup)

    def add_computer(self, level: str) -> int:
        """Seat the computer (always connected: it never leaves) at `level`."""
        if self.practice:
            raise ActionError("not_allowed", "Practice is played alone.")
        free = [i for i, s in enumerate(self.seats) if s is None]
        if not free:
            raise ActionError("room_full", "Both seats are taken.")
        seat = free[-1]  # the last seat: a person joining takes the first and breaks
        self.seats[seat] = Seat(f"Computer ({level})", hash_token(new_token()), connected=True)
        self.computer[seat] = level
        self._start_when_full()
        return seat

    def seat_of(self, token: str) -> int | None:
        """The seat this token opens, or None. Compares every seat in constant time."""
        found = None
        for i, seat in enumerate(self.seats):
            if seat is not None and token_matches(token, seat.token_hash):
                found = i
        return found

    def player_names(self) -> tuple[str, ...]:
        return tuple(s.name for s in self.seats if s is not None)

    def name_of(self, seat: int | None) -> str:
        if seat is None:
            return "spectator"
        s = self.seats[seat]
        return s.name if s else f"seat {seat}"

    def players_info(self) -> list[PlayerInfo]:
        return [
            PlayerInfo(seat=i, name=s.name, connected=s.connected)
            for i, s in enumerate(self.seats)
            if s is not None
        ]

    # ---- what is shown ----------------------------------------------------------------

    @property
    def phase(self) -> Phase:
        if self.match is None:
            return WAITING
        if self.shot is not None:
            return ROLLING
        if self.match.over or self.abandoned:
            return OVER
        return AIMING

    @property
    def status(self) -> Literal["waiting", "playing", "finished"]:
        phase = self.phase
        if phase == WAITING:
            return "waiting"
        return "finished" if phase == OVER else "playing"

    def acting_seat(self) -> int | None:
        """Who the match waits for: the seat of a pending decision, else the turn."""
        if self.phase != AIMING or self.match is None:
            return None
        decision = self.match.game.decision
        return decision.seat if decision is not None else self.match.game.turn

    def summary(self) -> dict[str, Any]:
        return {
            "room_id": self.room_id,
            "game": self.game,
            "race_to": self.race_to,
            "shot_clock": self.shot_clock,
            "seats": len(self.seats),
            "status": self.status,
            "players": [s.name if s else None for s in self.seats],
            "spectators": self.spectators,
            "score": self.shown_score(),
            "created_at": self.created_at,
        }

    def shown_score(self) -> list[int] | None:
        """The score as the members see it: while a shot is shown, the one before it."""
        if self.match is None:
            return None
        if self.shot is not None:
            return list(self.shot.match_before["score"])
        return list(self.match.score)

    def resting_balls(self) -> list[BallRow]:
        if self.match is None:
            return []
        balls: BallSet = self.match.game.balls
        return frame_rows(balls.ids, balls.positions, balls.cels(), balls.on_table)

    def table_dict(self) -> dict[str, Any]:
        return _table_dict(self._table())

    def table_json(self) -> str:
        """`table_dict` as JSON, encoded once per table."""
        return _table_json(self._table())

    def _table(self) -> Table:
        return self.match.game.table if self.match else rules_for(self.game).table()

    def room_info(self) -> RoomInfo:
        return RoomInfo(
            room_id=self.room_id,
            game=self.game,
            race_to=self.race_to,
            shot_clock=self.shot_clock,
            seats=len(self.seats),
            status=self.status,
            players=self.players_info(),
            spectators=self.spectators,
            rematch=sorted(self.rematch_votes),
            abandoned=self.abandoned,
            drill=None if self.setup is None else drill_info(self.setup, self.drill, self.tries),
        )

    def say(self, seat: int | None, text: str, at: float) -> ChatMessage:
        """A chat line: kept for members who connect later, returned to be broadcast."""
        name = self.name_of(seat)
        self.chat.append(ChatLine(seat=seat, name=name, text=text, at=at))
        return ChatMessage(seat=seat, name=name, text=text, at=at)

    def clock_limit(self) -> float:
        """Seconds on the shot clock for the seat to act now: the room's first break gets
        `FIRST_BREAK_FACTOR` times as long, so a newcomer reading the table (and the hint)
        for the first time does not lose the break to a clock that started when the
        opponent sat down."""
        match = self.match
        first_break = match is not None and match.game.breaking and self.shots_played == 0
        return self.shot_clock * (FIRST_BREAK_FACTOR if first_break else 1.0)

    def abandon(self) -> None:
        """Nobody came back: the match stops where it is, without a winner."""
        self.abandoned = True
        self.rematch_votes.clear()

    def state_message(
        self, clock: ClockInfo | None, grace: list[GraceInfo], chat: bool = False
    ) -> StateMessage:
        """The `state` message (its `seq` set by the sender); with `chat`, the last lines
        of the chat (for a member who just connected or asked for a `sync`)."""
        shot = self.shot
        match_state: dict[str, Any] | None
        if shot is not None:
            match_state = shot.match_before
            balls = shot.balls
            shot_info = ShotInfo(id=shot.id, seat=shot.seat, tick=shot.tick, ticks=shot.ticks)
        else:
            match_state = self.match.public_state() if self.match else None
            balls = self.resting_balls()
            shot_info = None
        return StateMessage(
            room=self.room_info(),
            phase=self.phase,
            table=self.table_dict(),
            balls=balls,
            shot=shot_info,
            clock=clock,
            grace=grace,
            match=match_state,
            chat=list(self.chat) if chat else None,
        )

    # ---- actions ----------------------------------------------------------------------

    def _require_player(self, seat: int | None) -> tuple[Match, int]:
        if seat is None:
            raise ActionError("spectator", "Spectators can watch and chat, not play.")
        if self.match is None:
            raise ActionError("not_started", "Waiting for the other player to join.")
        if self.shot is not None:
            raise ActionError("balls_moving", "Wait until the balls stop.")
        if self.abandoned:
            raise ActionError("abandoned", "Both players left; this match was abandoned.")
        if self.match.over:
            raise ActionError("match_over", "The match is over; ask for a rematch.")
        return self.match, seat

    def begin_shot(self, seat: int | None, intended: Shot | None = None) -> tuple[int, BallSet]:
        """Check that `seat` may shoot now and mark the table busy; returns (shot id, balls).
        `intended`: the stroke meant, when it differs from the one struck (the computer's).

        The caller simulates the shot from the returned copy, then calls `apply_shot`.
        """
        match, seat = self._require_player(seat)
        with _rules():
            match.game.check_shot(seat)
        self.shots_played += 1
        self.shots_by_seat[seat] += 1
        self.rematch_votes.clear()
        self.shot = ShotInProgress(
            self.shots_played, seat, match.public_state(), self.resting_balls(), intended=intended
        )
        return self.shots_played, match.game.balls.copy()

    def cue_ball(self) -> int:
        """The ball the striker strikes (`Game.cue_ball`: carom's white or yellow)."""
        return self.match.game.cue_ball if self.match else 0

    def apply_shot(self, result: ShotResult) -> Outcome:
        """Judge the simulated shot now (the stream shows it afterwards)."""
        assert self.shot is not None and self.match is not None
        before = self.match.game.balls
        with _rules():
            outcome = self.match.apply(self.shot.seat, result)
        self.shot.ticks = len(result.frames)
        self.shot.outcome = outcome
        if self.setup is not None:
            was, self.drill = self.drill, scored(self.setup, self.drill, before, result, outcome)
            self.tries = self.tries.after(was, self.drill)
        return outcome

    def abort_shot(self) -> None:
        self.shot = None

    def show(self, timed: Timed, frames: StreamFrames) -> None:
        """The stream has reached `timed`: remember what a member joining now must see."""
        if self.shot is None:
            return
        self.shot.shown = (frames, timed.frame)
        self.shot.tick = timed.tick

    def end_shot(self) -> None:
        self.shot = None
        if self.setup is not None and self.match is not None:
            after_shot(self.match, self.setup, self.drill)
        self.after_outcome()

    def after_outcome(self) -> None:
        """Rack the next game when one ended and the match goes on."""
        match = self.match
        if match is not None and match.game.over and not match.over:
            match.next_game()

    def place_cue(self, seat: int | None, x: float, y: float) -> None:
        match, seat = self._require_player(seat)
        with _rules():
            match.game.place_cue(seat, x, y)

    def call_pocket(self, seat: int | None, pocket: int) -> None:
        match, seat = self._require_player(seat)
        with _rules():
            match.game.call_pocket(seat, pocket)

    def nominate(self, seat: int | None, ball: int) -> None:
        match, seat = self._require_player(seat)
        with _rules():
            match.game.nominate(seat, ball)

    def decide(self, seat: int | None, option: str, game: int | None = None) -> None:
        match, seat = self._require_player(seat)
        _check_game(match, game)
        with _rules():
            match.game.decide(seat, option)

    def push_out(self, seat: int | None) -> None:
        match, seat = self._require_player(seat)
        with _rules():
            match.game.declare_push_out(seat)

    def rerack(self, seat: int | None) -> None:
        match, seat = self._require_player(seat)
        if not self.practice:
            raise ActionError("not_practice", "Only a practice table can be racked again.")
        with _rules():
            match.game.rerack()
        if self.setup is not None and self.setup.kind in RACKED:  # another try of the drill
            self.tries = self.tries.next(self.drill)
            self.drill = DrillScore()
            set_up(match, self.setup)

    def check_aim(self, seat: int | None) -> None:
        match, seat = self._require_player(seat)
        if seat != self.acting_seat() and not self.practice:
            raise ActionError("not_your_turn", f"It is {self.name_of(match.game.turn)}'s turn.")

    def concede(self, seat: int | None, game: int | None = None) -> Outcome:
        match, seat = self._require_player(seat)
        _check_game(match, game)
        if self.practice:
            raise ActionError("not_allowed", "There is nothing to concede in practice.")
        with _rules():
            return match.concede(seat)

    def timeout(self, seat: int) -> Outcome:
        match, seat = self._require_player(seat)
        with _rules():
            return match.timeout(seat)

    def forfeit(self, seat: int, reason: str) -> Outcome:
        """`seat` loses the current frame: a player who stayed away forfeits the frame, not
        the match."""
        match, seat = self._require_player(seat)
        with _rules():
            return match.forfeit_game(seat, reason)

    def vote_rematch(self, seat: int | None) -> bool:
        """Record a rematch request; True when every seat asked and a new match began."""
        if seat is None:
            raise ActionError("spectator", "Spectators can watch and chat, not play.")
        if self.abandoned:
            raise ActionError("abandoned", "This match was abandoned; open a new table.")
        if self.match is None or not self.match.over:
            raise ActionError("match_not_over", "A rematch can start once the match is over.")
        self.rematch_votes.add(seat)
        if len(self.rematch_votes) < len(self.seats):
            return False
        self.match.rematch()
        self.rematch_votes.clear()
        return True


def drill_info(setup: DrillSetup, score: DrillScore, tries: DrillTries) -> DrillInfo:
    """A drill as `state.room.drill` shows it."""
    position = setup.kind == "position"
    return DrillInfo(
        kind=setup.kind,
        match=setup.match_id,
        n=setup.n,
        par=setup.par,
        made=(score.score == 1) if position and score.done else None,
        score=score.score,
        done=score.done,
        won=score.won,
        balls=score.lineup_balls() if setup.kind == "lineup" else None,
        tries=tries.tries,
        best=tries.best,
    )


def _check_game(match: Match, game: int | None) -> None:
    """Refuse an action meant for another game of the match (`game` None: not named)."""
    if game is not None and game != match.games_played + 1:
        raise ActionError(
            "stale_action",
            f"That was meant for game {game}; game {match.games_played + 1} is being played.",
        )


@contextmanager
def _rules() -> Iterator[None]:
    try:
        yield
    except RulesError as exc:
        raise ActionError(exc.code, exc.message) from None
