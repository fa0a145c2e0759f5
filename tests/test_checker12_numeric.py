"""Fixes of checker12's numeric findings: densities and values near float64's limits.

References: a CVT does not change when the density is multiplied by a constant (a constant
density is the uniform one, whose moments are closed-form and exact); Sibson's interpolants
reproduce linear functions exactly.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import shapely

import voroforge as vf

PTS = np.random.default_rng(5).random((40, 2))
BOX = (0, 0, 1, 1)


def _constant(c):
    return lambda x, y: np.full(np.shape(x), c)


@pytest.mark.parametrize("method", ["lloyd", "lbfgs"])
@pytest.mark.parametrize("c", [1e-320, 1e-308, 1e-305, 1e160, 1e300, 1.7e308])
def test_a_constant_density_of_any_size_relaxes_as_the_uniform_one(method, c):
    # F1: mass subnormal -> 1 / mass = inf -> "points contains infinite coordinates";
    # F2: L-BFGS's curvature products overflowed (c >= 1e155) and it degraded to Lloyd steps
    ref = vf.lloyd(PTS, BOX, iterations=8, method=method)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no overflow / invalid-value warnings either
        r = vf.lloyd(PTS, BOX, iterations=8, method=method, density=_constant(c))
        ras = vf.lloyd(PTS, BOX, iterations=8, method=method, density=(np.full((3, 4), c), BOX))
    for got in (r, ras):
        assert got.iterations == ref.iterations
        assert np.abs(got.points - ref.points).max() <= 1e-13
        if c >= 1e-300:  # the energies themselves are subnormal below
            assert np.allclose(got.energy / c, ref.energy, rtol=1e-12, atol=0)


def test_capacity_relaxation_with_a_tiny_density_is_the_uniform_one():
    areas = np.linspace(1, 3, 40)
    areas /= areas.sum()
    ref = vf.lloyd(PTS, BOX, iterations=3, areas=areas)
    r = vf.lloyd(PTS, BOX, iterations=3, areas=areas, density=_constant(1e-310))
    assert np.abs(r.points - ref.points).max() <= 1e-12
    assert np.allclose(r.diagram.areas, areas, rtol=1e-8, atol=0)


@pytest.mark.parametrize("method", ["lloyd", "lbfgs"])
def test_a_narrow_density_keeps_the_sites_of_massless_cells(method):
    # F1: exp(-r^2 / 4e-4) has subnormal masses in the cells around its peak's
    def gauss(x, y):
        return np.exp(-((x - 0.5) ** 2 + (y - 0.5) ** 2) / 4e-4)

    r = vf.lloyd(PTS, BOX, iterations=6, method=method, density=gauss)
    assert np.isfinite(r.points).all() and np.isfinite(r.energy).all()
    assert r.energy[-1] <= r.energy[0]
    # scaling the density by a power of two changes no bit (the moments are scaled alike)
    for e in (20, 1000):
        s = vf.lloyd(
            PTS,
            BOX,
            iterations=6,
            method=method,
            density=lambda x, y, e=e: np.ldexp(gauss(x, y), e),
        )
        assert np.array_equal(s.points, r.points)
    # sites whose cells hold no density at all (exp underflows to 0 on the whole cell) stay
    d0 = vf.voronoi(PTS, BOX)
    far = [i for i, cell in enumerate(d0.cells) if cell.distance(shapely.Point(0.5, 0.5)) > 0.55]
    assert far
    one = vf.lloyd(PTS, BOX, iterations=1, method="lloyd", density=gauss)
    assert np.array_equal(one.points[far], PTS[far])


@pytest.mark.parametrize("top", [1.0, 1e300, 8e307, 1.7e308])
def test_smooth_natural_neighbour_reproduces_linear_data_near_the_double_limit(top):
    # F7: values +-8e307 gave Z1 = NaN (differences in the gradient fit overflowed)
    p = np.random.default_rng(0).random((20, 2))
    q = np.random.default_rng(1).random((40, 2)) * 0.4 + 0.3
    a, b, c = 0.3, -0.45, 0.1
    vals = top * (a * p[:, 0] + b * p[:, 1] + c)
    exact = top * (a * q[:, 0] + b * q[:, 1] + c)
    inside = ~np.isnan(vf.natural_neighbor(p, vals / top, q))
    assert inside.sum() >= 30
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for smooth in (False, True):
            z = vf.natural_neighbor(p, vals, q, smooth=smooth)
            assert np.isfinite(z[inside]).all()
            assert np.abs(z[inside] - exact[inside]).max() <= 1e-14 * top
    # the interpolant is linear in the values: a power-of-two scale changes no bit
    z1 = vf.natural_neighbor(p, vals, q, smooth=True)
    half = vf.natural_neighbor(p, np.ldexp(vals, -10), q, smooth=True)
    assert np.array_equal(z1[inside], np.ldexp(half[inside], 10))


def test_gradients_of_values_near_the_double_limit():
    from voroforge.engine.interpolate import estimate_gradients

    p = np.random.default_rng(2).random((30, 2))
    tri = vf.delaunay(p)
    vals = 8e307 * (0.7 * p[:, 0] - 0.9 * p[:, 1])
    g = estimate_gradients(tri, np.column_stack((vals, -vals)))
    assert np.allclose(g[:, 0], [5.6e307, -7.2e307], rtol=1e-12, atol=0)
    assert np.allclose(g[:, 1], [-5.6e307, 7.2e307], rtol=1e-12, atol=0)


def test_smooth_natural_neighbour_of_a_field_spanning_the_double_range():
    # F7's reproducer: values linspace(-8e307, 8e307) gave NaN at (0.5, 0.5)
    p = np.random.default_rng(0).random((20, 2))
    v = np.linspace(-8e307, 8e307, 20)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        z1 = vf.natural_neighbor(p, v, [0.5, 0.5], smooth=True)
    ref = 2.0**10 * vf.natural_neighbor(p, v * 2.0**-10, [0.5, 0.5], smooth=True)
    assert np.isfinite(z1) and z1 == ref


def test_power_fit_with_many_sites_in_the_hole_of_a_ring():
    # F9: 200 sites in the unit square, 55 of them in the hole of the ring, targets spanning
    # 1e6: Newton from either start stalled at error 1.1 (sliver cells at the hole's edge)
    ring = shapely.box(0, 0, 1, 1).difference(shapely.Point(0.5, 0.5).buffer(0.3))
    r = np.random.default_rng(21)
    pts = r.random((200, 2))
    t = np.geomspace(1e-6, 1, 200)
    r.shuffle(t)
    t *= ring.area / t.sum()
    assert (~shapely.contains_xy(ring, pts[:, 0], pts[:, 1])).sum() == 55
    d = vf.power_fit(pts, t, ring)
    # the cells' own polygons (shapely's areas, not the fit's) have the targets and tile it
    cells = list(d.cells)
    assert np.all(np.abs(shapely.area(cells) - t) <= 1e-6 * t)
    assert shapely.union_all(cells).symmetric_difference(ring).area <= 1e-9
    assert all(shapely.covered_by(c, ring.buffer(1e-9)) for c in cells)
