"""Tiny vector helpers for the kernels (math.hypot goes through libm and is slow)."""

import math

from numba import njit


@njit(cache=True, inline="always")
def norm(x, y):
    return math.sqrt(x * x + y * y)
