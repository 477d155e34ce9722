"""A cue stroke, and what it does to the cue ball.

The cue ball is struck by an impulse through the tip's contact point. With the ball speed
`V` along `d`, the tip offset `(side, height)` (fractions of the radius `R`) gives the
angular velocity `w = r x J / I` with `I = 2/5 m R^2`: a hit at 0.4 R above centre is a
natural roll, below centre is draw, left/right is side spin. Squirt and swerve are not
modelled.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

MAX_SPEED = 12.0  # m/s
MAX_TIP = 0.5  # fraction of the radius; beyond it a real cue miscues


@dataclass(frozen=True)
class Shot:
    """A stroke: direction in radians from +x, cue-ball speed in m/s, tip offset.

    `tip = (side, height)`: side > 0 strikes right of centre (seen from behind the cue),
    height > 0 above centre; both as fractions of the radius, with |tip| <= 0.5.

    Stored and sent through the codec as `{"angle", "speed", "tip": [side, height]}`;
    loading runs `__post_init__`, so a stored or received shot is checked like a new one.
    """

    angle: float
    speed: float
    tip: tuple[float, float] = (0.0, 0.0)

    def __post_init__(self) -> None:
        side, height = self.tip
        values = (self.angle, self.speed, side, height)
        if not all(isinstance(v, (int, float)) and math.isfinite(v) for v in values):
            raise ValueError("shot values must be finite numbers")
        if not 0.0 < self.speed <= MAX_SPEED:
            raise ValueError(f"speed must be in (0, {MAX_SPEED}] m/s")
        if math.hypot(side, height) > MAX_TIP + 1e-12:
            raise ValueError(f"tip offset must be within {MAX_TIP} of the radius")

    def cue_ball_motion(
        self, radius: float
    ) -> tuple[tuple[float, float], tuple[float, float, float]]:
        """Velocity (vx, vy) and angular velocity (wx, wy, wz) just after the strike."""
        dx, dy = math.cos(self.angle), math.sin(self.angle)
        side, height = self.tip
        a, b = side * radius, height * radius
        k = 5.0 * self.speed / (2.0 * radius * radius)
        # r = -c d + a s + b z with s = (dy, -dx, 0) the right-hand side; J = m V d.
        # s x d = z, z x d = (-dy, dx, 0)
        wx = k * b * -dy
        wy = k * b * dx
        wz = k * a
        return (self.speed * dx, self.speed * dy), (wx, wy, wz)
