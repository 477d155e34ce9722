import math

import pytest

from server.engine import Table


@pytest.mark.parametrize(
    "size,length,width", [("9ft", 2.54, 1.27), ("8ft", 2.34, 1.17), ("7ft", 1.98, 0.99)]
)
def test_pool_sizes(size, length, width):
    t = Table.pool(size)
    assert (t.length, t.width) == (length, width)
    assert t.head_spot == (length / 4, width / 2)
    assert t.foot_spot == (3 * length / 4, width / 2)
    assert t.head_string == length / 4


def test_unknown_size_is_refused():
    with pytest.raises(ValueError, match="unknown table size"):
        Table.pool("10ft")


def test_six_pockets_with_wpa_mouths(table):
    assert len(table.pockets) == 6
    for p in table.pockets:
        (ax, ay), (bx, by) = p.jaws
        mouth = math.hypot(bx - ax, by - ay)
        expected = 0.127 if "side" in p.name else 0.114
        assert mouth == pytest.approx(expected)
        # The drop circle lies behind the mouth, outside the bed.
        cx, cy = p.center
        assert not (0 < cx < table.length and 0 < cy < table.width)


def test_cushions_are_cut_at_the_mouths_and_their_ends_are_the_jaws(table):
    assert len(table.cushions) == 6
    jaws = set(table.jaws)
    assert len(jaws) == 12
    for p in table.pockets:
        assert set(p.jaws) <= jaws
    for c in table.cushions:
        nx, ny = c.normal
        # normals point into the bed
        mx, my = (c.start[0] + c.end[0]) / 2, (c.start[1] + c.end[1]) / 2
        assert 0 <= mx + 0.1 * nx <= table.length and 0 <= my + 0.1 * ny <= table.width


def test_contains_keeps_a_ball_clear_of_the_cushions(table):
    r = table.ball_radius
    assert table.contains(r, r)
    assert table.contains(table.length - r, table.width - r)
    assert not table.contains(r - 1e-6, 0.5)
    assert not table.contains(1.0, table.width - r + 1e-6)


def test_to_dict_is_plain_data(table):
    import json

    data = json.loads(json.dumps(table.to_dict()))
    assert data["length"] == table.length
    assert len(data["pockets"]) == 6
