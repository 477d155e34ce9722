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
sideways part of J turns a little of the side spin back).

Elevation (the cue's angle above the bed; Alciatore, TP A.30 "the effect of cue tip offset,
cue weight, and cue speed on cue ball speed and spin", the model pooltool 0.6.0's `theta`
follows): the impulse runs along the cue's axis, J = m V (cos(t) e - sin(t) z), so the
ball leaves at V cos(t) along the squirted line and the downward part goes into the
slate; the spin is r x J / I in three dimensions, which tilts its axis: side spin with
elevation curves the path through the cloth's friction (swerve, masse). The tip offset is
where the tip meets the ball, seen from behind at the bed's level; the cue reaches it
without miscueing only when its axis passes within `MAX_TIP` of the centre
(`cue_offset`): a raised cue must strike higher on the ball.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Annotated, Any

from pydantic import Field

if TYPE_CHECKING:
    from pydantic import GetCoreSchemaHandler
    from pydantic_core import CoreSchema

MAX_SPEED = 12.0  # m/s
MAX_TIP = 0.5  # fraction of the radius; beyond it a real cue miscues
MAX_ELEVATION = math.radians(80.0)  # the cue's angle above the bed: a steep masse
# Ball mass / cue end mass (pooltool 0.6.0's cue: end mass = ball mass / 30); the value
# the engine uses is `PhysicsParams.cue_mass_ratio`.
DEFAULT_CUE_MASS_RATIO = 30.0


class Miscue(ValueError):
    """A tip offset the cue cannot strike at its elevation without miscueing."""


def cue_offset(tip: tuple[float, float], elevation: float) -> float:
    """How far the cue's axis passes from the ball's centre, in radii, when the tip meets
    the ball at `tip` (seen from behind at the bed's level) with the cue raised by
    `elevation`; inf when no cue from that side can touch that point.

    The miscue limit (Alciatore, "The Illustrated Principles of Pool and Billiards": a
    tip miscues beyond about half a radius of offset, where the contact normal is ~30
    degrees off the cue's axis; MAX_TIP since the level strike) applies to this distance.
    With the contact point r = (side, -c, height) in the ball's frame (c the depth behind the
    centre) and the cue along u = (0, cos t, -sin t), the axis passes at sqrt(1 - k^2)
    with k = -r.u = c cos t + height sin t: at t = 0 that is |tip|; a tip below the
    centre with a steep cue gives k <= 0 or a large offset (the cue would dig under the
    ball, or glance off it)."""
    side, height = tip
    depth2 = 1.0 - side * side - height * height
    if depth2 < 0.0:
        return math.inf
    k = math.sqrt(depth2) * math.cos(elevation) + height * math.sin(elevation)
    if k <= 0.0:
        return math.inf
    return math.sqrt(max(1.0 - k * k, 0.0))


def tip_seen_level(along_cue: tuple[float, float], elevation: float) -> tuple[float, float]:
    """The `tip` (seen from behind at the bed's level) of the point the tip meets when
    seen along the cue at `along_cue` = (side, height): pooltool's (a, b) with its theta
    (mirrored: its a > 0 is left). Any |along_cue| <= MAX_TIP passes `check_stroke`,
    when the point is behind the ball's top (cos(t) depth >= sin(t) height along the cue:
    a steep cue striking high along itself meets the ball's front, which no tip seen from
    behind names)."""
    side, height = along_cue
    depth = math.sqrt(max(1.0 - side * side - height * height, 0.0))
    return side, math.sin(elevation) * depth + math.cos(elevation) * height


def check_stroke(tip: tuple[float, float], elevation: float) -> None:
    """Raise `Miscue` (a ValueError) for a tip and elevation the cue cannot play. A level
    cue keeps the plain |tip| <= MAX_TIP test and its ValueError, bit for bit what it
    always accepted and said."""
    if elevation == 0.0:
        if math.hypot(*tip) > MAX_TIP + 1e-12:
            raise ValueError(f"tip offset must be within {MAX_TIP} of the radius")
        return
    offset = cue_offset(tip, elevation)
    if offset > MAX_TIP + 1e-9:
        degrees = math.degrees(elevation)
        raise Miscue(
            f"miscue: with the cue raised {degrees:.0f} degrees the tip cannot strike "
            f"({tip[0]:.2f}, {tip[1]:.2f}); its axis would pass {min(offset, 1.0):.2f} R "
            f"from the centre (at most {MAX_TIP}): strike higher on the ball"
        )


@dataclass(frozen=True)
class Shot:
    """A stroke: direction in radians from +x, cue-ball speed in m/s, tip offset.

    `tip = (side, height)`: side > 0 strikes right of centre (seen from behind the cue),
    height > 0 above centre; both as fractions of the radius, with |tip| <= 0.5 for a
    level cue. `elevation`: the cue's angle above the bed in radians, in
    [0, MAX_ELEVATION]; a raised cue's tip must pass `check_stroke` (else `Miscue`), and
    `speed` is then the ball's speed along the cue (V cos(elevation) along the bed).

    `ball` is the ball the cue strikes: the cue ball (0) in pool and snooker; in carom
    the striker's own cue ball (the white 0 or the yellow 1).

    Stored and sent through the codec as `{"angle", "speed", "tip": [side, height]}`, plus
    `"elevation"` when it is not 0 (a stored shot without it is level) and `"ball"` when it
    is not 0 (so a pool shot's stored form is what it always was); loading runs
    `__post_init__`, so a stored or received shot is checked like a new one.
    """

    angle: float
    speed: float
    tip: tuple[float, float] = (0.0, 0.0)
    elevation: float = 0.0
    ball: Annotated[int, Field(exclude_if=lambda ball: ball == 0)] = 0

    @classmethod
    def __get_pydantic_core_schema__(cls, source: Any, handler: GetCoreSchemaHandler) -> CoreSchema:
        """The codec's schema: a level shot is written without `elevation`, as before it
        existed (old readers and stored records stay the same)."""
        from pydantic_core import core_schema

        inner = handler(source)
        outer = dict(inner)
        outer["serialization"] = core_schema.wrap_serializer_function_ser_schema(
            _without_level_elevation, schema=inner
        )
        return outer

    def __post_init__(self) -> None:
        side, height = self.tip
        values = (self.angle, self.speed, side, height, self.elevation)
        if not all(isinstance(v, (int, float)) and math.isfinite(v) for v in values):
            raise ValueError("shot values must be finite numbers")
        if not 0.0 < self.speed <= MAX_SPEED:
            raise ValueError(f"speed must be in (0, {MAX_SPEED}] m/s")
        if not 0.0 <= self.elevation <= MAX_ELEVATION:
            raise ValueError(f"elevation must be in [0, {MAX_ELEVATION:.4f}] rad")
        check_stroke(self.tip, self.elevation)
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
        if self.elevation == 0.0:
            return (self.speed * ex, self.speed * ey), (wx, wy, wz)
        # A raised cue: J = m V (cos(t) e - sin(t) z), so r x J / I is cos(t) times the
        # level spin above plus sin(t) V (5/2R^2) (z x r) = sin(t) k (a d + c s): a forward
        # axis from the side offset (the swerve) and backspin from striking down behind
        # the centre. The bed takes the downward part of J (`downward_speed`).
        cos_t, sin_t = math.cos(self.elevation), math.sin(self.elevation)
        dx, dy = math.cos(self.angle), math.sin(self.angle)
        wx = cos_t * wx + sin_t * k * (a * dx + c * dy)
        wy = cos_t * wy + sin_t * k * (a * dy - c * dx)
        wz = cos_t * wz
        speed = self.speed * cos_t
        return (speed * ex, speed * ey), (wx, wy, wz)

    def downward_speed(self) -> float:
        """The part of the strike's speed driven into the bed (m/s): V sin(elevation)."""
        return self.speed * math.sin(self.elevation)


def _without_level_elevation(shot: Shot, serialize: Any) -> Any:
    data = serialize(shot)
    if isinstance(data, dict) and data.get("elevation") == 0.0:
        del data["elevation"]
    return data
