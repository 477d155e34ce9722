"""A room on the event loop: members, the shot stream, the shot clock and reconnection grace.

`Room` decides; `LiveRoom` times and sends. Nothing here awaits a client: messages are
pushed into each member's bounded outbox (`Connection`) and its own task sends them; the
players' at once, the spectators' a few per turn of the loop (`FanOut`).
"""

from __future__ import annotations

import asyncio
import functools
import logging
import math
import time
from dataclasses import dataclass

from server.ai import Turn
from server.config import Settings
from server.engine import TICK_HZ, BallSet, Shot
from server.protocol import LIMITS, ShotPlan
from server.protocol.inbound import (
    Aim,
    AnyClientMessage,
    Chat,
    Concede,
    Decide,
    PlaceCue,
    Shoot,
)
from server.protocol.motion import with_seq
from server.protocol.outbound import (
    AimRelay,
    ClockInfo,
    ErrorMessage,
    GraceInfo,
    Pong,
    Presence,
    ResultCause,
    Sequenced,
    ServerMessage,
    ShotResultMessage,
    StateMessage,
    Welcome,
    text,
)
from server.rules import Outcome

from .clock import SYSTEM_CLOCK, Clock
from .computer import ComputerSeat
from .connection import CLOSE_REPLACED, Connection
from .errors import ActionError
from .fanout import FanOut
from .metrics import StreamMetrics
from .observer import NullObserver, RoomObserver
from .ratelimit import TokenBucket
from .room import Room, Seat
from .shot_runner import ShotRunner

log = logging.getLogger(__name__)
SLOW_SHOT = 0.25  # s from strike to stream start worth a warning in the log


@dataclass
class _Timer:
    seat: int
    deadline: float  # loop time
    handle: asyncio.TimerHandle


class LiveRoom:
    """Drives one `Room`: dispatches members' messages, streams shots, runs the clocks."""

    def __init__(
        self,
        room: Room,
        settings: Settings,
        observer: RoomObserver | None = None,
        clock: Clock = SYSTEM_CLOCK,
    ) -> None:
        self.room = room
        self.settings = settings
        self.clock = clock
        self.observer: RoomObserver = observer or NullObserver()
        self.members: dict[int, Connection] = {}
        self._fanout = FanOut()  # what is sent to them: players first, spectators in turn
        self.seq = 0
        self.last_activity = self.clock.monotonic()
        self.ever_joined = False
        self.metrics = StreamMetrics(capacity=1)  # the registry shares one for all rooms
        self.runner = ShotRunner(0, settings.frame_every)
        self._clock: _Timer | None = None
        self._grace: dict[int, _Timer] = {}
        self._stream: asyncio.Task | None = None
        # The shot being shown: its plan, its `motion` message as sent, the loop time of
        # its start (a member joining now gets the same message and plays from there).
        self._motion: tuple[ShotPlan, bytes, float] | None = None
        self._presence_timer: asyncio.TimerHandle | None = None
        # All spectators together: however many there are, the players get at most this.
        self._crowd_chat = TokenBucket(
            settings.crowd_chat_burst, settings.crowd_chat_per_second, clock.monotonic
        )
        self._last_presence = -math.inf
        self.computers = {
            seat: ComputerSeat(
                room,
                seat,
                level,
                settings.computer_pause,
                settings.computer_workers,
                settings.computer_starved,
            )
            for seat, level in room.computer.items()
        }
        self.closed = False

    # ---- sending ----------------------------------------------------------------------

    def broadcast(self, message: Sequenced, droppable: bool = False, social: bool = False) -> None:
        """Send to every member with the next room sequence number."""
        self.seq += 1
        message.seq = self.seq
        self._fanout.send(list(self.members.values()), text(message), droppable, social)

    def broadcast_motion(self, plan: ShotPlan) -> None:
        """The shot's binary `motion` message to every member, with the next sequence
        number (set in its header once, not per member)."""
        self.seq += 1
        motion = with_seq(plan.motion, self.seq)
        self._motion = (plan, motion, asyncio.get_running_loop().time())
        self._fanout.send(list(self.members.values()), motion)

    def _show_now(self) -> None:
        """Bring the room's shown frame up to now, for a `state` sent while balls roll."""
        if self._motion is not None:
            plan, _, start = self._motion
            elapsed = (asyncio.get_running_loop().time() - start) * self.settings.pace
            self.room.show(plan.shown_at(elapsed), plan.frames)

    def relay(self, message: ServerMessage, exclude: Connection | None) -> None:
        """Send to everyone else, without a sequence number, droppable (aim relays)."""
        self._fanout.send(list(self.members.values()), text(message), True, exclude=exclude)

    def reply(self, conn: Connection, message: ServerMessage) -> None:
        self._fanout.send_one(conn, text(message))

    def state_message(self, chat: bool = False) -> StateMessage:
        return self.room.state_message(self.clock_info(), self.grace_info(), chat)

    def state_text(self, seq: int, chat: bool = False) -> str:
        """The `state` message as JSON, the table's geometry spliced in from its cached
        text: ~1.5 KB that never changes; encoding it after every shot cost ~0.15 ms of the
        loop each time."""
        self._show_now()
        message = self.state_message(chat)
        message.seq = seq
        return f'{text(message, exclude={"table"})[:-1]},"table":{self.room.table_json()}}}'

    def send_state(self, conn: Connection) -> None:
        """The `state` for one member (on connecting or `sync`), with the chat so far."""
        self._fanout.send_one(conn, self.state_text(self.seq, chat=True))

    def broadcast_state(self) -> None:
        self.seq += 1
        self._fanout.send(list(self.members.values()), self.state_text(self.seq))

    def broadcast_presence(self) -> None:
        """Who is here. At most one every `presence_interval`: the rest of a burst of joins
        and leaves (a crowd reconnecting in a loop) is summed up in one trailing message."""
        if self.settings.presence_interval <= 0:
            self._send_presence()
            return
        if self._presence_timer is not None:
            return  # a summary is already due
        loop = asyncio.get_running_loop()
        wait = self._last_presence + self.settings.presence_interval - loop.time()
        if wait > 0:
            self._presence_timer = loop.call_later(wait, self._send_presence)
            return
        self._send_presence()

    def _send_presence(self) -> None:
        self._presence_timer = None
        if self.closed:
            return
        if self.settings.presence_interval > 0:
            self._last_presence = asyncio.get_running_loop().time()
        presence = Presence(
            players=self.room.players_info(),
            spectators=self.room.spectators,
            grace=self.grace_info(),
        )
        self.broadcast(presence, social=True)

    # ---- membership -------------------------------------------------------------------

    def touch(self) -> None:
        self.last_activity = self.clock.monotonic()

    def on_joined(self, seat: int) -> None:
        """A seat was taken over HTTP: tell the room; start the match clocks when full."""
        self.touch()
        self.ever_joined = True
        if self.room.match is not None and self.room.phase != "rolling":
            for i, s in enumerate(self.room.seats):
                if s is not None and not s.connected:
                    self._start_grace(i)
            self._arm_clock(restart=True)
        self.broadcast_state()
        self.observer.room_changed(self.room)

    def attach(self, conn: Connection) -> None:
        """A member connected: replace an older socket of the same seat, send welcome+state."""
        self.touch()
        if conn.seat is not None:
            for other in list(self.members.values()):
                if other.seat == conn.seat:
                    other.close(CLOSE_REPLACED, "replaced")
                    del self.members[other.id]
            seat = self.room.seats[conn.seat]
            assert seat is not None
            seat.connected = True
            seat.seen = True
            self._cancel_grace(conn.seat)
        else:
            self.room.spectators += 1
        self.members[conn.id] = conn
        self.reply(
            conn,
            Welcome(
                room_id=self.room.room_id,
                seat=conn.seat,
                role="spectator" if conn.seat is None else "player",
                name=conn.name,
                seq=self.seq,
                tick_hz=TICK_HZ,
                frame_every=self.settings.frame_every,
                frames_per_message=self.settings.frames_per_message,
                server_time=self.clock.wall(),
                limits=LIMITS,
            ),
        )
        self.send_state(conn)
        self.broadcast_presence()
        if self._motion is not None:  # a shot is being shown: its motion, to play from now
            self._fanout.send_one(conn, self._motion[1])

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
            self._start_grace(conn.seat)
        if not self.closed:
            self.broadcast_presence()

    def close(self, code: int, reason: str) -> None:
        """Stop clocks and the stream; ask every member's socket to close."""
        self.closed = True
        if self._stream is not None:
            self._stream.cancel()
        if self._presence_timer is not None:
            self._presence_timer.cancel()
        for computer in self.computers.values():
            computer.cancel()
        self._cancel_clock()
        for seat in list(self._grace):
            self._cancel_grace(seat)
        for conn in list(self.members.values()):
            conn.close(code, reason)
        self.observer.room_closed(self.room)

    def is_idle(self, now: float) -> bool:
        if self.members:
            return False
        ttl = self.settings.idle_ttl if self.ever_joined else self.settings.waiting_ttl
        return now - self.last_activity > ttl

    # ---- messages from members ----------------------------------------------------------

    def handle(self, conn: Connection, msg: AnyClientMessage) -> None:
        """Act on one validated message; a refusal is an `error` reply, nothing changes."""
        self.touch()
        try:
            self._dispatch(conn, msg)
        except ActionError as exc:
            self.reply(conn, ErrorMessage(code=exc.code, message=exc.message, ref=msg.type))

    def _dispatch(self, conn: Connection, msg: AnyClientMessage) -> None:
        room, seat = self.room, conn.seat
        match msg.type:
            case "ping":
                self.reply(conn, Pong(id=msg.id, server_time=self.clock.wall()))
            case "sync":
                self.send_state(conn)
            case "chat":
                assert isinstance(msg, Chat)
                self._chat(conn, msg.text)
            case "aim":
                assert isinstance(msg, Aim)
                room.check_aim(seat)
                self.relay(
                    AimRelay(seat=seat, angle=msg.angle, power=msg.power, tip=msg.tip, cue=msg.cue),
                    exclude=conn,
                )
            case "shoot":
                assert isinstance(msg, Shoot)
                self._shoot(seat, msg)
            case "place_cue":
                assert isinstance(msg, PlaceCue)
                room.place_cue(seat, msg.x, msg.y)
                self._changed()
            case "call":
                room.call_pocket(seat, msg.pocket)
                self._changed()
            case "decide":
                assert isinstance(msg, Decide)
                room.decide(seat, msg.option, msg.game)
                self._changed()
            case "push_out":
                room.push_out(seat)
                self._changed()
            case "rerack":
                room.rerack(seat)
                self._changed()
            case "concede":
                assert isinstance(msg, Concede)
                self._conclude("concede", room.concede(seat, msg.game))
            case "rematch":
                started = room.vote_rematch(seat)
                for computer_seat in room.computer:  # the computer always wants another
                    if not started and computer_seat != seat:
                        started = room.vote_rematch(computer_seat)
                if started:
                    for i, s in enumerate(room.seats):
                        if s is not None and not s.connected:
                            self._start_grace(i)
                    self._arm_clock(restart=True)
                    self.observer.room_changed(room)
                self.broadcast_state()

    def _chat(self, conn: Connection, text: str) -> None:
        """A chat line to everyone, within the sender's credits (and the spectators'
        together); a refusal is told once per streak, then dropped without a reply."""
        refusal = None
        if not conn.chat_allowed():
            refusal = ActionError("chat_rate_limited", "Too many chat messages; wait a moment.")
        elif conn.seat is None and not self._crowd_chat.take():
            refusal = ActionError("chat_busy", "The spectators' chat is full; wait a moment.")
        if refusal is not None:
            if conn.first_refusal():
                raise refusal
            return
        line = "".join(ch if ch.isprintable() else " " for ch in text).strip()
        if not line:
            raise ActionError("bad_message", "text: the message is empty")
        conn.accepted()
        self.broadcast(self.room.say(conn.seat, line, self.clock.wall()), social=True)

    def _changed(self) -> None:
        self._arm_clock(restart=False)
        self.broadcast_state()
        self.observer.room_changed(self.room)

    def resume(self, pending: tuple[int, Shot] | None = None) -> None:
        """A room restored after a restart (storage): players have the grace period to
        reconnect with their tokens; a shot that was in flight is played again from its
        stored start (same result, bit for bit)."""
        self.ever_joined = any(s is not None for s in self.room.seats)
        for i, s in enumerate(self.room.seats):
            if s is not None:
                self._start_grace(i)
        if pending is not None:
            try:
                self.start_shot(*pending)
                return
            except ActionError as exc:
                log.warning("room %s: stored shot not replayed: %s", self.room.room_id, exc.message)
        self._arm_clock(restart=True)

    # ---- shots ------------------------------------------------------------------------

    def _shoot(self, seat: int | None, msg: Shoot) -> None:
        try:
            shot = Shot(msg.angle, msg.speed, msg.tip)
        except ValueError as exc:
            raise ActionError("bad_message", str(exc)) from None
        self.start_shot(seat, shot)

    def start_shot(self, seat: int | None, shot: Shot) -> None:
        """Strike `shot` for `seat` (refused with `ActionError`), then simulate and stream."""
        shot_id, before = self.room.begin_shot(seat, shot)
        assert seat is not None
        self._cancel_clock()
        self.observer.shot_started(self.room, seat, shot, shot_id)
        self._fanout.hold()  # the spectators' copies wait while the shot is simulated
        self._stream = asyncio.get_running_loop().create_task(
            self._play(seat, shot, shot_id, before, time.perf_counter())
        )

    async def _play(
        self, seat: int, shot: Shot, shot_id: int, before: BallSet, started: float
    ) -> None:
        room = self.room
        assert room.match is not None
        table = room.match.game.table
        try:
            result, plan = await self.runner.prepare(table, before, shot, shot_id)
            prepared = time.perf_counter()
            outcome = room.apply_shot(result)
            judged = time.perf_counter()
            if judged - started > SLOW_SHOT:
                log.warning(
                    "room %s shot %s: %.0f ms to simulate and plan, %.0f ms to judge "
                    "(%d ticks, %d events, %s)",
                    room.room_id,
                    shot_id,
                    1000 * (prepared - started),
                    1000 * (judged - prepared),
                    len(result.frames),
                    len(result.events),
                    shot,
                )
        except Exception:
            log.exception("shot %s in room %s failed", shot_id, room.room_id)
            room.abort_shot()
            self._arm_clock(restart=True)
            self.broadcast_state()
            return
        finally:
            self._fanout.release()
        # The shot's events (hundreds of small objects) are judged and packed: let them go
        # now, not after the seconds it takes to show the shot (fewer live objects for the
        # cyclic collector to walk, docs/performance.md).
        del result
        loop = asyncio.get_running_loop()
        start = loop.time()
        self.metrics.shot_started(start, time.perf_counter() - started)
        pace = self.settings.pace
        try:
            # The whole motion at the strike: clients play it on their own clock.
            self.broadcast_motion(plan)
            self.metrics.sent(start, loop.time() - start)
            delay = start + plan.duration / pace - loop.time()
            if delay > 0:
                await asyncio.sleep(delay)
            room.show(plan.last, plan.frames)
        except Exception:  # a bug here must not leave the table busy for ever
            log.exception("streaming shot %s in room %s failed", shot_id, room.room_id)
        self._motion = None
        # Recorded only now: history, replays and the lobby must not tell a shot's outcome
        # before its members have seen it.
        self.observer.shot_played(room, seat, shot, before, outcome, plan)
        self._send_result(shot_id, "shot", outcome)
        room.end_shot()
        self._after_result()

    def _send_result(self, shot_id: int | None, cause: ResultCause, outcome: Outcome) -> None:
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

    def _after_result(self) -> None:
        self._arm_clock(restart=True)
        self.broadcast_state()
        self.observer.room_changed(self.room)

    def _conclude(self, cause: ResultCause, outcome: Outcome, absent: int | None = None) -> None:
        """A non-shot outcome (timeout, concession, forfeit): result, next rack, state.
        `absent`: a seat that forfeited and is still away; the next frame is at stake."""
        self._send_result(None, cause, outcome)
        self.observer.outcome(self.room, cause, outcome)
        self.room.after_outcome()
        if absent is not None:
            self._start_grace(absent)
        self._after_result()

    # ---- the computer -------------------------------------------------------------------

    def _wake_computer(self) -> None:
        """If the match now waits for a computer seat, let it take its turn."""
        for seat, computer in self.computers.items():
            if not self.closed and computer.due():
                computer.start(
                    functools.partial(self._computer_acts, seat),
                    functools.partial(self._computer_aims, seat),
                    self.settings.pace,
                )

    def _computer_aims(self, seat: int, angle: float, power: float) -> None:
        self.relay(AimRelay(seat=seat, angle=angle, power=power, tip=(0.0, 0.0)), None)

    def _computer_acts(self, seat: int, turn: Turn, shot: Shot | None) -> None:
        """The computer's turn through the same room actions as a person's."""
        room = self.room
        if turn.decision is not None:
            room.decide(seat, turn.decision)
            self._changed()
            return
        if turn.push_out:
            room.push_out(seat)
        if turn.place is not None:
            room.place_cue(seat, *turn.place)
        if turn.call is not None and room.match is not None and room.match.game.requires_call:
            room.call_pocket(seat, turn.call)
        if shot is not None:
            self.start_shot(seat, shot)

    # ---- shot clock ---------------------------------------------------------------------

    def clock_info(self) -> ClockInfo | None:
        if self._clock is None:
            return None
        remaining = max(0.0, self._clock.deadline - asyncio.get_running_loop().time())
        return ClockInfo(
            seat=self._clock.seat, remaining=round(remaining, 2), limit=self.room.shot_clock
        )

    def _arm_clock(self, restart: bool) -> None:
        self._wake_computer()
        seat = self.room.acting_seat() if self.room.shot_clock > 0 else None
        if seat is None:
            self._cancel_clock()
            return
        if not restart and self._clock is not None and self._clock.seat == seat:
            return
        self._cancel_clock()
        loop = asyncio.get_running_loop()
        limit = self.room.clock_limit()  # longer on the room's first break
        self._clock = _Timer(
            seat, loop.time() + limit, loop.call_later(limit, self._on_clock, seat)
        )

    def _cancel_clock(self) -> None:
        if self._clock is not None:
            self._clock.handle.cancel()
            self._clock = None

    def _on_clock(self, seat: int) -> None:
        self._clock = None
        if self.room.acting_seat() != seat:
            self._arm_clock(restart=True)
            return
        try:
            outcome = self.room.timeout(seat)
        except ActionError:
            log.warning("shot clock timeout refused in room %s", self.room.room_id)
            return
        self._conclude("timeout", outcome)

    # ---- reconnection grace ---------------------------------------------------------------

    def grace_info(self) -> list[GraceInfo]:
        if not self._grace:
            return []
        now = asyncio.get_running_loop().time()
        return [
            GraceInfo(seat=t.seat, remaining=round(max(0.0, t.deadline - now), 2))
            for t in sorted(self._grace.values(), key=lambda t: t.seat)
        ]

    def _start_grace(self, seat: int) -> None:
        match = self.room.match
        if self.room.practice or match is None or match.over or seat in self._grace:
            return
        if self.room.abandoned:
            return
        if seat in self.room.computer:
            return  # the computer never leaves
        loop = asyncio.get_running_loop()
        grace = self.settings.grace
        self._grace[seat] = _Timer(
            seat, loop.time() + grace, loop.call_later(grace, self._on_grace, seat)
        )

    def _people(self) -> list[Seat | None]:
        """The seats of people (the computer's seat is not one)."""
        return [s for i, s in enumerate(self.room.seats) if i not in self.room.computer]

    def _abandon(self) -> None:
        """Every player is gone past the grace: the match stops without a winner (recorded
        as abandoned), instead of the absentees forfeiting frames to each other."""
        for seat in list(self._grace):
            self._cancel_grace(seat)
        self._cancel_clock()
        self.room.abandon()
        self.broadcast_state()
        self.observer.room_changed(self.room)

    def _cancel_grace(self, seat: int) -> None:
        timer = self._grace.pop(seat, None)
        if timer is not None:
            timer.handle.cancel()

    def _on_grace(self, seat: int) -> None:
        timer = self._grace.get(seat)
        seat_info = self.room.seats[seat]
        if timer is None or seat_info is None or seat_info.connected:
            self._grace.pop(seat, None)
            return
        match = self.room.match
        if match is None or match.over:
            self._grace.pop(seat, None)
            return
        if self.room.phase == "rolling":  # let the shot finish first
            timer.handle = asyncio.get_running_loop().call_later(0.2, self._on_grace, seat)
            return
        people = [s for s in self._people() if s is not None]
        if all(s.seen and not s.connected for s in people):  # everyone was here and left
            self._abandon()
            return
        del self._grace[seat]
        outcome = self.room.forfeit(seat, f"{seat_info.name} left the table and did not come back.")
        self._conclude("forfeit", outcome, absent=seat)
