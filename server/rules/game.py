"""`Game`: one rack of 8-ball, 9-ball or practice, in the spirit of python-chess's `Board`.

Pure: no I/O. It knows the players, whose turn it is, the table at rest and what is legal
now; `apply` takes the engine's `ShotResult` and returns an `Outcome`. Every action that is
not allowed raises `IllegalActionError` and changes nothing. The rule modules judge a shot
(`Ruling`); this class owns the state and applies the ruling.
"""

from __future__ import annotations

import dataclasses

from server.engine import CUE, BallSet, ShotResult, Table, rack

from . import eight_ball, nine_ball
from .errors import IllegalActionError
from .fouls import label, shot_clock
from .options import DEFAULT_OPTIONS, GAME_KINDS, RuleOptions
from .outcome import ANYWHERE, BEHIND_HEAD_STRING, Decision, Outcome
from .placement import can_place
from .ruling import Ruling
from .shotfacts import shot_facts
from .spotting import respot
from .words import and_list, balls, capitalised

PRACTICE = "practice"


class Game:
    """One rack (players call it a frame; `Frame` is the engine's per-tick snapshot).

    State a client shows: `turn`, `ball_in_hand`, `groups`, `requires_call`,
    `called_pocket`, `decision`, `fouls_in_row`, `over` / `winner` / `reason`,
    `last_outcome`; `balls` is the table at rest (copy it before mutating it).
    """

    def __init__(self, kind: str, players: tuple[str, str] | tuple[str], breaker: int = 0,
                 table: Table | None = None, seed: int = 0,
                 options: RuleOptions = DEFAULT_OPTIONS) -> None:
        if kind not in GAME_KINDS:
            raise ValueError(f"unknown game {kind!r}; choose one of {GAME_KINDS}")
        players = tuple(players)
        if len(players) != (1 if kind == PRACTICE else 2):
            raise ValueError("practice takes one player, 8-ball and 9-ball two")
        if breaker not in range(len(players)):
            raise ValueError("breaker must be a seat (0 or 1)")
        self.kind = kind
        self.players: tuple[str, ...] = players
        self.table = table if table is not None else Table.pool("9ft")
        self.seed = seed
        self.options = options
        self.over = False
        self.winner: int | None = None
        self.reason: str | None = None
        self.last_outcome: Outcome | None = None
        self.notice: str | None = None  # what the last decision or push out did
        self.racks = 0
        self._rack(breaker)

    # --- racking -----------------------------------------------------------------------
    def _rack(self, breaker: int) -> None:
        """A fresh rack broken by `breaker`; re-racks get a new seed, deterministically."""
        rack_kind = "nine_ball" if self.kind == "nine_ball" else "eight_ball"
        self.balls: BallSet = rack(rack_kind, self.table, seed=self.seed + 7919 * self.racks)
        self.racks += 1
        self.breaker = breaker
        self.turn = breaker
        self.breaking = self.kind != PRACTICE
        self.ball_in_hand: str | None = ANYWHERE if self.kind == PRACTICE else BEHIND_HEAD_STRING
        self.groups: dict[int, str] | None = None
        self.called_pocket: int | None = None
        self.decision: Decision | None = None
        self._pending: str | None = None
        self._after_decision_bih: str | None = None
        self.fouls_in_row = [0] * len(self.players)
        self.push_out_available = False
        self.push_out_declared = False

    # --- what is legal now -------------------------------------------------------------
    @property
    def requires_call(self) -> bool:
        """8-ball: the shooter is on the 8 and must call its pocket before shooting."""
        return (self.kind == "eight_ball" and not self.over and not self.breaking
                and self.decision is None
                and eight_ball.on_eight(self.balls, self.groups, self.turn))

    def legal_targets(self) -> list[int]:
        """Balls the shooter may hit first now (empty in practice: anything goes)."""
        if self.kind == "eight_ball":
            return eight_ball.legal_targets(self.balls, self.groups, self.turn)
        if self.kind == "nine_ball":
            if self.push_out_declared:
                return [b for b in self.balls.on_table_ids() if b != CUE]
            lowest = nine_ball.lowest_ball(self.balls)
            return [lowest] if lowest is not None else []
        return []

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
            raise IllegalActionError("decision_pending",
                                     f"Waiting for a decision: {self.decision.prompt}")

    def check_shot(self, seat: int) -> None:
        """Raise `IllegalActionError` unless `seat` may shoot now."""
        self._check_free(seat)
        if not self._cue_on_table():
            raise IllegalActionError("cue_ball_off_table",
                                     "Place the cue ball before shooting.")
        if self.requires_call and self.called_pocket is None:
            raise IllegalActionError("call_required",
                                     "Call a pocket for the 8 before shooting.")

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
            where = ("behind the head string, " if self.ball_in_hand == BEHIND_HEAD_STRING
                     else "")
            raise IllegalActionError("illegal_placement",
                                     f"The cue ball must go {where}on the table and clear "
                                     "of the other balls.")
        self.balls = self.balls.with_ball(CUE, (float(x), float(y)))

    def call_pocket(self, seat: int, pocket: int) -> None:
        """8-ball: name the pocket (index into `table.pockets`) for the 8."""
        self._check_free(seat)
        if not self.requires_call:
            raise IllegalActionError("call_not_needed",
                                     "Only the 8 is called, once your group is cleared.")
        if (not isinstance(pocket, int) or isinstance(pocket, bool)
                or not 0 <= pocket < len(self.table.pockets)):
            raise IllegalActionError("bad_pocket",
                                     f"Pick a pocket from 0 to {len(self.table.pockets) - 1}.")
        self.called_pocket = pocket

    def declare_push_out(self, seat: int) -> None:
        """9-ball: announce a push out for the shot right after the break."""
        self._check_free(seat)
        if self.kind != "nine_ball" or not self.push_out_available:
            raise IllegalActionError("push_out_not_allowed",
                                     "A push out is only allowed on the shot after the break.")
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
            raise IllegalActionError("bad_option",
                                     f"Choose one of: {', '.join(self.decision.options)}.")
        self._take_decision(seat, option)

    def _take_decision(self, seat: int, option: str) -> None:
        name, other = self.players[seat], 1 - seat
        pending, bih = self._pending, self._after_decision_bih
        self.decision, self._pending, self._after_decision_bih = None, None, None
        if option == "rerack":
            self._rack(seat)
            self.notice = f"{name} chose a re-rack and breaks."
        elif option == "rerack_opponent_breaks":
            self._rack(other)
            self.notice = f"{name} chose a re-rack; {self.players[other]} breaks again."
        elif option == "spot":
            self.balls = respot(self.table, self.balls, (eight_ball.EIGHT,))
            self.turn, self.ball_in_hand = seat, bih
            self.notice = f"{name} spots the 8 and shoots."
        elif option == "accept":
            self.turn, self.ball_in_hand = seat, bih
            self.notice = f"{name} accepts the table and shoots."
        elif option == "shoot":
            self.turn, self.ball_in_hand = seat, None
            self.notice = f"{name} shoots after the push out."
        elif option == "pass":
            self.turn, self.ball_in_hand = other, None
            self.notice = f"{name} passes; {self.players[other]} must shoot."
        else:  # pragma: no cover - options come from the rule modules
            raise AssertionError(f"unhandled option {option!r} for {pending}")

    # --- shots -------------------------------------------------------------------------
    def apply(self, seat: int, result: ShotResult) -> Outcome:
        """Judge a simulated shot (after `check_shot` passed) and move the game on."""
        self.check_shot(seat)
        if list(result.final.ids) != list(self.balls.ids):
            raise IllegalActionError("bad_result", "The shot was not played on this table.")
        facts = shot_facts(self.balls, result)
        final = result.final.copy()
        if self.kind == PRACTICE:
            return self._apply_practice(seat, facts.pocketed, facts.scratch, final)
        judge = eight_ball.judge if self.kind == "eight_ball" else nine_ball.judge
        ruling = judge(self, seat, facts)
        pocketed = facts.pocketed + ((CUE,) if facts.scratch else ())
        if facts.pocketed:
            ruling.notes.insert(0, f"{self.players[seat]} pocketed {balls(facts.pocketed)}.")
        if ruling.spot:
            final = respot(self.table, final, ruling.spot)
            ruling.notes.append(capitalised(f"{balls(ruling.spot)} "
                                            f"{'is' if len(ruling.spot) == 1 else 'are'} "
                                            "spotted."))
        self.balls = final
        return self._settle(seat, ruling, pocketed)

    def timeout(self, seat: int) -> Outcome:
        """The shot clock ran out for `seat`: a foul, the turn passes with ball in hand.

        With a decision pending, time running out takes its first option instead (no foul).
        If the breaker runs out of time, the opponent breaks instead.
        """
        if self.decision is not None and not self.over and seat == self.decision.seat:
            option = self.decision.options[0]
            self._take_decision(seat, option)
            return self._record(Outcome(
                shooter=seat, pocketed=(), fouls=(), continues=self.turn == seat,
                next_turn=self.turn, ball_in_hand=self.ball_in_hand, frame_over=False,
                winner=None, reason=None, message=f"Time ran out. {self.notice}"))
        self._check_free(seat)
        if self.kind == PRACTICE:
            return self._record(Outcome(seat, (), (), True, seat, self.ball_in_hand, False,
                                        None, None, "Time ran out."))
        ruling = Ruling(fouls=[shot_clock(self.players[seat])], ball_in_hand=ANYWHERE)
        if self.breaking:
            self.breaker = 1 - seat
            ruling.ball_in_hand = BEHIND_HEAD_STRING
            ruling.notes.append(f"{self.players[1 - seat]} breaks instead.")
        elif self.kind == "nine_ball" and self.fouls_in_row[seat] + 1 >= nine_ball.FOULS_TO_LOSE:
            ruling.winner = 1 - seat
            ruling.reason = f"{self.players[seat]} fouled three times in a row."
        ruling.push_out_next = False
        return self._settle(seat, ruling, (), keep_breaking=self.breaking)

    def resign(self, seat: int, reason: str) -> Outcome:
        """`seat` loses this game (concession or forfeit); `reason` is a sentence."""
        if self.over:
            raise IllegalActionError("game_over", "The game is over.")
        if self.kind == PRACTICE or seat not in (0, 1):
            raise IllegalActionError("not_your_turn", "Only a seated player of a two-player "
                                     "game can concede.")
        ruling = Ruling(winner=1 - seat, reason=reason)
        return self._settle(seat, ruling, ())

    def _settle(self, seat: int, ruling: Ruling, pocketed: tuple[int, ...],
                keep_breaking: bool = False) -> Outcome:
        """Apply a ruling to the state and say what happened."""
        other = 1 - seat
        name = self.players[seat]
        fouled = bool(ruling.fouls)
        if self.kind == "nine_ball":  # WPA 8-ball does not count fouls in a row
            self.fouls_in_row[seat] = self.fouls_in_row[seat] + 1 if fouled else 0
        self.breaking = keep_breaking
        self.called_pocket = None
        self.push_out_declared = False
        self.push_out_available = ruling.push_out_next and ruling.winner is None
        if ruling.groups:
            self.groups = dict(ruling.groups)
        parts = []
        if fouled:
            parts.append(f"Foul: {and_list(label(f) for f in ruling.fouls)}.")
        parts.extend(ruling.notes)
        if ruling.winner is not None:
            self.over, self.winner, self.reason = True, ruling.winner, ruling.reason
            self.decision, self._pending = None, None
            self.ball_in_hand = None
            continues, next_turn = False, seat
            parts += [ruling.reason or "", f"{self.players[ruling.winner]} wins the game."]
        elif ruling.decision is not None:
            self.decision, self._pending = ruling.decision, ruling.pending
            self._after_decision_bih = ruling.ball_in_hand
            self.turn, self.ball_in_hand = ruling.decision.seat, None
            continues, next_turn = ruling.decision.seat == seat, ruling.decision.seat
            parts.append(ruling.decision.prompt)
        else:
            continues = ruling.continues and not fouled
            next_turn = seat if continues else other
            self.turn = next_turn
            self.ball_in_hand = ruling.ball_in_hand if fouled else None
            following = self.players[next_turn]
            if fouled:
                where = (" behind the head string" if self.ball_in_hand == BEHIND_HEAD_STRING
                         else "")
                parts.append(f"Ball in hand{where} for {following}.")
                if self.kind == "nine_ball" and self.fouls_in_row[seat] == 2:
                    parts.append(f"{name} is on two fouls: a third foul in a row loses.")
            elif continues:
                parts.append(f"{name} shoots again.")
            else:
                if not pocketed and not ruling.notes:
                    parts.append("No ball pocketed.")
                parts.append(f"{following} to shoot.")
            if self.push_out_available:
                parts.append(f"{following} may play a push out.")
        self.notice = None
        return self._record(Outcome(
            shooter=seat, pocketed=pocketed, fouls=tuple(ruling.fouls), continues=continues,
            next_turn=next_turn, ball_in_hand=self.ball_in_hand, frame_over=self.over,
            winner=self.winner, reason=self.reason, message=" ".join(p for p in parts if p),
            spotted=ruling.spot, decision=self.decision))

    def _apply_practice(self, seat: int, pocketed: tuple[int, ...], scratch: bool,
                        final: BallSet) -> Outcome:
        """Practice: no fouls; a pocketed cue ball comes back as ball in hand."""
        self.balls = final
        parts = [f"{self.players[seat]} pocketed {balls(pocketed)}."] if pocketed else []
        if scratch:
            parts.append("The cue ball went in: place it anywhere.")
        if not [b for b in final.on_table_ids() if b != CUE]:
            parts.append("Table cleared. Rerack to play again.")
        if not parts:
            parts.append("No ball pocketed.")
        return self._record(Outcome(
            shooter=seat, pocketed=pocketed + ((CUE,) if scratch else ()), fouls=(),
            continues=True, next_turn=seat, ball_in_hand=ANYWHERE, frame_over=False,
            winner=None, reason=None, message=" ".join(parts)))

    def _record(self, outcome: Outcome) -> Outcome:
        self.last_outcome = outcome
        return outcome

    def rerack(self) -> None:
        """Practice only: rack the balls again."""
        if self.kind != PRACTICE:
            raise IllegalActionError("practice_only", "Only practice can be re-racked at will.")
        self._rack(0)
        self.notice = "Balls re-racked."

    # --- storage ----------------------------------------------------------------------
    def to_dict(self) -> dict:
        """Everything needed to rebuild this game exactly (JSON-able; floats exact)."""
        return {
            "kind": self.kind, "players": list(self.players),
            "table": _table_fields(self.table), "seed": self.seed,
            "options": dataclasses.asdict(self.options),
            "over": self.over, "winner": self.winner, "reason": self.reason,
            "last_outcome": self.last_outcome.to_dict() if self.last_outcome else None,
            "notice": self.notice, "racks": self.racks, "balls": self.balls.to_dict(),
            "breaker": self.breaker, "turn": self.turn, "breaking": self.breaking,
            "ball_in_hand": self.ball_in_hand,
            "groups": ([[s, g] for s, g in sorted(self.groups.items())]
                       if self.groups is not None else None),
            "called_pocket": self.called_pocket,
            "decision": self.decision.to_dict() if self.decision else None,
            "pending": self._pending, "after_decision_bih": self._after_decision_bih,
            "fouls_in_row": list(self.fouls_in_row),
            "push_out_available": self.push_out_available,
            "push_out_declared": self.push_out_declared,
        }

    @classmethod
    def from_dict(cls, data: dict) -> Game:
        """The inverse of `to_dict`: the same game, ready to go on."""
        game = cls.__new__(cls)
        game.kind = data["kind"]
        game.players = tuple(data["players"])
        game.table = Table(*data["table"])
        game.seed = data["seed"]
        game.options = RuleOptions(**data["options"])
        game.over, game.winner, game.reason = data["over"], data["winner"], data["reason"]
        last = data["last_outcome"]
        game.last_outcome = Outcome.from_dict(last) if last else None
        game.notice, game.racks = data["notice"], data["racks"]
        game.balls = BallSet.from_dict(data["balls"])
        game.breaker, game.turn, game.breaking = data["breaker"], data["turn"], data["breaking"]
        game.ball_in_hand = data["ball_in_hand"]
        groups = data["groups"]
        game.groups = {int(s): g for s, g in groups} if groups is not None else None
        game.called_pocket = data["called_pocket"]
        game.decision = Decision.from_dict(data["decision"]) if data["decision"] else None
        game._pending, game._after_decision_bih = data["pending"], data["after_decision_bih"]
        game.fouls_in_row = list(data["fouls_in_row"])
        game.push_out_available = data["push_out_available"]
        game.push_out_declared = data["push_out_declared"]
        return game

    # --- what a client shows -----------------------------------------------------------
    def balls_left(self) -> list[list[int]] | None:
        """Per seat, the balls that seat still has to pocket before the 8 (8-ball, groups
        decided), or the object balls on the table (9-ball); None otherwise."""
        if self.kind == "eight_ball" and self.groups:
            return [eight_ball.group_left(self.balls, self.groups[s]) for s in (0, 1)]
        if self.kind == "nine_ball":
            left = [b for b in self.balls.on_table_ids() if b != CUE]
            return [left, list(left)]
        return None

    def public_state(self) -> dict:
        """JSON-able: everything a client shows."""
        return {
            "kind": self.kind,
            "players": list(self.players),
            "turn": self.turn,
            "breaker": self.breaker,
            "breaking": self.breaking,
            "balls": [{"id": int(b), "x": float(x), "y": float(y), "on_table": bool(on)}
                      for b, (x, y), on in zip(self.balls.ids, self.balls.positions,
                                               self.balls.on_table, strict=True)],
            "groups": ([self.groups[0], self.groups[1]] if self.groups else None),
            "balls_left": self.balls_left(),
            "legal_targets": self.legal_targets(),
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


def _table_fields(table: Table) -> list[float]:
    """The table's constructor arguments (its geometry is derived from them)."""
    return [table.length, table.width, table.ball_radius, table.corner_mouth,
            table.side_mouth]
