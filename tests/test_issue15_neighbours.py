"""Issue 15's classes on neighbouring inputs the other tests do not use (an independent check).

Other offsets, radii, counts, phases, scale mixes, ulp gaps and directions, non-square
boxes, polygon and MultiPolygon domains, power diagrams on them; every check is an
invariant (valid cells, tiling, nearest-site samples, own cell or flagged, Euler and
convexity, the algorithms agreeing), never a snapshot.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from shapely.geometry import MultiPolygon, Polygon, box

import voroforge as vf
from voroforge.cli import main

ALGS = ["delaunay", "fortune", "halfplane"]


def _grid(nx, ny, step, x0, y0):
    x, y = np.meshgrid(np.arange(nx) * step + x0, np.arange(ny) * step + y0)
    return np.column_stack((x.ravel(), y.ravel()))


def _circle(n, r=1.0, phase=0.0):
    t = np.arange(n) * (2.0 * np.pi / n) + phase
    return np.column_stack((r * np.cos(t), r * np.sin(t)))


def _walk(p, k, direction):
    for _ in range(k):
        p = np.nextafter(p, p + direction)
    return p


def _samples(pts, dom, seed, k=300):
    """Uniform points in the domain plus points at each site's nearest-neighbour distance."""
    g = np.random.default_rng(seed)
    x0, y0, x1, y1 = dom.bounds
    u = g.random((k, 2)) * [x1 - x0, y1 - y0] + [x0, y0]
    c = pts.mean(0)
    rel = pts - c
    d2 = ((rel[:, None, :] - rel[None, :, :]) ** 2).sum(-1)
    np.fill_diagonal(d2, np.inf)
    h = np.sqrt(d2.min(1))
    idx = g.integers(0, len(pts), k)
    near = pts[idx] + (g.random((k, 2)) - 0.5) * 2 * h[idx, None]
    q = np.concatenate((u, near))
    return q[shapely.contains_xy(dom, q[:, 0], q[:, 1])]


def _nearest_clear(pts, q, weights=None):
    d2 = (q[:, None, 0] - pts[None, :, 0]) ** 2 + (q[:, None, 1] - pts[None, :, 1]) ** 2
    if weights is not None:
        d2 = d2 - weights[None, :]
        o = np.argsort(d2, axis=1)[:, :2]
        a = np.take_along_axis(d2, o, 1)
        return o[:, 0], (a[:, 1] - a[:, 0]) > 1e-6 * (np.abs(a).max(1) + 1e-300)
    o = np.argsort(d2, axis=1)[:, :2]
    a = np.take_along_axis(d2, o, 1)
    return o[:, 0], np.sqrt(a[:, 1]) > np.sqrt(a[:, 0]) * (1 + 1e-6)


def _check(d, pts, q, weights=None, describe=True):
    cells = np.asarray(d.cells, dtype=object)
    bad = np.flatnonzero(~shapely.is_valid(cells))
    assert not len(bad), f"invalid cells {bad[:5].tolist()}"
    assert d.areas.sum() == pytest.approx(d.boundary.area, rel=1e-9)
    near, clear = _nearest_clear(pts, q, weights)
    inside = shapely.intersects(cells[near], shapely.points(q))
    assert inside[clear].all(), f"{int((clear & ~inside).sum())} clear samples outside"
    if weights is None:
        own = shapely.intersects(cells, shapely.points(pts))
        inside_domain = shapely.intersects(d.boundary, shapely.points(pts))
        missing = set(np.flatnonzero(~own & (d.duplicate_of < 0) & inside_domain).tolist())
        assert missing == set(d.unresolved.tolist())
    if describe:
        r = d.describe()
        assert r.euler_ok, str(r)
        assert r.convex_ok, str(r)


def _all_algorithms(pts, boundary, seed=0, weights=None):
    """Every algorithm (and power, given weights) passes the invariants, and they agree cell by
    cell to 1e-9 of each cell's own area (not the domain's: the cells span many scales)."""
    pts = np.asarray(pts, dtype=np.float64)
    ds = [vf.voronoi(pts, boundary, algorithm=alg) for alg in ALGS]
    q = _samples(pts, ds[0].boundary, seed)
    for d in ds:
        _check(d, pts, q)
    ca = np.asarray(ds[0].cells, dtype=object)
    for d in ds[1:]:
        sd = shapely.area(shapely.symmetric_difference(ca, np.asarray(d.cells, dtype=object)))
        assert (sd <= 1e-9 * np.maximum(ds[0].areas, d.areas) + 1e-300).all()
        assert set(d.unresolved.tolist()) == set(ds[0].unresolved.tolist())
    if weights is not None:
        _check(vf.power(pts, weights, boundary), pts, q, weights=weights)
    return ds


@pytest.mark.parametrize("off", [7e13, 2.5e14, -3e14, 2.25e15])
@pytest.mark.parametrize(("nx", "ny", "step"), [(4, 4, 1.0), (5, 3, 2.0)])
def test_lattice_offsets_give_exact_cells(off, nx, ny, step):
    """Unit and step-2 lattices at offsets the catalogue does not use, in a box taller than
    the lattice: every cell is its rectangle bit for bit, every algorithm and power (zero
    weights), and the None domain passes the invariants."""
    pts = _grid(nx, ny, step, off, -0.5 * off)
    h = step / 2
    top = pts[:, 1].max()
    b = (pts[:, 0].min() - h, pts[:, 1].min() - h, pts[:, 0].max() + h, top + 3 * h)
    for d in [vf.voronoi(pts, b, algorithm=alg) for alg in ALGS] + [
        vf.power(pts, np.zeros(len(pts)), b)
    ]:
        assert not len(d.unresolved)
        for k, (px, py) in enumerate(pts):
            want = shapely.box(px - h, py - h, px + h, b[3] if py == top else py + h)
            assert shapely.symmetric_difference(d.cells[k], want).area == 0.0, k
    _all_algorithms(pts, None)


@pytest.mark.parametrize(
    ("n", "r", "off", "phase"),
    [
        (65, 1e-6, (0.0, 0.0), 0.0),
        (96, 1e6, (0.0, 0.0), 0.3),
        (200, 1.0, (1e5, 3e5), 0.1),
        (200, 1e-6, (2e3, -7e3), 0.0),
    ],
)
def test_float_circles_other_radii_counts_phases(n, r, off, phase):
    """Float circles at counts, radii, phases and centres the catalogue does not use."""
    pts = _circle(n, r, phase) + off
    w = np.random.default_rng(1).random(n) * 1e-3 * (2 * r) ** 2 / n
    _all_algorithms(pts, None, weights=w)


def test_float_circle_in_a_hexagon_and_a_non_square_box():
    pts = _circle(200, 2.0) + [3.0, -1.0]
    hexagon = Polygon([(3 + 4 * np.cos(a), -1 + 4 * np.sin(a)) for a in np.arange(6) * np.pi / 3])
    _all_algorithms(pts, hexagon, weights=np.zeros(200) + np.linspace(0, 1e-4, 200))
    _all_algorithms(pts, (0.5, -3.5, 5.5, 8.5))


@pytest.mark.parametrize(
    ("small", "big", "seed"), [(1e-15, 1e3, 1), (1e-9, 1e9, 2), (1e-12, 1e7, 3), (1e-15, 1e9, 4)]
)
def test_mixed_scales_other_mixes(small, big, seed):
    """A tiny cluster beside a big one at other ratios; samples also inside the cluster."""
    g = np.random.default_rng(seed)
    pts = np.concatenate((g.random((40, 2)) * small, g.random((40, 2)) * big))
    ds = _all_algorithms(pts, None, seed=seed)
    q = g.random((300, 2)) * small
    near, clear = _nearest_clear(pts, q)
    for d in ds:
        inside = shapely.intersects(np.asarray(d.cells, dtype=object)[near], shapely.points(q))
        assert inside[clear].all()


@pytest.mark.parametrize(
    ("gaps", "direction", "off", "seed"),
    [
        ((3, 4), (1.0, -1.0), 0.7, 5),
        ((2, 2), (0.3, 1.0), -0.45, 8),
        ((5, 1), (1.0, 0.5), 7e5 + 0.125, 9),
    ],
)
def test_sites_ulps_apart_other_gaps_and_directions(gaps, direction, off, seed):
    """Three sites a few ulps apart in other directions, in a box 1 x 1.6 (not square)."""
    d = np.array(direction)
    b0 = np.array([off, off])
    p1 = _walk(b0.copy(), gaps[0], d)
    p2 = _walk(p1.copy(), gaps[1], d)
    others = off - 0.3 + np.random.default_rng(seed).random((25, 2)) * [1.0, 1.6]
    pts = np.concatenate(([b0, p1, p2], others))
    _all_algorithms(pts, (off - 0.3, off - 0.3, off + 0.7, off + 1.3), weights=np.zeros(len(pts)))


@pytest.mark.parametrize(
    ("dom", "chi"),
    [
        (MultiPolygon([box(0, 0, 2, 1), Polygon([(1, 1), (2, 2), (0, 2)])]), 1),
        (MultiPolygon([Polygon([(0, 0), (2, 0), (1, 1)]), Polygon([(1, 1), (2, 2), (0, 2)])]), 1),
        (
            MultiPolygon(
                [
                    box(1e6, 1e6, 1e6 + 1, 1e6 + 1),
                    box(1e6 + 1, 1e6 + 1, 1e6 + 2, 1e6 + 2),
                    box(1e6 + 2, 1e6, 1e6 + 3, 1e6 + 1),
                ]
            ),
            1,
        ),
        (
            MultiPolygon(
                [
                    Polygon([(0, 0), (3, 0), (3, 3), (0, 3), (0, 2), (2, 2), (2, 1), (0, 1)]),
                    box(-1, 1, 0, 2),
                ]
            ),
            0,
        ),
        (MultiPolygon([box(0, 0, 1e-7, 1e-7), box(1e-7, 1e-7, 3e-7, 2e-7)]), 1),
    ],
)
def test_describe_euler_on_other_touching_parts(dom, chi):
    """A corner on an edge, triangles tip to tip, a chain far out, two parts touching at two
    points (a ring), tiny parts: describe's expected characteristic is the union's."""
    x0, y0, x1, y1 = dom.bounds
    pts = np.random.default_rng(5).random((50, 2)) * [x1 - x0, y1 - y0] + [x0, y0]
    ds = _all_algorithms(
        pts, dom, weights=np.random.default_rng(1).random(50) * 1e-3 * (x1 - x0) ** 2
    )
    for d in ds:
        assert d.describe().euler_expected == chi


@pytest.mark.parametrize(
    ("pts", "dom", "target"),
    [
        (
            [[0.5, 0.5], [2.0, 0.5]],
            MultiPolygon([box(0, 0, 1, 1), box(1.5, 0, 2.5, 1)]),
            [1.75, 0.25],
        ),
        ([[1.5, 0.5], [0.5, 2.5]], MultiPolygon([box(0, 0, 3, 1), box(0, 2, 1, 3)]), [3.6, 0.4]),
        (
            [[0.2, 0.5], [0.5, 0.5], [0.8, 0.5]],
            MultiPolygon([box(0, 0, 1, 1), box(1.2, 0, 2.2, 1), box(2.4, 0, 3.4, 1)]),
            [1.0, 1.0, 1.0],
        ),
        (
            [[0.5, 0.5], [0.5, float(np.nextafter(np.nextafter(0.5, 1), 1))], [2.0, 0.5]],
            MultiPolygon([box(0, 0, 1, 1), box(1.5, 0, 2.5, 1)]),
            [0.6, 0.6, 0.8],
        ),
        (
            [[0.3, 0.5], [float(np.nextafter(0.3, 1)), 0.5], [0.7, 0.2]],
            box(0, 0, 1, 1),
            [0.3, 0.3, 0.4],
        ),
    ],
)
def test_power_fit_gaps_and_ulps(pts, dom, target, recwarn):
    """power_fit where cells must straddle gaps, and for sites 1-2 ulps apart: targets met,
    valid cells, no warning leaking out."""
    target = np.array(target)
    d = vf.power_fit(np.array(pts), target, dom)
    assert np.abs(d.areas - target).max() <= 1e-6 * target.sum()
    assert shapely.is_valid(np.asarray(d.cells, dtype=object)).all()
    assert not [w for w in recwarn.list if issubclass(w.category, Warning)]


@pytest.mark.parametrize(
    ("scale", "off"), [(1e200, 0.0), (1.0, 3e160), (1e-160, 0.0), (1e300, 0.0)]
)
def test_locate_far_out(scale, off):
    g = np.random.default_rng(3)
    pts = g.random((60, 2)) * scale + off
    q = g.random((50, 2)) * scale * 1.2 + off - 0.1 * scale
    want = np.argmin((((q[:, None, :] - pts[None]) / scale) ** 2).sum(-1), axis=1)
    assert np.array_equal(vf.locate(pts, q), want)
    assert np.array_equal(vf.voronoi(pts).locate(q), want)
    vals = vf.natural_neighbor(pts, np.arange(60.0), q, extrapolate="nearest")
    assert np.isfinite(vals).all()


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["voronoi", "P", "-o", "o.png", "--size", "50000"], ["too large", "16384"]),
        (["voronoi", "P", "-o", "o.png", "--size", "-5"], ["size", "-5"]),
        (["raster", "P", "-o", "o.npy", "--size", "3x2000000000"], ["too large", "pixels"]),
        (["explain", "fortune", "P", "-o", "o.gif", "--frames", "1000000"], ["frames", "1000000"]),
        (["explain", "fortune", "P", "-o", "o.gif", "--size", "0"], ["size", "0"]),
    ],
)
def test_size_guards_other_values(tmp_path, capsys, argv, words):
    src = tmp_path / "p.npy"
    np.save(src, np.random.default_rng(0).random((20, 2)) * 10)
    argv = [str(src) if a == "P" else str(tmp_path / a) if a.startswith("o.") else a for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert "voroforge: error:" in err and all(w in err for w in words), err
    assert not list(tmp_path.glob("o.*"))


@pytest.mark.parametrize(
    "dom", [box(0, 0, 300, 30), shapely.Point(0, 0).buffer(60), box(0, 0, 1e4, 1e4)]
)
def test_poisson_refuses_huge_counts_up_front(dom):
    from voroforge.design import populate

    with pytest.raises(ValueError, match="too small"):
        populate.poisson(dom, 0.05 if dom.area < 2e4 else 1.0, seed=1)


@pytest.mark.parametrize(
    ("shape", "per_site", "clustered"), [((480, 640), 30, False), ((512, 512), 25, True)]
)
def test_jfa_dense_sites(shape, per_site, clustered):
    """JFA against the exact labels at 25-30 pixels per site (uniform, 20 Gaussian clusters)."""
    g = np.random.default_rng(11)
    n = shape[0] * shape[1] // per_site
    if clustered:
        pts = g.random((20, 2))[g.integers(0, 20, n)] + g.normal(0, 0.02, (n, 2))
    else:
        pts = g.random((n, 2))
    b = (0.0, 0.0, 1.0, 1.0)
    e = vf.rasterize(pts, shape, b, method="exact")
    j = vf.rasterize(pts, shape, b, method="jfa")
    assert (e.labels != j.labels).mean() <= 0.005
