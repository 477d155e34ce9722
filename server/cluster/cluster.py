"""One process's part in the cluster: presence, room leases, the shared room list, calls to
other processes, taking over the rooms of a dead process, and handing its own over.

Everything runs on the event loop, in two tasks. The heartbeat (every `heartbeat` s) renews
the leases of this process's rooms in one script call and announces the process and its
load, on a Redis connection of its own and within half a lease: it never waits on the
store, so a database outage (writes retried, reads waiting their deadline) cannot let this
process's leases lapse. The upkeep (as often) publishes the lobby summaries that changed,
registers rooms not registered yet and takes over rooms whose owner stopped announcing
itself: the work that needs the store, and may wait for it. A room is taken by acquiring
its lease (a fresh epoch), claiming it in the store with that epoch (older epochs' writes
are refused from then on), and only then reading its saved state: nothing its old owner
wrote before the claim is missed.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import logging
import math
import random
import secrets
from collections.abc import Iterable

from redis.asyncio import Redis
from redis.exceptions import RedisError

from server.config import Settings
from server.rooms import LiveRoom, RoomRegistry
from server.store import Database, RoomSnapshot, StaleOwner

from . import keys, scripts
from .background import Background
from .calls import Inbox, Unreachable
from .directory import Directory
from .match_ids import MatchIds

log = logging.getLogger(__name__)
CLOSE_MOVED = 1012  # "service restart": reconnect (and ask again where)


class Cluster:
    """Presence, leases and fencing, takeover and drain for this process's rooms; the
    shared list is `directory`, calls to other processes go through `inbox`."""

    def __init__(
        self,
        settings: Settings,
        registry: RoomRegistry,
        store: Database,
        node_id: str | None = None,
    ) -> None:
        if settings.redis_url is None or settings.public_url is None:
            raise ValueError("cluster mode needs redis_url and public_url")
        self.settings = settings
        self.registry = registry
        self.store = store
        self.node = node_id or secrets.token_hex(6)
        self.url = settings.public_url.rstrip("/")
        self.redis: Redis = Redis.from_url(
            settings.redis_url,
            decode_responses=True,
            socket_timeout=settings.rpc_timeout,
            socket_connect_timeout=settings.rpc_timeout,
            health_check_interval=30,
        )
        # Liveness (renewals, presence) on its own connection: never queued behind a call
        # or a listing, and given up after half a lease (a later beat tries again while
        # the lease still holds; the heartbeat is at most half a lease).
        self.beat_deadline = settings.lease_ttl / 2
        self.liveness: Redis = Redis.from_url(
            settings.redis_url,
            decode_responses=True,
            socket_timeout=self.beat_deadline,
            socket_connect_timeout=self.beat_deadline,
        )
        self.ttl_ms = int(settings.lease_ttl * 1000)
        self.epochs: dict[str, int] = {}  # rooms this process owns -> their epoch
        self.inbox = Inbox(self.redis, self.node, settings.rpc_timeout)
        self.inbox.on_adopt = self.take
        self.directory = Directory(self.redis, self.node)
        self.match_ids = MatchIds(store)
        self.peers: dict[str, str] = {}  # live node id -> public url (last heartbeat)
        self.dead: list[str] = []  # processes that stopped announcing themselves
        self._tasks: list[asyncio.Task[None]] = []
        self._taking: dict[str, int] = {}  # rooms leased, being claimed -> their epoch
        self._recovering: asyncio.Task[None] | None = None
        self._opening: dict[str, asyncio.Task[None]] = {}  # rooms being registered
        self._clearing = Background()  # the shared entries of rooms closed here
        self._peers_seen = 0.0  # loop time `peers` was last refreshed out of turn
        self._republish = False  # the next upkeep publishes every summary (Redis forgot)
        self._acquire = self.redis.register_script(scripts.ACQUIRE)
        self._renew = self.liveness.register_script(scripts.RENEW)
        self._release = self.redis.register_script(scripts.RELEASE)
        self._place = self.redis.register_script(scripts.PLACE)
        self._raise = self.redis.register_script(scripts.RAISE)
        registry.on_forget = self._forgotten
        registry.on_create = self._created

    # ---- life ---------------------------------------------------------------------------

    async def start(self) -> None:
        """Announce this process and listen; raises if Redis cannot be reached."""
        await self.redis.ping()
        await self.inbox.start()
        await self.match_ids.refill()
        if not await self.redis.exists(keys.NODES):  # a new Redis: it knows of no room
            self._recover_soon()
        await self._announce()
        await self._see_peers()
        self._tasks = [
            asyncio.create_task(self.inbox.run(), name="cluster-inbox"),
            asyncio.create_task(self._run_heartbeat(), name="cluster-heartbeat"),
            asyncio.create_task(self._run_upkeep(), name="cluster-upkeep"),
        ]
        log.info("cluster: node %s at %s", self.node, self.url)

    async def stop(self) -> None:
        extra = [self._recovering] if self._recovering is not None else []
        for task in [*self._tasks, *extra]:
            task.cancel()
            with contextlib.suppress(asyncio.CancelledError, Exception):
                await task
        await self.match_ids.stop()
        await self.inbox.close()
        await self.redis.aclose()
        await self.liveness.aclose()

    async def drain(self) -> list[str]:
        """Hand every room over now (SIGTERM): the caller has stopped them and flushed the
        store. Leases released, the rooms offered to the live processes (least loaded
        first), this process shown as gone. A room nobody adopts is taken over by the next
        heartbeat of any process. Returns the rooms handed over."""
        rooms = list(self.epochs)
        peers = [p for p in await self._see_peers() if p != self.node]
        async with self.redis.pipeline(transaction=False) as pipe:
            for room_id in rooms:
                await self._release(
                    keys=[keys.lease(room_id)],
                    args=[f"{self.node} {self.epochs[room_id]}"],
                    client=pipe,
                )
            pipe.delete(keys.node(self.node))
            pipe.zrem(keys.LOAD, self.node)
            await pipe.execute()
        self.epochs.clear()
        if peers:
            loads = await self.redis.zmscore(keys.LOAD, peers)
            order = [p for _, p in sorted(zip([v or 0 for v in loads], peers, strict=True))]
            shares: dict[str, list[str]] = {p: [] for p in order}
            for i, room_id in enumerate(rooms):
                shares[order[i % len(order)]].append(room_id)
            for peer, share in shares.items():
                if share:
                    message = {"kind": "adopt", "rooms": share, "from": self.node}
                    await self.inbox.send(peer, message)
        log.info("cluster: drained %d rooms to %d processes", len(rooms), len(peers))
        return rooms

    # ---- rooms of this process ----------------------------------------------------------

    def own_new(self, live: LiveRoom) -> asyncio.Task[None]:
        """A room just created here (by any caller: a request, Play now): take its lease,
        claim it in the store, publish its lobby entry. The same task for every caller,
        to await when the answer must wait for it; a room that could not be registered
        (Redis or the store out of reach) is tried again at each heartbeat."""
        room_id = live.room.room_id
        task = self._opening.get(room_id)
        if task is None:
            task = asyncio.get_running_loop().create_task(self._own(live))
            self._opening[room_id] = task
            task.add_done_callback(lambda _: self._opening.pop(room_id, None))
        return task

    async def _own(self, live: LiveRoom) -> None:
        room_id = live.room.room_id
        floor = await self.store.call(lambda repo: repo.room_epoch(room_id) or 0)
        epoch = await self._acquire(
            keys=[keys.lease(room_id), keys.epoch(room_id)], args=[self.node, self.ttl_ms, floor]
        )
        if not epoch:  # another process took it (it had no lease here): it is theirs
            self.stale(room_id, force=True)
            raise RuntimeError(f"room {room_id} is owned elsewhere")
        try:
            claimed = await self._claim(room_id, int(epoch))
        except StaleOwner:
            self.stale(room_id, force=True)
            raise
        if self.registry.get(room_id) is not live:  # closed meanwhile
            await self._let_go(room_id, claimed)
            return
        self.epochs[room_id] = claimed
        await self.redis.sadd(keys.node_rooms(self.node), room_id)
        await self.directory.publish([live], force=True)

    def _created(self, live: LiveRoom) -> None:
        """Registry hook: every new room becomes this process's in the cluster."""
        task = self.own_new(live)
        task.add_done_callback(_log_failure)

    async def take(self, room_ids: Iterable[str], source: str | None = None) -> list[str]:
        """Take over rooms whose lease is free (their owner died or handed them over);
        returns those now played here. `source`: the process they came from."""
        wanted = [r for r in room_ids if r not in self.epochs and r not in self._taking]
        if not wanted:
            return []
        taken = await self._lease(wanted, source)
        if not taken:
            return []
        try:
            restored = await self._adopt(taken, source)
        finally:
            for room_id in taken:
                self._taking.pop(room_id, None)
        if restored:
            log.info("cluster: took over %d rooms (from %s)", len(restored), source or "?")
        return restored

    async def _lease(self, wanted: list[str], source: str | None) -> dict[str, int]:
        """The leases of `wanted` this process won, with their new epochs (each marked as
        being taken)."""
        # The epochs the store has seen: a new one must be above them even if Redis lost
        # its counter (else an old owner's epoch could come round again).
        floors = await self.store.call(lambda repo: {r: repo.room_epoch(r) or 0 for r in wanted})
        taken: dict[str, int] = {}
        for room_id in wanted:
            if room_id in self.epochs or room_id in self._taking:
                continue
            epoch = await self._acquire(
                keys=[keys.lease(room_id), keys.epoch(room_id)],
                args=[self.node, self.ttl_ms, floors[room_id]],
            )
            if not epoch:
                holder = await self.redis.get(keys.lease(room_id))
                if source is not None and holder and holder.split()[0] != source:
                    await self.redis.srem(keys.node_rooms(source), room_id)  # not theirs now
                continue
            self._taking[room_id] = int(epoch)
            taken[room_id] = int(epoch)
        return taken

    async def _adopt(self, taken: dict[str, int], source: str | None) -> list[str]:
        """Claim the leased rooms in the store and restore them here; returns those now
        played here (a lease given back for each that could not be)."""
        claimed = {}
        for room_id, epoch in taken.items():
            try:
                claimed[room_id] = await self._claim(room_id, epoch)
            except StaleOwner:
                log.warning("cluster: room %s has a newer owner than %d", room_id, epoch)
            except Exception as exc:  # the store out of reach: a later heartbeat
                log.warning("cluster: room %s not claimed: %s", room_id, exc)
        try:
            snaps = await self.store.call(
                lambda repo: [s for r in claimed if (s := repo.room(r)) is not None]
            )
        except Exception:
            for room_id, epoch in claimed.items():
                await self._let_go(room_id, epoch)
            raise
        restored = self._restore(snaps, claimed)
        gone = [r for r in claimed if r not in restored]
        await self._settle(restored, gone, source)
        return restored

    def _restore(self, snaps: list[RoomSnapshot], epochs: dict[str, int]) -> list[str]:
        for snap in snaps:
            self.epochs[snap.room_id] = epochs[snap.room_id]
        lives = self.registry.restore(snaps)
        restored = [live.room.room_id for live in lives]
        for snap in snaps:
            if snap.room_id not in restored:
                self.epochs.pop(snap.room_id, None)
        return restored

    async def _settle(self, restored: list[str], gone: list[str], source: str | None) -> None:
        async with self.redis.pipeline(transaction=False) as pipe:
            for room_id in restored:
                pipe.sadd(keys.node_rooms(self.node), room_id)
                if source is not None:
                    pipe.srem(keys.node_rooms(source), room_id)
            for room_id in gone:  # closed meanwhile, or unreadable: nothing to play
                pipe.delete(keys.lease(room_id), keys.epoch(room_id), keys.room(room_id))
                pipe.zrem(keys.LISTED, room_id)
                if source is not None:
                    pipe.srem(keys.node_rooms(source), room_id)
            await pipe.execute()
        await self.directory.publish(
            [live for r in restored if (live := self.registry.get(r)) is not None], force=True
        )

    async def _claim(self, room_id: str, epoch: int, again: bool = True) -> int:
        """Tell the store `epoch` owns the room: from now on it refuses older epochs'
        writes. Returns the epoch claimed; raises `StaleOwner` when a newer owner has it
        (or the store's error), letting the lease go."""
        try:
            await self.store.call(lambda repo: repo.claim_room(room_id, epoch, self.node))
            return epoch
        except StaleOwner as exc:
            # We hold the lease, so nobody plays the room under a newer epoch: the store
            # remembers one that Redis forgot (it restarted). Go past it, once.
            raised = 0
            if again:
                with contextlib.suppress(RedisError, OSError):
                    raised = await self._raise(
                        keys=[keys.lease(room_id), keys.epoch(room_id)],
                        args=[f"{self.node} {epoch}", exc.stored],
                    )
            if raised:
                if room_id in self._taking:
                    self._taking[room_id] = int(raised)
                return await self._claim(room_id, int(raised), again=False)
            await self._let_go(room_id, epoch)
            raise
        except Exception:
            await self._let_go(room_id, epoch)
            raise

    async def _let_go(self, room_id: str, epoch: int) -> None:
        if self._taking.get(room_id) == epoch:  # no longer renewed by the heartbeat
            del self._taking[room_id]
        with contextlib.suppress(RedisError, OSError):
            await self._release(keys=[keys.lease(room_id)], args=[f"{self.node} {epoch}"])

    def epoch_of(self, room_id: str) -> int | None:
        return self.epochs.get(room_id)

    def stale(self, room_id: str, force: bool = False) -> None:
        """The store refused a write of ours for this room (or its lease is another's):
        another process owns it now. Stop playing it (its members reconnect to the new
        owner). `force`: also a room this process never owned in the cluster."""
        if self.epochs.pop(room_id, None) is None and not force:
            return
        log.warning("cluster: room %s is owned elsewhere now; dropped here", room_id)
        self.directory.forget(room_id)
        self.registry.release(room_id, CLOSE_MOVED, "room_moved")

    def _forgotten(self, room_id: str) -> None:
        """The room closed here for good (it expired): clear its shared entries. Its epoch
        is kept until the closing code that follows has queued its last writes (deleting
        the saved room, closing the match), so they are fenced like every other."""
        epoch = self.epochs.get(room_id)
        self.directory.forget(room_id)
        if epoch is not None:
            loop = asyncio.get_running_loop()
            loop.call_soon(self.epochs.pop, room_id, None)
            self._clearing.start(self._clear(room_id, epoch))

    async def _clear(self, room_id: str, epoch: int) -> None:
        with contextlib.suppress(RedisError):
            async with self.redis.pipeline(transaction=False) as pipe:
                pipe.delete(keys.room(room_id), keys.epoch(room_id))
                pipe.zrem(keys.LISTED, room_id)
                pipe.srem(keys.node_rooms(self.node), room_id)
                await self._release(
                    keys=[keys.lease(room_id)], args=[f"{self.node} {epoch}"], client=pipe
                )
                await pipe.execute()

    # ---- where a room is played ----------------------------------------------------------

    async def owner(self, room_id: str) -> str | None:
        """The process that holds the room's lease now, or None."""
        try:
            holder = await self.redis.get(keys.lease(room_id))
        except (RedisError, OSError) as exc:
            raise Unreachable("redis") from exc
        return str(holder).split()[0] if holder else None

    async def saved(self, room_id: str) -> bool:
        """Whether the store holds the room: it exists though no process announces it (Redis
        came back empty and its owner has not renewed yet, or nobody has taken it over
        yet). `StoreUnavailable` when the store cannot say."""
        return await self.store.call(lambda repo: repo.room(room_id) is not None)

    async def place(self) -> str:
        """The least loaded live process (this one when alone, or when Redis is out of
        reach)."""
        try:
            chosen = await self._place(keys=[keys.LOAD, keys.NODES], args=[keys.NODE_PREFIX])
        except (RedisError, OSError) as exc:
            log.warning("cluster: placing a room here: %s", exc)
            return self.node
        return str(chosen) if chosen else self.node

    async def fresh_origins(self) -> tuple[str, ...]:
        """`origins`, asking Redis again if the last look is over a second old (a process
        that started since the last heartbeat); never more than once a second."""
        loop = asyncio.get_running_loop()
        if loop.time() - self._peers_seen > 1.0:
            self._peers_seen = loop.time()
            with contextlib.suppress(RedisError, OSError):
                await self._see_peers()
        return self.origins()

    def origins(self) -> tuple[str, ...]:
        """The public URLs of the live processes: pages served by any of them may open a
        room socket here."""
        return (self.url, *(url for node, url in self.peers.items() if node != self.node))

    # ---- heartbeat ----------------------------------------------------------------------

    async def _run_heartbeat(self) -> None:
        while True:
            await asyncio.sleep(self.settings.heartbeat)
            try:
                async with asyncio.timeout(self.beat_deadline):  # (wait_for: see store.call)
                    await self.keep_alive()
            except (RedisError, OSError, TimeoutError) as exc:
                log.warning("cluster: heartbeat: %s", exc or "no answer within half a lease")
            except Exception:
                log.exception("cluster: heartbeat failed")

    async def _run_upkeep(self) -> None:
        while True:
            await asyncio.sleep(self.settings.heartbeat)
            try:
                await self.upkeep()
            except (RedisError, OSError) as exc:
                log.warning("cluster: upkeep: %s", exc)
            except Exception:
                log.exception("cluster: upkeep failed")

    async def beat(self) -> None:
        """One heartbeat and one upkeep, in turn (a benchmark's or a test's step)."""
        await self.keep_alive()
        await self.upkeep()

    async def keep_alive(self) -> None:
        """Renew the leases and announce this process: Redis alone, never the store."""
        again = await self._renew_leases()
        if await self._announce():  # Redis forgot us: rooms of processes that died
            self._recover_soon()  # meanwhile are known to the store alone
            again = True
        self._republish = self._republish or again

    async def upkeep(self) -> None:
        """Publish, register the rooms not registered yet, take over: what may wait on the
        store (a room's claim, its snapshot) runs here, not in the heartbeat."""
        force, self._republish = self._republish, False
        lives = [live for r in self.epochs if (live := self.registry.get(r)) is not None]
        try:
            await self.directory.publish(lives, force=force)
        except BaseException:
            self._republish = self._republish or force
            raise
        for room_id, live in list(self.registry.rooms.items()):
            if room_id not in self.epochs and room_id not in self._taking:
                with contextlib.suppress(Exception):  # logged by `_created` the first time
                    await self.own_new(live)
        await self._take_orphans(await self._see_peers())

    async def _renew_leases(self) -> bool:
        """True when Redis had lost leases of ours (it restarted): everything shared is
        written again. Rooms being taken over are renewed too: their claim and snapshot
        may wait on the store longer than a lease."""
        taking = [(r, e) for r, e in self._taking.items() if r not in self.epochs]
        owned = [*self.epochs.items(), *taking]
        if not owned:
            return False
        lease_keys = [k for room_id, _ in owned for k in (keys.lease(room_id), keys.epoch(room_id))]
        results = await self._renew(
            keys=lease_keys, args=[self.node, self.ttl_ms, *(e for _, e in owned)]
        )
        lost = [room_id for (room_id, _), r in zip(owned, results, strict=True) if int(r) == 0]
        again = [room_id for (room_id, _), r in zip(owned, results, strict=True) if int(r) == 2]
        for room_id in lost:
            if self.epochs.get(room_id) is not None:
                self.stale(room_id)
        if again:
            log.warning("cluster: %d leases were gone from Redis; taken again", len(again))
            if self.epochs:
                await self.liveness.sadd(keys.node_rooms(self.node), *self.epochs)
            self._recover_soon()
        return bool(again)

    async def _announce(self) -> bool:
        """Presence and load; True when Redis did not know this process any more (it lost
        its data: whatever it held must be rebuilt)."""
        rooms = len(self.registry.rooms)
        async with self.liveness.pipeline(transaction=False) as pipe:
            pipe.set(
                keys.node(self.node), json.dumps({"url": self.url, "rooms": rooms}), px=self.ttl_ms
            )
            pipe.sadd(keys.NODES, self.node)
            pipe.zadd(keys.LOAD, {self.node: rooms})
            _, added, _ = await pipe.execute()
        return bool(added)

    async def _see_peers(self) -> list[str]:
        """Refresh `peers` (live processes); returns their ids. Processes that stopped
        announcing themselves are kept aside in `dead`."""
        nodes = sorted(str(n) for n in await self.redis.smembers(keys.NODES))
        found = await self.redis.mget([keys.node(n) for n in nodes]) if nodes else []
        self.peers = {}
        self.dead = []
        for node, entry in zip(nodes, found, strict=True):
            if entry is None:
                self.dead.append(node)
            else:
                self.peers[node] = json.loads(entry)["url"]
        return list(self.peers)

    async def _take_orphans(self, live: list[str]) -> None:
        """Take this process's share of the rooms of processes that are gone."""
        for dead in self.dead:
            orphans = sorted(str(r) for r in await self.redis.smembers(keys.node_rooms(dead)))
            if not orphans:
                async with self.redis.pipeline(transaction=False) as pipe:
                    pipe.srem(keys.NODES, dead)
                    pipe.zrem(keys.LOAD, dead)
                    pipe.delete(keys.node_rooms(dead))
                    await pipe.execute()
                continue
            random.shuffle(orphans)
            share = math.ceil(len(orphans) / max(1, len(live)))
            await self.take(orphans[:share], dead)

    def _recover_soon(self) -> None:
        """Redis lost its data (or is new): once the owners still alive have taken their
        rooms' leases again (a heartbeat; we wait a lease), take the rooms nobody holds."""
        if self._recovering is None or self._recovering.done():
            self._recovering = asyncio.get_running_loop().create_task(self._recover_later())

    async def _recover_later(self) -> None:
        await asyncio.sleep(self.settings.lease_ttl)
        try:
            await self.recover()
        except Exception:
            log.exception("cluster: recovering rooms from the store failed")

    async def recover(self) -> list[str]:
        """Take the rooms saved in the store that no process holds a lease for: after
        Redis lost its data, the store is the only list of rooms (one full read of it,
        which is why it runs only then)."""
        ids = [snap.room_id for snap in await self.store.call(lambda repo: repo.rooms())]
        if not ids:
            return []
        async with self.redis.pipeline(transaction=False) as pipe:
            for room_id in ids:
                pipe.exists(keys.lease(room_id))
            held = await pipe.execute()
        here = self.registry.rooms  # played here, if not (yet) under a lease
        orphans = [r for r, h in zip(ids, held, strict=True) if not h and r not in here]
        if orphans:
            log.warning("cluster: %d rooms in the store had no owner", len(orphans))
        return await self.take(orphans)


def _log_failure(task: asyncio.Task[object]) -> None:
    if not task.cancelled() and task.exception() is not None:
        log.warning("cluster: a new room is not registered yet: %s", task.exception())
