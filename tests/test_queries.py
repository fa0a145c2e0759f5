"""Point queries: nearest site (vf.locate, Diagram.locate) and Sibson interpolation."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest
import shapely
from hypothesis import given
from hypothesis import strategies as st
from scipy.interpolate import griddata

import voroforge as vf

from reference import brute_nearest, brute_sibson

# ---------------------------------------------------------------------------- locate


def test_locate_matches_brute_force_with_ties_and_duplicates():
    rng = np.random.default_rng(3)
    grid = np.stack(np.meshgrid(np.arange(6.0), np.arange(5.0)), -1).reshape(-1, 2)
    sites = np.concatenate((grid, rng.random((40, 2)) * 5, grid[:7]))  # duplicates at the end
    sites = sites[rng.permutation(len(sites))]
    # exact ties: midpoints between grid neighbours and centres of grid squares (4-way)
    mids = np.concatenate((grid + [0.5, 0.0], grid + [0.5, 0.5], grid + [0.0, 0.5]))
    queries = np.concatenate((mids, rng.random((3000, 2)) * 9 - 2))  # many outside the sites
    got = vf.locate(sites, queries)
    want, _ = brute_nearest(sites, queries)
    assert got.dtype == np.int64 and got.shape == (len(queries),)
    np.testing.assert_array_equal(got, want)
    # a duplicated site answers with its first occurrence
    dup = vf.delaunay(sites).duplicate_of
    assert (dup[got] < 0).all()


def test_locate_many_equidistant_sites_picks_lowest_index():
    # 12 integer points exactly on the circle of radius 5, queried at its centre
    ring = np.array(
        [(x, y) for x in range(-5, 6) for y in range(-5, 6) if x * x + y * y == 25], dtype=float
    )
    sites = ring[np.random.default_rng(0).permutation(len(ring))]
    assert vf.locate(sites, [0.0, 0.0]) == 0
    far = np.concatenate((np.full((20, 2), 100.0) + np.arange(20)[:, None], sites))
    assert vf.locate(far, [0.0, 0.0]) == 20
    # 20 points on the circle of radius 25: more ties than the staged KD-tree queries fetch
    big = np.array(
        [(x, y) for x in range(-25, 26) for y in range(-25, 26) if x * x + y * y == 625], float
    )
    assert len(big) == 20
    order = np.random.default_rng(1).permutation(20)
    sites = np.concatenate((big[order], [[0.5, 100.0]]))
    got = vf.locate(sites, [[0.0, 0.0], [0.0, 0.0], [0.0, 1.0]])
    np.testing.assert_array_equal(got, [0, 0, brute_nearest(sites, [[0.0, 1.0]])[0][0]])


def test_locate_single_point_and_errors():
    pts = [[0.0, 0.0], [2.0, 0.0]]
    out = vf.locate(pts, (1.5, 3.0))
    assert isinstance(out, int) and out == 1
    assert vf.locate(pts, np.zeros((0, 2))).shape == (0,)
    with pytest.raises(ValueError, match="xy"):
        vf.locate(pts, [[1.0, 2.0, 3.0]])
    with pytest.raises(ValueError, match="NaN"):
        vf.locate(pts, [np.nan, 1.0])
    with pytest.raises(ValueError, match="without sites"):
        vf.locate(np.zeros((0, 2)), [1.0, 1.0])


def test_diagram_locate_agrees_with_cells():
    rng = np.random.default_rng(5)
    sites = rng.random((300, 2))
    domain = shapely.box(0, 0, 1, 1).difference(shapely.Point(0.5, 0.5).buffer(0.2))
    d = vf.voronoi(sites, domain)
    q = rng.random((2000, 2))
    idx = d.locate(q)
    np.testing.assert_array_equal(idx, brute_nearest(sites, q)[0])
    inside = shapely.contains_xy(domain, q[:, 0], q[:, 1])
    pts = shapely.points(q[inside])
    # the query point lies in the cell of the site returned
    assert shapely.dwithin(d.cells[idx[inside]], pts, 1e-12).all()


def test_diagram_locate_duplicates_map_to_owner():
    sites = np.array([[0.2, 0.2], [0.8, 0.8], [0.2, 0.2], [0.8, 0.8]])
    d = vf.voronoi(sites, (0, 0, 1, 1))
    np.testing.assert_array_equal(d.locate([[0.1, 0.1], [0.9, 0.9], [0.2, 0.2]]), [0, 1, 0])


# ---------------------------------------------------------------------- natural_neighbor


def _inside_hull(sites, q, margin=1e-9):
    hull = shapely.convex_hull(shapely.multipoints(sites))
    inner = hull.buffer(-margin)
    outer = hull.buffer(margin)
    return (
        shapely.contains_xy(inner, q[:, 0], q[:, 1]),
        ~shapely.contains_xy(outer, q[:, 0], q[:, 1]),
    )


def test_linear_precision_random():
    rng = np.random.default_rng(11)
    sites = rng.random((400, 2)) * [3.0, 2.0] + [10.0, -5.0]
    coef = np.array([[1.5, -2.0, 0.7], [-3.0, 0.25, 4.0]])
    vals = np.stack([c[0] + c[1] * sites[:, 0] + c[2] * sites[:, 1] for c in coef], axis=1)
    q = rng.random((5000, 2)) * [3.4, 2.4] + [9.8, -5.2]
    out = vf.natural_neighbor(sites, vals, q)
    assert out.shape == (len(q), 2)
    inside, outside = _inside_hull(sites, q)
    want = np.stack([c[0] + c[1] * q[:, 0] + c[2] * q[:, 1] for c in coef], axis=1)
    assert inside.sum() > 3000 and outside.sum() > 300
    np.testing.assert_allclose(out[inside], want[inside], rtol=0, atol=1e-11)
    assert np.isnan(out[outside]).all()


def test_linear_precision_on_cocircular_grid():
    g = np.stack(np.meshgrid(np.arange(8.0), np.arange(7.0)), -1).reshape(-1, 2)
    f = 2.0 - g[:, 0] + 3.0 * g[:, 1]
    rng = np.random.default_rng(2)
    # centres of grid squares (on four sites' circle), grid lines, random points
    inner = g[(g[:, 0] < 7) & (g[:, 1] < 6)]
    q = np.concatenate(
        (inner + 0.5, inner + [0.5, 0.0], inner + [0.0, 0.25], rng.random((500, 2)) * 6)
    )
    out = vf.natural_neighbor(g, f, q)
    np.testing.assert_allclose(out, 2.0 - q[:, 0] + 3.0 * q[:, 1], atol=1e-12)


@given(st.integers(0, 2**32 - 1), st.integers(4, 60))
def test_linear_precision_property(seed, n):
    rng = np.random.default_rng(seed)
    sites = rng.random((n, 2))
    a, b, c = rng.normal(size=3)
    q = rng.random((50, 2))
    out = vf.natural_neighbor(sites, a + b * sites[:, 0] + c * sites[:, 1], q)
    inside, outside = _inside_hull(sites, q, 1e-6)
    np.testing.assert_allclose(out[inside], (a + b * q[:, 0] + c * q[:, 1])[inside], atol=1e-9)
    assert np.isnan(out[outside]).all()


def test_values_at_sites_duplicates_and_hull_edges():
    sites = np.array([[0, 0], [4, 0], [4, 3], [0, 3], [1, 1], [3, 2], [1, 1]], dtype=float)
    vals = np.array([1.0, 5.0, -2.0, 7.0, 3.0, 0.5, 99.0])
    out = vf.natural_neighbor(sites, vals, sites)
    # a duplicated site takes the first occurrence's value
    np.testing.assert_array_equal(out, [1.0, 5.0, -2.0, 7.0, 3.0, 0.5, 3.0])
    # on a hull edge: linear between its end points, and the limit from inside
    edge = vf.natural_neighbor(sites, vals, [[1.0, 0.0], [4.0, 2.0]])
    np.testing.assert_allclose(edge, [0.75 * 1.0 + 0.25 * 5.0, (5.0 - 2 * 2.0) / 3.0 + 0.0])
    near = vf.natural_neighbor(sites, vals, [[1.0, 1e-7], [4.0 - 1e-7, 2.0]])
    np.testing.assert_allclose(near, edge, atol=1e-5)
    # on the hull edge's line but beyond it: outside
    assert np.isnan(vf.natural_neighbor(sites, vals, [5.0, 0.0]))


def test_extrapolate_nearest_and_single_query():
    rng = np.random.default_rng(4)
    sites = rng.random((50, 2))
    vals = rng.random((50, 3))
    q = np.array([[2.0, 2.0], [-1.0, 0.5], [0.5, 0.5]])
    out = vf.natural_neighbor(sites, vals, q, extrapolate="nearest")
    np.testing.assert_array_equal(out[:2], vals[vf.locate(sites, q[:2])])
    np.testing.assert_array_equal(out[2], vf.natural_neighbor(sites, vals, q[2]))
    assert vf.natural_neighbor(sites, vals, q[2]).shape == (3,)
    assert isinstance(vf.natural_neighbor(sites, vals[:, 0], q[2]), float)


def test_collinear_and_tiny_inputs():
    line = np.array([[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]])
    vals = np.array([1.0, 2.0, 3.0])
    out = vf.natural_neighbor(line, vals, [[1.0, 1.0], [0.5, 0.5]])
    assert out[0] == 2.0 and np.isnan(out[1])
    out = vf.natural_neighbor(line, vals, [[0.5, 0.5]], extrapolate="nearest")
    assert out[0] == 1.0
    assert vf.natural_neighbor([[1.0, 1.0]], [4.0], [1.0, 1.0]) == 4.0


def test_errors_and_inputs_untouched():
    sites = np.random.default_rng(0).random((10, 2))
    vals = np.arange(10.0)
    keep = (sites.copy(), vals.copy())
    with pytest.raises(ValueError, match="shape"):
        vf.natural_neighbor(sites, vals[:9], [0.5, 0.5])
    with pytest.raises(ValueError, match="extrapolate"):
        vf.natural_neighbor(sites, vals, [0.5, 0.5], extrapolate="linear")
    with pytest.raises(ValueError, match="at least one site"):
        vf.natural_neighbor(np.zeros((0, 2)), np.zeros(0), [0.5, 0.5])
    vf.natural_neighbor(sites, vals, [[0.5, 0.5]])
    np.testing.assert_array_equal(sites, keep[0])
    np.testing.assert_array_equal(vals, keep[1])


def test_continuous():
    rng = np.random.default_rng(8)
    sites = rng.random((150, 2))
    vals = rng.random(150)  # rough data: a discontinuity would show as a jump of ~0.5
    t = np.linspace(0.0, 1.0, 20001)
    for y in (0.31, 0.5, 0.77):
        line = np.column_stack((0.1 + 0.8 * t, np.full_like(t, y)))
        f = vf.natural_neighbor(sites, vals, line)
        f = f[~np.isnan(f)]
        assert len(f) > 15000
        assert np.abs(np.diff(f)).max() < 0.02


def test_matches_brute_force_area_differences():
    rng = np.random.default_rng(21)
    sites = rng.random((60, 2))
    vals = rng.normal(size=60)
    inside, _ = _inside_hull(sites, rng.random((30, 2)) * 0.6 + 0.2)
    q = (rng.random((30, 2)) * 0.6 + 0.2)[inside]
    got = vf.natural_neighbor(sites, vals, q)
    weights = brute_sibson(sites, q)  # area stolen from each cell, by brute force
    for w, g in zip(weights, got, strict=True):
        want, k = w @ vals, np.count_nonzero(w)
        assert k >= 3
        assert abs(g - want) < 1e-9


def _franke(x, y):
    return (
        0.75 * np.exp(-((9 * x - 2) ** 2) / 4 - (9 * y - 2) ** 2 / 4)
        + 0.75 * np.exp(-((9 * x + 1) ** 2) / 49 - (9 * y + 1) / 10)
        + 0.5 * np.exp(-((9 * x - 7) ** 2) / 4 - (9 * y - 3) ** 2 / 4)
        - 0.2 * np.exp(-((9 * x - 4) ** 2) - (9 * y - 7) ** 2)
    )


def test_franke_error_against_linear_griddata():
    rng = np.random.default_rng(1)
    sites = rng.random((500, 2))
    vals = _franke(*sites.T)
    g = np.linspace(0.0, 1.0, 101)
    q = np.stack(np.meshgrid(g, g), -1).reshape(-1, 2)
    z0 = vf.natural_neighbor(sites, vals, q)
    z1 = vf.natural_neighbor(sites, vals, q, smooth=True)
    lin = griddata(sites, vals, q, method="linear")
    np.testing.assert_array_equal(np.isnan(z0), np.isnan(lin))
    np.testing.assert_array_equal(np.isnan(z1), np.isnan(lin))
    both = ~np.isnan(lin)
    assert both.sum() > 8000
    exact = _franke(*q[both].T)

    def rms(f):
        return np.sqrt(np.mean((f[both] - exact) ** 2))

    # Z1 (smooth=True) is well below linear interpolation, Z0 about level with it
    assert rms(z1) < 0.5 * rms(lin)
    assert np.abs(z1[both] - exact).max() < np.abs(lin[both] - exact).max()
    assert rms(z0) < 1.1 * rms(lin)


def test_smooth_reproduces_linear_and_spherical_quadratics():
    rng = np.random.default_rng(6)
    sites = rng.random((300, 2))
    q = rng.random((2000, 2)) * 0.8 + 0.1
    lin = 0.5 + 2.0 * sites[:, 0] - 3.0 * sites[:, 1]
    out = vf.natural_neighbor(sites, lin, q, smooth=True)
    np.testing.assert_allclose(out, 0.5 + 2.0 * q[:, 0] - 3.0 * q[:, 1], atol=1e-10)
    # Sibson's Z1 is exact for a + b.x + c |x|^2 when given the exact gradients
    quad = 1.0 + sites[:, 0] - sites[:, 1] + 3.0 * (sites**2).sum(1)
    grads = np.column_stack((1.0 + 6.0 * sites[:, 0], -1.0 + 6.0 * sites[:, 1]))
    out = vf.natural_neighbor(sites, quad, q, smooth=True, gradients=grads)
    np.testing.assert_allclose(out, 1.0 + q[:, 0] - q[:, 1] + 3.0 * (q**2).sum(1), atol=1e-10)
    # ... which plain Sibson is not
    z0 = vf.natural_neighbor(sites, quad, q)
    assert np.abs(z0 - (1.0 + q[:, 0] - q[:, 1] + 3.0 * (q**2).sum(1))).max() > 1e-4


@pytest.mark.parametrize("aspect", [1e-2, 1e-6, 1e-9])
@pytest.mark.parametrize("turn", [0.0, 0.5])
def test_estimated_gradients_on_thin_strips(aspect, turn):
    """Sites on a 1 x 1e-6 strip: the fit's columns were 1e6 apart in size (found by an
    independent check: 3.8e-2 error on linear data); each site's offsets are whitened now."""
    from voroforge.engine.delaunay import delaunay
    from voroforge.engine.interpolate import estimate_gradients

    rng = np.random.default_rng(5)
    c, s = np.cos(turn), np.sin(turn)
    rot = np.array([[c, -s], [s, c]])
    sites = (rng.random((40, 2)) * [1.0, aspect]) @ rot.T
    q = (rng.random((500, 2)) * [0.8, 0.8 * aspect] + [0.1, 0.1 * aspect]) @ rot.T
    lin = 2.5 + 0.7 * sites[:, 0] - 1.3 * sites[:, 1]
    out = vf.natural_neighbor(sites, lin, q, smooth=True)
    ok = ~np.isnan(out)
    assert ok.sum() > 300
    # a turned strip's sites round across it by ~1e-16 / aspect of its width (plain Sibson
    # is off by 4.8e-9 at 1e-9 too)
    tol = 1e-12 + 1e-17 / aspect
    np.testing.assert_allclose(out[ok], 2.5 + 0.7 * q[ok, 0] - 1.3 * q[ok, 1], atol=tol)
    # the fit is exact for quadratics: gradients where the two-ring fit is used
    quad = sites[:, 0] ** 2 - 3.0 * sites[:, 0] * sites[:, 1] + 0.25 * sites[:, 1] ** 2
    x, y = sites.T
    want = np.column_stack((2 * x - 3 * y, -3 * x + 0.5 * y))
    got = estimate_gradients(delaunay(sites), quad[:, None])[:, 0]
    assert np.median(np.abs(got - want).max(axis=1)) < 1e-6


def test_smooth_at_sites_continuity_and_errors():
    rng = np.random.default_rng(9)
    sites = rng.random((120, 2))
    vals = rng.random((120, 2))
    np.testing.assert_array_equal(vf.natural_neighbor(sites, vals, sites, smooth=True), vals)
    shifted = sites + 1e-9
    inside, _ = _inside_hull(sites, shifted, 1e-12)
    near = vf.natural_neighbor(sites, vals, shifted[inside], smooth=True)
    np.testing.assert_allclose(near, vals[inside], atol=1e-5)
    t = np.linspace(0.0, 1.0, 20001)
    line = np.column_stack((0.1 + 0.8 * t, np.full_like(t, 0.45)))
    f = vf.natural_neighbor(sites, vals[:, 0], line, smooth=True)
    assert np.abs(np.diff(f[~np.isnan(f)])).max() < 0.02
    with pytest.raises(ValueError, match="gradients"):
        vf.natural_neighbor(sites, vals, [0.5, 0.5], smooth=True, gradients=np.zeros((120, 2)))
    with pytest.raises(ValueError, match="smooth=True"):
        vf.natural_neighbor(sites, vals, [0.5, 0.5], gradients=np.zeros((120, 2, 2)))


def test_sibson_kernel_runs_without_jit(tmp_path):
    # the kernel must stay plain Python too (coverage runs with NUMBA_DISABLE_JIT=1)
    code = textwrap.dedent(
        """
        import numpy as np
        import voroforge as vf
        rng = np.random.default_rng(0)
        p = rng.random((40, 2))
        q = rng.random((30, 2)) * 0.5 + 0.25
        f = 1.0 + 2.0 * p[:, 0] - p[:, 1]
        out = [vf.natural_neighbor(p, f, q), vf.natural_neighbor(p, f, q, smooth=True)]
        np.save("out.npy", np.stack(out))
        """
    )
    env = {**os.environ, "NUMBA_DISABLE_JIT": "1"}
    subprocess.run([sys.executable, "-c", code], check=True, env=env, cwd=tmp_path, timeout=120)
    got = np.load(tmp_path / "out.npy")
    rng = np.random.default_rng(0)
    rng.random((40, 2))  # the sites, drawn first above
    q = rng.random((30, 2)) * 0.5 + 0.25
    want = 1.0 + 2.0 * q[:, 0] - q[:, 1]
    np.testing.assert_allclose(got, np.stack([want, want]), atol=1e-12)


# --- regressions from the QA pass of issue 4 ------------------------------------------------


@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_natural_neighbor_rejects_non_finite_values(bad):
    # NaN/inf data were interpolated silently (NaN around that site, and with smooth=True
    # in the gradients of its neighbours too)
    pts = np.random.default_rng(0).random((20, 2))
    vals = np.zeros((20, 2))
    vals[7, 1] = bad
    with pytest.raises(ValueError, match="values contains a non-finite value .*row 7"):
        vf.natural_neighbor(pts, vals, [0.5, 0.5])


@pytest.mark.parametrize("scale", [1e-300, 1e-150, 1e150, 1e300])
def test_queries_at_extreme_scales(scale):
    # squared distances under/overflowed: locate tied everything (1e-300) or raised an
    # IndexError (1e300); Sibson's incircle and areas gave NaN everywhere beyond 1e+-150
    rng = np.random.default_rng(16)
    pts = rng.random((30, 2))
    q = rng.random((200, 2))
    ref = np.argmin(((q[:, None] - pts[None]) ** 2).sum(-1), axis=1)
    assert np.array_equal(vf.locate(pts * scale, q * scale), ref)
    assert np.array_equal(vf.locate(pts, q), ref)
    periodic = vf.voronoi(pts * scale, (0, 0, scale, scale), periodic=True)
    assert np.array_equal(
        periodic.locate(q * scale), vf.voronoi(pts, (0, 0, 1, 1), periodic=True).locate(q)
    )
    wrapped = vf.voronoi(pts * scale, (0, 0, scale, scale), periodic=True, wrap=True)
    unit = vf.voronoi(pts, (0, 0, 1, 1), periodic=True, wrap=True)
    assert shapely.get_num_geometries(wrapped.cells).tolist() == (
        shapely.get_num_geometries(unit.cells).tolist()
    )
    z = vf.natural_neighbor(pts * scale, 2 * pts[:, 0] - pts[:, 1], q * scale)
    inside = np.isfinite(vf.natural_neighbor(pts, pts[:, 0], q))
    assert np.array_equal(np.isfinite(z), inside) and inside.sum() > 100
    assert np.allclose(z[inside], (2 * q[:, 0] - q[:, 1])[inside], rtol=0, atol=1e-12)


@pytest.mark.parametrize("scale", [1e-310, 1e-300, 1e-200, 1e160, 1e200, 1e300])
def test_smooth_natural_neighbor_at_extreme_scales(scale):
    # checker9 F2: the gradient fit's normal equations (fourth powers of the offsets)
    # overflowed or vanished past ~1e+-155 (numpy's "Eigenvalues did not converge"); they
    # are formed on each site's offsets scaled by a power of two, in the working frame, so
    # Z1 is the unit-scale Z1 (the fit is scale-invariant) and exact on quadratics
    rng = np.random.default_rng(7)
    pts = rng.random((40, 2))
    q = 0.3 + 0.4 * rng.random((50, 2))
    quad = 1.0 + pts[:, 0] - pts[:, 1] + 3.0 * (pts**2).sum(1)
    unit = vf.natural_neighbor(pts, quad, q, smooth=True)
    got = vf.natural_neighbor(pts * scale, quad, q * scale, smooth=True)
    ok = np.isfinite(unit)
    assert ok.sum() > 40 and np.array_equal(np.isfinite(got), ok)
    # subnormal sites (1e-310) are rounded to 2**-1074: their fit moves by ~1e-13
    atol = 1e-12 if scale > 1e-300 else 1e-9
    np.testing.assert_allclose(got[ok], unit[ok], rtol=0, atol=atol)
    # the gradients in the user's units scale as 1 / scale
    from voroforge.engine.delaunay import delaunay
    from voroforge.engine.interpolate import estimate_gradients

    lin = 2.0 * pts[:, 0] - pts[:, 1]
    g = estimate_gradients(delaunay(pts * 1e200), lin[:, None])[:, 0]
    np.testing.assert_allclose(g * 1e200, np.tile([2.0, -1.0], (40, 1)), rtol=1e-9)


def test_locate_far_queries_exactly_nearest():
    # |q| >= 1e155: squared distances overflow in float64; the answer is still the nearest
    # site, checked in exact rational arithmetic (lowest index on a tie)
    from fractions import Fraction

    rng = np.random.default_rng(12)
    pts = rng.random((80, 2))
    qs = [[1e155, 0.5], [-1e200, 1e200], [1e308, 1e308], [-1e308, -3e307], [3.0, 2e160]]
    d = vf.voronoi(pts, (0, 0, 1, 1))

    def exact(q):
        qx, qy = (Fraction(v) for v in q)
        d2 = [(qx - Fraction(x)) ** 2 + (qy - Fraction(y)) ** 2 for x, y in pts]
        return min(range(len(pts)), key=lambda i: (d2[i], i))

    want = [exact(q) for q in qs]
    assert vf.locate(pts, qs).tolist() == want
    assert d.locate(qs).tolist() == want
    values = np.arange(80.0)
    assert vf.natural_neighbor(pts, values, qs, extrapolate="nearest").tolist() == want
    assert vf.locate(pts, [[0.25, 0.75], qs[0]]).tolist() == [vf.locate(pts, [0.25, 0.75]), want[0]]


def test_locate_decides_float_ties_exactly():
    # squared distances 2.5e11 apart by 1e-6 round to the same float: the nearest site is
    # the one whose cell holds the query, not the lower index (independent check, F6)
    sites = np.array([[0.3, 0.3], [0.3 + 1e-12, 0.3], [1e6, 1e6]])
    q = np.array([[5e5, 0.3], [5e5, 1e5], [0.3, 0.3]])
    d = vf.voronoi(sites, (0, 0, 1e6, 1e6))
    want = [1, 1, 0]
    assert vf.locate(sites, q).tolist() == want
    assert d.locate(q).tolist() == want
    for k in range(2):
        assert d.cells[1].covers(shapely.Point(q[k]))
    # an exact tie still goes to the lowest index
    assert vf.locate([[0.0, 0.0], [2.0, 0.0]], [1.0, 5.0]) == 0


@pytest.mark.parametrize("off", [(5e5, 4e6), (1e9, 1e9), (-3e7, 2e5)])
def test_natural_neighbor_far_from_the_origin_keeps_its_digits(off):
    # the same sites and queries shifted by an exact offset give the same interpolant: the
    # areas are computed at the sites' corner (independent check: 1.25e-8 off at 1e9)
    g = np.random.default_rng(3)
    x, y = np.meshgrid(np.arange(5.0), np.arange(5.0))
    sites = np.column_stack((x.ravel(), y.ravel()))
    vals = g.random(25)
    far = np.add(off, 0.3 + g.random((10, 2)) * 3.4)
    q = far - off  # exact: the queries are the same points in both frames
    here = vf.natural_neighbor(sites, vals, q)
    there = vf.natural_neighbor(sites + off, vals, far)
    assert np.abs(there - here).max() <= 1e-13
