"""Glicko-2 against Glickman's worked example ("Example of the Glicko-2 system", 2012)."""

from __future__ import annotations

import pytest

from server.players import Rating, expected_score, idle, rate


def test_the_papers_worked_example():
    """1500/200/0.06 against 1400/30, 1550/100, 1700/300 winning the first game only: the
    Glickman's (2012) 1464.06 / 151.52 / 0.05999 (he rounds each step; exact arithmetic gives
    1464.05, within 0.01)."""
    player = Rating(1500, 200, 0.06)
    games = [(Rating(1400, 30), 1.0), (Rating(1550, 100), 0.0), (Rating(1700, 300), 0.0)]
    after = rate(player, games)
    assert after.rating == pytest.approx(1464.06, abs=0.015)
    assert after.rd == pytest.approx(151.52, abs=0.005)
    assert after.volatility == pytest.approx(0.05999, abs=0.00001)


def test_a_period_without_games_only_widens_the_deviation():
    after = rate(Rating(1500, 200, 0.06), [])
    assert after.rating == 1500
    assert after.rd == pytest.approx((200**2 + (0.06 * 173.7178) ** 2) ** 0.5)


def test_the_deviation_grows_with_idle_periods_up_to_350():
    start = Rating(1800, 60, 0.06)
    assert idle(start, 0).rd == 60
    assert 60 < idle(start, 10).rd < idle(start, 100).rd < 350
    assert idle(start, 1e6).rd == 350


def test_the_favourite_is_expected_to_win_and_a_win_against_it_counts_more():
    strong, weak = Rating(1800, 50), Rating(1500, 50)
    assert expected_score(strong, weak) > 0.8
    upset = rate(weak, [(strong, 1.0)]).rating - weak.rating
    expected = rate(weak, [(Rating(1500, 50), 1.0)]).rating - weak.rating
    assert upset > expected > 0
