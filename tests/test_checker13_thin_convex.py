"""Thin Convex containers (checker13 F5): `.volume` is the exact polytope's of the rows, and
boxes a few ulps thick far from the origin are built, against exact rationals and the box
container of the same box."""

import itertools
from fractions import Fraction

import numpy as np
import pytest

import voroforge as vf


def _box(lo, hi):
    corners = np.array(
        [
            [(lo, hi)[b][i] for i, b in enumerate(bits)]
            for bits in itertools.product((0, 1), repeat=3)
        ]
    )
    rows = [[-1, 0, 0, -lo[0]], [1, 0, 0, hi[0]], [0, -1, 0, -lo[1]]]
    rows += [[0, 1, 0, hi[1]], [0, 0, -1, -lo[2]], [0, 0, 1, hi[2]]]
    exact = np.prod([Fraction(float(h)) - Fraction(float(a)) for h, a in zip(hi, lo, strict=True)])
    return corners, np.array(rows, float), float(exact)


CASES = [
    ([1, 1e-7, 1e-7], 0.0),
    ([1, 1, 1e-8], 0.0),
    ([1, 1e-9, 1e-9], 0.0),
    ([1, 1e-9, 1e-9], 1e6),  # 8.6 ulps thick: refused as flat before
    ([1, 1, 3e-10], 1e6),  # 2.6 ulps
    ([1, 2e-9, 1e-9], 4e6),
]


@pytest.mark.parametrize(("ext", "off"), CASES)
def test_thin_box_convex_matches_box_container(ext, off):
    lo = np.full(3, off)
    hi = lo + np.array(ext)
    corners, rows, V = _box(lo, hi)
    p = lo + np.random.default_rng(6).random((40, 3)) * (hi - lo)
    box = vf.voronoi3d(p, (*lo, *hi))
    assert abs(box.volumes.sum() / V - 1) <= 4e-16
    for c in (vf.Convex(points=corners), vf.Convex(halfspaces=rows)):
        assert abs(c.volume / V - 1) <= 2.3e-16  # the exact volume, rounded once
        d = vf.voronoi3d(p, c)
        assert d.container_volume == c.volume
        assert abs(d.volumes.sum() / V - 1) <= 4e-16
        assert np.abs(d.volumes - box.volumes).max() <= 1e-15 * V
        for a, b in zip(d.neighbors, box.neighbors, strict=True):
            assert np.array_equal(a, b)


def test_box_an_ulp_thick_is_flat():
    off = 1e6
    lo = np.full(3, off)
    hi = lo + np.array([1.0, 1.0, np.spacing(off)])
    corners, rows, _ = _box(lo, hi)
    for make in (lambda: vf.Convex(points=corners), lambda: vf.Convex(halfspaces=rows)):
        with pytest.raises(ValueError, match="ulp of its coordinates"):
            make()


def test_two_ulps_thick_box_far_out():
    off = 1e6
    lo = np.full(3, off)
    hi = lo + np.array([1.0, 1.0, 2 * np.spacing(off)])
    corners, _, V = _box(lo, hi)
    c = vf.Convex(points=corners)
    assert c.volume == V
    p = lo + np.random.default_rng(2).random((10, 3)) * (hi - lo)
    d = vf.voronoi3d(p, c)
    assert abs(d.volumes.sum() / V - 1) <= 4e-16
    box = vf.voronoi3d(p, (*lo, *hi))
    assert np.abs(d.volumes - box.volumes).max() <= 1e-15 * V
