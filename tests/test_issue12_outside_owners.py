"""Sites outside a container whose cells are empty own no vertex (issue 12).

Half-integer sites around a box or hull whose corners are integer points: a site outside
whose cell shrinks to a corner, an edge or a face lies on that vertex's sphere, and was
counted among its owner sites although no cell of it references the vertex
(``unmatched_vertices`` 26 in the box ``[-1, 1]^3`` with sites -1.5..1.5), and a float hull
template was built a second time from its exact twin. Checked: no unmatched vertex, one
build, volumes against brute-force half-space cells (Qhull), samples in their nearest
site's cell, and the vertices of a cell exactly on its bounding planes (rationals).
"""

import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial import ConvexHull

import voroforge as vf
from voroforge.engine import voronoi3d as v3

sys.path.insert(0, str(Path(__file__).parent))
from reference3d import brute_volumes, dyadic_ints  # noqa: E402


def _grid(a, b, step=1.0):
    r = np.arange(a, b + step / 2, step)
    return np.array(np.meshgrid(r, r, r, indexing="ij")).reshape(3, -1).T


def _walls_of_box(lo, hi):
    rows = []
    for a in range(3):
        e = np.zeros(3)
        e[a] = 1.0
        rows += [[*(-e), -lo], [*e, hi]]
    return np.array(rows)


def _builds(monkeypatch):
    n = [0]
    orig = v3._convex_cells

    def counted(*a):
        n[0] += 1
        return orig(*a)

    monkeypatch.setattr(v3, "_convex_cells", counted)
    return n


def _check(d, sites, walls, vol):
    info = d.describe()
    assert info["euler_ok"]
    assert info["unmatched_vertices"] == 0
    assert d.volumes.sum() == pytest.approx(vol, rel=1e-13, abs=0)
    ref = brute_volumes(sites, walls)
    assert np.abs(d.volumes - ref).max() <= 1e-12 * vol
    # every vertex of a cell is exactly equidistant from its site and the nearest other
    # sites, and no site is nearer (rationals, as ints times one power of two)
    cells = np.flatnonzero(d.volumes > 0)[:20]
    S, *cell_vertices = dyadic_ints(sites, *(d.cell(int(i)).vertices for i in cells))
    for i, vertices in zip(cells, cell_vertices, strict=True):
        for X in vertices:
            dist = [sum((a - b) ** 2 for a, b in zip(X, s, strict=True)) for s in S]
            assert dist[i] == min(dist)
    # samples in their nearest site's cell
    rng = np.random.default_rng(0)
    lo, hi = d.vertices.min(axis=0), d.vertices.max(axis=0)
    x = lo + (hi - lo) * rng.random((2000, 3))
    x = x[(x @ walls[:, :3].T - walls[:, 3] < -1e-9).all(axis=1)]
    near = np.argmin(((x[:, None, :] - sites[None]) ** 2).sum(-1), axis=1)
    for i in np.unique(near):
        eq = ConvexHull(np.asarray(d.cell(int(i)).vertices)).equations
        assert (x[near == i] @ eq[:, :3].T + eq[:, 3] <= 1e-9).all(), int(i)


@pytest.mark.parametrize("a, step", [(-1.5, 1.0), (-1.75, 0.5), (-2.5, 1.0)])
def test_box_with_sites_outside(a, step, monkeypatch):
    n = _builds(monkeypatch)
    sites = _grid(a, -a, step)
    d = vf.voronoi3d(sites, (-1, -1, -1, 1, 1, 1))
    assert n[0] == 1
    assert (d.volumes == 0).sum() == (np.abs(sites) > 1).any(axis=1).sum()
    _check(d, sites, _walls_of_box(-1.0, 1.0), 8.0)


@pytest.mark.parametrize("a, step", [(-1.5, 1.0), (-1.75, 0.5)])
def test_cube_hull_built_once(a, step, monkeypatch):
    # Convex(points=) keeps the float cut of its hull: before, the outside sites' vertices
    # were unmatched there too, and the build was done again from the exact twin
    n = _builds(monkeypatch)
    sites = _grid(a, -a, step)
    c = vf.Convex(points=_grid(-1, 1, 2.0))
    d = vf.voronoi3d(sites, c)
    assert n[0] == 1
    _check(d, sites, c.halfspaces, 8.0)


def test_octahedron_hull_built_once(monkeypatch):
    n = _builds(monkeypatch)
    sites = _grid(-2.5, 2.5)
    c = vf.Convex(points=2.0 * np.vstack([np.eye(3), -np.eye(3)]))
    d = vf.voronoi3d(sites, c)
    assert n[0] == 1
    _check(d, sites, c.halfspaces, 32.0 / 3.0)


@pytest.mark.parametrize("k", [-40, 0, 40])
def test_scaled_and_far(k):
    sites = np.ldexp(_grid(-1.5, 1.5), k)
    for off in (0.0, 1e6 * 2.0**k):
        d = vf.voronoi3d(sites + off, tuple(np.ldexp([-1, -1, -1, 1, 1, 1], k) + off))
        info = d.describe()
        assert info["euler_ok"] and info["unmatched_vertices"] == 0
        assert d.volumes.sum() == pytest.approx(8.0 * 2.0 ** (3 * k), rel=1e-12, abs=0)


def test_sites_all_inside_unchanged():
    # no site outside: no first pass, the same build (a site on a wall is inside)
    sites = _grid(-1.0, 1.0, 0.5)
    d = vf.voronoi3d(sites, (-1, -1, -1, 1, 1, 1))
    assert d.describe()["unmatched_vertices"] == 0
    assert (d.volumes > 0).all()
    assert d.volumes.sum() == pytest.approx(8.0, rel=1e-14)
