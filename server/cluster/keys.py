"""Every Redis key and channel of the cluster, in one place (sizes and expiry: docs/scaling.md)."""

from __future__ import annotations

PREFIX = "pool:"
NODES = PREFIX + "nodes"  # set of node ids that announced themselves
LOAD = PREFIX + "load"  # sorted set: node id -> rooms it plays (placement)
LISTED = PREFIX + "rooms"  # sorted set: listed room id -> created_at


NODE_PREFIX = PREFIX + "node:"


def node(node_id: str) -> str:
    """The node's presence: JSON {url, rooms}, expiring `lease_ttl` after its heartbeat."""
    return NODE_PREFIX + node_id


def node_rooms(node_id: str) -> str:
    """Set of the room ids a node plays (read by whoever takes them over)."""
    return f"{PREFIX}node:{node_id}:rooms"


def lease(room_id: str) -> str:
    """ "<node> <epoch>" of the room's owner, expiring unless renewed."""
    return f"{PREFIX}lease:{room_id}"


def epoch(room_id: str) -> str:
    """The room's fencing counter (INCR on every change of owner)."""
    return f"{PREFIX}epoch:{room_id}"


def room(room_id: str) -> str:
    """The room's lobby summary, JSON."""
    return f"{PREFIX}room:{room_id}"


def inbox(node_id: str) -> str:
    """Pub/sub channel of a node: calls to it and replies to its calls."""
    return f"{PREFIX}inbox:{node_id}"
