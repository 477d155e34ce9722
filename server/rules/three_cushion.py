"""Three-cushion billiards, the UMB "World Rules of Carom Billiard" (cited "UMB Art. n":
Art. 23 Starting position, cue-ball; Art. 24 Cannon; Art. 27 Balls in contact with each
other; Art. 28 Balls bounding out of the billiard; Art. 29 End of the match; Art. 41 Fouls;
Art. 83 Three cushions), judged from a position and a shot's facts.

What the server judges, plainly:
- the opening (UMB Art. 23): the red on the top (foot) spot, the opponent's cue ball on the
  head spot, the opener's (the white) on a starting spot beside it; the opening stroke
  must hit the red first, directly: otherwise it is a foul and the inning ends.
- the point (UMB Art. 83): the striker's cue ball meets both other balls and at least
  three cushions before it meets the second; cushions and the first ball in any order, a
  cushion counted each time it is met. Meeting the opponent's cue ball first is no foul.
- the striker plays on after a point; an inning ends at the first stroke that scores
  nothing (UMB Art. 24), and each seat's innings are counted.
- fouls (UMB Art. 41) the engine can tell: the opening stroke not on the red, and the shot
  clock. Striking the wrong cue ball cannot happen (the server strikes the striker's);
  the engine has no cue to push or touch a ball with. A foul scores nothing and ends the
  inning; the balls stay where they stopped.
- a ball bounding off the table (UMB Art. 28, a raised cue's jump): a foul that ends the
  inning; the balls are set up as at the opening with the next striker's ball on a
  starting spot (as for balls in contact: the server does not judge the Article's spot
  by spot placement).
- balls in contact (UMB Art. 27): when the striker's cue ball comes to rest touching
  another ball, the balls are set up as at the opening, the striker's on a starting spot
  (the UMB lets the striker choose between that and playing away; the server sets up).
- the end (UMB Art. 29): the first to `race_to` points wins. With equal innings the other
  player then has a last inning: passing the opener's points wins; short of them, the
  opener wins; level, the two play on a pair of innings at a time until one leads after a
  pair (the UMB breaks ties with penalty shots, which a race online leaves out).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace

from typing_extensions import override

from server.engine import BallSet, Table
from server.engine.rack import RED, carom_placement

from .carom_score import CaromScore, is_point
from .outcome import Foul
from .position import Position
from .ruling import Ruling
from .shotfacts import ShotFacts
from .strategy import GameRules

FROZEN_GAP = 1e-4  # m between two balls that are touching (a sheet of paper's thickness)
BALL_NAMES = {0: "the white", 1: "the yellow", 2: "the red"}


class ThreeCushionRules(GameRules):
    """Three-cushion as a `GameRules` strategy (module docstring: what it judges)."""

    kind = "three_cushion"
    seats = 2
    rack = "three_cushion"
    breaks = False
    opening_ball_in_hand = None
    rerack_at_will = False
    spot_choice: tuple[int, ...] = ()

    @override
    def table(self) -> Table:
        return Table.carom()

    @override
    def new_carom(self, opener: int) -> CaromScore | None:
        return CaromScore.start(opener)

    @override
    def cue_ball(self, pos: Position) -> int:
        return pos.carom.cue_ball(pos.turn) if pos.carom else 0

    @override
    def legal_targets(self, pos: Position) -> list[int]:
        """The red on the opening stroke (UMB Art. 23); otherwise any ball."""
        return [RED] if pos.carom and pos.carom.opening else []

    @override
    def balls_left(self, pos: Position) -> list[list[int]] | None:
        return None

    @override
    def requires_call(self, pos: Position) -> bool:
        return False

    @override
    def ball_names(self, ball_ids: Sequence[int]) -> str:
        return " and ".join(BALL_NAMES.get(b, f"ball {b}") for b in ball_ids)

    @override
    def judge(self, pos: Position, facts: ShotFacts) -> Ruling:
        score = pos.carom or CaromScore.start(pos.turn)
        seat, name = pos.turn, pos.shooter
        cue = score.cue_ball(seat)
        if score.opening and (not facts.cue_path or facts.cue_path[0] != RED):
            foul = Foul("opening", f"{name}'s opening stroke did not hit the red first.")
            return self._inning_over(pos, score, Ruling(fouls=[foul]), facts)
        if facts.off_table or facts.cue_off_table:
            return self._off_table(pos, score, facts)
        if not is_point(facts.cue_path, cue):
            ruling = Ruling(notes=[_miss_words(facts.cue_path, cue)])
            return self._inning_over(pos, score, ruling, facts)
        score = score.scored(seat)
        ruling = Ruling(continues=True, carom=score)
        ruling.notes.append(f"Point for {name} ({score.points[seat]}; run {score.run}).")
        _end_on_point(pos, score, ruling)
        if ruling.winner is None:
            next_cue = cue if ruling.continues else score.cue_ball(pos.opponent)
            _set_up_if_frozen(pos, facts, next_cue, ruling)
        return ruling

    def _inning_over(
        self, pos: Position, score: CaromScore, ruling: Ruling, facts: ShotFacts | None
    ) -> Ruling:
        """The striker's inning ends: the other seat's begins, unless the game ends."""
        seat, other = pos.turn, pos.opponent
        ruling.continues = False
        ruling.carom = score.inning_over(other)
        if score.last_inning and seat != score.opener:
            _end_of_last_inning(pos, score, ruling)
        if ruling.winner is None and facts is not None:
            _set_up_if_frozen(pos, facts, score.cue_ball(other), ruling)
        return ruling

    def _off_table(self, pos: Position, score: CaromScore, facts: ShotFacts) -> Ruling:
        """UMB Art. 28: a ball off the table is a foul; the balls are set up again."""
        off = [*([score.cue_ball(pos.turn)] if facts.cue_off_table else []), *facts.off_table]
        said = self.ball_names(off)
        foul = Foul("ball_off_table", f"{pos.shooter} drove {said} off the table.")
        ruling = self._inning_over(pos, score, Ruling(fouls=[foul]), None)
        if ruling.winner is None:
            ruling.spot = (score.cue_ball(pos.opponent),)
            ruling.notes.append("The balls are set up as at the opening.")
        return ruling

    @override
    def timeout(self, pos: Position) -> Ruling:
        """A foul (UMB Art. 41): the inning ends."""
        score = pos.carom or CaromScore.start(pos.turn)
        foul = Foul("shot_clock", f"{pos.shooter} ran out of time.")
        return self._inning_over(pos, score, Ruling(fouls=[foul]), None)

    @override
    def count_fouls(self, fouls_in_row: Sequence[int], seat: int, fouled: bool) -> list[int]:
        counts = list(fouls_in_row)
        counts[seat] = counts[seat] + 1 if fouled else 0
        return counts

    @override
    def foul_warning(self, fouls_in_row: Sequence[int], seat: int, name: str) -> str | None:
        return None

    @override
    def respot(self, table: Table, balls: BallSet, ball_ids: tuple[int, ...]) -> BallSet:
        """The balls set up as at the opening, `ball_ids[0]` (the striker's) on a starting
        spot (UMB Art. 27)."""
        out = balls
        for ball, xy in carom_placement(table, ball_ids[0]).items():
            out = out.with_ball(ball, xy)
        return out


def _miss_words(path: Sequence[int], cue: int) -> str:
    """What the stroke lacked, for the outcome line."""
    met = {b for b in path if b >= 0 and b != cue}
    cushions = sum(1 for b in path if b < 0)
    if len(met) < 2:
        return f"No point: the cue ball met {len(met)} of the two balls."
    return f"No point: {min(cushions, 2)} cushions before the second ball."


def _end_on_point(pos: Position, score: CaromScore, ruling: Ruling) -> None:
    """After a point: does it end the game, or the opener's inning (equal innings)?"""
    seat, other = pos.turn, pos.opponent
    if score.last_inning:
        if seat != score.opener and score.points[seat] > score.points[score.opener]:
            ruling.winner, ruling.reason = seat, f"{pos.shooter} passes in the last inning."
        return
    if score.points[seat] < score.race_to:
        return
    if not score.equal_innings or seat != score.opener:
        ruling.winner = seat
        ruling.reason = f"{pos.shooter} reaches {score.race_to} points."
        return
    # UMB Art. 29: the opener reached the distance; the other player has a last inning.
    ruling.continues = False
    ruling.carom = replace(score.inning_over(other), last_inning=True)
    ruling.notes.append(f"{pos.players[other]} plays a last inning (equal innings).")


def _end_of_last_inning(pos: Position, score: CaromScore, ruling: Ruling) -> None:
    """The other player's last inning ended: the leader wins; level, play on."""
    seat, opener = pos.turn, score.opener
    if score.points[opener] > score.points[seat]:
        ruling.winner = opener
        ruling.reason = f"{pos.players[opener]} keeps the lead after equal innings."
    else:
        ruling.notes.append("Level after equal innings: another inning each.")


def _set_up_if_frozen(pos: Position, facts: ShotFacts, next_cue: int, ruling: Ruling) -> None:
    """UMB Art. 27: the next striker's ball at rest touching another ball: set up."""
    final = facts.final
    if final is None:
        return
    x, y = final.position_of(next_cue)
    reach = 2 * pos.table.ball_radius + FROZEN_GAP
    for ball in final.ids.tolist():
        if ball == next_cue:
            continue
        bx, by = final.position_of(ball)
        if math.hypot(bx - x, by - y) <= reach:
            ruling.spot = (next_cue,)
            ruling.notes.append("The balls are touching: they are set up as at the opening.")
            return


class ThreeCushionPracticeRules(ThreeCushionRules):
    """Three-cushion practice: one player on the white from the opening position, every
    stroke judged and counted as in a game (points, innings, runs) but never a foul and
    never over; the balls stay where they stop, a re-rack sets the opening up again."""

    kind = "three_cushion_practice"
    seats = 1
    rerack_at_will = True

    @override
    def new_carom(self, opener: int) -> CaromScore | None:
        return CaromScore.start_alone(race_to=PRACTICE_RACE)

    @override
    def judge(self, pos: Position, facts: ShotFacts) -> Ruling:
        ruling = super().judge(pos, facts)
        return _alone(ruling)

    @override
    def timeout(self, pos: Position) -> Ruling:
        return Ruling(continues=True, notes=["Time ran out."])

    @override
    def _inning_over(
        self, pos: Position, score: CaromScore, ruling: Ruling, facts: ShotFacts | None
    ) -> Ruling:
        ruling.carom = score.inning_over(pos.turn)
        if facts is not None:
            _set_up_if_frozen(pos, facts, score.cue_ball(pos.turn), ruling)
        return ruling


PRACTICE_RACE = 10**6  # practice is never won


def _alone(ruling: Ruling) -> Ruling:
    """Alone at the table the player always plays on: a foul only says what was wrong."""
    ruling.notes = [f.message for f in ruling.fouls] + ruling.notes
    ruling.fouls = []
    ruling.continues = True
    ruling.winner = ruling.reason = None
    return ruling
