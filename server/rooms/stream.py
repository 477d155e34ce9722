"""`RoomStream`: what a room sends its members, and the room sequence numbers.

Nothing here awaits a client: messages are pushed into each member's bounded outbox
(`Connection`) and its own task sends them; the players' at once, the spectators' a few
per turn of the loop (`FanOut`). Game messages carry the next `seq`; relays and replies
carry none. While a shot is shown its `motion` message is kept, so a member joining then
gets the same message and plays from where the others are.
"""

from __future__ import annotations

import asyncio

from server.config import Settings
from server.protocol import ShotPlan
from server.protocol.motion import with_seq
from server.protocol.outbound import (
    Presence,
    ResultCause,
    Sequenced,
    ServerMessage,
    ShotResultMessage,
    StateMessage,
    text,
)
from server.rules import Outcome

from .connection import Connection
from .fanout import FanOut
from .room import Room
from .throttle import Throttle
from .timers import SeatTimers


class RoomStream:
    """The members' connections (by id) and everything sent to them."""

    def __init__(self, room: Room, settings: Settings, timers: SeatTimers) -> None:
        self.room = room
        self.pace = settings.pace
        self.timers = timers
        self.members: dict[int, Connection] = {}
        self.seq = 0
        self._fanout = FanOut()  # players first, spectators in turn
        # The shot being shown: its plan, its `motion` message as sent, the loop time of
        # its start.
        self._motion: tuple[ShotPlan, bytes, float] | None = None
        # Who is here, at most once every `presence_interval`: the rest of a burst of
        # joins and leaves (a crowd reconnecting in a loop) is summed up in one message.
        self._presence = Throttle(settings.presence_interval, self._send_presence)

    def close(self) -> None:
        self._presence.stop()

    # ---- to everyone --------------------------------------------------------------------

    def broadcast(self, message: Sequenced, droppable: bool = False, social: bool = False) -> None:
        """Send to every member with the next room sequence number."""
        self.seq += 1
        message.seq = self.seq
        self._fanout.send(list(self.members.values()), text(message), droppable, social)

    def relay(self, message: ServerMessage, exclude: Connection | None) -> None:
        """Send to everyone else, without a sequence number, droppable (aim relays)."""
        self._fanout.send(list(self.members.values()), text(message), True, exclude=exclude)

    def broadcast_state(self) -> None:
        self.seq += 1
        self._fanout.send(list(self.members.values()), self.state_text(self.seq))

    def broadcast_presence(self) -> None:
        self._presence.request()

    def _send_presence(self) -> None:
        presence = Presence(
            players=self.room.players_info(),
            spectators=self.room.spectators,
            grace=self.timers.grace_info(),
        )
        self.broadcast(presence, social=True)

    def broadcast_result(self, shot_id: int | None, cause: ResultCause, outcome: Outcome) -> None:
        match = self.room.match
        assert match is not None
        self.broadcast(
            ShotResultMessage(
                shot=shot_id,
                cause=cause,
                outcome=outcome,
                score=list(match.score),
                match_over=match.over,
                match_winner=match.winner,
            )
        )

    # ---- to one member ------------------------------------------------------------------

    def reply(self, conn: Connection, message: ServerMessage) -> None:
        self._fanout.send_one(conn, text(message))

    def send_state(self, conn: Connection) -> None:
        """The `state` for one member (on connecting or `sync`), with the chat so far."""
        self._fanout.send_one(conn, self.state_text(self.seq, chat=True))

    def send_motion(self, conn: Connection) -> None:
        """The `motion` of the shot being shown, if any, for a member joining now."""
        if self._motion is not None:
            self._fanout.send_one(conn, self._motion[1])

    # ---- the table ----------------------------------------------------------------------

    def state_message(self, chat: bool = False) -> StateMessage:
        return self.room.state_message(self.timers.clock_info(), self.timers.grace_info(), chat)

    def state_text(self, seq: int, chat: bool = False) -> str:
        """The `state` message as JSON, the table's geometry spliced in from its cached
        text: ~1.5 KB that never changes; encoding it after every shot cost ~0.15 ms of the
        loop each time."""
        self._show_now()
        message = self.state_message(chat)
        message.seq = seq
        return f'{text(message, exclude={"table"})[:-1]},"table":{self.room.table_json()}}}'

    def _show_now(self) -> None:
        """Bring the room's shown frame up to now, for a `state` sent while balls roll."""
        if self._motion is not None:
            plan, _, start = self._motion
            elapsed = (asyncio.get_running_loop().time() - start) * self.pace
            self.room.show(plan.shown_at(elapsed), plan.frames)

    # ---- a shot -------------------------------------------------------------------------

    def hold(self) -> None:
        """The spectators' copies wait (while a shot is simulated); the players' go."""
        self._fanout.hold()

    def release(self) -> None:
        self._fanout.release()

    def broadcast_motion(self, plan: ShotPlan) -> None:
        """The shot's binary `motion` message to every member, with the next sequence
        number (set in its header once, not per member)."""
        self.seq += 1
        motion = with_seq(plan.motion, self.seq)
        self._motion = (plan, motion, asyncio.get_running_loop().time())
        self._fanout.send(list(self.members.values()), motion)

    def motion_shown(self) -> None:
        self._motion = None
