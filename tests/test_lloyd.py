"""Lloyd relaxation, the L-BFGS CVT solver and density-weighted cell moments."""

from __future__ import annotations

from math import factorial

import numpy as np
import pytest
import shapely
from hypothesis import given
from hypothesis import strategies as st

import voroforge as vf
from voroforge.engine.diagram import buffers
from voroforge.engine.integrate import RADON_NODES, RADON_WEIGHTS, Integrator

from reference import brute_lloyd_step, pixel_density_moments, triangulated_moments

SQUARE = shapely.box(0, 0, 1, 1)
HOLED = shapely.box(0, 0, 1, 1).difference(shapely.Point(0.5, 0.5).buffer(0.25, quad_segs=6))
L_SHAPE = shapely.Polygon([(0, 0), (1, 0), (1, 0.4), (0.4, 0.4), (0.4, 1), (0, 1)])
TWO_PARTS = shapely.MultiPolygon([shapely.box(0, 0, 0.45, 1), shapely.box(0.55, 0, 1, 1)])


@pytest.mark.parametrize("domain", [SQUARE, HOLED, L_SHAPE, TWO_PARTS])
def test_uniform_moments_are_exact(domain):
    rng = np.random.default_rng(0)
    pts = rng.random((60, 2))
    d = vf.voronoi(pts, domain)
    mass, first, second = Integrator(None, 60)(buffers(d), pts)
    ref = triangulated_moments(d.cells, pts)
    assert np.allclose(mass, ref[0], rtol=0, atol=1e-14)
    assert np.allclose(first, ref[1], rtol=0, atol=1e-14)
    assert np.allclose(second, ref[2], rtol=0, atol=1e-14)
    assert np.allclose(mass, d.areas, rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize("domain", [SQUARE, HOLED, L_SHAPE, TWO_PARTS])
def test_energy_never_increases(domain):
    pts = np.random.default_rng(1).random((150, 2))
    r = vf.lloyd(pts, domain, iterations=25)
    assert r.energy.shape == (26,) and r.shift.shape == (25,) and r.iterations == 25
    assert np.all(np.diff(r.energy) <= 1e-15 * r.energy[0])
    assert r.energy[-1] < 0.9 * r.energy[0]
    assert np.array_equal(r.diagram.sites, r.points)
    # the recorded energy is the energy of the returned diagram and points
    _, _, second = Integrator(None, 150)(buffers(r.diagram), r.points)
    assert second.sum() == pytest.approx(r.energy[-1], rel=1e-12)
    if domain is SQUARE:  # centroids of cells cut by a concave boundary may lie outside it
        assert np.all((r.points >= 0) & (r.points <= 1))


def test_converged_sites_are_centroids():
    pts = np.random.default_rng(2).random((40, 2))
    r = vf.lloyd(pts, (0, 0, 1, 1), iterations=2000, tol=1e-10)
    assert r.iterations < 2000 and r.shift[-1] <= 1e-10
    assert np.max(np.hypot(*(r.diagram.centroids - r.points).T)) <= 1e-9


def test_radon_rule_degree_five():
    assert RADON_WEIGHTS.sum() == pytest.approx(1.0, abs=1e-15)
    # reference triangle (0,0), (1,0), (0,1): ∫ x^p y^q = p! q! / (p + q + 2)!
    x = RADON_NODES[:, 1]
    y = RADON_NODES[:, 2]
    for p in range(6):
        for q in range(6 - p):
            exact = factorial(p) * factorial(q) / factorial(p + q + 2)
            approx = 0.5 * (RADON_WEIGHTS * x**p * y**q).sum()
            assert approx == pytest.approx(exact, rel=1e-13, abs=1e-16), (p, q)


@pytest.mark.parametrize("domain", [SQUARE, HOLED, L_SHAPE])
def test_callable_density_linear_is_exact(domain):
    pts = np.random.default_rng(3).random((50, 2))
    d = vf.voronoi(pts, domain)
    mass, first, _ = Integrator(lambda x, y: 1.0 + 2.0 * x + 0.5 * y, 50)(buffers(d), pts)
    area = shapely.area(d.cells)
    cen = np.array([c.centroid.coords[0] if not c.is_empty else (0, 0) for c in d.cells])
    assert np.allclose(mass, area * (1 + 2 * cen[:, 0] + 0.5 * cen[:, 1]), rtol=1e-12)
    # constant density: the same numbers as the closed form
    m1, f1, s1 = (a.copy() for a in Integrator(None, 50)(buffers(d), pts))
    m2, f2, s2 = Integrator(lambda x, y: np.ones_like(x), 50)(buffers(d), pts)
    assert np.allclose(m1, m2, rtol=1e-12) and np.allclose(s1, s2, rtol=1e-12)
    assert np.allclose(f1, f2, rtol=1e-10, atol=1e-16)


@pytest.mark.parametrize("domain", [SQUARE, HOLED, L_SHAPE])
def test_raster_density_exact_over_cells(domain):
    rng = np.random.default_rng(4)
    pts = rng.random((30, 2))
    values = rng.uniform(0.0, 3.0, size=(7, 9))
    values[2, 3] = 0.0
    bounds = (-0.05, 0.1, 1.02, 0.93)  # not aligned with the domain; 0 outside
    d = vf.voronoi(pts, domain)
    mass, first, _ = Integrator((values, bounds), 30)(buffers(d), pts)
    ref_mass, ref_first = pixel_density_moments(d.cells, pts, values, bounds)
    assert np.allclose(mass, ref_mass, rtol=1e-10, atol=1e-14)
    assert np.allclose(first, ref_first, rtol=1e-9, atol=1e-14)


def test_raster_density_relaxation_monotone_and_attracts_sites():
    values = np.ones((20, 20))
    values[:, 10:] = 9.0  # right half nine times denser
    pts = np.random.default_rng(5).random((120, 2))
    r = vf.lloyd(pts, (0, 0, 1, 1), iterations=30, density=(values, (0, 0, 1, 1)))
    assert np.all(np.diff(r.energy) <= 1e-15 * r.energy[0])
    # a CVT's site density goes as density**0.5: 3:1 here; 30 Lloyd steps get part way
    assert (r.points[:, 0] > 0.5).sum() > 0.55 * len(pts) > (pts[:, 0] > 0.5).sum()


def test_callable_density_attracts_sites():
    pts = np.random.default_rng(6).random((100, 2))

    def rho(x, y):
        return np.exp(-20 * ((x - 0.3) ** 2 + (y - 0.3) ** 2))

    r = vf.lloyd(pts, (0, 0, 1, 1), iterations=30, density=rho)
    near = np.hypot(r.points[:, 0] - 0.3, r.points[:, 1] - 0.3) < 0.3
    start = np.hypot(pts[:, 0] - 0.3, pts[:, 1] - 0.3) < 0.3
    assert near.sum() > 1.5 * start.sum()
    # decreasing up to the quadrature error
    assert np.all(np.diff(r.energy) <= 1e-9 * r.energy[0])


def test_gradient_matches_finite_differences():
    pts = np.random.default_rng(7).random((25, 2))
    integ = Integrator(None, 25)

    def energy(z):
        d = vf.voronoi(z, (0, 0, 1, 1))
        return integ(buffers(d), z)[2].sum()

    d = vf.voronoi(pts, (0, 0, 1, 1))
    grad = -2.0 * integ(buffers(d), pts)[1].copy()
    h = 1e-6
    for i, k in [(0, 0), (3, 1), (11, 0), (24, 1)]:
        zp = pts.copy()
        zm = pts.copy()
        zp[i, k] += h
        zm[i, k] -= h
        fd = (energy(zp) - energy(zm)) / (2 * h)
        assert fd == pytest.approx(grad[i, k], rel=1e-5, abs=1e-11)


def test_lbfgs_beats_lloyd_per_iteration():
    pts = np.random.default_rng(8).random((300, 2))
    lloyd = vf.lloyd(pts, (0, 0, 1, 1), iterations=60)
    quasi = vf.lloyd(pts, (0, 0, 1, 1), iterations=60, method="lbfgs")
    assert quasi.method == "lbfgs" and quasi.energy.shape == (quasi.iterations + 1,)
    assert quasi.energy[-1] < lloyd.energy[-1]
    assert np.all(np.diff(quasi.energy) <= 1e-15 * quasi.energy[0])
    assert np.array_equal(quasi.diagram.sites, quasi.points)
    _, _, second = Integrator(None, 300)(buffers(quasi.diagram), quasi.points)
    assert second.sum() == pytest.approx(quasi.energy[-1], rel=1e-12)


def test_lbfgs_on_holed_domain_with_density():
    pts = np.random.default_rng(9).random((80, 2))
    pts = pts[shapely.contains_xy(HOLED, pts[:, 0], pts[:, 1])]
    r = vf.lloyd(pts, HOLED, iterations=30, method="lbfgs", density=lambda x, y: 1 + x)
    assert r.energy[-1] < 0.8 * r.energy[0]


def test_duplicates_and_outside_sites():
    pts = np.array([[0.2, 0.2], [0.2, 0.2], [0.7, 0.6], [1.1, 0.5], [0.4, 0.8]])
    one = vf.lloyd(pts, (0, 0, 1, 1), iterations=1)
    # the later copy has an empty cell and stays put; the outside site moves into the box
    assert np.array_equal(one.points[1], pts[1]) and not np.array_equal(one.points[0], pts[0])
    assert 0 <= one.points[3, 0] <= 1
    # once its twin has moved away the copy gets a cell of its own
    r = vf.lloyd(pts, (0, 0, 1, 1), iterations=5)
    assert np.all(r.diagram.duplicate_of == -1) and np.all(r.diagram.areas > 0)
    assert np.all(np.diff(r.energy) <= 1e-15 * r.energy[0])


def test_capacity_constrained_cvt():
    rng = np.random.default_rng(10)
    pts = rng.uniform(0.05, 0.95, size=(60, 2))
    raw = np.where(pts[:, 0] < 0.5, 1.0, 3.0)
    target = raw / raw.sum()
    r = vf.lloyd(pts, (0, 0, 1, 1), iterations=15, areas=target)
    assert isinstance(r.diagram, vf.PowerDiagram)
    assert np.array_equal(r.weights, r.diagram.weights)
    assert np.all(np.abs(r.diagram.areas - target) <= 1e-6 * target)
    assert r.energy[-1] < r.energy[0]
    # the sites ended near their power cells' centroids
    assert r.shift[-1] < r.shift[0]


def test_tol_and_zero_iterations():
    pts = np.random.default_rng(11).random((30, 2))
    r = vf.lloyd(pts, (0, 0, 1, 1), iterations=0)
    assert r.iterations == 0 and r.energy.shape == (1,) and np.array_equal(r.points, pts)
    r = vf.lloyd(pts, (0, 0, 1, 1), iterations=500, tol=1e-3)
    assert r.iterations < 500 and r.shift[-1] <= 1e-3 and np.all(r.shift[:-1] > 1e-3)
    q = vf.lloyd(pts, (0, 0, 1, 1), iterations=500, tol=1e-3, method="lbfgs")
    assert q.iterations < 500


def test_errors_and_input_untouched():
    pts = np.random.default_rng(12).random((20, 2))
    keep = pts.copy()
    vf.lloyd(pts, iterations=3)
    assert np.array_equal(pts, keep)
    with pytest.raises(ValueError, match="unknown method"):
        vf.lloyd(pts, method="newton")
    with pytest.raises(ValueError, match="iterations"):
        vf.lloyd(pts, iterations=-1)
    with pytest.raises(ValueError, match="density must be"):
        vf.lloyd(pts, density="dense")
    with pytest.raises(ValueError, match="non-negative"):
        vf.lloyd(pts, (0, 0, 1, 1), iterations=1, density=lambda x, y: x - 2)
    with pytest.raises(ValueError, match="one value per point"):
        vf.lloyd(pts, (0, 0, 1, 1), iterations=1, density=lambda x, y: np.ones(3))
    with pytest.raises(ValueError, match="raster"):
        vf.lloyd(pts, density=(np.ones(5), (0, 0, 1, 1)))
    with pytest.raises(ValueError, match="bounds"):
        vf.lloyd(pts, density=(np.ones((5, 5)), (1, 0, 0, 1)))
    with pytest.raises(ValueError, match="not complex"):  # was cast to its real part, 0
        vf.lloyd(pts, (0, 0, 1, 1), density=(np.full((2, 2), 1j), (0, 0, 1, 1)))
    with pytest.raises(ValueError, match="method='lloyd'"):
        vf.lloyd(pts, (0, 0, 1, 1), method="lbfgs", areas=np.full(20, 0.05))
    with pytest.raises(ValueError, match="^areas must sum to the domain"):
        vf.lloyd(pts, (0, 0, 1, 1), areas=np.full(20, 1.0))
    with pytest.raises(ValueError, match=r"^areas must have shape \(20,\)"):  # its own name
        vf.lloyd(pts, (0, 0, 1, 1), areas=np.full(19, 1 / 19))


class _Raster:
    """A small raster object: ``values`` and ``bounds``."""

    def __init__(self, values, bounds):
        self.values = values
        self.bounds = bounds


def test_raster_object_and_lbfgs_with_raster():
    values = np.linspace(1.0, 4.0, 12).reshape(3, 4)
    pts = np.random.default_rng(13).random((40, 2))
    a = vf.lloyd(pts, (0, 0, 1, 1), iterations=5, density=_Raster(values, (0, 0, 1, 1)))
    b = vf.lloyd(pts, (0, 0, 1, 1), iterations=5, density=(values, (0, 0, 1, 1)))
    assert np.array_equal(a.points, b.points)
    q = vf.lloyd(pts, (0, 0, 1, 1), iterations=20, density=(values, (0, 0, 1, 1)), method="lbfgs")
    assert np.all(np.diff(q.energy) <= 0) and q.energy[-1] < b.energy[-1]


def test_capacity_cvt_on_a_disk():
    disk = shapely.Point(0, 0).buffer(1.0, quad_segs=16)
    rng = np.random.default_rng(14)
    pts = rng.uniform(-0.6, 0.6, size=(50, 2))
    target = np.full(50, disk.area / 50)
    r = vf.lloyd(pts, disk, iterations=10, areas=target)
    assert np.all(np.abs(r.diagram.areas - target) <= 1e-6 * target)
    assert abs(r.diagram.areas.sum() - disk.area) <= 1e-9 * disk.area


@given(
    st.integers(1, 40),
    st.integers(0, 2**32 - 1),
    st.sampled_from([SQUARE, HOLED, L_SHAPE]),
)
def test_property_lloyd_monotone(n, seed, domain):
    rng = np.random.default_rng(seed)
    pts = np.round(rng.uniform(-0.1, 1.1, size=(n, 2)), 2)  # duplicates, outside sites
    r = vf.lloyd(pts, domain, iterations=6)
    assert np.all(np.diff(r.energy) <= 1e-14 * max(r.energy[0], 1e-300))
    assert np.isfinite(r.points).all()
    q = vf.lloyd(pts, domain, iterations=6, method="lbfgs")
    assert np.all(np.diff(q.energy) <= 0)


@pytest.mark.parametrize("domain", [HOLED, L_SHAPE])
def test_capacity_cvt_on_concave_domains(domain):
    rng = np.random.default_rng(17)
    pts = rng.random((200, 2))
    pts = pts[shapely.contains_xy(domain, pts[:, 0], pts[:, 1])][:60]
    target = np.full(len(pts), domain.area / len(pts))
    r = vf.lloyd(pts, domain, iterations=12, areas=target)
    assert np.all(np.abs(r.diagram.areas - target) <= 1e-6 * target)
    assert np.all(shapely.covers(domain, shapely.points(r.points)))
    assert r.energy[-1] < r.energy[0]


def test_capacity_cvt_pulls_outside_centroids_onto_the_domain():
    u_shape = shapely.box(0, 0, 3, 3).difference(shapely.box(1, 1, 2, 3))
    pts = np.array([[0.5, 2.5], [2.5, 0.5]])
    # one site owns the whole U, whose centroid lies in the gap between the arms
    one = vf.lloyd(pts[:1], u_shape, iterations=1)
    assert one.points[0] == pytest.approx([1.5, 9.5 / 7])  # the U's centroid, in the gap
    assert not u_shape.covers(shapely.Point(one.points[0]))
    cap = vf.lloyd(pts[:1], u_shape, iterations=1, areas=[u_shape.area])
    assert cap.points[0] == pytest.approx([1.5, 1.0])  # nearest boundary point
    two = vf.lloyd(pts, u_shape, iterations=8, areas=[2.0, 5.0])
    assert np.all(shapely.covers(u_shape, shapely.points(two.points)))
    assert np.allclose(two.diagram.areas, [2.0, 5.0], rtol=1e-6)


@pytest.mark.parametrize("domain", [SQUARE, HOLED, L_SHAPE])
def test_matches_a_brute_force_lloyd(domain):
    pts = np.random.default_rng(20).random((30, 2))
    z = pts.copy()
    for _ in range(4):  # reference: half-plane cells, GEOS clip, GEOS centroids
        z = brute_lloyd_step(z, domain)
    r = vf.lloyd(pts, domain, iterations=4)
    assert np.allclose(r.points, z, rtol=0, atol=1e-9)


# --- regressions from the QA pass of issue 4 ------------------------------------------------


def test_lloyd_capacity_with_sites_outside_an_l_shape():
    ell = shapely.Polygon([(0, 0), (1, 0), (1, 0.4), (0.4, 0.4), (0.4, 1), (0, 1)])
    pts = np.random.default_rng(9).random((40, 2))  # some start in the notch
    target = np.full(40, ell.area / 40)
    r = vf.lloyd(pts, ell, iterations=3, areas=target)
    assert np.abs(r.diagram.areas - target).max() <= 1e-6 * target.min()


def test_lloyd_option_errors():
    pts = np.random.default_rng(0).random((10, 2))
    with pytest.raises(ValueError, match="tol"):
        vf.lloyd(pts, (0, 0, 1, 1), tol="x")  # was a TypeError from np.isfinite
    with pytest.raises(ValueError, match="duplicate"):  # was "the cell of site 10 stays empty"
        vf.lloyd(np.vstack([pts, pts[:1]]), (0, 0, 1, 1), areas=np.full(11, 1 / 11))


@pytest.mark.parametrize("scale", [1e-150, 1e150])
@pytest.mark.parametrize("method", ["lloyd", "lbfgs"])
def test_lloyd_at_extreme_scales(scale, method):
    # cell moments grow with the 2nd-4th power of the size: at 1e150 they overflowed and the
    # sites became NaN ("points contains NaN coordinates"), at 1e-150 they underflowed
    pts = np.random.default_rng(19).random((40, 2))
    ras = (np.random.default_rng(1).random((5, 6)), (0.1, -0.1, 0.9, 1.2))
    for density, scaled in [
        (None, None),
        (lambda x, y: 1 + 3 * x, lambda x, y: 1 + 3 * x / scale),
        (ras, (ras[0], tuple(np.array(ras[1]) * scale))),
    ]:
        unit = vf.lloyd(pts, (0, 0, 1, 1), iterations=4, method=method, density=density)
        big = vf.lloyd(
            pts * scale, (0, 0, scale, scale), iterations=4, method=method, density=scaled
        )
        assert np.allclose(big.points / scale, unit.points, rtol=0, atol=1e-12)
        assert np.allclose(big.shift / scale, unit.shift, rtol=1e-12, atol=0)
        assert np.allclose(big.diagram.areas / scale**2, unit.diagram.areas, rtol=1e-12, atol=0)


def test_lloyd_on_3d_sites_is_lloyd3d():
    p = np.random.default_rng(0).random((60, 3))
    before = p.copy()
    r = vf.lloyd(p, (0, 0, 0, 1, 1, 1), iterations=4)
    ref = vf.lloyd3d(p, (0, 0, 0, 1, 1, 1), iterations=4, tol=0.0)
    assert np.array_equal(r.points, ref.points) and r.iterations == 4
    assert np.array_equal(p, before)
    dense = vf.lloyd(p, (0, 0, 0, 1, 1, 1), iterations=3, density=lambda x, y, z: 1 + 9 * x)
    assert dense.points[:, 0].mean() > r.points[:, 0].mean()  # pulled towards high density
    with pytest.raises(ValueError, match="method='lloyd' only"):
        vf.lloyd(p, (0, 0, 0, 1, 1, 1), method="lbfgs")
    with pytest.raises(ValueError, match=r"rho\(x, y, z\)"):
        vf.lloyd(p, (0, 0, 0, 1, 1, 1), density=(np.ones((2, 2)), (0, 0, 1, 1)))


@pytest.mark.parametrize("size", [(1.0, 1e-6), (1e-6, 1.0), (1.0, 1e-3)])
def test_lbfgs_meets_tol_on_the_short_side_of_a_thin_box(size):
    # the short axis' share of the energy is below the energy's rounding: L-BFGS's line
    # search stalled there and its tiny steps read as convergence, 8-24x tol off (checker22)
    w, h = size
    box = (0.0, 0.0, w, h)
    pts = np.random.default_rng(4).random((30, 2)) * [w, h]
    r = vf.lloyd(pts, box, iterations=5000, tol=1e-8, method="lbfgs")
    cells = vf.voronoi(r.points, box).cells
    centroids = np.array([c.centroid.coords[0] for c in cells])  # shapely's, independent
    off = np.abs(centroids - r.points) / [w, h]
    assert off.max() <= 2e-8, off.max(axis=0)
