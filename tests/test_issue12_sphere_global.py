"""Issue 12: cells past the grid search's budget are built from Delaunay candidate lists.

Points on a sphere made the search quadratic (every cell reaches from the centre to the
walls, so no site is out of reach). ``engine.lists3d`` stops a cell's search after
``SITE_BUDGET`` sites and builds it from the sites of its Delaunay polytopes. These tests
check that a cell built from its list is the cell the full search gives (the same vertex
bits and faces; only the order of vertices and faces and the volume's rounding may
differ), on ordinary and degenerate inputs with the list path forced, and that the
sphere families take it and keep the invariants.
"""

from __future__ import annotations

import numpy as np
import pytest

import voroforge as vf
from catalogue3d import CATALOGUE3D, _bcc, _fcc, _grid, _sphere, _sphere_exact
from test_issue12_exact3d import _check_cells
from voroforge.engine import lists3d
from voroforge.kernels.candidates3d import candidate_lists

BOX2 = (-2.0, -2.0, -2.0, 2.0, 2.0, 2.0)


def _canon(d):
    """Per cell: its vertices' coordinates (sorted) and its faces as (label, ring of
    coordinates from the least), sorted: the cell, whatever order it was built in."""
    out = []
    for i in range(len(d)):
        c = d.cell(i)
        V = [tuple(v) for v in np.asarray(c.vertices).tolist()]
        faces = []
        for f, lab in zip(c.faces, c.neighbors, strict=True):
            r = [V[v] for v in f]
            k = r.index(min(r))
            faces.append((int(lab), tuple(r[k:] + r[:k])))
        out.append((sorted(V), sorted(faces)))
    return out


def _forced(monkeypatch, p, box, **kw):
    monkeypatch.setattr(lists3d, "FORCE", False)
    full = vf.voronoi3d(p, box, **kw)
    monkeypatch.setattr(lists3d, "FORCE", True)
    listed = vf.voronoi3d(p, box, **kw)
    return full, listed


def _same(full, listed):
    assert _canon(full) == _canon(listed)
    # the same vertices, bit for bit (their order may differ)
    assert np.array_equal(np.unique(full.vertices, axis=0), np.unique(listed.vertices, axis=0))
    np.testing.assert_allclose(listed.volumes, full.volumes, rtol=1e-13, atol=0)
    # (periodic: the vertices shared with images, whose cells are not built)
    assert listed.unmatched_vertices == full.unmatched_vertices
    assert full.periodic or full.unmatched_vertices == 0
    for a, b in zip(full.neighbors, listed.neighbors, strict=True):
        assert np.array_equal(a, b)


_rng = np.random.default_rng(21)
_CASES = {
    "uniform": (_rng.random((600, 3)), (0, 0, 0, 1, 1, 1)),
    "uniform_default": (_rng.random((400, 3)), None),
    "cubic_grid": (_grid(5), None),
    "bcc": (_bcc(4), None),
    "fcc": (_fcc(3), None),
    "sites_on_walls": (
        np.vstack([_rng.random((200, 3)), np.c_[_rng.random((40, 2)), np.zeros(40)]]),
        (0, 0, 0, 1, 1, 1),
    ),
    "sphere_rounded": (_sphere(300), BOX2),
    "sphere_rounded_centre": (np.r_[_sphere(300), [[0.0, 0.0, 0.0]]], BOX2),
    "sphere_exact_centre": (np.r_[_sphere_exact(60), [[0.0, 0.0, 0.0]]], BOX2),
    **{f"catalogue_{k}": v for k, v in CATALOGUE3D.items()},
}


@pytest.mark.parametrize("name", sorted(_CASES))
def test_cells_from_lists_are_the_full_search_cells(monkeypatch, name):
    p, box = _CASES[name]
    full, listed = _forced(monkeypatch, p, box)
    _same(full, listed)


def test_periodic_and_mesh_cells_from_lists(monkeypatch):
    p = np.random.default_rng(3).random((300, 3))
    _same(*_forced(monkeypatch, p, (0, 0, 0, 1, 1, 1), periodic=True))
    # mesh containers keep the search (the mesh cut rounds by the order of a cell's faces)
    trimesh = pytest.importorskip("trimesh")
    q = np.random.default_rng(4).random((300, 3)) * 1.6 - 0.8
    full, listed = _forced(monkeypatch, q, trimesh.creation.icosphere(2, 1.0))
    assert np.array_equal(full.vertices, listed.vertices)
    assert np.array_equal(full.volumes, listed.volumes)


def test_weighted_cells_never_take_lists(monkeypatch):
    # the lists are Delaunay, not regular (power) triangulations: weights keep the search
    def refuse(*a):
        raise AssertionError("lists made for a weighted input")

    monkeypatch.setattr(lists3d, "candidate_lists", refuse)
    monkeypatch.setattr(lists3d, "FORCE", True)
    p = np.random.default_rng(5).random((300, 3))
    d = vf.voronoi3d(p, (0, 0, 0, 1, 1, 1), weights=np.random.default_rng(6).random(300) * 1e-3)
    assert abs(d.volumes.sum() - 1.0) <= 1e-12


def test_candidate_lists_hold_polytopes_and_delaunay_edges():
    # a cube's corners are one polytope (all on one empty sphere): each lists the other 7
    cube = np.array([[x, y, z] for x in (0.0, 1.0) for y in (0.0, 1.0) for z in (0.0, 1.0)])
    t = vf.delaunay3d(cube)
    start, sites, listed, big, _ = candidate_lists(cube, t.simplices, t.neighbors, 64)
    assert listed.all() and (big[0] == -1).all()
    for i in range(8):
        assert sorted(sites[start[i] : start[i + 1]].tolist()) == [j for j in range(8) if j != i]
    # too big a polytope: each corner lists the corners of its three square faces (not the
    # opposite one), and the polytope's sites are given whole
    start, sites, listed, (bigof, bstart, bsite), _ = candidate_lists(
        cube, t.simplices, t.neighbors, 7
    )
    assert listed.all() and (bigof == 0).all() and bsite.tolist() == list(range(8))
    for i in range(8):
        assert sorted(sites[start[i] : start[i + 1]].tolist()) == [
            j for j in range(8) if j not in (i, 7 - i)
        ]
    # random points: every Delaunay edge in both lists, nearest first
    p = np.random.default_rng(8).random((300, 3))
    t = vf.delaunay3d(p)
    start, sites, listed, _, _ = candidate_lists(p, t.simplices, t.neighbors, 64)
    assert listed.all()
    lists = [set(sites[start[i] : start[i + 1]].tolist()) for i in range(300)]
    for s in t.simplices:
        for a in s:
            assert set(s.tolist()) - {a} <= lists[a]
    for i in range(300):
        d = ((p[sites[start[i] : start[i + 1]]] - p[i]) ** 2).sum(1)
        assert (np.diff(d) >= 0).all()


@pytest.mark.parametrize("kind", ["rounded", "rounded_centre", "exact_centre"])
def test_sphere_families_take_the_lists(monkeypatch, kind):
    # the budget lowered so that 1,500 points run past it (at the default, 3,000 points
    # without the centre do): the cells are built from lists, made once, and keep the
    # invariants
    n = 1500
    monkeypatch.setattr(lists3d, "SITE_BUDGET", 256.0)
    made = []
    real = lists3d.candidate_lists

    def spy(*a):
        made.append(1)
        return real(*a)

    monkeypatch.setattr(lists3d, "candidate_lists", spy)
    S = _sphere_exact(n) if kind.startswith("exact") else _sphere(n)
    if kind.endswith("centre"):
        S = np.r_[S, [[0.0, 0.0, 0.0]]]
    d = vf.voronoi3d(S, BOX2)
    assert made == [1]
    assert d.unmatched_vertices == 0 and (d.volumes > 0).all()
    _check_cells(d, BOX2)
    r = d.describe()
    assert r["euler_ok"] and r["convex"], r
    if kind.endswith("centre"):  # the centre's cell meets every other
        indptr, nbr = d.neighbors
        assert set(nbr[indptr[n] : indptr[n + 1]].tolist()) == set(range(n))
