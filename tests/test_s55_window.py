"""Domains far smaller than the sites' spacing (issue 15, checker37 F1-F3).

A box ``w`` wide around a point whose sites are ~1 away: the bisectors' values at the box's
corners, ``d.(x - p_i) - h``, round at the sites' magnitude, so below ``w ~ 1e-16`` every
corner read 0, nothing was cut and every cell was the whole box (F1); a little larger, the
box sides' crossings were rounded on the sites' ulp grid, a visible part of the box (F3:
the four triangles of sites ``(+-1, 0), (0, +-1)`` got a vertex 2.7e-17 from a corner at
``w = 1e-6``). The cut now takes the exact side of a vertex where its float value is within
rounding of 0, and a crossing in such a box is the double nearest the exact one.

Checked against exact references for every algorithm: the exact cells where float64
represents them, the cells' exact (Fraction) areas summing to the box's, and samples in the
cell of their exactly nearest site (Fractions).
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import shapely

import voroforge as vf

from reference import exact_area

ALGS = ["delaunay", "fortune", "halfplane"]


def _nearest(q, pts):
    """Index of the exactly nearest site of ``q`` and the gap to the second (Fractions)."""
    qx, qy = Fraction(q[0]), Fraction(q[1])
    d = sorted(
        ((Fraction(x) - qx) ** 2 + (Fraction(y) - qy) ** 2, k) for k, (x, y) in enumerate(pts)
    )
    return d[0][1], d[1][0] - d[0][0]


def _check(d, pts, box, margin):
    """Exact tiling, valid cells, samples in their exactly nearest site's cell."""
    want = (Fraction(box[2]) - Fraction(box[0])) * (Fraction(box[3]) - Fraction(box[1]))
    cells = list(d.cells)
    assert all(c.is_empty or c.is_valid for c in cells)
    assert sum(exact_area(c) for c in cells if not c.is_empty) == want
    rng = np.random.default_rng(5)
    t = rng.random((60, 2))
    qs = np.column_stack(
        (box[0] + t[:, 0] * (box[2] - box[0]), box[1] + t[:, 1] * (box[3] - box[1]))
    )
    for q in qs:
        k, gap = _nearest(q, pts)
        if gap <= margin:
            continue  # within rounding of a bisector
        assert cells[k].covers(shapely.Point(q)), (q.tolist(), k)


@pytest.mark.parametrize("alg", ALGS)
@pytest.mark.parametrize("w", [1e-15, 1e-16, 1e-20, 1e-100, 1e-300])
def test_two_sites_halves(alg, w):
    """F1: sites (+-1, 0) in a box ``w`` wide at the origin: the two halves, exactly."""
    pts = np.array([(-1.0, 0.0), (1.0, 0.0)])
    d = vf.voronoi(pts, (-w, -w, w, w), algorithm=alg)
    left = shapely.Polygon([(-w, -w), (0, -w), (0, w), (-w, w)])
    right = shapely.Polygon([(0, -w), (w, -w), (w, w), (0, w)])
    for cell, ref in zip(d.cells, (left, right), strict=True):
        assert shapely.equals_exact(shapely.normalize(cell), shapely.normalize(ref), 0)


@pytest.mark.parametrize("alg", ALGS)
@pytest.mark.parametrize("w", [1e-6, 1e-12, 2.0**-20, 1e-100])
def test_four_sites_triangles(alg, w):
    """F3: sites (+-1, 0), (0, +-1) in a box ``w`` wide: four triangles, exactly."""
    pts = np.array([(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)])
    d = vf.voronoi(pts, (-w, -w, w, w), algorithm=alg)
    corners = [(w, -w), (w, w), (-w, w), (-w, -w)]
    for k, cell in enumerate(d.cells):
        ref = shapely.Polygon([(0, 0), corners[k], corners[(k + 1) % 4]])
        assert shapely.equals_exact(shapely.normalize(cell), shapely.normalize(ref), 0), k


@pytest.mark.parametrize("alg", ALGS)
@pytest.mark.parametrize("w", [1e-17, 1e-40, 1e-200])
def test_three_sites_at_vertex(alg, w):
    """F1: three sites around the exact vertex (0, 0) in a tiny box: three exact cells."""
    pts = np.array([(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0)])
    box = (-w, -w, w, w)
    d = vf.voronoi(pts, box, algorithm=alg)
    refs = [
        shapely.Polygon([(0, 0), (0, -w), (w, -w), (w, w)]),
        shapely.Polygon([(0, 0), (w, w), (-w, w)]),
        shapely.Polygon([(0, 0), (-w, w), (-w, -w), (0, -w)]),
    ]
    for cell, ref in zip(d.cells, refs, strict=True):
        assert shapely.equals_exact(shapely.normalize(cell), shapely.normalize(ref), 0)
    rep = d.describe()
    assert rep.euler_ok, rep


@pytest.mark.parametrize("alg", ALGS)
@pytest.mark.parametrize("radius", [1e4, 1e16])
def test_circle_window(alg, radius):
    """F2: float sites on a circle of radius ``radius`` seen through a unit window at its
    centre: tiling, valid cells, samples in their nearest site's cell."""
    n = 5 if radius < 1e10 else 12
    t = (np.arange(n) + 0.17) * 2 * np.pi / n
    pts = np.column_stack((radius * np.cos(t), radius * np.sin(t)))
    box = (0.0, 0.0, 1.0, 1.0)
    d = vf.voronoi(pts, box, algorithm=alg)
    rep = d.describe()
    assert rep.euler_ok, rep
    # a sample within 1e-9 of a bisector may fall on the rounded edge's other side
    _check(d, pts.tolist(), box, Fraction(2 * radius) * Fraction(1e-9))
