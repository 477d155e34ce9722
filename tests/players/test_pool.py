"""The Play now queue: pairing by rating with a widening window, once per player, and the
computer offered after 20 s (the time is passed in: no sleeping)."""

from __future__ import annotations

from server.players import MatchPool, Waiting, Window


def entry(pid: str, rating: float, since: float = 0.0, kind: str = "eight_ball") -> Waiting:
    return Waiting(pid, pid.title(), kind, rating, since, f"key-{pid}")


def test_two_players_of_like_rating_are_paired_at_once_the_first_comer_breaks():
    pool = MatchPool()
    assert pool.join(entry("ana", 1500)) is None
    pairing = pool.join(entry("ben", 1550, since=1.0))
    assert pairing is not None
    assert (pairing.first.player_id, pairing.second.player_id) == ("ana", "ben")
    assert len(pool) == 0


def test_games_are_not_mixed():
    pool = MatchPool()
    pool.join(entry("ana", 1500, kind="eight_ball"))
    assert pool.join(entry("ben", 1500, kind="nine_ball")) is None
    assert len(pool) == 2


def test_the_window_widens_with_waiting_time():
    window = Window(base=100, widen=20, most=700)
    pool = MatchPool(window)
    pool.join(entry("ana", 1500))
    assert pool.join(entry("ben", 1800, since=0.0)) is None
    assert pool.pair(now=9.0) == []  # 100 + 20*9 = 280 < 300
    (pairing,) = pool.pair(now=10.0)  # 300
    assert {pairing.first.player_id, pairing.second.player_id} == {"ana", "ben"}
    assert len(pool) == 0


def test_the_nearest_rating_is_chosen():
    pool = MatchPool(Window(base=600, widen=0, most=600))
    pool.join(entry("a", 1000))
    pool.join(entry("b", 1700))  # 700 apart: both wait
    assert len(pool) == 2
    pairing = pool.join(entry("c", 1400))  # a is 400 away, b 300
    assert pairing is not None
    assert (pairing.first.player_id, pairing.second.player_id) == ("b", "c")
    assert pool.get("a") is not None


def test_one_entry_per_player():
    pool = MatchPool()
    pool.join(entry("ana", 1500, since=0.0))
    assert pool.join(entry("ana", 1500, since=5.0)) is None  # keeps the place
    entry_held = pool.get("ana")
    assert len(pool) == 1 and entry_held is not None and entry_held.since == 0.0
    pool.join(entry("ana", 1500, since=6.0, kind="nine_ball"))  # moves to the other game
    entry_held = pool.get("ana")
    assert len(pool) == 1 and entry_held is not None and entry_held.kind == "nine_ball"
    assert pool.join(entry("ben", 1500, kind="eight_ball")) is None  # ana is not there


def test_a_wave_pairs_everyone_once():
    pool = MatchPool(Window(base=0, widen=0, most=0))
    for i in range(10):
        pool.join(entry(f"p{i}", 1000 + 1000 * i))  # nobody suits anybody yet
    pool.window = Window(base=5000, most=5000)
    pairings = pool.pair(now=1.0)
    seen = [p for pairing in pairings for p in (pairing.first.player_id, pairing.second.player_id)]
    assert len(pairings) == 5 and sorted(seen) == sorted(f"p{i}" for i in range(10))
    assert len(pool) == 0


def test_after_twenty_seconds_alone_the_computer_is_offered():
    pool = MatchPool()
    pool.join(entry("ana", 1500, since=100.0))
    assert not pool.offered_computer("ana", 119.9)
    assert pool.offered_computer("ana", 120.0)
    assert not pool.offered_computer("ben", 120.0)
    pool.leave("ana")
    assert not pool.offered_computer("ana", 200.0)


def test_a_pair_put_back_waits_without_pairing_and_is_paired_by_the_next_wave():
    pool = MatchPool(Window(base=100, widen=20, most=700))
    pool.join(entry("new", 1000, since=50.0))
    pool.put_back(entry("ana", 1500, since=0.0))  # waited longest, put back last
    pool.put_back(entry("ben", 1500, since=0.0))
    assert len(pool) == 3  # nobody paired by being put back
    (pairing,) = pool.pair(now=50.0)
    assert {pairing.first.player_id, pairing.second.player_id} == {"ana", "ben"}
    assert pool.get("new") is not None
    pool.put_back(entry("old", 1600, since=0.0))  # waited 60 s: a window of 700 by now
    (pairing,) = pool.pair(now=60.0)  # "new" (window 300) meets it through its window
    assert {pairing.first.player_id, pairing.second.player_id} == {"new", "old"}


def test_two_entries_from_one_address_are_never_paired():
    pool = MatchPool()
    ana = Waiting("ana", "Ana", "eight_ball", 1500, 0.0, "key-ana", address="10.0.0.1")
    ben = Waiting("ben", "Ben", "eight_ball", 1500, 1.0, "key-ben", address="10.0.0.1")
    cara = Waiting("cara", "Cara", "eight_ball", 1600, 2.0, "key-cara", address="10.0.0.2")
    assert pool.join(ana) is None and pool.join(ben) is None
    assert pool.pair(now=100.0) == []  # the widest window, still not each other
    pairing = pool.join(cara)  # farther in rating, but from elsewhere
    assert pairing is not None and pairing.second.player_id == "cara"
    left = "ana" if pairing.first.player_id == "ben" else "ben"
    assert pool.get(left) is not None
    unknown = entry("dan", 1500, since=3.0)  # no address known: paired as before
    assert pool.join(unknown) is not None and pool.get(left) is None


def test_two_entries_from_one_device_are_never_paired():
    """Two profiles of one browser (its device id), even from two addresses."""
    pool = MatchPool()
    ana = Waiting("ana", "Ana", "eight_ball", 1500, 0.0, "k-a", address="10.0.0.1", device="d1")
    ben = Waiting("ben", "Ben", "eight_ball", 1500, 1.0, "k-b", address="10.0.0.2", device="d1")
    assert pool.join(ana) is None and pool.join(ben) is None
    assert pool.pair(now=100.0) == []
    cara = Waiting("cara", "Cara", "eight_ball", 1500, 2.0, "k-c", address="10.0.0.3", device="d2")
    pairing = pool.join(cara)
    assert pairing is not None and pairing.second.player_id == "cara"
    dan = Waiting("dan", "Dan", "eight_ball", 1500, 3.0, "k-d", address="10.0.0.4")  # no device
    assert pool.join(dan) is not None
