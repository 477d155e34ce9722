"""The Play now queue of one process: who waits for which game at what rating, paired by
rating with a window that widens while they wait (lichess's pool does the same in waves).

Pure and synchronous, the time passed in (`now`, monotonic seconds): every change happens
in one call, so two players pressing Play now at once can never both be paired with a
third, and nobody is in the queue twice.
"""

from __future__ import annotations

import bisect
from dataclasses import dataclass


class QueueError(ValueError):
    def __init__(self, code: str, message: str) -> None:
        super().__init__(message)
        self.code = code
        self.message = message


@dataclass(frozen=True)
class Waiting:
    """One queue entry. `seat_key` lets the server make the player's seat token in the
    room it pairs them into (see `profile.seat_key`). `address`: where the player asked
    from; `device`: the browser's device id (its `pool_device` cookie, hashed). Two
    entries of one address or one device are never paired (fresh profiles conceding to
    one another farmed a rating)."""

    player_id: str
    name: str
    kind: str
    rating: float
    since: float
    seat_key: str
    address: str | None = None
    device: str | None = None


@dataclass(frozen=True)
class Pairing:
    """Two players for a new room: `first` (who waited longer) breaks."""

    kind: str
    first: Waiting
    second: Waiting


@dataclass(frozen=True)
class Window:
    """The rating difference a player accepts: `base` at once, `widen` more per second of
    waiting, never more than `most`. After `computer_after` seconds the player is offered
    the computer."""

    base: float = 100.0
    widen: float = 20.0
    most: float = 700.0
    computer_after: float = 20.0

    def at(self, waited: float) -> float:
        return min(self.most, self.base + self.widen * max(0.0, waited))


class MatchPool:
    def __init__(self, window: Window | None = None) -> None:
        self.window = window or Window()
        self._entries: dict[str, Waiting] = {}  # player id -> entry
        self._sorted: dict[str, list[tuple[float, str]]] = {}  # kind -> (rating, id), sorted
        self._in_order = True  # entries are in the order of `since` (as they joined)

    def __len__(self) -> int:
        return len(self._entries)

    def waiting_ids(self) -> set[str]:
        return set(self._entries)

    def get(self, player_id: str) -> Waiting | None:
        return self._entries.get(player_id)

    def join(self, entry: Waiting) -> Pairing | None:
        """Queue `entry` and pair it at once if someone suitable waits. A player already
        waiting for the same game keeps their place; for the other game the entry moves."""
        held = self._entries.get(entry.player_id)
        if held is not None and held.kind == entry.kind:
            return None
        self.put_back(entry)
        match = self._best_for(entry, entry.since)
        if match is None:
            return None
        return self._take(entry, match)

    def put_back(self, entry: Waiting) -> None:
        """Queue `entry` again as it was, without pairing it now (its pairing could not
        be played: the server had no room for it); the next wave tries again."""
        self.leave(entry.player_id)
        last = next(reversed(self._entries.values()), None)
        if last is not None and last.since > entry.since:
            self._in_order = False  # `_widest` can no longer read the oldest off the front
        self._entries[entry.player_id] = entry
        bisect.insort(self._sorted.setdefault(entry.kind, []), (entry.rating, entry.player_id))

    def leave(self, player_id: str) -> Waiting | None:
        entry = self._entries.pop(player_id, None)
        if entry is not None:
            line = self._sorted[entry.kind]
            del line[bisect.bisect_left(line, (entry.rating, player_id))]
        return entry

    def offered_computer(self, player_id: str, now: float) -> bool:
        """Whether the player has waited long enough to be offered the computer."""
        entry = self._entries.get(player_id)
        return entry is not None and now - entry.since >= self.window.computer_after

    def pair(self, now: float) -> list[Pairing]:
        """Pair whoever the widened windows now allow, the longest waiting first, each with
        the nearest rating that suits both."""
        pairings: list[Pairing] = []
        order = list(self._entries.values())  # the order they joined: by `since`
        if not self._in_order:
            order.sort(key=lambda e: e.since)
        for entry in order:
            if entry.player_id not in self._entries:
                continue  # paired already in this wave
            match = self._best_for(entry, now)
            if match is not None:
                self.leave(entry.player_id)
                self.leave(match.player_id)
                pairings.append(Pairing(entry.kind, entry, match))
        return pairings

    def _widest(self, now: float) -> float:
        """The widest window anyone has now: the first to join has waited longest (the
        entries keep the order they joined in)."""
        oldest = next(iter(self._entries.values()), None)
        if oldest is None:
            self._in_order = True
            return 0.0
        return self.window.at(now - oldest.since) if self._in_order else self.window.most

    def _suits(self, a: Waiting, b: Waiting, now: float) -> bool:
        """Within the wider of the two windows: the one who waited longer has accepted more."""
        reach = max(self.window.at(now - a.since), self.window.at(now - b.since))
        return abs(a.rating - b.rating) <= reach

    def _best_for(self, entry: Waiting, now: float) -> Waiting | None:
        """The nearest rating that suits both, walking outward from the entry's own rating
        in the kind's sorted line (cheap: the walk stops at the widest window anyone has)."""
        reach = max(self._widest(now), self.window.at(now - entry.since))
        line = self._sorted.get(entry.kind, [])
        i = bisect.bisect_left(line, (entry.rating, ""))
        left, right = i - 1, i
        best: Waiting | None = None
        while left >= 0 or right < len(line):
            step_left = left >= 0 and (
                right >= len(line) or entry.rating - line[left][0] <= line[right][0] - entry.rating
            )
            other = self._entries[line[left][1] if step_left else line[right][1]]
            if step_left:
                left -= 1
            else:
                right += 1
            if abs(other.rating - entry.rating) > reach:
                break  # sorted outward: nobody further can suit
            if other.player_id == entry.player_id or _same_client(entry, other):
                continue
            if self._suits(entry, other, now):
                best = other
                break
        return best

    def _take(self, entry: Waiting, match: Waiting) -> Pairing:
        self.leave(entry.player_id)
        self.leave(match.player_id)
        return Pairing(entry.kind, match, entry)  # the one who waited longer breaks


def _same_client(a: Waiting, b: Waiting) -> bool:
    """One address or one device (unknown ones are never the same)."""
    same_address = a.address is not None and a.address == b.address
    return same_address or (a.device is not None and a.device == b.device)
