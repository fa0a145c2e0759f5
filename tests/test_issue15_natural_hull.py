"""Natural-neighbour values near a hull edge stay inside the data's range (checker5 F1).

A query on a hull edge's line up to rounding (the rounded midpoint of two hull sites) was
taken as inside: its Sibson cell is bounded but about 1 / distance long, and its areas
cancelled to garbage (2.68 for data in [-2, 1]). Within ``NATURAL_HULL_RTOL`` of an edge's
length the edge's limit (linear along it) is used.
"""

from __future__ import annotations

import numpy as np
import pytest

import voroforge as vf


def _lattice(scale, off=0.0):
    i, j = np.meshgrid(np.arange(6.0), np.arange(6.0))
    b = np.column_stack((4 * i.ravel() - 3 * j.ravel(), 3 * i.ravel() + 4 * j.ravel()))
    return b * scale + off, b[:, 0] * 2.0 - b[:, 1] * 3.0 + 1.0


def test_four_nearly_collinear_sites():
    p = np.array(
        [[0, 0], [0.4, 0.30000000000000004], [0.8, 0.6000000000000001], [1.2000000000000002, 0.9]]
    )
    f = np.array([1.0, 0.0, -1.0, -2.0])
    q = [0.6000000000000001, 0.45000000000000007]
    for kw in ({}, {"extrapolate": "nearest"}, {"smooth": True}):
        assert vf.natural_neighbor(p, f, q, **kw) == pytest.approx(-0.5, abs=1e-7)


@pytest.mark.parametrize("scale", [0.1, 0.3, 1e-10, 3.7e-5, 1e-100, 1e200, 1e-200])
def test_rotated_lattice_hull_midpoints_in_range(scale):
    p, f = _lattice(scale)
    pairs = [(0, 1), (1, 2), (4, 5), (0, 6), (6, 12), (30, 31), (5, 11), (29, 35)]
    q = np.array([(p[a] + p[b]) / 2 for a, b in pairs])
    for kw in ({}, {"extrapolate": "nearest"}):
        z = vf.natural_neighbor(p, f, q, **kw)
        z = z[np.isfinite(z)]
        # (before: 2.888 at scale 0.1, 164.2 and -194.7 at 1e-200; data in [-94, 1])
        assert ((z >= f.min()) & (z <= f.max())).all(), z


def test_close_to_the_hull_is_near_the_limit_and_continuous():
    # a query 1e-10 (relative) inside a hull edge: the limit's value; farther in, Sibson's
    # own cells (the values move continuously from the limit)
    p = np.array([[0.0, 0.0], [1.0, 0.0], [0.5, 1.0], [0.3, 0.4], [0.7, 0.3]])
    f = np.array([0.0, 2.0, 5.0, -1.0, 3.0])
    xs = [1e-12, 1e-10, 1e-8, 1e-6, 1e-4]
    z = vf.natural_neighbor(p, f, [[0.25, y] for y in xs])
    assert z[0] == pytest.approx(0.5, abs=1e-12)
    assert z[1] == pytest.approx(0.5, abs=1e-9)
    assert np.all(np.abs(np.diff(z)) <= 1e-2)
    assert ((z >= f.min()) & (z <= f.max())).all()
