"""A room on the event loop: its members, their messages, and what follows each action.

`Room` decides; `LiveRoom` drives it and sees each action through: the stream to the
members (`RoomStream`), the shot clock and reconnection grace (`SeatTimers`), shots
simulated and shown (`ShotPlayer`), the computer's seats (`ComputerTurns`) and the chat
(`RoomChat`) are its parts; it tells the observer (storage) what happened.
"""

from __future__ import annotations

import logging
from dataclasses import replace
from typing import assert_never

from server.config import Settings
from server.engine import TICK_HZ, BallSet, Shot
from server.protocol import LIMITS, ShotPlan
from server.protocol.inbound import (
    Aim,
    AnyClientMessage,
    Call,
    Chat,
    Concede,
    Decide,
    Nominate,
    Ping,
    PlaceCue,
    PushOut,
    Rematch,
    Rerack,
    Shoot,
    Sync,
)
from server.protocol.limits import FRAMES_PER_MESSAGE
from server.protocol.outbound import (
    AimRelay,
    ErrorMessage,
    GraceInfo,
    Pong,
    ResultCause,
    StateMessage,
    Welcome,
)
from server.rules import Outcome

from .chat import RoomChat
from .clock import SYSTEM_CLOCK, Clock
from .computer_turns import ComputerTurns
from .connection import CLOSE_REPLACED, Connection
from .errors import ActionError
from .metrics import StreamMetrics
from .observer import NullObserver, RoomObserver
from .room import Room
from .shot_runner import ShotRunner
from .shots import ShotPlayer
from .stream import RoomStream
from .timers import SeatTimers

log = logging.getLogger(__name__)


class LiveRoom:
    """Drives one `Room`: members come and go, their messages act on it, and every change
    is sent, timed and recorded. `runner` and `metrics` are the server's, shared by all
    rooms."""

    def __init__(
        self,
        room: Room,
        settings: Settings,
        observer: RoomObserver | None = None,
        clock: Clock = SYSTEM_CLOCK,
        *,
        runner: ShotRunner,
        metrics: StreamMetrics,
    ) -> None:
        self.room = room
        self.settings = settings
        self.clock = clock
        self.observer: RoomObserver = observer or NullObserver()
        self.metrics = metrics
        self.last_activity = self.clock.monotonic()
        self.ever_joined = False
        self.closed = False
        self.timers = SeatTimers(room, settings.grace, self)
        self.stream = RoomStream(room, settings, self.timers)
        self.shots = ShotPlayer(room, self.stream, runner, metrics, settings.pace, self)
        self.computers = ComputerTurns(room, settings, self.stream, self)
        self.chat = RoomChat(room, self.stream, settings, clock)

    @property
    def members(self) -> dict[int, Connection]:
        """Connected members by connection id."""
        return self.stream.members

    def state_message(self, chat: bool = False) -> StateMessage:
        return self.stream.state_message(chat)

    def grace_info(self) -> list[GraceInfo]:
        return self.timers.grace_info()

    # ---- membership -------------------------------------------------------------------

    def touch(self) -> None:
        self.last_activity = self.clock.monotonic()

    def on_joined(self) -> None:
        """A seat was taken over HTTP: tell the room; start the match clocks when full."""
        self.touch()
        self.ever_joined = True
        if self.room.match is not None and self.room.phase != "rolling":
            self.timers.grace_for_absent()
            self.next_turn(restart=True)
        self.stream.broadcast_state()
        self.observer.room_changed(self.room)

    def attach(self, conn: Connection) -> None:
        """A member connected: replace an older socket of the same seat, send welcome,
        state, and the motion of a shot being shown (to play from now)."""
        self.touch()
        conn.on_drop = self.metrics.skipped
        if conn.seat is not None:
            self._replace_seat(conn.seat)
        else:
            self.room.spectators += 1
        self.members[conn.id] = conn
        self.stream.reply(conn, self._welcome(conn))
        self.stream.send_state(conn)
        self.stream.broadcast_presence()
        self.stream.send_motion(conn)

    def _replace_seat(self, seat_index: int) -> None:
        for other in list(self.members.values()):
            if other.seat == seat_index:
                other.close(CLOSE_REPLACED, "replaced")
                del self.members[other.id]
        seat = self.room.seats[seat_index]
        assert seat is not None
        seat.connected = True
        seat.seen = True
        self.timers.cancel_grace(seat_index)

    def _welcome(self, conn: Connection) -> Welcome:
        return Welcome(
            room_id=self.room.room_id,
            seat=conn.seat,
            role="spectator" if conn.seat is None else "player",
            name=conn.name,
            seq=self.stream.seq,
            tick_hz=TICK_HZ,
            frame_every=self.settings.frame_every,
            frames_per_message=FRAMES_PER_MESSAGE,
            server_time=self.clock.wall(),
            limits=LIMITS,
        )

    def detach(self, conn: Connection) -> None:
        """A member's socket ended. A player keeps the seat for the grace period."""
        self.touch()
        if self.members.pop(conn.id, None) is None:
            return  # already replaced by a newer socket
        if conn.seat is None:
            self.room.spectators -= 1
        elif not any(m.seat == conn.seat for m in self.members.values()):
            seat = self.room.seats[conn.seat]
            assert seat is not None
            seat.connected = False
            self.timers.start_grace(conn.seat)
        if not self.closed:
            self.stream.broadcast_presence()

    def close(self, code: int, reason: str) -> None:
        """Stop clocks and the stream; ask every member's socket to close."""
        self.closed = True
        self.shots.cancel()
        self.stream.close()
        self.computers.cancel()
        self.timers.cancel_all()
        for conn in list(self.members.values()):
            conn.close(code, reason)
        self.observer.room_closed(self.room)

    def is_idle(self, now: float) -> bool:
        if self.members:
            return False
        ttl = self.settings.idle_ttl if self.ever_joined else self.settings.waiting_ttl
        if self.ever_joined and self.room.practice:
            ttl = min(ttl, self.settings.practice_ttl)  # its player left: nobody else plays it
        return now - self.last_activity > ttl

    def resume(self, pending: tuple[int, Shot] | None = None) -> None:
        """A room restored after a restart (storage): players have the grace period to
        reconnect with their tokens; a shot that was in flight is played again from its
        stored start (same result, bit for bit)."""
        self.ever_joined = any(s is not None for s in self.room.seats)
        for i, s in enumerate(self.room.seats):
            if s is not None:
                self.timers.start_grace(i)
        if pending is not None:
            try:
                self.start_shot(*pending)
                return
            except ActionError as exc:
                log.warning("room %s: stored shot not replayed: %s", self.room.room_id, exc.message)
        self.next_turn(restart=True)

    # ---- messages from members ----------------------------------------------------------

    def handle(self, conn: Connection, msg: AnyClientMessage) -> None:
        """Act on one validated message; a refusal is an `error` reply, nothing changes."""
        self.touch()
        try:
            self._dispatch(conn, msg)
        except ActionError as exc:
            self.stream.reply(conn, ErrorMessage(code=exc.code, message=exc.message, ref=msg.type))

    def _dispatch(self, conn: Connection, msg: AnyClientMessage) -> None:
        room, seat = self.room, conn.seat
        match msg:
            case Ping(id=ping_id):
                self.stream.reply(conn, Pong(id=ping_id, server_time=self.clock.wall()))
            case Sync():
                self.stream.send_state(conn)
            case Chat(text=line):
                self.chat.say(conn, line)
            case Aim(angle=angle, power=power, tip=tip, elevation=elevation, cue=cue):
                room.check_aim(seat)
                relay = AimRelay(
                    seat=seat, angle=angle, power=power, tip=tip, elevation=elevation, cue=cue
                )
                self.stream.relay(relay, exclude=conn)
            case Shoot(angle=angle, speed=speed, tip=tip, elevation=elevation):
                self.start_shot(seat, _shot(angle, speed, tip, elevation))
            case PlaceCue() | Call() | Nominate() | Decide() | PushOut() | Rerack():
                self._arrange(seat, msg)
                self.changed()
            case Concede(game=game):
                self.conclude("concede", room.concede(seat, game))
            case Rematch():
                self._rematch(seat)
            case _:
                assert_never(msg)

    def _arrange(
        self, seat: int | None, msg: PlaceCue | Call | Nominate | Decide | PushOut | Rerack
    ) -> None:
        """The actions that set the table up for the next shot (each then `changed`)."""
        room = self.room
        match msg:
            case PlaceCue(x=x, y=y):
                room.place_cue(seat, x, y)
            case Call(pocket=pocket):
                room.call_pocket(seat, pocket)
            case Nominate(ball=ball):
                room.nominate(seat, ball)
            case Decide(option=option, game=game):
                room.decide(seat, option, game)
            case PushOut():
                room.push_out(seat)
            case Rerack():
                room.rerack(seat)
            case _:
                assert_never(msg)

    def _rematch(self, seat: int | None) -> None:
        room = self.room
        started = room.vote_rematch(seat)
        for computer_seat in room.computer:  # the computer always wants another
            if not started and computer_seat != seat:
                started = room.vote_rematch(computer_seat)
        if started:
            self.timers.grace_for_absent()
            self.next_turn(restart=True)
            self.observer.room_changed(room)
        self.stream.broadcast_state()

    # ---- what follows an action -----------------------------------------------------------

    def changed(self) -> None:
        """The position changed (not by a shot): the clock, if the turn moved; `state`."""
        self.next_turn(restart=False)
        self.stream.broadcast_state()
        self.observer.room_changed(self.room)

    def next_turn(self, restart: bool) -> None:
        """Wake the computer if it is to act, and run the shot clock for the seat to act
        (`restart`: afresh, even for the same seat)."""
        if not self.closed:
            self.computers.wake()
        self.timers.arm_clock(restart)

    def start_shot(self, seat: int | None, shot: Shot, intended: Shot | None = None) -> None:
        """Strike `shot` for `seat` (refused with `ActionError`), then simulate and show;
        `intended`: the stroke meant, when it differs (the computer's plan), for the record."""
        shot_id, before = self.room.begin_shot(seat, intended)
        assert seat is not None
        shot = replace(shot, ball=self.room.cue_ball())  # carom: the striker's own ball
        self.timers.cancel_clock()
        kept = self.observer.shot_started(self.room, seat, shot, shot_id)
        self.shots.start(seat, shot, shot_id, before, kept)

    def shot_shown(
        self, seat: int, shot: Shot, shot_id: int, before: BallSet, outcome: Outcome, plan: ShotPlan
    ) -> None:
        """Recorded only now: history, replays and the lobby must not tell a shot's
        outcome before its members have seen it."""
        self.observer.shot_played(self.room, seat, shot, before, outcome, plan)
        self.stream.broadcast_result(shot_id, "shot", outcome)
        self.room.end_shot()
        self._after_result()

    def shot_failed(self) -> None:
        self.next_turn(restart=True)
        self.stream.broadcast_state()

    def conclude(self, cause: ResultCause, outcome: Outcome, absent: int | None = None) -> None:
        """A non-shot outcome (timeout, concession, forfeit): result, next rack, state.
        `absent`: a seat that forfeited and is still away; the next frame is at stake."""
        self.stream.broadcast_result(None, cause, outcome)
        self.observer.outcome(self.room, cause, outcome)
        self.room.after_outcome()
        if absent is not None:
            self.timers.start_grace(absent)
        self._after_result()

    def abandon(self) -> None:
        """Every player is gone past the grace: the match stops without a winner (recorded
        as abandoned), instead of the absentees forfeiting frames to each other."""
        self.timers.cancel_all()
        self.room.abandon()
        self.stream.broadcast_state()
        self.observer.room_changed(self.room)

    def _after_result(self) -> None:
        self.next_turn(restart=True)
        self.stream.broadcast_state()
        self.observer.room_changed(self.room)


def _shot(angle: float, speed: float, tip: tuple[float, float], elevation: float) -> Shot:
    try:
        return Shot(angle, speed, tip, elevation)
    except ValueError as exc:
        raise ActionError("bad_message", str(exc)) from None
