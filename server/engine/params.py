"""Physical constants of the ball, cloth and cushions (pooltool's and the WPA's defaults)."""

from __future__ import annotations

from dataclasses import astuple, dataclass

import numpy as np

from .table import BALL_MASS, BALL_RADIUS


@dataclass(frozen=True)
class PhysicsParams:
    """Friction and restitution. Coefficients are dimensionless; g in m/s^2."""

    radius: float = BALL_RADIUS
    mass: float = BALL_MASS
    g: float = 9.81
    u_slide: float = 0.2  # sliding friction, ball on cloth
    u_roll: float = 0.01  # rolling resistance
    u_spin: float = 0.044  # spinning friction (vertical-axis spin)
    e_ball: float = 0.95  # ball-ball restitution
    e_cushion: float = 0.8  # ball-cushion (and jaw) restitution
    f_cushion: float = 0.2  # ball-cushion friction: lets side spin bend the rebound
    cels: int = 16  # sprite cels per turn of the ball

    def array(self) -> np.ndarray:
        """The values in field order, for the compiled kernels."""
        return np.array(astuple(self), dtype=np.float64)


DEFAULT_PARAMS = PhysicsParams()
