"""`Game`: one rack of 8-ball, 9-ball or practice, in the spirit of python-chess's `Board`.

Pure: no I/O. It knows the players, whose turn it is, the table at rest and what is legal
now; `apply` takes the engine's `ShotResult` and returns an `Outcome`. Every action that is
not allowed raises `IllegalActionError` and changes nothing. What differs between kinds of
game is asked of the kind's strategy (`kinds.GameRules`), which judges a frozen `Position`
and returns a `Ruling`; this class owns the state and applies the ruling.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Annotated, Any

from pydantic import Field

from server.codec import from_data, to_dict
from server.engine import CUE, BallSet, ShotResult, Table, rack

from .carom_score import CaromScore
from .errors import IllegalActionError
from .fouls import label
from .kinds import rules_for
from .options import DEFAULT_OPTIONS, RuleOptions
from .outcome import BEHIND_HEAD_STRING, IN_D, Decision, Outcome
from .placement import can_place
from .position import Position
from .ruling import Ruling
from .shotfacts import shot_facts
from .snooker import scoreboard
from .snooker_score import FrameScore
from .stored import Groups, StoredTable
from .strategy import GameRules
from .words import and_list, capitalised

RERACK_SEED_STEP = 7919  # each rack of a game gets its own seed, reproducibly


def _racked(rules: GameRules, table: Table, seed: int, racks: int) -> BallSet:
    """The balls of rack number `racks` (from 0) of a game seeded `seed`."""
    return rack(rules.rack, table, seed=seed + RERACK_SEED_STEP * racks)


# Snooker's fields are not stored while empty, so a pool game's stored form is what it
# always was.
_UNLESS_SET = Field(exclude_if=lambda value: value is None)


@dataclass(eq=False)
class Game:
    """One rack (players call it a frame; `Frame` is the engine's per-tick snapshot).

    The fields are the whole state and its stored form (`to_dict`). A client shows `turn`,
    `ball_in_hand`, `groups`, `requires_call`, `called_pocket`, `decision`,
    `fouls_in_row`, `over` / `winner` / `reason`, `last_outcome` and `notice` (what the
    last decision, push out or re-rack did); `balls` is the table at rest (copy it before
    mutating it). `pending` names the pending decision's kind and `after_decision_bih` the
    ball in hand once it is taken. `score` is a snooker frame's points, break and ball on
    (`points` reads them); `replaced` / `replaced_on` the table and ball on before a miss,
    for the decision to replace the balls. `carom` is a three-cushion game's points,
    innings and runs (`points` reads them). Start a game with `Game.new`.
    """

    kind: str
    players: tuple[str, ...]
    table: StoredTable
    balls: BallSet
    seed: int = 0
    options: RuleOptions = DEFAULT_OPTIONS
    racks: int = 1
    breaker: int = 0
    turn: int = 0
    breaking: bool = False
    ball_in_hand: str | None = None
    groups: Groups | None = None
    called_pocket: int | None = None
    decision: Decision | None = None
    pending: str | None = None
    after_decision_bih: str | None = None
    fouls_in_row: list[int] = field(default_factory=list)
    push_out_available: bool = False
    push_out_declared: bool = False
    over: bool = False
    winner: int | None = None
    reason: str | None = None
    last_outcome: Outcome | None = None
    notice: str | None = None
    score: Annotated[FrameScore | None, _UNLESS_SET] = None
    replaced: Annotated[BallSet | None, _UNLESS_SET] = None
    replaced_on: Annotated[str | None, _UNLESS_SET] = None
    carom: Annotated[CaromScore | None, _UNLESS_SET] = None

    @classmethod
    def new(
        cls,
        kind: str,
        players: Sequence[str],
        breaker: int = 0,
        table: Table | None = None,
        seed: int = 0,
        options: RuleOptions = DEFAULT_OPTIONS,
    ) -> Game:
        """A game with its first rack set up, `breaker` to break (in practice, to play)."""
        rules = rules_for(kind)
        seated = tuple(players)
        if len(seated) != rules.seats:
            plural = "s" if rules.seats != 1 else ""
            raise ValueError(f"{kind} takes {rules.seats} player{plural}, not {len(seated)}")
        if breaker not in range(len(seated)):
            raise ValueError("breaker must be a seat (0 or 1)")
        table = table if table is not None else rules.table()
        game = cls(kind, seated, table, _racked(rules, table, seed, 0), seed, options)
        game._ready(breaker)
        return game

    @property
    def rules(self) -> GameRules:
        """The strategy of this kind of game."""
        return rules_for(self.kind)

    # --- racking -----------------------------------------------------------------------
    def _rack(self, breaker: int) -> None:
        """A fresh rack broken by `breaker`; each re-rack gets a new seed, reproducibly."""
        self.balls = _racked(self.rules, self.table, self.seed, self.racks)
        self.racks += 1
        self._ready(breaker)

    def _ready(self, breaker: int) -> None:
        """The state of a rack before its first shot."""
        rules = self.rules
        self.breaker = self.turn = breaker
        self.breaking = rules.breaks
        self.ball_in_hand = rules.opening_ball_in_hand
        self.groups = None
        self.called_pocket = None
        self.decision = None
        self.pending = None
        self.after_decision_bih = None
        self.fouls_in_row = [0] * len(self.players)
        self.push_out_available = False
        self.push_out_declared = False
        self.score = rules.new_score(len(self.players))
        self.carom = rules.new_carom(breaker)
        self.replaced, self.replaced_on = None, None

    @property
    def points(self) -> tuple[int, ...]:
        """Each seat's points in the frame (snooker), in the game (three-cushion); zeros
        for the pool games."""
        if self.carom is not None:
            return self.carom.points
        return self.score.points if self.score else (0,) * len(self.players)

    @property
    def cue_ball(self) -> int:
        """The ball the striker strikes: the cue ball (0), or in carom the striker's."""
        return self.rules.cue_ball(self.position())

    # --- what is legal now -------------------------------------------------------------
    def position(self) -> Position:
        """The frozen view of this game that the rules judge."""
        groups = self.groups
        return Position(
            players=self.players,
            table=self.table,
            options=self.options,
            on_table=tuple(self.balls.on_table_ids()),
            turn=self.turn,
            breaking=self.breaking,
            groups=tuple(groups[s] for s in range(len(self.players))) if groups else None,
            fouls_in_row=tuple(self.fouls_in_row),
            called_pocket=self.called_pocket,
            push_out_declared=self.push_out_declared,
            score=self.score,
            balls=self.balls,
            carom=self.carom,
        )

    @property
    def requires_call(self) -> bool:
        """The shooter must call a pocket before shooting (8-ball: on the 8)."""
        return not self.over and self.decision is None and self.rules.requires_call(self.position())

    def legal_targets(self) -> list[int]:
        """Balls the shooter may hit first now (empty in practice: anything goes)."""
        return self.rules.legal_targets(self.position())

    def _cue_on_table(self) -> bool:
        return bool(self.balls.on_table[self.balls.index(CUE)])

    def _check_seat(self, seat: int) -> None:
        if self.over:
            raise IllegalActionError("game_over", "The game is over.")
        if not isinstance(seat, int) or seat != self.turn:
            raise IllegalActionError("not_your_turn", "It is not your turn.")

    def _check_free(self, seat: int) -> None:
        self._check_seat(seat)
        if self.decision is not None:
            raise IllegalActionError(
                "decision_pending", f"Waiting for a decision: {self.decision.prompt}"
            )

    def check_shot(self, seat: int) -> None:
        """Raise `IllegalActionError` unless `seat` may shoot now."""
        self._check_free(seat)
        if not self._cue_on_table():
            raise IllegalActionError("cue_ball_off_table", "Place the cue ball before shooting.")
        if self.requires_call and self.called_pocket is None:
            raise IllegalActionError("call_required", "Call a pocket for the 8 before shooting.")

    def can_place_cue(self, x: float, y: float) -> bool:
        """True when the player with ball in hand may put the cue ball at (x, y)."""
        if self.over or self.decision is not None:
            return False
        return can_place(self.table, self.balls, self.ball_in_hand, x, y)

    def place_cue(self, seat: int, x: float, y: float) -> None:
        """Ball in hand: put the cue ball at (x, y); may be repeated before the shot."""
        self._check_free(seat)
        if self.ball_in_hand is None:
            raise IllegalActionError("no_ball_in_hand", "You do not have ball in hand.")
        if not can_place(self.table, self.balls, self.ball_in_hand, x, y):
            where = {BEHIND_HEAD_STRING: "behind the head string, ", IN_D: "in the D, "}.get(
                self.ball_in_hand or "", ""
            )
            raise IllegalActionError(
                "illegal_placement",
                f"The cue ball must go {where}on the table and clear of the other balls.",
            )
        self.balls = self.balls.with_ball(CUE, (float(x), float(y)))

    def call_pocket(self, seat: int, pocket: int) -> None:
        """8-ball: name the pocket (index into `table.pockets`) for the 8."""
        self._check_free(seat)
        if not self.requires_call:
            raise IllegalActionError(
                "call_not_needed", "Only the 8 is called, once your group is cleared."
            )
        if (
            not isinstance(pocket, int)
            or isinstance(pocket, bool)
            or not 0 <= pocket < len(self.table.pockets)
        ):
            raise IllegalActionError(
                "bad_pocket", f"Pick a pocket from 0 to {len(self.table.pockets) - 1}."
            )
        self.called_pocket = pocket

    def nominate(self, seat: int, ball: int) -> None:
        """Snooker: nominate the colour on, or the free ball (WPBSA 2.12 Nominated Ball)."""
        self._check_free(seat)
        choices = self.rules.nominations(self.position())
        if not choices:
            raise IllegalActionError("nomination_not_needed", "There is nothing to nominate now.")
        if isinstance(ball, bool) or ball not in choices or self.score is None:
            raise IllegalActionError("bad_nomination", "Nominate a ball that may be nominated.")
        self.score = replace(self.score, nominated=ball)

    def declare_push_out(self, seat: int) -> None:
        """9-ball: announce a push out for the shot right after the break (the rules offer
        it through a ruling's `push_out_next`)."""
        self._check_free(seat)
        if not self.push_out_available:
            raise IllegalActionError(
                "push_out_not_allowed", "A push out is only allowed on the shot after the break."
            )
        self.push_out_declared = True
        self.notice = f"{self.players[seat]} declares a push out."

    def decide(self, seat: int, option: str) -> None:
        """Answer the pending `decision` with one of its options."""
        if self.over:
            raise IllegalActionError("game_over", "The game is over.")
        if self.decision is None:
            raise IllegalActionError("no_decision", "There is nothing to decide.")
        if seat != self.decision.seat:
            raise IllegalActionError("not_your_turn", "It is not your decision.")
        if option not in self.decision.options:
            raise IllegalActionError(
                "bad_option", f"Choose one of: {', '.join(self.decision.options)}."
            )
        self._take_decision(seat, option)

    def _take_decision(self, seat: int, option: str) -> None:
        name, other = self.players[seat], 1 - seat
        pending, bih = self.pending, self.after_decision_bih
        self.decision, self.pending, self.after_decision_bih = None, None, None
        if option == "rerack":
            self._rack(seat)
            self.notice = f"{name} chose a re-rack and breaks."
        elif option == "rerack_opponent_breaks":
            self._rack(other)
            self.notice = f"{name} chose a re-rack; {self.players[other]} breaks again."
        elif option == "spot":
            spotted = self.rules.spot_choice
            self.balls = self.rules.respot(self.table, self.balls, spotted)
            self.turn, self.ball_in_hand = seat, bih
            self.notice = f"{name} spots {self.rules.ball_names(spotted)} and shoots."
        elif option == "accept":
            self.turn, self.ball_in_hand = seat, bih
            self.notice = f"{name} accepts the table and shoots."
        elif option == "shoot":
            self.turn, self.ball_in_hand = seat, None
            self.notice = f"{name} shoots after the push out."
        elif option == "pass":
            self.turn, self.ball_in_hand = other, None
            self.notice = f"{name} passes; {self.players[other]} must shoot."
        elif option in ("play", "free_ball", "play_again", "replace"):
            self._after_snooker_foul(seat, option, bih)
        else:  # pragma: no cover - options come from the rules
            raise AssertionError(f"unhandled option {option!r} for {pending}")

    def _after_snooker_foul(self, seat: int, option: str, bih: str | None) -> None:
        """Snooker: play on, with a free ball (WPBSA 3.12), or have the offender play again
        (3.13), from here or, after a miss, with the balls replaced (3.14); misses count
        toward three only from the balls replaced, so playing again from here ends the run."""
        name, other = self.players[seat], 1 - seat
        score = self.score
        assert score is not None
        if option == "replace" and self.replaced is not None:
            self.balls = self.replaced
            self.score = replace(score, on=self.replaced_on or score.on)
            bih = None
        self.replaced, self.replaced_on = None, None
        if option in ("play", "free_ball"):
            self.turn, self.ball_in_hand = seat, bih
            self.score = replace(score, free_ball=option == "free_ball")
            self.notice = (
                f"{name} takes a free ball." if option == "free_ball" else f"{name} plays."
            )
        else:
            if option == "play_again":
                misses = list(score.misses)
                misses[other] = 0
                self.score = replace(score, misses=tuple(misses))
            self.turn, self.ball_in_hand = other, bih
            how = "from where the balls were" if option == "replace" else "again"
            self.notice = f"{name} has {self.players[other]} play {how}."

    # --- shots -------------------------------------------------------------------------
    def apply(self, seat: int, result: ShotResult) -> Outcome:
        """Judge a simulated shot (after `check_shot` passed) and move the game on."""
        self.check_shot(seat)
        if list(result.final.ids) != list(self.balls.ids):
            raise IllegalActionError("bad_result", "The shot was not played on this table.")
        cue = self.cue_ball
        if result.events and result.events[0].ids[0] != cue:
            raise IllegalActionError("wrong_cue_ball", "That is not your cue ball.")
        facts = shot_facts(self.balls, result, cue, self.table.ball_radius)
        ruling = self.rules.judge(self.position(), facts)
        pocketed = facts.pocketed + ((CUE,) if facts.scratch and not facts.cue_off_table else ())
        if facts.pocketed:
            said = self.rules.ball_names(facts.pocketed)
            ruling.notes.insert(0, f"{self.players[seat]} pocketed {said}.")
        final = result.final.copy()
        self.replaced = self.balls.copy() if ruling.miss else None
        self.replaced_on = self.score.on if ruling.miss and self.score else None
        if ruling.spot:
            final = self.rules.respot(self.table, final, ruling.spot)
            verb = "is" if len(ruling.spot) == 1 else "are"
            ruling.notes.append(
                capitalised(f"{self.rules.ball_names(ruling.spot)} {verb} spotted.")
            )
        self.balls = final
        return self._settle(seat, ruling, pocketed)

    def timeout(self, seat: int) -> Outcome:
        """The shot clock ran out for `seat`: what that means is the rules' call.

        With a decision pending, time running out takes its first option instead (no foul).
        """
        if self.decision is not None and not self.over and seat == self.decision.seat:
            self._take_decision(seat, self.decision.options[0])
            return self._record(
                Outcome(
                    shooter=seat,
                    pocketed=(),
                    fouls=(),
                    continues=self.turn == seat,
                    next_turn=self.turn,
                    ball_in_hand=self.ball_in_hand,
                    frame_over=False,
                    winner=None,
                    reason=None,
                    message=f"Time ran out. {self.notice}",
                )
            )
        self._check_free(seat)
        return self._settle(seat, self.rules.timeout(self.position()), ())

    def resign(self, seat: int, reason: str) -> Outcome:
        """`seat` loses this game (concession or forfeit); `reason` is a sentence."""
        if self.over:
            raise IllegalActionError("game_over", "The game is over.")
        if len(self.players) != 2 or seat not in (0, 1):
            raise IllegalActionError(
                "not_your_turn", "Only a seated player of a two-player game can concede."
            )
        return self._settle(seat, Ruling(winner=1 - seat, reason=reason), ())

    def _settle(self, seat: int, ruling: Ruling, pocketed: tuple[int, ...]) -> Outcome:
        """Apply a ruling to the state and say what happened."""
        other = 1 - seat
        name = self.players[seat]
        fouled = bool(ruling.fouls)
        self.fouls_in_row = self.rules.count_fouls(self.fouls_in_row, seat, fouled)
        self.breaking = ruling.break_passes_to is not None
        if ruling.break_passes_to is not None:
            self.breaker = ruling.break_passes_to
        self.called_pocket = None
        self.push_out_declared = False
        self.push_out_available = ruling.push_out_next and ruling.winner is None
        if ruling.groups:
            self.groups = dict(ruling.groups)
        if ruling.score is not None:
            self.score = ruling.score
        if ruling.carom is not None:
            self.carom = ruling.carom
        parts = []
        if fouled:
            parts.append(f"Foul: {and_list(label(f) for f in ruling.fouls)}.")
        parts.extend(ruling.notes)
        if ruling.winner is not None:
            self.over, self.winner, self.reason = True, ruling.winner, ruling.reason
            self.decision, self.pending = None, None
            self.ball_in_hand = None
            continues, next_turn = False, seat
            parts += [ruling.reason or "", f"{self.players[ruling.winner]} wins the game."]
        elif ruling.decision is not None:
            self.decision, self.pending = ruling.decision, ruling.pending
            self.after_decision_bih = ruling.ball_in_hand
            self.turn, self.ball_in_hand = ruling.decision.seat, None
            continues, next_turn = ruling.decision.seat == seat, ruling.decision.seat
            parts.append(ruling.decision.prompt)
        else:
            continues = ruling.continues and not fouled
            next_turn = seat if continues else other
            self.turn = next_turn
            self.ball_in_hand = ruling.ball_in_hand
            following = self.players[next_turn]
            if fouled:
                parts += self._after_foul_words(seat, following)
            else:
                if not pocketed and not ruling.notes:
                    parts.append("No ball pocketed.")
                if len(self.players) > 1:  # alone at the table, the turn never passes
                    parts.append(f"{name} shoots again." if continues else f"{following} to shoot.")
            if self.push_out_available:
                parts.append(f"{following} may play a push out.")
        self.notice = None
        return self._record(
            Outcome(
                shooter=seat,
                pocketed=pocketed,
                fouls=tuple(ruling.fouls),
                continues=continues,
                next_turn=next_turn,
                ball_in_hand=self.ball_in_hand,
                frame_over=self.over,
                winner=self.winner,
                reason=self.reason,
                message=" ".join(p for p in parts if p),
                spotted=ruling.spot,
                decision=self.decision,
            )
        )

    def _after_foul_words(self, seat: int, following: str) -> list[str]:
        """Who plays after a foul and from where, and the rules' warning if any."""
        if self.ball_in_hand is None:
            return [f"{following} to play."]
        where = {BEHIND_HEAD_STRING: " behind the head string", IN_D: " in the D"}
        words = [f"Ball in hand{where.get(self.ball_in_hand, '')} for {following}."]
        warning = self.rules.foul_warning(self.fouls_in_row, seat, self.players[seat])
        return [*words, warning] if warning else words

    def _record(self, outcome: Outcome) -> Outcome:
        self.last_outcome = outcome
        return outcome

    def rerack(self) -> None:
        """Rack the balls again at will (practice)."""
        if not self.rules.rerack_at_will:
            raise IllegalActionError("practice_only", "Only practice can be re-racked at will.")
        self._rack(0)
        self.notice = "Balls re-racked."

    # --- storage ----------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """The stored form: `server.codec.to_data(self)` (JSON-able; floats exact)."""
        return to_dict(self)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Game:
        """The inverse of `to_dict`; also reads what the code before the codec stored."""
        return from_data(cls, data)

    # --- what a client shows -----------------------------------------------------------
    def balls_left(self) -> list[list[int]] | None:
        """Per seat, the balls that seat still has to pocket (8-ball once the groups are
        decided: its group; 9-ball: every object ball); None otherwise."""
        return self.rules.balls_left(self.position())

    def public_state(self) -> dict[str, Any]:
        """JSON-able: everything a client shows."""
        pos = self.position()
        rules = self.rules
        state = {
            "kind": self.kind,
            "players": list(self.players),
            "turn": self.turn,
            "breaker": self.breaker,
            "breaking": self.breaking,
            "balls": [
                {"id": int(b), "x": float(x), "y": float(y), "on_table": bool(on)}
                for b, (x, y), on in zip(
                    self.balls.ids, self.balls.positions, self.balls.on_table, strict=True
                )
            ],
            "groups": list(pos.groups) if pos.groups else None,
            "balls_left": rules.balls_left(pos),
            "legal_targets": rules.legal_targets(pos),
            "ball_in_hand": self.ball_in_hand,
            "requires_call": self.requires_call,
            "called_pocket": self.called_pocket,
            "decision": self.decision.to_dict() if self.decision else None,
            "fouls_in_row": list(self.fouls_in_row),
            "push_out_available": self.push_out_available,
            "push_out_declared": self.push_out_declared,
            "over": self.over,
            "winner": self.winner,
            "reason": self.reason,
            "notice": self.notice,
            "last_outcome": self.last_outcome.to_dict() if self.last_outcome else None,
        }
        if self.score is not None:  # snooker's scoreboard (a pool game's state is as it was)
            state["points"] = list(self.points)
            state["nominations"] = [] if self.over or self.decision else rules.nominations(pos)
            state["frame"] = scoreboard(pos)
        if self.carom is not None:  # three-cushion's scoreboard
            state["points"] = list(self.points)
            state["carom"] = self._carom_board()
        return state

    def _carom_board(self) -> dict[str, Any]:
        """Three-cushion's scoreboard: points, innings, average, high run, the run, each
        seat's cue ball and the cushions the last stroke's cue ball met before its second
        ball."""
        carom = self.carom
        assert carom is not None
        seats = range(len(self.players))
        return {
            "points": list(carom.points),
            "innings": list(carom.innings),
            "average": [round(carom.average(s), 3) for s in seats],
            "high_run": list(carom.high_run),
            "run": carom.run,
            "race_to": carom.race_to,
            "equal_innings": carom.equal_innings,
            "last_inning": carom.last_inning,
            "cue_balls": [carom.cue_ball(s) for s in seats],
            "opening": carom.opening,
        }
