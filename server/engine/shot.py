"""A cue stroke, and what it does to the cue ball.

The cue ball is struck by an impulse through the tip's contact point. With the ball speed
`V` along `d`, the tip offset `(side, height)` (fractions of the radius `R`) gives the
angular velocity `w = r x J / I` with `I = 2/5 m R^2`: a hit at 0.4 R above centre is a
natural roll, below centre is draw, left/right is side spin.

Squirt (Alciatore, TP A-31 "squirt angle"): a side offset x = side pushes the cue ball off
the aim line, away from the side struck, by

    tan(a) = 5/2 x sqrt(1 - x^2) / (1 + m_ball / m_end + 5/2 (1 - x^2))

where m_end is the cue's end mass (`PhysicsParams.cue_mass_ratio` = m_ball / m_end). The
ball travels along the squirted line, and its spin is r x J / I for that impulse J (the
sideways part of J turns a little of the side spin back). Swerve and masse (an elevated
cue) are not modelled.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Annotated

from pydantic import Field

MAX_SPEED = 12.0  # m/s
MAX_TIP = 0.5  # fraction of the radius; beyond it a real cue miscues
# Ball mass / cue end mass (pooltool 0.6.0's cue: end mass = ball mass / 30); the value
# the engine uses is `PhysicsParams.cue_mass_ratio`.
DEFAULT_CUE_MASS_RATIO = 30.0


@dataclass(frozen=True)
class Shot:
    """A stroke: direction in radians from +x, cue-ball speed in m/s, tip offset.

    `tip = (side, height)`: side > 0 strikes right of centre (seen from behind the cue),
    height > 0 above centre; both as fractions of the radius, with |tip| <= 0.5.

    `ball` is the ball the cue strikes: the cue ball (0) in pool and snooker; in carom
    the striker's own cue ball (the white 0 or the yellow 1).

    Stored and sent through the codec as `{"angle", "speed", "tip": [side, height]}`, and
    `"ball"` when it is not 0 (so a pool shot's stored form is what it always was);
    loading runs `__post_init__`, so a stored or received shot is checked like a new one.
    """

    angle: float
    speed: float
    tip: tuple[float, float] = (0.0, 0.0)
    ball: Annotated[int, Field(exclude_if=lambda ball: ball == 0)] = 0

    def __post_init__(self) -> None:
        side, height = self.tip
        values = (self.angle, self.speed, side, height)
        if not all(isinstance(v, (int, float)) and math.isfinite(v) for v in values):
            raise ValueError("shot values must be finite numbers")
        if not 0.0 < self.speed <= MAX_SPEED:
            raise ValueError(f"speed must be in (0, {MAX_SPEED}] m/s")
        if math.hypot(side, height) > MAX_TIP + 1e-12:
            raise ValueError(f"tip offset must be within {MAX_TIP} of the radius")
        if not isinstance(self.ball, int) or isinstance(self.ball, bool) or self.ball < 0:
            raise ValueError("the struck ball must be a ball id")

    def squirt(self, mass_ratio: float = DEFAULT_CUE_MASS_RATIO) -> float:
        """The squirt angle in radians, positive to the left of the aim line (right
        english squirts left); 0 without side offset."""
        x = self.tip[0]
        cos2 = 1.0 - x * x
        return math.atan(2.5 * x * math.sqrt(cos2) / (1.0 + mass_ratio + 2.5 * cos2))

    def direction(self, mass_ratio: float = DEFAULT_CUE_MASS_RATIO) -> float:
        """The angle in radians of the cue ball's path just after the strike: the aim
        turned by the squirt (a guide line shows this one)."""
        return self.angle + self.squirt(mass_ratio)

    def cue_ball_motion(
        self, radius: float, mass_ratio: float = DEFAULT_CUE_MASS_RATIO
    ) -> tuple[tuple[float, float], tuple[float, float, float]]:
        """Velocity (vx, vy) and angular velocity (wx, wy, wz) just after the strike."""
        side, height = self.tip
        alpha = self.squirt(mass_ratio)
        ex, ey = math.cos(self.angle + alpha), math.sin(self.angle + alpha)
        a, b = side * radius, height * radius
        c = math.sqrt(max(radius * radius - a * a - b * b, 0.0))
        k = 5.0 * self.speed / (2.0 * radius * radius)
        # r = -c d + a s + b z with s = (dy, -dx, 0) the aim's right-hand side; J = m V e,
        # e = d turned left by the squirt. s x e = cos(alpha) z, d x e = sin(alpha) z,
        # z x e = (-ey, ex, 0).
        wx = k * b * -ey
        wy = k * b * ex
        wz = k * (a * math.cos(alpha) - c * math.sin(alpha))
        return (self.speed * ex, self.speed * ey), (wx, wy, wz)
