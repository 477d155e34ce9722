"""Physical constants of the ball, cloth, cushions and cue, each with its source.

Sources: Dr. Dave Alciatore's "pool and billiards physical properties" page (DA-PP,
billiards.colostate.edu/faq/physics/physical-properties), his technical proofs (TP A-14
ball-ball throw, TP A-31 squirt), the WPA equipment specifications, Han 2005 and Mathavan
et al. 2010 for the cushion, and pooltool 0.6.0's defaults (which follow DA-PP).
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace
from typing import Any

import numpy as np

from .shot import DEFAULT_CUE_MASS_RATIO
from .table import BALL_MASS, BALL_RADIUS, Table


@dataclass(frozen=True)
class PhysicsParams:
    """Friction, restitution, cushion and cue constants. Coefficients are dimensionless;
    g in m/s^2, speeds in m/s.

    The field order is the kernels' array layout (`physics/constants.py`, `P_*`).
    """

    radius: float = BALL_RADIUS
    mass: float = BALL_MASS
    g: float = 9.81
    u_slide: float = 0.2  # sliding friction, ball on cloth (DA-PP 0.15-0.4; pooltool 0.2)
    u_roll: float = 0.01  # rolling resistance (DA-PP 0.005-0.015; pooltool 0.01)
    # Spinning friction: side spin decays at 5 u_spin g / (2R) = 10.9 rad/s^2 (DA-PP: 5-15).
    # pooltool's u_sp is 10*2/5/9 R = 0.444 R = 0.0127. The 0.044 used before (37.8 rad/s^2,
    # called "pooltool's default") was that 0.444 mis-copied, and without the factor R.
    u_spin: float = 0.0127
    e_ball: float = 0.95  # ball-ball restitution (DA-PP 0.92-0.98)
    # Cushion restitution at normal speeds up to e_cushion_knee (Han 2005's e; pooltool's
    # e_c 0.85); above the knee the rubber deforms (Mathavan et al. 2010: the rigid-cushion
    # model holds below 2.5 m/s) and e falls by e_cushion_slope per m/s, to e_cushion_min.
    e_cushion: float = 0.85
    f_cushion: float = 0.2  # ball-cushion friction (pooltool f_c 0.2; Mathavan 2010: 0.14)
    cels: int = 16  # sprite cels per turn of the ball
    # Height of the cushion nose above the bed, as a fraction of the ball's diameter
    # (WPA: 62.5-64.5 %; pooltool 64 %). 63.5 % puts the contact 0.27 R above the centre.
    cushion_nose: float = 0.635
    e_cushion_knee: float = 2.5  # m/s
    e_cushion_slope: float = 0.04  # per m/s of normal speed above the knee
    e_cushion_min: float = 0.6  # DA-PP's lowest cushion restitution
    # Ball-ball friction mu = a + b exp(-c v_slip), v_slip the contact's sliding speed in
    # m/s: Alciatore's fit to Marlow's measurements (TP A-14; pooltool 0.6.0's default),
    # 0.11 for a slow slip, 0.06 at 0.5 m/s, 0.01 at speed (DA-PP: 0.03-0.08).
    u_ball_a: float = 0.009951
    u_ball_b: float = 0.108
    u_ball_c: float = 1.088
    # Ball mass / cue end mass, for squirt (TP A-31; `shot.py`). 30 is pooltool's cue and
    # gives 1.9 degrees at the 0.5 R maximum english (DA: 1-3 degrees for common shafts).
    cue_mass_ratio: float = DEFAULT_CUE_MASS_RATIO

    def array(self) -> np.ndarray:
        """The values in field order, for the compiled kernels (read field by field:
        `astuple` deep-copies, a cost the server paid on the event loop every shot)."""
        return np.array([getattr(self, f.name) for f in fields(self)], dtype=np.float64)


DEFAULT_PARAMS = PhysicsParams()


_by_table: dict[tuple[float, float, tuple[tuple[str, float], ...]], PhysicsParams] = {}


def params_for(table: Table) -> PhysicsParams:
    """The physics of `table`'s balls: `DEFAULT_PARAMS` (pool) with the table's ball radius,
    its style's ball mass and the cloth and cushion values its style changes (a carom
    table's, `styles.CAROM`). A snooker table keeps the pool cloth and cushions: the WPBSA
    specifies neither, and no measurement of a snooker cloth's friction was at hand to
    cite. The same object comes back for the same table, so the engine's caches find it by
    identity."""
    cut = table.cut
    key = (table.ball_radius, cut.ball_mass, cut.physics)
    if key == (DEFAULT_PARAMS.radius, DEFAULT_PARAMS.mass, ()):
        return DEFAULT_PARAMS
    found = _by_table.get(key)
    if found is None:
        changes: dict[str, Any] = dict(cut.physics)
        found = _by_table[key] = replace(DEFAULT_PARAMS, radius=key[0], mass=key[1], **changes)
    return found
