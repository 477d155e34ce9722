"""Cluster mode (`POOL_REDIS_URL`): many `python -m server` processes share one Redis.

Each room is played by one process, its owner, which holds the room's lease (a Redis key it
renews) under a fencing epoch; the store refuses writes from an older epoch. Redis holds
only what can be rebuilt (presence, leases, the room list, messages): the rooms themselves
are in the store, and a live process takes over the rooms of a dead one from there.
See docs/scaling.md.
"""

from .calls import Forwarded, Unreachable
from .cluster import Cluster
from .urls import ws_url

__all__ = ["Cluster", "Forwarded", "Unreachable", "ws_url"]
