"""Big Convex hulls (issue 12): box cells, then the cells that reach a wall from the template.

A hull past the cell builder's scratch (more than 512 template faces) made every cell run
again alone: 2,000 sites in the hull of 300 points on a sphere took 3.2 s, of 2,000 points
~60 s. ``engine.hull3d`` builds every cell in a box around the hull and builds again, from
the hull's template and a candidate list, only the cells with a vertex near a wall. The
cells and their vertex bits must be the template path's (checked here against it, and
against brute-force half-space intersections, sample points and the hull's volume).
"""

import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial import ConvexHull

import voroforge as vf
import voroforge.engine.voronoi3d as v3
from voroforge.engine.containers import box_template
from voroforge.engine.hull3d import takes_hull_path

sys.path.insert(0, str(Path(__file__).parent))
from reference3d import brute_volumes  # noqa: E402


def _sphere(rng, m):
    h = rng.normal(size=(m, 3))
    return h / np.linalg.norm(h, axis=1)[:, None]


def _inside(c, pts):
    hs = c.halfspaces
    return pts[(pts @ hs[:, :3].T - hs[:, 3] < -1e-9).all(axis=1)]


def _template_path(monkeypatch, sites, c, **kw):
    with monkeypatch.context() as m:
        m.setattr(v3, "takes_hull_path", lambda t: False)
        return vf.voronoi3d(sites, c, **kw)


def _same_cells(d0, d1):
    """Every cell has the same vertices, bit for bit, and the same faces' neighbours."""
    for i in range(len(d0.sites)):
        a, b = d0.cell(i), d1.cell(i)
        assert sorted(map(tuple, np.asarray(a.vertices).tolist())) == sorted(
            map(tuple, np.asarray(b.vertices).tolist())
        ), i
    pairs0 = sorted(map(tuple, np.asarray(d0.faces.cells).tolist()))
    pairs1 = sorted(map(tuple, np.asarray(d1.faces.cells).tolist()))
    assert pairs0 == pairs1
    assert len(d0.vertices) == len(d1.vertices)


def _check_exact(d, c, sites, weights=None, samples=2000, seed=0):
    """Volumes against brute force, their sum, faces paired, samples in their nearest cell."""
    info = d.describe()
    assert info["euler_ok"] and info["unmatched_vertices"] == 0
    assert d.volumes.sum() == pytest.approx(c.volume, rel=1e-12, abs=0)
    ref = brute_volumes(sites, c.halfspaces, weights)
    assert np.abs(d.volumes - ref).max() <= 1e-11 * c.volume
    rng = np.random.default_rng(seed)
    lo, hi = d.vertices.min(axis=0), d.vertices.max(axis=0)
    x = _inside(c, lo + (hi - lo) * rng.random((samples, 3)))
    pw = np.zeros(len(sites)) if weights is None else weights
    near = np.argmin(((x[:, None, :] - sites[None]) ** 2).sum(-1) - pw[None], axis=1)
    for i in np.unique(near):
        eq = ConvexHull(np.asarray(d.cell(int(i)).vertices)).equations
        pts = x[near == i]
        size = np.ptp(np.asarray(d.cell(int(i)).vertices), axis=0).max()
        assert (pts @ eq[:, :3].T + eq[:, 3] <= 1e-9 * size).all(), int(i)


def test_big_hull_takes_the_path_and_small_ones_do_not():
    rng = np.random.default_rng(0)
    assert not takes_hull_path(vf.Convex(points=_sphere(rng, 60))._template)
    assert takes_hull_path(vf.Convex(points=_sphere(rng, 300))._template)
    assert not takes_hull_path(box_template([0.0] * 3, [1.0] * 3))


@pytest.mark.parametrize("n", [1, 3, 400])
def test_big_hull_cells_are_the_template_paths(monkeypatch, n):
    rng = np.random.default_rng(n)
    c = vf.Convex(points=_sphere(rng, 300))
    sites = _inside(c, rng.random((4 * n + 20, 3)) * 2 - 1)[:n]
    d = vf.voronoi3d(sites, c)
    _same_cells(_template_path(monkeypatch, sites, c), d)
    _check_exact(d, c, sites)


def test_big_hull_power_cells(monkeypatch):
    rng = np.random.default_rng(1)
    c = vf.Convex(points=_sphere(rng, 300))
    sites = _inside(c, rng.random((1200, 3)) * 2 - 1)[:300]
    w = rng.random(len(sites)) * 0.02
    d = vf.voronoi3d(sites, c, weights=w)
    _same_cells(_template_path(monkeypatch, sites, c, weights=w), d)
    _check_exact(d, c, sites, weights=w)


def test_big_hull_sites_on_and_outside_it(monkeypatch):
    # the hull's own points as sites (every one on three or more walls), then sites
    # scattered past the hull (cells cut to the part of the hull nearest them, or empty)
    rng = np.random.default_rng(2)
    h = _sphere(rng, 300)
    c = vf.Convex(points=h)
    for sites in (h, rng.random((300, 3)) * 2.4 - 1.2):
        d = vf.voronoi3d(sites, c)
        _same_cells(_template_path(monkeypatch, sites, c), d)
        assert d.describe()["unmatched_vertices"] == 0
        assert d.volumes.sum() == pytest.approx(c.volume, rel=1e-12, abs=0)


def test_big_hull_far_from_the_origin(monkeypatch):
    # walls kept about an origin near the solid (7-column rows)
    rng = np.random.default_rng(3)
    off = np.array([5e5, 4e6, 100.0])
    c = vf.Convex(points=_sphere(rng, 300) * 10 + off)
    assert c._template.WP.shape[1] == 7
    s = _sphere(rng, 400) * rng.random((400, 1)) ** (1 / 3) * 9 + off
    d = vf.voronoi3d(s, c)
    _same_cells(_template_path(monkeypatch, s, c), d)
    assert d.describe()["unmatched_vertices"] == 0
    assert d.volumes.sum() == pytest.approx(c.volume, rel=1e-11, abs=0)


def test_big_exact_polytope_from_halfspaces(monkeypatch):
    # Convex(halfspaces=): the exact polytope template, kept as it is
    rng = np.random.default_rng(4)
    c = vf.Convex(halfspaces=np.column_stack([_sphere(rng, 300), np.ones(300)]))
    assert takes_hull_path(c._template)
    sites = _inside(c, rng.random((800, 3)) * 2 - 1)[:300]
    d = vf.voronoi3d(sites, c)
    _same_cells(_template_path(monkeypatch, sites, c), d)
    _check_exact(d, c, sites)


def test_template_cut_in_one_call_is_the_cut_a_plane():
    # kernels.template3d.cut_all: the same template as one container_cut a plane
    from voroforge.engine.containers import box_template
    from voroforge.kernels.cells3d import container_cut
    from voroforge.kernels.template3d import cut_all

    for seed, m in ((0, 40), (1, 200), (2, 100)):
        rng = np.random.default_rng(seed)
        h = _sphere(rng, m) if seed != 2 else np.round(rng.normal(size=(m, 3)) * 4) / 4
        hs = vf.Convex(points=h).halfspaces
        k = len(hs)
        t = box_template([-5.0] * 3, [5.0] * 3, labels=[-1 - (k + b) for b in range(6)])
        TV, TF, TR = t.TV, t.TF, t.TR
        for w in range(k):
            st, TV, TF, TR = container_cut(
                TV, TF, TR, *hs[w, :3], hs[w, 3], -1 - w, 4 * (len(TV) + 8 * k + 64)
            )
            assert st in (0, 1)
        st, _, V2, F2, R2 = cut_all(t.TV, t.TF, t.TR, hs[:, :3].copy(), hs[:, 3].copy(), -1)
        assert st == 0
        assert np.array_equal(TV, V2) and np.array_equal(TF, F2) and np.array_equal(TR, R2)
