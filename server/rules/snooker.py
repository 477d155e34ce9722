"""Snooker, the WPBSA "Official Rules of the Games of Snooker and English Billiards"
(the edition revised November 2019), judged from a position and a shot's facts. Rules are
cited as "WPBSA s.r" (Section s, Rule r): Section 2 Definitions (2.9 In-hand, 2.11 Ball
On, 2.12 Nominated Ball, 2.13 Free Ball, 2.14 Forced Off the Table, 2.15 Infringements,
Fouls and Penalties, 2.17 Snookered, and "Jump Shot", cited by name: its number in this
edition was not checked), Section 3 The Game (3.2 Position of Balls, 3.3 Mode of Play,
3.4 End of Frame, Game or Match, 3.5 Playing from In-hand, 3.7 Spotting Colours, 3.11
Penalty Values, 3.12 Snookered After a Foul, 3.13 Play Again, 3.14 Foul and a Miss),
Section 4 The Players (4.1 Conduct).

What the server judges, plainly:
- the ball on and the nomination (WPBSA 2.11, 2.12, 3.3): on a colour the striker may
  nominate one (`Game.nominate`); without a nomination the colour the cue ball hits first
  is taken as nominated (the referee's "obvious" case). A free ball is nominated the
  same way, else the ball first hit is the free ball.
- fouls (WPBSA 2.15, 3.11): no ball hit; a ball not on hit first; a ball not on potted;
  the cue ball potted (in-off); a ball forced off the table (2.14; the cue ball off is
  played from in-hand, a colour off is re-spotted, a red off stays off, 3.7). Each costs
  the value of the ball on or the highest value of the balls involved, at least 4 (3.11);
  a foul on a colour after a red with no colour nominated (none named, none hit first)
  costs 7 (3.11). A free ball hit first is the ball on and worth the ball on (2.13). The
  engine has no cue to touch a ball with: push strokes and touching a ball cannot happen.
- a jump shot (Section 2 "Jump Shot", a foul under 3.11, worth the ball on, at least 4):
  the cue ball passed over some part of an object ball before its first contact with a
  ball (`jumps.passed_over`). Over a ball after that first contact is no jump shot (the
  definition's exception); the cue ball that strikes a ball in the air and comes down on
  its far side is not judged (the server reads no jump over the first ball touched).
- after a foul the next player plays from where the balls lie or has the offender play
  again (WPBSA 3.13); if the foul leaves them snookered (2.17, `snooker_table`) they may
  take a free ball (3.12).
- foul and a miss (WPBSA 3.14): a foul in which the cue ball did not first hit a ball on
  is a miss when, before the stroke, some part of a ball on was open to a straight stroke
  (`snooker_table.open_path`), unless a player needed penalty points before or after the
  stroke, or the points on the table equalled the difference (3.14(a)(i), (ii); the
  server cannot judge intent, so it is taken as not intended). From a snooker (no
  straight path) the server judges no miss: it cannot tell a good attempt from a poor
  one. The next player may also have the balls replaced and the offender play again. A
  miss with a ball on wholly open (struck at both extreme edges, so full-ball contact) is
  counted; the count goes on only while the balls are replaced and the same player plays
  again, and such a repeated failure is a miss whatever the scores; the third loses the
  frame, after a warning at the second.
- the frame ends when the black is potted or fouled as the last ball; tied, the black is
  re-spotted and the player who did not end the frame plays first from the D (the WPBSA
  draws lots; a server has no coin both players see), and the next score or foul ends it
  (WPBSA 3.4).
- not judged: a free ball that snookers the opponent on all reds (3.12), a free ball with
  the cue ball in hand (2.17: snookered from every point of the D), and stalemate
  (Section 3, Stalemate).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

from typing_extensions import override

from server.engine import CUE, BallSet, Table
from server.engine.rack import COLOURS

from . import fouls
from .outcome import IN_D, Decision, Foul
from .position import Position
from .ruling import Ruling
from .shotfacts import ShotFacts
from .snooker_score import (
    BLACK,
    COLOUR,
    COLOUR_IDS,
    NAMES,
    RED,
    VALUES,
    FrameScore,
    balls_on,
    colours_left,
    on_after_turn,
    remaining,
    snookers_required,
    value_on,
)
from .snooker_table import open_path, respot_colours, snookered
from .strategy import GameRules
from .words import and_list, snooker_ball

MISSES_TO_LOSE = 3
NO_NOMINATION_PENALTY = 7  # WPBSA 3.11: a foul after a red, before a colour is nominated
PLAY = "play"
PLAY_AGAIN = "play_again"
FREE_BALL = "free_ball"
REPLACE = "replace"


def nominee(score: FrameScore, facts: ShotFacts, on_table: Sequence[int]) -> int | None:
    """The nominated ball (WPBSA 2.12): as nominated, else (on a colour, or with a free
    ball) the ball first hit when it could have been nominated."""
    if score.nominated is not None:
        return score.nominated
    first = facts.first_contact
    if first is None:
        return None
    if score.on == COLOUR and first in COLOUR_IDS:
        return first
    if score.free_ball and first not in balls_on(score, on_table):
        return first
    return None


def allowed_pots(score: FrameScore, on_table: Sequence[int]) -> set[int]:
    """The balls the striker may pot: the balls on (nothing on a colour not nominated)."""
    if score.on == COLOUR and score.nominated is None:
        return set()
    return set(balls_on(score, on_table))


def foul_value(
    score: FrameScore, facts: ShotFacts, wrong: Sequence[int], on_table: Sequence[int]
) -> int:
    """WPBSA 3.11 Penalty Values: the value of the ball on, or the highest value of a ball
    not on hit first, potted or forced off the table, at least 4; 7 for a foul after a red
    before a colour is nominated. A free ball hit first is the ball on (2.13)."""
    if score.on == COLOUR and score.nominated is None:
        return NO_NOMINATION_PENALTY
    involved = [value_on(score), *(VALUES[b] for b in wrong)]
    first = facts.first_contact
    if first is not None and first not in balls_on(score, on_table):
        involved.append(VALUES[first])
    return max(4, *involved)


def fouls_of(pos: Position, score: FrameScore, facts: ShotFacts) -> tuple[list[Foul], list[int]]:
    """Every foul of the shot (WPBSA 2.15, 3.11) and the balls potted that were not on. A
    jump shot (Section 2 "Jump Shot") costs the value of the ball on (3.11): the ball
    jumped over is not a ball involved."""
    name = pos.shooter
    wrong = [b for b in facts.pocketed if b not in allowed_pots(score, pos.on_table)]
    wrong += facts.off_table  # forced off the table (WPBSA 2.14), valued as involved (3.11)
    found = []
    first = facts.first_contact
    if first is None:
        found.append(fouls.no_ball_hit(name))
    elif first not in balls_on(score, pos.on_table):
        found.append(fouls.snooker_wrong_first(name, first, on_words(score)))
    if facts.jumped_over:
        found.append(fouls.jump_shot(name, facts.jumped_over))
    potted_wrong = [b for b in wrong if b in facts.pocketed]
    if potted_wrong:
        found.append(fouls.potted_not_on(name, potted_wrong))
    if facts.off_table:
        off = and_list(snooker_ball(b) for b in facts.off_table)
        found.append(Foul("ball_off_table", f"{name} forced {off} off the table."))
    if facts.cue_off_table:
        found.append(fouls.scratch(name, off_table=True))
    elif facts.scratch:
        found.append(fouls.in_off(name))
    return found, wrong


def on_words(score: FrameScore) -> str:
    """'a red', 'the pink', 'a colour'."""
    if score.on == RED:
        return "a red"
    if score.on == COLOUR:
        return snooker_ball(score.nominated) if score.nominated else "a colour"
    return f"the {score.on}"


def needs_penalty_points(score: FrameScore, on_table: Sequence[int]) -> bool:
    """WPBSA 3.14(a)(i), (ii): a player is behind by the points on the table or more (more:
    they need penalty points; as many: only the re-spotted black is left to them)."""
    left = remaining(score, on_table)
    top = max(score.points)
    return any(top - p > 0 and top - p >= left for p in score.points)


def judge_miss(
    pos: Position, score: FrameScore, facts: ShotFacts, after: FrameScore, left: Sequence[int]
) -> tuple[bool, bool]:
    """(a miss, counted toward three): WPBSA 3.14 as the server judges it (the module's
    docstring). `after`, `left`: the score and the object balls once the foul is paid."""
    on = balls_on(score, pos.on_table)
    if facts.first_contact is not None and facts.first_contact in on:
        return False, False
    if pos.object_balls == [BLACK] or pos.balls is None:
        return False, False  # with the black alone the foul ends the frame (3.4)
    repeated = score.misses[pos.turn] > 0  # the same position again: a miss whatever the scores
    if not repeated and (
        needs_penalty_points(score, pos.on_table) or needs_penalty_points(after, left)
    ):
        return False, False
    blocked, open_before = _sight_before(pos, on)
    return open_before, open_before and not blocked


_Sight = tuple[Table, tuple[bytes, bytes, bytes, tuple[int, ...]], tuple[bool, bool]]
_last_before: _Sight | None = None


def _sight_before(pos: Position, on: Sequence[int]) -> tuple[bool, bool]:
    """(`snookered`, `open_path`) on the table the stroke was played from. The search
    judges thousands of simulated strokes from one table a turn, so the last answer is
    kept (a pure function's memo: the same table object, balls and balls on give the same
    answer)."""
    global _last_before
    balls = pos.balls
    assert balls is not None
    key = (balls.ids.tobytes(), balls.positions.tobytes(), balls.on_table.tobytes(), tuple(on))
    last = _last_before
    if last is not None and last[0] is pos.table and last[1] == key:
        return last[2]
    found = (snookered(pos.table, balls, on), open_path(pos.table, balls, on))
    _last_before = (pos.table, key, found)
    return found


def judge(pos: Position, facts: ShotFacts) -> Ruling:
    score = pos.score
    if score is None:
        raise ValueError("a snooker position carries its frame score")
    # A stroke by this player ends the opponent's run of misses (WPBSA 3.14 counts the
    # failures from one position: the offender made to play again with the balls replaced).
    misses = _with(score.misses, pos.opponent, 0)
    score = replace(score, nominated=nominee(score, facts, pos.on_table), misses=misses)
    found, wrong = fouls_of(pos, score, facts)
    if found:
        return _foul(pos, score, facts, found, wrong)
    return _legal(pos, score, facts)


def respotted(score: FrameScore, potted: Sequence[int], legal: bool) -> tuple[int, ...]:
    """Colours that go back (WPBSA 3.7): every colour potted on a foul or while reds
    remain (the last red's colour too), and a free ball; in the colours' turn the ball
    on, legally potted, stays down."""
    colours = [b for b in potted if b in COLOUR_IDS]
    if legal and score.on not in (RED, COLOUR):
        return tuple(b for b in colours if b != COLOURS[score.on])
    return tuple(colours)


def _left(pos: Position, facts: ShotFacts, spot: Sequence[int]) -> list[int]:
    """The object balls on the table once the shot's colours are back."""
    gone = (set(facts.pocketed) | set(facts.off_table)) - set(spot)
    return [b for b in pos.object_balls if b not in gone]


def _legal(pos: Position, score: FrameScore, facts: ShotFacts) -> Ruling:
    """A fair stroke: points for the balls on potted (WPBSA 3.3; a free ball scores as the
    ball on, 3.12); the striker plays on after a pot."""
    seat, name = pos.turn, pos.shooter
    potted = facts.pocketed
    if not potted:
        gained = 0
    elif score.on == RED:
        gained = len(potted)
    else:
        gained = value_on(score)
    r = Ruling(spot=respotted(score, potted, legal=True))
    left = _left(pos, facts, r.spot)
    misses = _with(score.misses, seat, 0)  # (the opponent's were cleared by `judge`)
    if not gained:
        r.score = replace(score, current_break=0, on=on_after_turn(left), nominated=None,
                          free_ball=False, misses=misses)  # fmt: skip
        return r
    brk = score.current_break + gained
    best = _with(score.highest_break, seat, max(score.highest_break[seat], brk))
    r.continues = True
    r.notes.append(f"{name} scores {gained}: a break of {brk}.")
    nxt = COLOUR if score.on == RED else on_after_turn(left)
    points = _with(score.points, seat, score.points[seat] + gained)
    r.score = replace(score, points=points, current_break=brk, on=nxt, nominated=None,
                      free_ball=False, highest_break=best, misses=misses)  # fmt: skip
    return _frame_end(pos, r, ends=score.on == NAMES[BLACK])


def _with(values: tuple[int, ...], seat: int, value: int) -> tuple[int, ...]:
    out = list(values)
    out[seat] = value
    return tuple(out)


def _foul(
    pos: Position, score: FrameScore, facts: ShotFacts, found: list[Foul], wrong: list[int]
) -> Ruling:
    """Penalty to the opponent, colours back, then the next player's choice
    (WPBSA 3.11-3.14)."""
    seat, opp = pos.turn, pos.opponent
    value = foul_value(score, facts, wrong, pos.on_table)
    gone = [*facts.pocketed, *facts.off_table]  # a colour off the table is re-spotted (3.7)
    r = Ruling(fouls=found, spot=respotted(score, gone, legal=False))
    left = _left(pos, facts, r.spot)
    points = _with(score.points, opp, score.points[opp] + value)
    paid = replace(score, points=points, on=on_after_turn(left))
    miss, counted = judge_miss(pos, score, facts, paid, left)
    misses = _with(score.misses, seat, score.misses[seat] + 1 if counted else 0)
    r.notes.append(f"{value} points to {pos.players[opp]}.")
    r.score = replace(paid, current_break=0, nominated=None, free_ball=False, misses=misses)
    r.ball_in_hand = IN_D if facts.scratch else None
    if miss:
        r.miss = True
        r.fouls.append(fouls.miss(pos.shooter))
    if pos.object_balls == [BLACK]:
        return _frame_end(pos, r, ends=True)
    if counted and misses[seat] >= MISSES_TO_LOSE:
        r.winner = opp
        r.reason = f"{pos.shooter} missed the ball on three times in a row."
        return r
    if counted and misses[seat] == MISSES_TO_LOSE - 1:
        r.notes.append(
            f"{pos.shooter} is warned: a third miss from the balls replaced gives "
            f"{pos.players[opp]} the frame."
        )
    r.pending = "snooker_foul"
    options = _options(pos, r, facts, left, miss)
    r.decision = Decision(opp, options, _prompt(pos, options))
    return r


def _options(
    pos: Position, r: Ruling, facts: ShotFacts, left: list[int], miss: bool
) -> tuple[str, ...]:
    """The next player's choices after a foul: a free ball when snookered (3.12; not with
    the cue ball in hand), play, have the offender play again (3.13), and after a miss the
    balls replaced (3.14)."""
    options = [PLAY, PLAY_AGAIN]
    if not facts.scratch and facts.final is not None and r.score is not None:
        after = respot_colours(pos.table, facts.final, r.spot)
        if snookered(pos.table, after, balls_on(r.score, left)):
            options.insert(0, FREE_BALL)
            r.notes.append(f"Free ball: {pos.players[pos.opponent]} is snookered.")
    if miss:
        options.append(REPLACE)
    return tuple(options)


def _prompt(pos: Position, options: Sequence[str]) -> str:
    name = pos.shooter
    words = {
        FREE_BALL: "take a free ball",
        PLAY: "play from here",
        PLAY_AGAIN: f"have {name} play again",
        REPLACE: f"have the balls replaced and {name} play again",
    }
    said = [words[o] for o in options]
    return f"{pos.players[pos.opponent]}, " + ", ".join(said[:-1]) + f" or {said[-1]}?"


def _frame_end(pos: Position, r: Ruling, ends: bool) -> Ruling:
    """WPBSA 3.4: the frame ends when the black, the last ball, is potted or fouled (so
    also on the first score or foul once the black is re-spotted); tied, the black is
    re-spotted and the other player plays first from the D."""
    score = r.score
    if not ends or score is None:
        return r
    a, b = score.points
    r.decision, r.pending = None, None
    if a != b:
        r.winner = 0 if a > b else 1
        r.reason = f"{pos.players[r.winner]} wins the frame {max(a, b)}-{min(a, b)}."
        return r
    r.spot = tuple(sorted({*r.spot, BLACK}))
    r.continues = False
    r.ball_in_hand = IN_D
    r.score = replace(score, on=NAMES[BLACK], respotted_black=True, current_break=0,
                      nominated=None, free_ball=False)  # fmt: skip
    r.notes.append(
        f"The scores are level: the black is re-spotted and {pos.players[pos.opponent]} "
        "plays first, from the D."
    )
    return r


class SnookerRules(GameRules):
    """Snooker as a `GameRules` strategy (WPBSA; the module's docstring)."""

    kind = "snooker"
    seats = 2
    rack = "snooker"
    breaks = False  # the break-off is an ordinary stroke on a red (WPBSA 3.3)
    opening_ball_in_hand = IN_D  # WPBSA 3.5 Playing from In-hand
    rerack_at_will = False
    spot_choice: tuple[int, ...] = ()

    @override
    def table(self) -> Table:
        return Table.snooker()

    @override
    def new_score(self, seats: int) -> FrameScore | None:
        return FrameScore.start(seats)

    @override
    def legal_targets(self, pos: Position) -> list[int]:
        """The balls on (WPBSA 2.11)."""
        score = pos.score or FrameScore.start(len(pos.players))
        return balls_on(score, pos.on_table)

    @override
    def nominations(self, pos: Position) -> list[int]:
        """On a colour: the colours on the table; with a free ball: any object ball other
        than the ball on (WPBSA 2.13)."""
        score = pos.score
        if score is None:
            return []
        if score.free_ball:
            on = balls_on(replace(score, nominated=None), pos.on_table)
            return [b for b in pos.object_balls if b not in on]
        if score.on == COLOUR:
            return colours_left(pos.on_table)
        return []

    @override
    def balls_left(self, pos: Position) -> list[list[int]] | None:
        left = pos.object_balls
        return [left, list(left)]

    @override
    def requires_call(self, pos: Position) -> bool:
        return False

    @override
    def judge(self, pos: Position, facts: ShotFacts) -> Ruling:
        return judge(pos, facts)

    @override
    def timeout(self, pos: Position) -> Ruling:
        """Time wasting (WPBSA 4.1 Conduct asks the referee to warn, then award the
        frame): here a foul worth the ball on (at least 4), and the next player plays from
        where the balls lie."""
        score = pos.score or FrameScore.start(len(pos.players))
        value = max(4, value_on(score))
        points = _with(score.points, pos.opponent, score.points[pos.opponent] + value)
        r = Ruling(fouls=[fouls.shot_clock(pos.shooter)])
        r.notes.append(f"{value} points to {pos.players[pos.opponent]}.")
        r.score = replace(score, points=points, current_break=0, nominated=None,
                          free_ball=False, on=on_after_turn(pos.object_balls))  # fmt: skip
        if pos.balls is not None and not pos.balls.on_table[pos.balls.index(CUE)]:
            r.ball_in_hand = IN_D  # the cue ball was in hand: the next player has it
        return r

    @override
    def ball_names(self, ball_ids: Sequence[int]) -> str:
        """'a red, a red and the pink'."""
        return and_list(snooker_ball(b) for b in ball_ids)

    @override
    def respot(self, table: Table, balls: BallSet, ball_ids: tuple[int, ...]) -> BallSet:
        return respot_colours(table, balls, ball_ids)

    @override
    def count_fouls(self, fouls_in_row: Sequence[int], seat: int, fouled: bool) -> list[int]:
        """Snooker counts misses (in the frame score), not fouls."""
        return list(fouls_in_row)

    @override
    def foul_warning(self, fouls_in_row: Sequence[int], seat: int, name: str) -> str | None:
        return None


def scoreboard(pos: Position) -> dict[str, object]:
    """What the scoreboard shows: points, the break, the ball on, the points remaining
    and the snookers each seat requires."""
    score = pos.score or FrameScore.start(len(pos.players))
    return {
        "points": list(score.points),
        "current_break": score.current_break,
        "highest_break": list(score.highest_break),
        "on": score.on,
        "nominated": score.nominated,
        "free_ball": score.free_ball,
        "remaining": remaining(score, pos.on_table),
        "snookers_required": [
            snookers_required(score, pos.on_table, s) for s in range(len(pos.players))
        ],
        "misses": list(score.misses),
        "respotted_black": score.respotted_black,
    }
