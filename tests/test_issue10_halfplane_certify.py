"""Issue 10: the half-plane cells' certificate in one pass (``clip.rings_convex_area``).

It must give exactly what ``rings_convex(...).all()`` and the compensated sum of the rings'
areas (the engine's ``_certified`` used both, the latter as ``moments.rings_area``, now
:func:`_rings_area` here) give, and rings it certified skip ``_drop_folded``'s test.
"""

import numpy as np
import pytest

from voroforge.engine import planar
from voroforge.kernels.clip import rings_convex, rings_convex_area, tiny_folded
from voroforge.kernels.halfplane import halfplane_cells
from voroforge.kernels.moments import neumaier_add, ring_sums

BOX = np.array([0.0, 0.0, 1.0, 1.0])


def _rings_area(xs, ys, lengths):
    """The rings' signed areas (each relative to its first vertex) summed with compensation."""
    xs, ys = np.ascontiguousarray(xs), np.ascontiguousarray(ys)
    total = comp = 0.0
    for a, b in zip(lengths[:-1], lengths[1:], strict=True):
        if b - a >= 2:
            ring = ring_sums(xs, ys, a, b, xs[a], ys[a], True)[0]
            total, comp = neumaier_add(total, comp, ring)
    return 0.5 * (total + comp)


def _cells(seed, n, far=0.0):
    rng = np.random.default_rng(seed)
    p = rng.random((n, 2)) + far
    box = BOX + far
    closed, lengths, owner, hard = halfplane_cells(p[:, 0], p[:, 1], box)
    assert not hard.any()
    return closed, lengths, owner, box


@pytest.mark.parametrize("seed, n, far", [(0, 50, 0.0), (1, 2000, 0.0), (2, 500, 4e6)])
def test_equals_the_two_passes(seed, n, far):
    closed, lengths, _, _ = _cells(seed, n, far)
    convex, area = rings_convex_area(closed, lengths)
    assert convex == bool(rings_convex(closed, lengths).all())
    want = _rings_area(closed[:, 0], closed[:, 1], lengths)
    assert area == want  # bit for bit: the same sums in the same order
    assert convex


def test_a_fold_stops_it_and_empty_rings_pass():
    closed, lengths, _, _ = _cells(3, 200)
    # an empty ring first, then the cells
    lengths2 = np.concatenate(([0], lengths))
    convex, area = rings_convex_area(closed, lengths2)
    assert convex and area == _rings_area(closed[:, 0], closed[:, 1], lengths2)
    bent = closed.copy()
    k = int(lengths[7]) + 1  # a vertex of ring 7, pushed inside: a reflex turn
    a, b = int(lengths[7]), int(lengths[8]) - 1
    bent[k] = 0.5 * (bent[k - 1] + bent[k + 1]) + 0.25 * (bent[a:b].mean(0) - bent[k])
    assert not rings_convex(bent, lengths)[7]
    convex, area = rings_convex_area(bent, lengths)
    assert not convex and np.isnan(area)
    # no rings at all: nothing to certify
    assert not planar._certified(closed[:0], np.zeros(1, np.int64), BOX)


def test_certified_rings_skip_the_fold_test():
    closed, lengths, owner, box = _cells(4, 1000)
    memo = {}
    assert planar._certified(closed, lengths, box, memo)
    assert not tiny_folded(closed, lengths, planar._FOLDED_ULPS).any()
    got = planar._drop_folded(closed, lengths, owner, memo)
    assert got[0] is closed and got[1] is lengths and got[2] is owner
    # other rings (not certified: a copy) still get the test, with the same answer
    other = lengths.copy()
    got = planar._drop_folded(closed, other, owner, memo)
    assert np.array_equal(got[1], lengths)
    # a box the rings do not tile is not certified, and nothing is noted
    memo = {}
    assert not planar._certified(closed, lengths, np.array([0.0, 0.0, 2.0, 1.0]), memo)
    assert "convex" not in memo
