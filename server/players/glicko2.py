"""Glicko-2 (Glickman, "Example of the Glicko-2 system", 2012), step by step as Glickman
gives it.

Why our own: the one PyPI package (`glicko2` 2.1.0) is a mutable single-file port whose CI
has been dead for years; the algorithm is fifty lines and is checked here against
Glickman's worked example (tests/players/test_glicko2.py). Pure: no clock, no I/O.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

SCALE = 173.7178  # Glicko-2's scale factor (400 / ln 10)
BASE = 1500.0
START_RD = 350.0  # a new player's deviation, and the most any deviation grows to
START_VOLATILITY = 0.06
TAU = 0.5  # constrains the change of volatility (Glickman (2012): 0.3 to 1.2)
EPSILON = 1e-6  # convergence of the volatility iteration


@dataclass(frozen=True)
class Rating:
    """A player's strength: `rating` and deviation `rd` on the Glicko scale, `volatility`."""

    rating: float = BASE
    rd: float = START_RD
    volatility: float = START_VOLATILITY

    @property
    def conservative(self) -> float:
        """What the leaderboard shows: rating - 2 RD (97.7 % sure the player is stronger)."""
        return self.rating - 2 * self.rd


def _g(phi: float) -> float:
    return 1.0 / math.sqrt(1.0 + 3.0 * phi * phi / (math.pi * math.pi))


def _expected(mu: float, mu_j: float, phi_j: float) -> float:
    return 1.0 / (1.0 + math.exp(-_g(phi_j) * (mu - mu_j)))


def expected_score(a: Rating, b: Rating) -> float:
    """The chance that `a` beats `b` (Glicko-2's E, with b's deviation)."""
    return _expected((a.rating - BASE) / SCALE, (b.rating - BASE) / SCALE, b.rd / SCALE)


def idle(player: Rating, periods: float) -> Rating:
    """`periods` rating periods without a game: the deviation grows (Glickman (2012) step 6,
    once per period: phi^2 + sigma^2 each), up to `START_RD`."""
    if periods <= 0:
        return player
    phi = player.rd / SCALE
    grown = math.sqrt(phi * phi + periods * player.volatility**2) * SCALE
    return Rating(player.rating, min(START_RD, grown), player.volatility)


def rate(player: Rating, games: Sequence[tuple[Rating, float]], tau: float = TAU) -> Rating:
    """`player` after one rating period of `games` (opponent as rated before the period,
    score 1 win / 0.5 draw / 0 loss). No games: only the deviation grows."""
    if not games:
        return idle(player, 1)
    # Step 2: to the Glicko-2 scale.
    mu = (player.rating - BASE) / SCALE
    phi = player.rd / SCALE
    sigma = player.volatility
    # Steps 3 and 4: estimated variance v and improvement delta.
    v_inv = 0.0
    delta_sum = 0.0
    for opponent, score in games:
        mu_j = (opponent.rating - BASE) / SCALE
        g_j = _g(opponent.rd / SCALE)
        e_j = _expected(mu, mu_j, opponent.rd / SCALE)
        v_inv += g_j * g_j * e_j * (1.0 - e_j)
        delta_sum += g_j * (score - e_j)
    v = 1.0 / v_inv
    delta = v * delta_sum
    # Step 5: the new volatility (the Illinois algorithm).
    a = math.log(sigma * sigma)

    def f(x: float) -> float:
        ex = math.exp(x)
        d = phi * phi + v + ex
        return ex * (delta * delta - d) / (2.0 * d * d) - (x - a) / (tau * tau)

    big_a = a
    if delta * delta > phi * phi + v:
        big_b = math.log(delta * delta - phi * phi - v)
    else:
        k = 1
        while f(a - k * tau) < 0:
            k += 1
        big_b = a - k * tau
    f_a, f_b = f(big_a), f(big_b)
    while abs(big_b - big_a) > EPSILON:
        big_c = big_a + (big_a - big_b) * f_a / (f_b - f_a)
        f_c = f(big_c)
        if f_c * f_b <= 0:
            big_a, f_a = big_b, f_b
        else:
            f_a /= 2.0
        big_b, f_b = big_c, f_c
    sigma_new = math.exp(big_a / 2.0)
    # Steps 6 and 7: the new deviation and rating.
    phi_star = math.sqrt(phi * phi + sigma_new * sigma_new)
    phi_new = 1.0 / math.sqrt(1.0 / (phi_star * phi_star) + 1.0 / v)
    mu_new = mu + phi_new * phi_new * delta_sum
    # Step 8: back to the Glicko scale.
    return Rating(mu_new * SCALE + BASE, min(START_RD, phi_new * SCALE), sigma_new)
