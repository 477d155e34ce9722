"""Indices and codes shared by the compiled kernels (numba treats module globals as constants)."""

# MotionState values (see balls.MotionState)
STATIONARY = 0
SPINNING = 1
SLIDING = 2
ROLLING = 3
POCKETED = 4
AIRBORNE = 5
# The pocket index of a ball that flew off the table (state POCKETED: out of play).
OFF_TABLE = -2

# Event kind codes (see results.EVENT_CODES)
EV_STRIKE = 0
EV_BALL = 1
EV_CUSHION = 2
EV_JAW = 3
EV_POCKET = 4
EV_REST = 5
EV_LAND = 6
EV_OFF = 7
EV_NONE = -1

# PhysicsParams.array() layout
P_RADIUS = 0
P_MASS = 1
P_G = 2
P_U_SLIDE = 3
P_U_ROLL = 4
P_U_SPIN = 5
P_E_BALL = 6
P_E_CUSHION = 7
P_F_CUSHION = 8
P_CELS = 9
P_CUSHION_NOSE = 10
P_E_CUSHION_KNEE = 11
P_E_CUSHION_SLOPE = 12
P_E_CUSHION_MIN = 13
P_U_BALL_A = 14
P_U_BALL_B = 15
P_U_BALL_C = 16

# Speeds below this (m/s) count as zero: far below anything a player can see.
EPS_SPEED = 1e-9
# Spin below this (rad/s) counts as zero.
EPS_SPIN = 1e-7
# A tick may resolve at most this many events; beyond it the tick stops early (no overlap).
MAX_EVENTS_PER_TICK = 5000

# The airborne ball. They are not PhysicsParams fields, so the engine version's digest (and
# every level shot's version) stays as it was; a change here must bump PHYSICS_REVISION.
# Ball-slate restitution: Alciatore's physical-properties page (DA-PP) gives 0.5 for the
# ball-table restitution, the figure behind his jump-shot articles (a cue ball driven into
# the slate comes back up with about half the speed); not re-checked for this constant.
E_SLATE = 0.5
# A bounce slower than this (m/s up: a hop of 0.5 mm) ends the flight: the ball stays down.
MIN_HOP_SPEED = 0.1
