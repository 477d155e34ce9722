"""A drill's practice table: set up from the stored position when its seat is taken (the
ball in hand as it was, no break), kept through a restart, its first shot judged made or
not."""

from __future__ import annotations

from server.engine import Table, rack
from server.rooms.drills import DrillSetup, made
from server.rooms.room import Room
from server.rooms.snapshot import room_from_snapshot, room_to_snapshot
from server.rules import Foul, Outcome
from server.rules.outcome import ANYWHERE

TABLE = Table.pool("9ft")


def setup() -> DrillSetup:
    balls = rack("eight_ball", TABLE, seed=3).with_ball(0, (0.5, 0.4))
    return DrillSetup(balls.to_dict(), ANYWHERE, 0.75, match_id=4, n=9)


def test_the_drill_table_is_the_stored_one_with_its_ball_in_hand() -> None:
    room = Room("r1", "practice", setup=setup())
    room.join("Ana")
    assert room.match is not None
    game = room.match.game
    assert game.balls.to_dict() == setup().balls
    assert (game.ball_in_hand, game.breaking) == (ANYWHERE, False)
    info = room.room_info().drill
    assert info is not None
    assert (info.match, info.n, info.par, info.made) == (4, 9, 0.75, None)


def test_a_drill_room_keeps_its_setup_through_a_restart() -> None:
    room = Room("r2", "practice", setup=setup())
    restored = room_from_snapshot(room_to_snapshot(room, None)).room
    assert restored.setup == setup()
    restored.join("Ana")
    assert restored.match is not None
    assert restored.match.game.balls.to_dict() == setup().balls


def _outcome(pocketed: tuple[int, ...], fouls: tuple[Foul, ...] = ()) -> Outcome:
    return Outcome(0, pocketed, fouls, bool(pocketed), 0, None, False, None, None, "")


def test_a_position_is_made_by_a_ball_pocketed_without_a_foul() -> None:
    assert made(_outcome((3,)))
    assert not made(_outcome(()))
    assert not made(_outcome((0,)))
    assert not made(_outcome((3, 0), (Foul("scratch", "Scratch."),)))
