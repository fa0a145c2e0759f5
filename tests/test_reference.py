"""The slow references in reference.py against closed forms (they are trusted, so test them)."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import shapely

from reference import (
    brute_lloyd_step,
    brute_power,
    brute_sibson,
    brute_voronoi,
    exact_circumcentre,
    exact_polygon_moments,
    exact_ring_moments,
    power_owner,
)


def test_exact_circumcentre_closed_forms():
    assert exact_circumcentre((0.0, 0.0), (4.0, 0.0), (0.0, 2.0)) == (2.0, 1.0)
    # orientation does not matter, large offsets keep every bit
    assert exact_circumcentre((5e6, 5e6), (5e6, 5e6 + 2.0), (5e6 + 4.0, 5e6)) == (5e6 + 2, 5e6 + 1)
    # 7/6 is not a double: the result is the nearest one
    assert exact_circumcentre((0.0, 0.0), (3.0, 0.0), (1.0, 3.0)) == (1.5, float(Fraction(7, 6)))
    with pytest.raises(ZeroDivisionError):
        exact_circumcentre((0.0, 0.0), (1.0, 1.0), (2.0, 2.0))


def test_exact_circumcentre_is_equidistant():
    rng = np.random.default_rng(0)
    for a, b, c in rng.random((50, 3, 2)):
        x, y = exact_circumcentre(a, b, c)
        r = [np.hypot(x - p[0], y - p[1]) for p in (a, b, c)]
        assert max(r) - min(r) <= 1e-12 * max(r)


def test_ring_moments_of_a_square():
    sq = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
    assert exact_ring_moments(sq) == (1, Fraction(1, 2), Fraction(1, 2), Fraction(2, 3))
    # closed or open, the same; clockwise flips every sign
    assert exact_ring_moments([*sq, sq[0]]) == exact_ring_moments(sq)
    assert exact_ring_moments(sq[::-1]) == tuple(-m for m in exact_ring_moments(sq))
    # about the centre: no first moment, polar moment 1/6
    assert exact_ring_moments(sq, (0.5, 0.5)) == (1, 0, 0, Fraction(1, 6))


def test_polygon_moments_against_shapely_with_holes_and_parts():
    geom = shapely.MultiPolygon(
        [
            shapely.box(0, 0, 3, 2).difference(shapely.box(1, 0.5, 2, 1.5)),
            shapely.Polygon([(4, 0), (6, 0), (5, 3)]),
        ]
    )
    area, mx, my, m2 = exact_polygon_moments(geom, (1.0, 1.0))
    assert float(area) == pytest.approx(geom.area, rel=1e-15)
    cx, cy = geom.centroid.coords[0]
    assert float(mx / area) + 1.0 == pytest.approx(cx, rel=1e-14)
    assert float(my / area) + 1.0 == pytest.approx(cy, rel=1e-14)
    # polar moment of the 3 x 2 box less the 1 x 1 hole about (1, 1), plus the triangle's
    box = Fraction(3 * 2) * (Fraction(9 + 4, 12) + Fraction(1, 2) ** 2 + Fraction(0) ** 2)
    hole = Fraction(1) * (Fraction(2, 12) + Fraction(1, 2) ** 2 + Fraction(0) ** 2)
    # triangle: area 3, centroid (5, 1) -> offset (4, 0); spread = sum |v - g|^2 / 12
    spread = Fraction((1 + 1) + (1 + 1) + (0 + 4), 12)
    tri = Fraction(3) * (Fraction(16) + spread)
    assert m2 == box - hole + tri


def test_power_with_equal_weights_is_voronoi():
    rng = np.random.default_rng(1)
    pts = rng.random((25, 2))
    dom = shapely.box(0, 0, 1, 1)
    a = shapely.area(brute_power(pts, np.full(25, 0.3), dom))
    b = shapely.area(brute_voronoi(pts, dom))
    assert np.allclose(a, b, rtol=0, atol=1e-13)
    assert a.sum() == pytest.approx(1.0, rel=1e-13)


def test_power_owner_and_a_heavy_site():
    pts = np.array([[0.2, 0.5], [0.8, 0.5], [0.2, 0.5]])
    w = np.array([0.0, 0.0, 0.12])
    assert power_owner(pts, w).tolist() == [2, 1, 2]  # the heavier copy owns the cell
    cells = brute_power(pts, w, shapely.box(0, 0, 1, 1))
    assert cells[0].is_empty and not cells[2].is_empty
    # the power bisector of 2 and 1: |x-p2|^2 - 0.12 = |x-p1|^2  ->  x = (0.6 + 0.12) / 1.2
    assert cells[2].bounds[2] == pytest.approx(0.6, abs=1e-15)
    assert cells[1].area == pytest.approx(0.4, abs=1e-15)
    w = np.array([0.0, -1.0, 0.0])  # a light site loses its cell altogether
    assert brute_power(pts, w, shapely.box(0, 0, 1, 1))[1].is_empty


def test_sibson_weights_reproduce_linear_functions():
    rng = np.random.default_rng(2)
    sites = rng.random((30, 2))
    q = rng.random((10, 2)) * 0.4 + 0.3
    w = brute_sibson(sites, q)
    assert w.shape == (10, 30) and np.all(w >= 0)
    assert np.allclose(w.sum(1), 1.0, rtol=0, atol=1e-14)
    assert np.allclose(w @ sites, q, rtol=0, atol=1e-12)  # linear precision of Sibson's weights
    assert np.all(np.count_nonzero(w, axis=1) >= 3)
    # at a site the weight is 1 there; outside the hull the reference refuses
    assert brute_sibson(sites, sites[4])[0].tolist() == np.eye(30)[4].tolist()
    with pytest.raises(ValueError, match="hull"):
        brute_sibson(sites, [[5.0, 5.0]])


def test_sibson_at_a_square_centre_is_a_quarter_each():
    sites = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    w = brute_sibson(sites, [[0.5, 0.5]])[0]
    assert np.allclose(w, 0.25, rtol=0, atol=1e-15)


def test_lloyd_step_of_four_symmetric_sites():
    pts = np.array([[0.1, 0.1], [0.9, 0.1], [0.9, 0.9], [0.1, 0.9]])
    z = brute_lloyd_step(pts, shapely.box(0, 0, 1, 1))
    want = np.array([[0.25, 0.25], [0.75, 0.25], [0.75, 0.75], [0.25, 0.75]])
    assert np.allclose(z, want, rtol=0, atol=1e-15)
    # a duplicate has no cell and stays where it is; the input is not modified
    dup = np.vstack((pts, pts[:1]))
    z = brute_lloyd_step(dup, shapely.box(0, 0, 1, 1))
    assert np.array_equal(z[4], pts[0]) and np.array_equal(dup[4], pts[0])
