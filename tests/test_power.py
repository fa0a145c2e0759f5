"""Power (Laguerre) diagrams and capacity-constrained cells against brute-force references."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import shapely
from hypothesis import given
from hypothesis import strategies as st

import voroforge as vf

from reference import brute_power
from validate import overlay_frame, symmetric_difference_areas

HOLED = shapely.box(0, 0, 10, 10).difference(shapely.Point(5, 5).buffer(2.5, quad_segs=8))
L_SHAPE = shapely.Polygon([(0, 0), (10, 0), (10, 4), (4, 4), (4, 10), (0, 10)])


def power_dist(q, pts, w):
    return ((q[:, None, :] - pts[None, :, :]) ** 2).sum(-1) - w[None, :]


def check_power(d, pts, w, domain, *, samples=400, seed=0):
    """Areas vs the brute force, tiling, no overlaps, samples in the power-nearest cell."""
    pts = np.asarray(pts, dtype=np.float64)
    w = np.asarray(w, dtype=np.float64)
    area = domain.area
    ref = brute_power(pts, w, domain)
    assert np.allclose(d.areas, shapely.area(ref), rtol=0, atol=1e-9 * area)
    assert abs(d.areas.sum() - area) <= 1e-9 * area
    cells = np.asarray(d.cells, dtype=object)
    assert np.all(shapely.is_valid(cells))
    assert np.allclose(shapely.area(cells), d.areas, rtol=1e-9, atol=1e-12 * area)
    # overlays snap-rounded in a centred frame (GEOS's float overlay misreads cells that
    # share vertices bit for bit now and then)
    origin, grid = overlay_frame(domain)
    loc = shapely.transform(cells, lambda xy: xy - origin)
    tree = shapely.STRtree(cells)
    ii, jj = tree.query(cells, predicate="intersects")
    keep = ii < jj
    overlap = shapely.area(shapely.intersection(loc[ii[keep]], loc[jj[keep]], grid_size=grid))
    assert overlap.sum() <= 1e-9 * area
    assert symmetric_difference_areas(cells, ref, domain).max() <= 1e-9 * area
    rng = np.random.default_rng(seed)
    x0, y0, x1, y1 = domain.bounds
    q = rng.uniform((x0, y0), (x1, y1), size=(samples, 2))
    q = q[shapely.contains_xy(domain, q[:, 0], q[:, 1])]
    pd = power_dist(q, pts, w)
    best = pd.min(axis=1)
    for k, j in enumerate(np.argmin(pd, axis=1)):
        g = shapely.Point(q[k])
        if not cells[j].covers(g) and cells[j].distance(g) > 1e-9 * np.sqrt(area):
            ties = np.flatnonzero(pd[k] <= best[k] + 1e-9 * area)
            assert any(cells[t].distance(g) <= 1e-9 * np.sqrt(area) for t in ties), (
                f"sample {q[k]} not in the cell of its power-nearest site {j}"
            )
    # edges lie on the power bisector of their pair
    coords, pairs = d.edges
    for end in (0, 1):
        x = coords[:, end]
        a = ((x - pts[pairs[:, 0]]) ** 2).sum(1) - w[pairs[:, 0]]
        b = ((x - pts[pairs[:, 1]]) ** 2).sum(1) - w[pairs[:, 1]]
        assert np.allclose(a, b, rtol=0, atol=1e-9 * area)


@pytest.mark.parametrize("domain", [shapely.box(0, 0, 10, 10), HOLED, L_SHAPE])
@pytest.mark.parametrize("n", [5, 60])
def test_random_against_brute_force(domain, n):
    rng = np.random.default_rng(n)
    pts = rng.uniform(0, 10, size=(n, 2))
    w = rng.uniform(0, 4.0, size=n)
    d = vf.power(pts, w, domain)
    assert isinstance(d, vf.Diagram) and d.algorithm == "power"
    assert np.array_equal(d.weights, w)
    check_power(d, pts, w, domain)


def test_weights_that_empty_cells():
    rng = np.random.default_rng(7)
    pts = rng.uniform(0, 10, size=(40, 2))
    w = np.zeros(40)
    w[:4] = 30.0  # four heavy sites swallow their light neighbours
    d = vf.power(pts, w, (0, 0, 10, 10))
    assert (d.areas == 0).sum() > 0
    check_power(d, pts, w, shapely.box(0, 0, 10, 10))
    assert np.all(shapely.is_empty(d.cells[d.areas == 0]))
    # empty cells have no neighbours and no edges
    indptr, _ = d.neighbors
    assert np.all(np.diff(indptr)[d.areas == 0] == 0)


def test_equal_weights_give_voronoi_exactly():
    rng = np.random.default_rng(3)
    pts = rng.random((300, 2))
    for boundary in [(0, 0, 1, 1), shapely.Point(0.5, 0.5).buffer(0.6)]:
        v = vf.voronoi(pts, boundary)
        for c in (0.0, 2.5):
            p = vf.power(pts, np.full(300, c), boundary)
            for a, b in zip(v.to_geoarrow()[1], p.to_geoarrow()[1], strict=True):
                assert np.array_equal(a, b)
            assert np.array_equal(v.to_geoarrow()[0], p.to_geoarrow()[0])
            assert np.array_equal(v.edges.pairs, p.edges.pairs)


def test_nearly_equal_weights_match_voronoi_cells():
    rng = np.random.default_rng(4)
    pts = rng.random((200, 2))
    w = np.zeros(200)
    w[0] = 1e-300  # not all equal: takes the power path
    p = vf.power(pts, w, (0, 0, 1, 1))
    v = vf.voronoi(pts, (0, 0, 1, 1))
    assert np.allclose(p.areas, v.areas, rtol=0, atol=1e-13)
    assert np.max(shapely.area(shapely.symmetric_difference(p.cells, v.cells))) <= 1e-13


def test_adding_a_constant_changes_nothing():
    rng = np.random.default_rng(5)
    pts = rng.random((80, 2))
    w = rng.random(80) * 0.01
    a = vf.power(pts, w, (0, 0, 1, 1))
    b = vf.power(pts, w + 7.0, (0, 0, 1, 1))
    assert np.allclose(a.areas, b.areas, rtol=0, atol=1e-12)


def test_duplicates_heavier_wins_equal_first():
    pts = np.array([[1.0, 1.0], [2.0, 3.0], [1.0, 1.0], [3.0, 1.5], [2.0, 3.0], [1.0, 1.0]])
    w = np.array([0.1, 0.5, 0.3, 0.0, 0.5, 0.3])
    d = vf.power(pts, w, (0, 0, 4, 4))
    # (1, 1): rows 0, 2, 5 -> row 2 (heaviest, first of the two 0.3s); (2, 3): rows 1, 4 -> 1
    assert d.duplicate_of.tolist() == [2, -1, -1, -1, 1, 2]
    assert np.all(d.areas[[0, 4, 5]] == 0)
    check_power(d, pts, w, shapely.box(0, 0, 4, 4))


@pytest.mark.parametrize("n", [3, 30])
def test_collinear(n):
    t = np.linspace(0, 1, n)
    pts = np.column_stack((0.2 + 0.6 * t, 0.1 + 0.7 * t))
    w = np.random.default_rng(n).random(n) * 0.02
    d = vf.power(pts, w, (0, 0, 1, 1))
    check_power(d, pts, w, shapely.box(0, 0, 1, 1))
    assert (d.areas > 0).sum() >= 2


def test_coplanar_lift():
    # weights |p|^2 lift every site to height 0: all power bisectors meet in one point
    g = np.stack(np.meshgrid(np.arange(5.0), np.arange(5.0)), -1).reshape(-1, 2) + 0.5
    w = (g**2).sum(1)
    d = vf.power(g, w, (0, 0, 5, 5))
    assert abs(d.areas.sum() - 25) <= 1e-9 * 25
    check_power(d, g, w, shapely.box(0, 0, 5, 5))


@pytest.mark.parametrize("n", [1, 2])
def test_one_and_two_sites(n):
    pts = np.array([[0.3, 0.4], [0.7, 0.5]])[:n]
    w = np.array([0.0, 0.1])[:n]
    d = vf.power(pts, w, (0, 0, 1, 1))
    check_power(d, pts, w, shapely.box(0, 0, 1, 1))
    if n == 1:
        assert d.areas.tolist() == [1.0]


def test_large_coordinates():
    rng = np.random.default_rng(9)
    pts = rng.random((50, 2)) * 100 + np.array([500000.0, 4000000.0])
    w = rng.random(50) * 20
    box = shapely.box(500000, 4000000, 500100, 4000100)
    d = vf.power(pts, w, box)
    check_power(d, pts, w, box)


def test_input_not_mutated_and_errors():
    pts = np.random.default_rng(1).random((10, 2))
    w = np.arange(10.0) * 1e-3
    p0, w0 = pts.copy(), w.copy()
    vf.power(pts, w, (0, 0, 1, 1))
    assert np.array_equal(pts, p0) and np.array_equal(w, w0)
    with pytest.raises(ValueError, match="weights must have shape"):
        vf.power(pts, w[:-1])
    with pytest.raises(ValueError, match="non-finite"):
        vf.power(pts, np.full(10, np.nan))
    with pytest.raises(ValueError, match="NaN"):
        vf.power(np.full((3, 2), np.nan), np.zeros(3))


@given(
    st.integers(2, 25),
    st.integers(0, 2**32 - 1),
    st.sampled_from([1e-4, 1e-2, 0.2]),
)
def test_property_random(n, seed, spread):
    rng = np.random.default_rng(seed)
    pts = np.round(rng.random((n, 2)), 3)  # rounding makes duplicates and collinear runs
    w = rng.random(n) * spread
    d = vf.power(pts, w, (0, 0, 1, 1))
    check_power(d, pts, w, shapely.box(0, 0, 1, 1), samples=100, seed=seed)


# ---------------------------------------------------------------- capacity-constrained cells


@pytest.mark.parametrize("domain", [shapely.box(0, 0, 10, 10), HOLED, L_SHAPE])
def test_power_fit_reaches_targets(domain):
    rng = np.random.default_rng(11)
    n = 80
    pts = rng.uniform(0, 10, size=(4 * n, 2))
    pts = pts[shapely.contains_xy(domain, pts[:, 0], pts[:, 1])][:n]
    raw = rng.uniform(1, 4, size=n)
    target = raw / raw.sum() * domain.area
    d = vf.power_fit(pts, target, domain)
    assert np.all(np.abs(d.areas - target) <= 1e-6 * target)
    # the result is the power diagram of the weights it reports
    check_power(d, pts, d.weights, domain, samples=200)
    # warm start from the answer: no step needed
    again = vf.power_fit(pts, target, domain, weights=d.weights, max_iter=0)
    assert np.array_equal(again.areas, d.areas)


def test_power_fit_10k_equal_areas():
    pts = np.random.default_rng(12).random((10_000, 2))
    target = np.full(10_000, 1e-4)
    d = vf.power_fit(pts, target, (0, 0, 1, 1))
    assert np.max(np.abs(d.areas - target) / target) <= 1e-6


def test_power_fit_errors():
    pts = np.random.default_rng(13).random((10, 2))
    with pytest.raises(ValueError, match="sum to the domain"):
        vf.power_fit(pts, np.full(10, 0.2), (0, 0, 1, 1))
    with pytest.raises(ValueError, match="positive"):
        vf.power_fit(pts, np.r_[-0.1, np.full(9, 1.1 / 9)], (0, 0, 1, 1))
    dup = np.vstack((pts, pts[:1]))
    with pytest.raises(ValueError, match="duplicate sites"):
        vf.power_fit(dup, np.full(11, 1 / 11), (0, 0, 1, 1))
    with pytest.raises(ValueError, match="shape"):
        vf.power_fit(pts, np.full(9, 1 / 9), (0, 0, 1, 1))
    skewed = np.r_[0.9, np.full(9, 0.1 / 9)]
    with pytest.raises(RuntimeError, match="did not reach"):
        vf.power_fit(pts, skewed, (0, 0, 1, 1), max_iter=1)


def test_scaling_and_translation():
    rng = np.random.default_rng(15)
    pts = rng.random((60, 2))
    w = rng.random(60) * 0.01
    base = vf.power(pts, w, (0, 0, 1, 1))
    s = 2.0**20
    shift = np.array([1e5, -3e4])
    big = vf.power(pts * s + shift, w * s * s, tuple(np.r_[shift, shift + s]))
    assert np.allclose(big.areas / (s * s), base.areas, rtol=0, atol=1e-10)


def test_sites_outside_the_domain():
    rng = np.random.default_rng(16)
    pts = rng.uniform(-0.5, 1.5, size=(40, 2))
    w = rng.random(40) * 0.05
    d = vf.power(pts, w, (0, 0, 1, 1))
    check_power(d, pts, w, shapely.box(0, 0, 1, 1))
    d = vf.power(pts * 10, w * 100, L_SHAPE)
    check_power(d, pts * 10, w * 100, L_SHAPE)


def test_locate_finds_the_power_nearest_site():
    rng = np.random.default_rng(18)
    pts = rng.random((80, 2))
    pts[5] = pts[3]  # a duplicate: the heavier copy owns the cell
    w = rng.random(80) * 0.02
    d = vf.power(pts, w, (0, 0, 1, 1))
    q = rng.uniform(-0.2, 1.2, size=(3000, 2))
    pd = power_dist(q, pts, w)
    got = d.locate(q)
    assert np.array_equal(got, np.argmin(pd, axis=1))
    assert d.locate(q[0]) == got[0]
    # every located sample lies in (or on) that site's clipped cell
    inside = shapely.contains_xy(shapely.box(0, 0, 1, 1), q[:, 0], q[:, 1])
    cells = d.cells
    far = [cells[j].distance(shapely.Point(x)) for x, j in zip(q[inside], got[inside], strict=True)]
    assert max(far) <= 1e-12


def test_power_fit_opens_cells_of_sites_outside_the_domain():
    rng = np.random.default_rng(19)
    pts = rng.uniform(-1, 11, size=(60, 2))  # some in the hole, some outside the square
    assert (~shapely.contains_xy(HOLED, pts[:, 0], pts[:, 1])).sum() >= 10
    assert (vf.voronoi(pts, HOLED).areas == 0).any()
    target = np.full(60, HOLED.area / 60)
    d = vf.power_fit(pts, target, HOLED)
    assert np.all(np.abs(d.areas - target) <= 1e-6 * target)
    check_power(d, pts, d.weights, HOLED, samples=200)


@given(st.integers(3, 20), st.integers(0, 2**32 - 1))
def test_property_polygon_domains(n, seed):
    rng = np.random.default_rng(seed)
    domain = [HOLED, L_SHAPE][seed % 2]
    pts = rng.uniform(-1, 11, size=(n, 2))
    w = rng.random(n) * 6.0
    d = vf.power(pts, w, domain)
    check_power(d, pts, w, domain, samples=100, seed=seed)


# --- regressions from the QA pass of issue 4 ------------------------------------------------


def test_power_large_weights_leave_no_gap():
    # |d|^2 + w_i was rounded at the scale of w (1e8) before w_j was subtracted, so two
    # neighbours cut along bisectors 4e-9 apart and the cells missed part of the box
    rng = np.random.default_rng(2)
    pts = rng.random((80, 2))
    w = np.r_[1e8, 1e8 - 0.01, rng.random(78)]
    d = vf.power(pts, w, (0, 0, 1, 1))
    assert abs(d.areas.sum() - 1.0) <= 1e-13
    ref = brute_power(pts[:2], w[:2], shapely.box(0, 0, 1, 1))
    assert np.allclose(d.areas[:2], shapely.area(ref), rtol=0, atol=1e-13)
    assert (d.areas[2:] == 0).all()


def _fit_ok(pts, dom, bnd):
    target = np.full(len(pts), dom.area / len(pts))
    d = vf.power_fit(pts, target, bnd)
    assert np.abs(d.areas - target).max() <= 1e-6 * target.min()
    # the weights found give those areas in an independent power diagram
    again = vf.power(pts, d.weights, bnd)
    assert np.allclose(again.areas, d.areas, rtol=0, atol=1e-9 * dom.area)


def test_power_fit_many_sites_outside_the_box():
    # sites beyond a corner share the corner as nearest domain point: opening one cell
    # there emptied another, ten rounds long ("the cell of site 2 stays empty")
    pts = np.random.default_rng(8).random((50, 2)) * 3 - 1
    _fit_ok(pts, shapely.box(0, 0, 1, 1), (0, 0, 1, 1))


def test_power_fit_sites_in_the_notch_of_an_l_shape():
    ell = shapely.Polygon([(0, 0), (1, 0), (1, 0.4), (0.4, 0.4), (0.4, 1), (0, 1)])
    pts = np.random.default_rng(8).random((100, 2))  # a quarter of them in the notch
    _fit_ok(pts, ell, ell)


def test_power_fit_two_part_domain():
    # the parts' areas do not match the number of sites in them: some cell must straddle
    # the gap, where the Newton step from the Voronoi start stalled (RuntimeError)
    mp = shapely.MultiPolygon(
        [
            shapely.box(0, 0, 0.4, 1),
            shapely.box(0.6, 0, 1, 1).difference(shapely.box(0.7, 0.4, 0.9, 0.6)),
        ]
    )
    pts = np.random.default_rng(8).random((100, 2))
    _fit_ok(pts, mp, mp)


def test_power_enormous_weight_range():
    # Qhull failed on the lift of weights spanning 1e300 (QhullError, not a diagram)
    rng = np.random.default_rng(0)
    pts = rng.random((20, 2))
    w = np.r_[rng.random(19) * 0.01, 1e300]
    d = vf.power(pts, w, (0, 0, 1, 1))
    assert d.areas[-1] == 1.0 and (d.areas[:-1] == 0).all()
    # the sites a heavy one hides change nothing for the others
    w = np.r_[rng.random(19) * 0.01, -50.0]
    pts[-1] = [0.5, 0.5]
    assert np.array_equal(
        vf.power(pts, w, (0, 0, 1, 1)).areas[:-1], vf.power(pts[:-1], w[:-1], (0, 0, 1, 1)).areas
    )


@pytest.mark.parametrize(
    ("kw", "word"),
    [({"tol": "a"}, "tol"), ({"max_iter": 1.5}, "max_iter"), ({"max_iter": "x"}, "max_iter")],
)
def test_power_fit_option_errors(kw, word):
    pts = np.random.default_rng(0).random((10, 2))
    with pytest.raises(ValueError, match=word):
        vf.power_fit(pts, np.full(10, 0.1), (0, 0, 1, 1), **kw)


def test_power_locate_breaks_ties_towards_the_lowest_index():
    # four or more sites at the same power distance (grid corners): only the two nearest
    # in the KD-tree were compared, so the documented lowest-index rule failed
    rng = np.random.default_rng(0)
    grid = np.stack(np.meshgrid(np.arange(6.0), np.arange(6.0)), -1).reshape(-1, 2)
    grid = grid[rng.permutation(len(grid))]
    q = np.stack(np.meshgrid(np.arange(11) / 2, np.arange(11) / 2), -1).reshape(-1, 2)
    d2 = ((q[:, None] - grid[None]) ** 2).sum(-1)
    for w in (np.zeros(36), rng.integers(0, 3, 36).astype(float)):
        pd = d2 - w
        ref = [int(np.flatnonzero(row == row.min()).min()) for row in pd]
        assert vf.power(grid, w).locate(q).tolist() == ref
    assert np.array_equal(vf.power(grid, np.zeros(36)).locate(q), vf.locate(grid, q))


def test_power_locate_names_a_bad_query():
    d = vf.power(np.random.default_rng(0).random((10, 2)), np.arange(10) * 0.01, (0, 0, 1, 1))
    with pytest.raises(ValueError, match="xy must be"):  # was numpy's bare message
        d.locate("ab")
    assert (
        d.locate([0.5, 0.5]) == vf.power(d.sites, d.weights, (0, 0, 1, 1)).locate([[0.5, 0.5]])[0]
    )


def test_power_cell_cut_through_a_box_corner_stays_simple():
    # the bisector of sites 0 and 1 passes through the corner (-0.05, -0.05): the crossing
    # a + 1.0 * (b - a) rounded past the corner and cell 1 got a self-intersecting spike
    pts = np.array([[0.0, 1 / 12], [1 / 12, 0.0], [1 / 12, 1 / 6]])
    w = np.array([0.002, 0.002, 0.0])
    box = (-0.05, -0.05, 1.05, 1.05)
    d = vf.power(pts, w, box)
    assert shapely.is_valid(d.cells).all()
    ref = brute_power(pts, w, shapely.box(*box))
    assert np.allclose(d.areas, shapely.area(ref), rtol=0, atol=1e-14)


@pytest.mark.parametrize("boundary", ["box", "holed"])
def test_power_cells_share_their_vertices(boundary):
    # every cell cut its own ring, so the vertex of three cells came out a few ulps apart in
    # each: the union of the cells had dozens of sliver holes (41 for these 100 sites)
    rng = np.random.default_rng(0)
    pts = rng.random((100, 2))
    box = shapely.box(0, 0, 1, 1)
    dom = box if boundary == "box" else box.difference(shapely.Point(0.5, 0.5).buffer(0.2))
    d = vf.power(pts, rng.random(100) * 1e-3, (0, 0, 1, 1) if boundary == "box" else dom)
    union = shapely.union_all(d.cells)
    assert union.geom_type == "Polygon" and len(union.interiors) == len(dom.interiors)
    assert d.describe().mismatched_vertices == 0


@pytest.mark.parametrize(
    ("parts", "pts", "share"),
    [
        ("side", [[0.5, 0.5], [2.5, 0.5]], [0.7, 0.1]),
        ("side", [[0.5, 0.5], [2.5, 0.5]], [0.1, 0.7]),
        ("above", [[0.5, 0.5], [0.5, 2.0]], [0.9, 0.1]),
        ("side", [[0.5, 0.5], [1.5, 0.5]], [0.6, 0.4]),  # a site in the gap
    ],
)
def test_power_fit_cells_straddle_a_gap(parts, pts, share):
    """One site per part, targets a cell can only meet across the gap: no warning, converged."""
    from shapely.geometry import MultiPolygon, box

    other = box(2, 0, 3, 1) if parts == "side" else box(0, 1.5, 1, 2.5)
    dom = MultiPolygon([box(0, 0, 1, 1), other])
    target = np.array(share) / sum(share) * dom.area
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        d = vf.power_fit(np.array(pts, dtype=float), target, dom)
    assert np.all(np.abs(d.areas - target) <= 1e-6 * target)
    assert d.areas.sum() == pytest.approx(dom.area, rel=1e-12)


@pytest.mark.parametrize("ulps", [1, 3])
@pytest.mark.parametrize("off", [0.0, 1000.5])
def test_power_fit_sites_ulps_apart(ulps, off):
    """Distinct sites a few ulps apart get their own area (Jacobi or two-level steps)."""
    x = off + 0.3
    y = x
    for _ in range(ulps):
        y = np.nextafter(y, np.inf)
    pts = np.array([[x, x], [y, y], [off + 0.7, off + 0.7]])
    d = vf.power_fit(pts, np.full(3, 1 / 3), (off, off, off + 1, off + 1))
    assert np.all(np.abs(d.areas - 1 / 3) <= 1e-6 / 3)


def test_power_fit_too_close_for_float_weights_says_so():
    """Many sites and twins one ulp apart: float64 weights cannot place their bisector."""
    g = np.random.default_rng(3)
    pts = g.random((50, 2))
    pts = np.concatenate((pts, np.nextafter(pts[:5], 2)))
    with pytest.raises(RuntimeError, match="too close for float64 weights"):
        vf.power_fit(pts, np.full(55, 1 / 55), (0, 0, 1, 1))
