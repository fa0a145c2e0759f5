"""QA regressions for the CVT, power, periodic, query and describe features (issue 4).

Each test reproduces an input that broke one of these features, checked against a slow,
obvious reference (shapely half-planes, brute-force minima) rather than stored answers.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely

import voroforge as vf


def _power_cells_ref(pts, w, dom):
    """Power cells by intersecting half-planes with shapely (slow and obvious)."""
    x0, y0, x1, y1 = dom.bounds
    size = max(x1 - x0, y1 - y0)
    cells = []
    for i in range(len(pts)):
        cell = shapely.box(x0, y0, x1, y1)
        for j in range(len(pts)):
            d = pts[j] - pts[i]
            if j == i or not d.any():
                continue
            # u . (x - p_i) <= t with u = d / |d|
            norm = float(np.hypot(*d))
            u = d / norm
            t = (d @ d + (w[i] - w[j])) / (2.0 * norm)
            base = pts[i] + u * t
            perp = np.array([-u[1], u[0]])
            far = 10.0 * size + abs(t) + float(np.hypot(*(pts[i] - [x0, y0])))
            cell = cell.intersection(
                shapely.Polygon(
                    [
                        base + perp * far,
                        base - perp * far,
                        base - (perp + 2 * u) * far,
                        base + (perp - 2 * u) * far,
                    ]
                )
            )
        cells.append(cell.intersection(dom))
    return np.array(cells, dtype=object)


def test_power_large_weights_leave_no_gap():
    # |d|^2 + w_i was rounded at the scale of w (1e8) before w_j was subtracted, so two
    # neighbours cut along bisectors 4e-9 apart and the cells missed part of the box
    rng = np.random.default_rng(2)
    pts = rng.random((80, 2))
    w = np.r_[1e8, 1e8 - 0.01, rng.random(78)]
    d = vf.power(pts, w, (0, 0, 1, 1))
    assert abs(d.areas.sum() - 1.0) <= 1e-13
    ref = _power_cells_ref(pts[:2], w[:2], shapely.box(0, 0, 1, 1))
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


@pytest.mark.parametrize("k", [5, 10])
def test_periodic_wrap_has_no_rounding_slivers(k):
    # a grid whose cell edges fall on the box edges: 0.9 - 1 is not -0.1 in floats, so an
    # image's cell crossed the edge by 1e-17 and each wrapped cell of the last column got a
    # second, 1e-17-wide polygon part (describe(): Euler FAILED)
    h = 1.0 / k
    g = np.stack(np.meshgrid(np.arange(k) * h, np.arange(k) * h), -1).reshape(-1, 2) + h / 2
    w = vf.voronoi(g, (0, 0, 1, 1), periodic=True, wrap=True)
    assert all(len(shapely.get_parts(c)) == 1 for c in w.cells)
    assert abs(w.areas.sum() - 1.0) <= 1e-14
    assert w.describe().euler_ok
    # the seams inside the box, each once: k - 1 vertical and k - 1 horizontal lines
    length = np.hypot(*(w.edges.coords[:, 1] - w.edges.coords[:, 0]).T)
    assert length.min() > 0.5 * h and abs(length.sum() - 2 * (k - 1)) <= 1e-12
    # the tiled reference: each site's cell is the h x h square around it
    ref = shapely.box(*(g - h / 2).T, *(g + h / 2).T)
    assert np.allclose(w.areas, shapely.area(ref), rtol=1e-12, atol=0)


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


def test_areas_and_centroids_are_read_only():
    # they are cached: writing into d.areas changed every later d.areas of that diagram
    pts = np.random.default_rng(0).random((30, 2))
    for d in (
        vf.voronoi(pts, (0, 0, 1, 1)),
        vf.power(pts, np.linspace(0, 0.01, 30), (0, 0, 1, 1)),
        vf.voronoi(pts, (0, 0, 1, 1), periodic=True),
    ):
        for arr in (d.areas, d.centroids):
            with pytest.raises(ValueError, match="read-only"):
                arr[0] = 5.0


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
    ref = _power_cells_ref(pts, w, shapely.box(*box))
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
