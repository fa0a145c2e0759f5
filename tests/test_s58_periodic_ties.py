"""periodic_ties: the groups with two different points of one ring in one box copy (perlines7).

``_tie_points`` leaves alone a group holding two different points of one ring in one copy of
the box (an ulp-short edge, not the rounding of one vertex). That test was two
``np.unique(axis=0)`` of the members' rows; :func:`_split_groups` is one lexsort. Checked
against the two uniques (floats compared as values: ``-0.0 == 0.0``) on random rows with
repeats, and the tied cells of sites on a line against the torus.
"""

from __future__ import annotations

import numpy as np
import pytest

from test_issue15_periodic import _check_torus
from voroforge.engine.periodic_ties import _split_groups


def _by_unique(g, rid, q, coords, groups):
    """The test as it was: two ``np.unique(axis=0)`` of the rows."""
    key = np.unique(np.column_stack((g, rid, q, coords)), axis=0)
    head, count = np.unique(key[:, :4], axis=0, return_counts=True)
    out = np.zeros(groups, dtype=bool)
    out[head[count > 1, 0].astype(np.int64)] = True
    return out


@pytest.mark.parametrize("seed", range(4))
def test_split_groups_equals_the_two_uniques(seed):
    rng = np.random.default_rng(seed)
    values = np.array([0.0, -0.0, 1.0, 0.5, 2.0**-1074, -3.0])
    for _ in range(100):
        m = int(rng.integers(1, 80))
        groups = int(rng.integers(1, 8))
        g = np.sort(rng.integers(0, groups, m))
        rid = rng.integers(0, 4, m)
        q = rng.integers(-1, 2, (m, 2)).astype(float)
        coords = values[rng.integers(0, len(values), (m, 2))]
        got = np.zeros(groups, dtype=bool)
        got[_split_groups(g, rid, q, coords)] = True
        np.testing.assert_array_equal(got, _by_unique(g, rid, q, coords, groups))


def test_split_groups_minus_zero_is_zero():
    g = np.zeros(2, dtype=np.int64)
    rid = np.zeros(2, dtype=np.int64)
    q = np.zeros((2, 2))
    assert not len(_split_groups(g, rid, q, np.array([[0.0, 1.0], [-0.0, 1.0]])))
    assert _split_groups(g, rid, q, np.array([[0.0, 1.0], [2.0**-1074, 1.0]])).tolist() == [0]
    assert not len(_split_groups(g[:0], rid[:0], q[:0], np.zeros((0, 2))))


def test_vertical_line_and_one_tied_cells_tile_the_torus():
    # a box at the origin: the copies a period over in y are rounded sums, their vertices
    # tied to exact shifts (tie_images joins ~n of them here)
    t = np.random.default_rng(2).random(400)
    p = np.vstack((np.column_stack((np.full(400, 1.125), t * 2.0)), [[1.234375, 1.5625]]))
    d = _check_torus(p, (0.0, 0.0, 3.0, 2.0), "delaunay", False, samples=200)
    assert abs(d.areas.sum() - 6.0) <= 1e-14 * 6.0
