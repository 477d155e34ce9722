"""The `shoot` message's elevation: optional (an old client plays level), bounded by
`max_elevation`, and a tip the raised cue cannot reach refused as a `miscue` before the shot
(the rule in docs/protocol.md, "Elevation and the miscue rule")."""

import json
import math

import pytest

from server.engine import MAX_ELEVATION
from server.protocol import LIMITS
from server.protocol.inbound import BadMessage, Shoot, parse_client_message


def shoot(**fields: object) -> str:
    return json.dumps({"type": "shoot", "angle": 0.0, "speed": 2.0, **fields})


def test_an_old_client_leaving_elevation_out_plays_level():
    msg = parse_client_message(shoot(tip=[0.1, -0.2]))
    assert isinstance(msg, Shoot)
    assert msg.elevation == 0.0


def test_limits_carry_the_largest_elevation_80_degrees():
    assert LIMITS.max_elevation == MAX_ELEVATION == pytest.approx(math.radians(80))


def test_a_raised_cue_striking_high_on_the_ball_is_a_shot():
    msg = parse_client_message(shoot(tip=[0.5, 0.75], elevation=math.radians(60)))
    assert isinstance(msg, Shoot)
    assert msg.elevation == math.radians(60)


@pytest.mark.parametrize("elevation", [-0.1, MAX_ELEVATION + 1e-6, "steep"])
def test_an_elevation_out_of_bounds_is_a_bad_message(elevation: object):
    with pytest.raises(BadMessage) as refused:
        parse_client_message(shoot(elevation=elevation))
    assert refused.value.code == "bad_message"


@pytest.mark.parametrize(
    ("tip", "degrees"),
    [([0.0, -0.3], 45.0), ([0.5, 0.0], 60.0), ([0.0, 0.0], 45.0), ([0.45, 0.3], 1e-3)],
)
def test_a_tip_the_raised_cue_cannot_reach_is_a_miscue(tip: list[float], degrees: float):
    # Below centre (or at it) with a steep cue, side spin without striking higher, and
    # 0.54 R off centre with a barely raised cue: the axis passes beyond 0.5 R.
    with pytest.raises(BadMessage) as refused:
        parse_client_message(shoot(tip=tip, elevation=math.radians(degrees)))
    assert refused.value.code == "miscue"
    assert refused.value.ref == "shoot"
    assert "strike higher on the ball" in refused.value.message


def test_a_level_tip_beyond_half_a_radius_is_still_a_bad_message():
    with pytest.raises(BadMessage) as refused:
        parse_client_message(shoot(tip=[0.45, 0.3]))
    assert refused.value.code == "bad_message"
    assert "tip offset must be within 0.5" in refused.value.message
