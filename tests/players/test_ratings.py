"""Ratings per game kind over time: the ranked match update, provisional players, the
leaderboard order and the computer's levels."""

from __future__ import annotations

import itertools

import pytest

from server.ai import Bot
from server.players import (
    COMPUTER_RATINGS,
    COUNTED_GAMES,
    PROVISIONAL_RD,
    RATING_PERIOD,
    KindRating,
    Rating,
    nearest_level,
    rate,
    rate_match,
    rate_ranked,
    standings,
)

NOW = 1_000_000.0


def test_a_ranked_match_rates_each_player_against_the_others_rating_before_it():
    ana = KindRating("ana", "eight_ball", Rating(1600, 80, 0.06), games=12, wins=7, rated_at=NOW)
    ben = KindRating("ben", "eight_ball", Rating(1500, 200, 0.06), games=2, wins=1, rated_at=NOW)
    a, b = rate_match(ana, ben, first_won=False, now=NOW)
    assert a.rating == rate(ana.rating, [(ben.rating, 0.0)])
    assert b.rating == rate(ben.rating, [(ana.rating, 1.0)])
    assert a.rating.rating < 1600 < b.rating.rating
    assert (a.games, a.wins, b.games, b.wins) == (13, 7, 3, 2)
    assert a.rated_at == b.rated_at == NOW


def test_idle_days_widen_the_deviation_before_the_match_is_rated():
    ana = KindRating("ana", "nine_ball", Rating(1600, 60, 0.06), games=30, rated_at=NOW)
    later = NOW + 100 * RATING_PERIOD
    assert ana.at(later).rd > 60
    a, _ = rate_match(ana, KindRating("ben", "nine_ball"), first_won=True, now=later)
    assert a.rating == rate(ana.at(later), [(Rating(), 1.0)])


def test_new_players_are_provisional_until_their_deviation_is_low():
    new = KindRating("ana", "eight_ball")
    assert new.provisional(NOW)
    settled = KindRating("ana", "eight_ball", Rating(1500, PROVISIONAL_RD - 1), 20, 10, NOW)
    assert not settled.provisional(NOW)
    assert settled.provisional(NOW + 400 * RATING_PERIOD)  # a year away: provisional again


def test_the_leaderboard_orders_by_rating_minus_two_deviations_provisional_apart():
    rows = [
        KindRating("high-but-unsure", "eight_ball", Rating(1900, 100), 9, 8, NOW),  # 1700
        KindRating("steady", "eight_ball", Rating(1800, 40), 60, 40, NOW),  # 1720
        KindRating("low", "eight_ball", Rating(1400, 50), 30, 10, NOW),  # 1300
        KindRating("new", "eight_ball", Rating(2000, 300), 1, 1, NOW),  # provisional
        KindRating("never", "eight_ball"),  # no games: not listed
    ]
    ranked, provisional = standings(rows, NOW)
    assert [(s.rank, s.player_id) for s in ranked] == [
        (1, "steady"),
        (2, "high-but-unsure"),
        (3, "low"),
    ]
    assert [s.rating for s in ranked] == [1720, 1700, 1300]
    assert [(s.rank, s.player_id, s.games) for s in provisional] == [(None, "new", 1)]


def test_every_computer_level_has_a_rating_and_the_nearest_is_offered():
    assert tuple(COMPUTER_RATINGS) == Bot.LEVELS
    assert sorted(COMPUTER_RATINGS.values()) == list(COMPUTER_RATINGS.values())
    assert nearest_level(1500) == "amateur"
    assert nearest_level(900) == "beginner"
    assert nearest_level(1900) == "club"  # 121 from club, 180 from pro
    assert nearest_level(3000) == "pro"


@pytest.mark.parametrize(("share", "gap"), [(0.817, 260), (0.833, 279), (0.85, 301)])
def test_the_level_gaps_come_from_the_measured_win_shares(share: float, gap: float):
    import math

    assert 400 * math.log10(share / (1 - share)) == pytest.approx(gap, abs=1)
    steps = list(COMPUTER_RATINGS.values())
    assert round(gap) in [round(b - a) for a, b in itertools.pairwise(steps)]


def test_a_result_moves_a_rating_only_against_an_opponent_with_a_record():
    """The farm rule: fresh profiles are free to make, so a win over one (or a loss) leaves
    the other player's rating as it was; the games are counted, and the fresh side is
    rated by Glicko-2 against the one with a record."""
    known = KindRating("ana", "eight_ball", Rating(1600, 80, 0.06), COUNTED_GAMES, 5, NOW)
    fresh = KindRating("ben", "eight_ball")
    a, b = rate_ranked(known, fresh, first_won=True, now=NOW)
    assert a.rating == known.rating and (a.games, a.wins, a.rated_at) == (11, 6, NOW)
    assert b.rating == rate_match(known, fresh, True, NOW)[1].rating
    assert (b.games, b.wins) == (1, 0)
    f1, f2 = rate_ranked(fresh, KindRating("cara", "eight_ball"), first_won=True, now=NOW)
    assert f1.rating == f2.rating == Rating()  # two fresh profiles move nobody
    assert (f1.games, f1.wins, f2.games, f2.wins) == (1, 1, 1, 0)


def test_between_players_with_records_the_ladder_rates_by_glicko2_untouched():
    ana = KindRating("ana", "eight_ball", Rating(1600, 80, 0.06), COUNTED_GAMES, 5, NOW)
    ben = KindRating("ben", "eight_ball", Rating(1500, 200, 0.06), COUNTED_GAMES + 3, 6, NOW)
    assert rate_ranked(ana, ben, False, NOW) == rate_match(ana, ben, False, NOW)


def test_a_kept_rating_still_takes_the_time_away_into_account():
    """The rating kept is the one as of the match: its deviation grown over the idle days."""
    away = KindRating("ana", "eight_ball", Rating(1600, 60, 0.06), 30, 15, NOW)
    later = NOW + 100 * RATING_PERIOD
    a, _ = rate_ranked(away, KindRating("ben", "eight_ball"), True, later)
    assert a.rating == away.at(later) and a.rating.rd > 60 and a.rated_at == later
