"""Lloyd's moments of cells spanning far MultiPolygon parts, against exact Fractions.

``uniform_moments`` and ``raster_moments`` summed every part's shoelace about the cell's
site: across a gap of 1e12 the terms are the gap times the part's size and cancel to its
area (mass off by 6e-5 relative, the centroid by 4e-6 of the gap). Where the terms cancel,
each far part is now summed about its own vertex and moved to the site.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import shapely
from shapely.geometry import MultiPolygon, box

import voroforge as vf
from voroforge.engine.diagram import buffers
from voroforge.engine.integrate import Integrator


def _exact_moments(geom, origin):
    """``(mass, first x, first y, second)`` of uniform density on ``geom`` about ``origin``."""
    ox, oy = Fraction(origin[0]), Fraction(origin[1])
    m = fx = fy = s2 = Fraction(0)
    for poly in shapely.get_parts(geom):
        for k, ring in enumerate([poly.exterior, *poly.interiors]):
            xy = [(Fraction(x) - ox, Fraction(y) - oy) for x, y in ring.coords]
            a = sx = sy = q = Fraction(0)
            for (x0, y0), (x1, y1) in zip(xy[:-1], xy[1:], strict=True):
                cr = x0 * y1 - x1 * y0
                a += cr
                sx += (x0 + x1) * cr
                sy += (y0 + y1) * cr
                q += (x0 * x0 + x0 * x1 + x1 * x1 + y0 * y0 + y0 * y1 + y1 * y1) * cr
            sign = (1 if a >= 0 else -1) * (1 if k == 0 else -1)
            m += sign * a / 2
            fx += sign * sx / 6
            fy += sign * sy / 6
            s2 += sign * q / 12
    return m, fx, fy, s2


def _far_parts(gap):
    rng = np.random.default_rng(33)
    dom = MultiPolygon([box(0, 0, 1, 1), box(gap, 0, gap + 1, 1)])
    return rng.random((20, 2)), dom


@pytest.mark.parametrize("gap", [1e6, 1e9, 1e12])
def test_uniform_moments_of_cells_spanning_far_parts(gap):
    pts, dom = _far_parts(gap)
    d = vf.voronoi(pts, dom)
    mass, first, second = Integrator(None, len(pts))(buffers(d), pts)
    spanning = 0
    for i, cell in enumerate(d.cells):
        if cell.is_empty:
            continue
        m, fx, fy, s2 = _exact_moments(cell, pts[i])
        assert abs(Fraction(mass[i]) - m) <= Fraction(1, 10**14) * m, i
        assert abs(Fraction(second[i]) - s2) <= Fraction(1, 10**13) * s2, i
        # centroid: the site plus first / mass, within 1e-14 of the gap (its coordinates' ulp)
        cx = Fraction(pts[i, 0]) + fx / m
        cy = Fraction(pts[i, 1]) + fy / m
        got_x = Fraction(pts[i, 0]) + Fraction(first[i, 0]) / Fraction(mass[i])
        got_y = Fraction(pts[i, 1]) + Fraction(first[i, 1]) / Fraction(mass[i])
        assert abs(float(got_x - cx)) <= 1e-14 * gap, i
        assert abs(float(got_y - cy)) <= 1e-14, i
        if len(shapely.get_parts(cell)) > 1:
            spanning += 1
            # shapely's centroid as a second reference
            assert abs(float(cx) - cell.centroid.x) <= 1e-13 * gap, i
    assert spanning  # some cell reaches across the gap (else nothing far was checked)


@pytest.mark.parametrize("gap", [1e6, 1e9, 1e12])
def test_raster_moments_of_cells_spanning_far_parts(gap):
    # a raster of ones over both parts: the uniform density's exact moments (cut into pixel
    # rows at y = 0.25, 0.5, 0.75, exact binary fractions); it was 6e-5 off at 1e12
    pts, dom = _far_parts(gap)
    d = vf.voronoi(pts, dom)
    raster = (np.ones((4, 4)), (0.0, 0.0, gap + 1.0, 1.0))
    mass, first, _ = Integrator(raster, len(pts))(buffers(d), pts)
    spanning = 0
    for i, cell in enumerate(d.cells):
        m, fx, _, _ = _exact_moments(cell, pts[i])
        spanning += len(shapely.get_parts(cell)) > 1
        assert abs(Fraction(mass[i]) - m) <= Fraction(1, 10**13) * m, i
        got_x = Fraction(pts[i, 0]) + Fraction(first[i, 0]) / Fraction(mass[i])
        assert abs(float(got_x - Fraction(pts[i, 0]) - fx / m)) <= 1e-13 * gap, i
    assert spanning


@pytest.mark.parametrize("gap", [1e6, 1e12])
def test_lloyd_step_to_exact_centroids_across_far_parts(gap):
    pts, dom = _far_parts(gap)
    d = vf.voronoi(pts, dom)
    r = vf.lloyd(pts, dom, iterations=1)
    for i, cell in enumerate(d.cells):
        m, fx, fy, _ = _exact_moments(cell, pts[i])
        assert abs(r.points[i, 0] - float(Fraction(pts[i, 0]) + fx / m)) <= 1e-14 * gap, i
        assert abs(r.points[i, 1] - float(Fraction(pts[i, 1]) + fy / m)) <= 1e-14, i


def test_uniform_moments_of_cells_away_from_their_sites():
    # sites in the notch of a U: their cells lie beside them, the shoelace's terms about the
    # site cancel (the mass was 1.9e-13 off relative, now summed about the cell's vertex)
    dom = box(0, 0, 1, 1).difference(box(0.3, 0.3, 0.7, 1.0))
    pts = np.random.default_rng(5).random((300, 2))
    d = vf.voronoi(pts, dom)
    mass, first, second = Integrator(None, len(pts))(buffers(d), pts)
    for i, cell in enumerate(d.cells):
        m, fx, fy, s2 = _exact_moments(cell, pts[i])
        assert abs(Fraction(mass[i]) - m) <= Fraction(1, 10**15) * m, i
        assert abs(Fraction(first[i, 0]) - fx) <= Fraction(1, 10**15) * (abs(fx) + m), i
        assert abs(Fraction(first[i, 1]) - fy) <= Fraction(1, 10**15) * (abs(fy) + m), i
        assert abs(Fraction(second[i]) - s2) <= Fraction(1, 10**15) * s2, i
