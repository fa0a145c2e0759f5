"""``Diagram3D.describe`` counted and checked with arrays is the plain per-face loop's answer.

``describe3d`` took ~75% of the 3D cell checks as a Python loop over every face of every
cell. It now counts vertices and edges per cell with ``np.unique`` and tests every face's
convexity at once; a face whose test lies within rounding of its threshold sends its cell
to the plain loop. ``_loop`` below is that loop as it stood (the slow, obvious reference):
both must give the same dict on boxes, degenerate and far inputs, weights, a torus, a
hull and a mesh that cuts cells into non-convex pieces.
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import voroforge as vf
from voroforge.config import CONVEX3D_RTOL, CONVEX3D_ULPS
from voroforge.engine import describe3d as D

sys.path.insert(0, str(Path(__file__).parent))
from catalogue3d import CATALOGUE3D, helix  # noqa: E402
from test_checker8_3d import torus  # noqa: E402

EPS = float(np.finfo(np.float64).eps)


def _loop(d):
    """The per-cell, per-face loop ``describe3d`` was: fails, non-convex cells, edges."""
    cf, _, farea, roff, ring = d.cell_face_table()
    fails, nonconvex, edges = [], [], set()
    for i in range(len(d)):
        f0, f1 = cf[i], cf[i + 1]
        if f1 == f0:
            continue
        cell_edges, verts = set(), set()
        for f in range(f0, f1):
            r = ring[roff[f] : roff[f + 1]]
            for a, b in zip(r, np.roll(r, -1), strict=False):
                e = (min(a, b), max(a, b))
                cell_edges.add(e)
                edges.add(e)
            verts.update(r.tolist())
        chi = len(verts) - len(cell_edges) + (f1 - f0)
        if d.container == "mesh" and d.cut_cells is not None and bool(d.cut_cells[i]):
            if chi % 2 or chi > 2 * D._pieces(ring, roff, f0, f1):
                fails.append(i)
        elif chi != 2:
            fails.append(i)
        V = d.vertices[list(verts)]
        size = float(np.ptp(V, axis=0).max()) if len(V) else 0.0
        res = max(CONVEX3D_RTOL * size, CONVEX3D_ULPS * EPS * float(np.abs(V).max(initial=0)))
        for f in range(f0, f1):
            a = farea[f]
            na = D._norm(a)
            if na <= res * size:
                continue
            r = d.vertices[ring[roff[f] : roff[f + 1]]]
            tol = res * (1.0 + size * D._perimeter(r) / na)
            if ((V - r[0]) @ (a / na)).max() > tol:
                nonconvex.append(i)
                break
    return fails, nonconvex, len(edges)


def _same(d):
    got = d.describe()
    fails, nonconvex, ne = _loop(d)
    assert got["euler_failures"] == fails
    assert got["nonconvex_cells"] == nonconvex
    assert got["convex"] == (not nonconvex)
    if not d.periodic:
        assert got["edges"] == ne
    return got


def _rand(n, seed=1):
    return np.random.default_rng(seed).random((n, 3))


CASES = {
    **{
        k: (lambda k=k: vf.voronoi3d(*CATALOGUE3D[k]))
        for k in ("cubic_grid", "sphere_centre", "duplicates", "utm", "huge")
    },
    "helix": lambda: vf.voronoi3d(helix(120), (0, 0, 0, 1, 1, 1)),
    "weights": lambda: vf.voronoi3d(
        _rand(60), (0, 0, 0, 1, 1, 1), weights=_rand(60, 2)[:, 0] * 0.05
    ),
    "periodic": lambda: vf.voronoi3d(_rand(50), (0, 0, 0, 1, 1, 1), periodic=True),
    "hull": lambda: vf.voronoi3d(_rand(50) * 0.5 + 0.25, vf.Convex(points=_rand(30, 3))),
    "torus": lambda: vf.voronoi3d(
        np.c_[np.cos(np.arange(24) / 3.82), np.sin(np.arange(24) / 3.82), np.zeros(24)],
        torus(r=0.35, nu=28, nv=14),
    ),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_describe_is_the_loops_answer(name):
    d = CASES[name]()
    got = _same(d)
    if name == "torus":  # the mesh cuts cells into non-convex pieces: both see them
        assert got["nonconvex_cells"] and got["cut_cells"]


@pytest.mark.parametrize("name", ["torus", "utm"])
def test_decided_cells_are_the_loops_and_the_rest_go_to_it(name, monkeypatch):
    d = CASES[name]()
    cf, _, farea, roff, ring = d.cell_face_table()
    _, _, cv_ptr, cv_idx, _ = D._cell_counts(len(d), cf, roff, ring, len(d.vertices))
    conv = D._convexity(d, cf, farea, roff, ring, cv_ptr, cv_idx)
    for i in np.flatnonzero(np.diff(cf) > 0):
        loop = D._cell_convex(d, cf, farea, roff, ring, i, cv_idx[cv_ptr[i] : cv_ptr[i + 1]])
        assert conv[i] in (-1, int(loop)), i
    want = d.describe()
    # every cell undecided: the loop alone answers, the same
    monkeypatch.setattr(D, "_convexity", lambda *a: np.full(len(d), -1, np.int8))
    assert d.describe() == want


def test_far_flat_box_without_warnings():
    # a slab 2**360 wide and 2**260 thick: the thresholds of faces left out overflowed
    # (a RuntimeWarning where the loop never computed them); those faces are not computed
    # now, and anything that still overflows is left to the loop
    P = np.random.default_rng(3).random((30, 3)) * [2.0**360, 2.0**360, 2.0**260]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        d = vf.voronoi3d(P, (0.0, 0.0, 0.0, 2.0**360, 2.0**360, 2.0**260))
        got = _same(d)
    assert got["euler_ok"] and got["convex"]
