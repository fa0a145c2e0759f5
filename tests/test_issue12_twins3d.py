"""Issue 12: 3D sites a few ulps apart ("twins") get the exact diagram's cells.

The twins' bisectors with a third site are nearly one plane; a cut by the second made its
new vertices by interpolating along edges nearly parallel to it, so they landed anywhere on
the edge and later planes were trusted on wrong points (vertices outside the box, faces the
exact cell lacks, a rotated Convex's cell builder failing). References: exact rational cells
(vertex enumeration in Fractions), a brute-force nearest-site check of every vertex, and the
neighbour relation's symmetry.
"""

from __future__ import annotations

import itertools
from fractions import Fraction as Fr

import numpy as np
import pytest

import voroforge as vf

BOX = (0.0, 0.0, 0.0, 1.0, 1.0, 1.0)


def _solve3(A, b):
    """Exact solution of the 3x3 system ``A x = b`` (Fractions), or None when singular."""
    M = [list(A[r]) + [b[r]] for r in range(3)]
    for c in range(3):
        p = next((r for r in range(c, 3) if M[r][c] != 0), None)
        if p is None:
            return None
        M[c], M[p] = M[p], M[c]
        for r in range(3):
            if r != c and M[r][c] != 0:
                f = M[r][c] / M[c][c]
                M[r] = [x - f * y for x, y in zip(M[r], M[c], strict=True)]
    return tuple(M[r][3] / M[r][r] for r in range(3))


def _exact_cell_vertices(S, i, box=BOX):
    """The vertices of site ``i``'s exact cell in the box (rational vertex enumeration)."""
    lo, hi = box[:3], box[3:]
    rows = []
    for a in range(3):
        e = [Fr(0)] * 3
        e[a] = Fr(1)
        rows.append((e, Fr(hi[a])))
        rows.append(([-x for x in e], -Fr(lo[a])))
    pi = [Fr(float(v)) for v in S[i]]
    for k in range(len(S)):
        if k != i:
            pk = [Fr(float(v)) for v in S[k]]
            n = [2 * (pk[a] - pi[a]) for a in range(3)]
            rows.append((n, sum(v * v for v in pk) - sum(v * v for v in pi)))
    out = set()
    for tri in itertools.combinations(rows, 3):
        x = _solve3([r[0] for r in tri], [r[1] for r in tri])
        if x is not None and all(
            sum(a * v for a, v in zip(n, x, strict=True)) <= d for n, d in rows
        ):
            out.add(x)
    return np.array([[float(v) for v in x] for x in out])


def _check(d, S, inside, tol=1e-12):
    """Every vertex of cell ``i`` is no nearer another site than ``i`` and inside the container."""
    for i in range(len(S)):
        V = np.asarray(d.cell(i).vertices)
        if not len(V):
            continue
        assert inside(V), f"cell {i}: a vertex outside the container"
        own = ((V - S[i]) ** 2).sum(1)
        best = ((V[:, None, :] - S[None]) ** 2).sum(2).min(1)
        assert (own - best).max() <= tol, f"cell {i}: a vertex nearer another site"
    ip, ix = d.neighbors
    nb = {i: set(ix[ip[i] : ip[i + 1]].tolist()) for i in range(len(S))}
    assert all(i in nb[j] for i in nb for j in nb[i]), "neighbours not symmetric"
    assert d.unmatched_vertices == 0 or d.periodic


def _in_box(V):
    return V.min() >= 0.0 and V.max() <= 1.0


def _twins(seed, k, n=30):
    r = np.random.default_rng(100 + seed)
    base = r.random((n, 3))
    tw = base[:3] + r.integers(-k, k + 1, (3, 3)) * np.spacing(base[:3])
    return np.r_[base, tw]


def test_minimal_four_sites_exact_cells():
    """Sites 0 and 3 (-2, -2, +1) ulps apart: each cell has the exact cell's vertices."""
    S = np.array(
        [
            [0.4389640958981894, 0.9598728385793203, 0.30945904270592706],
            [0.22264275011938295, 0.9106147154076719, 0.7254884495480645],
            [0.7933947239584096, 0.8967968118958176, 0.5649475000887172],
            [0.4389640958981893, 0.95987283857932, 0.3094590427059271],
        ]
    )
    d = vf.voronoi3d(S, BOX)
    for i in range(4):
        ours = np.asarray(d.cell(i).vertices)
        ref = _exact_cell_vertices(S, i)
        # each exact vertex is one of ours (ours may repeat one within the twins' ulps)
        gap = np.abs(ours[:, None, :] - ref[None]).max(2)
        assert gap.min(0).max() < 1e-12, f"cell {i}: an exact vertex missing"
        assert gap.min(1).max() < 1e-12, f"cell {i}: a vertex the exact cell lacks"
    assert d.unmatched_vertices == 0
    assert abs(d.volumes.sum() - 1.0) < 1e-15
    _check(d, S, _in_box)


@pytest.mark.parametrize("k", [1, 8])
def test_random_twins_box(k):
    """30 uniform sites and 3 twins within ``k`` ulps: right cells (was 16/16 wrong)."""
    for seed in range(8):
        S = _twins(seed, k)
        d = vf.voronoi3d(S, BOX)
        _check(d, S, _in_box)
        assert abs(d.volumes.sum() - 1.0) < 1e-14


def test_random_twins_other_containers():
    """The same in a Convex of the box's half-spaces, a rotated cube (it raised), the torus."""
    H = np.array(
        [[1, 0, 0, 1], [-1, 0, 0, 0], [0, 1, 0, 1], [0, -1, 0, 0], [0, 0, 1, 1], [0, 0, -1, 0.0]]
    )
    R = np.linalg.qr(np.random.default_rng(2).normal(size=(3, 3)))[0]
    cube = np.array(list(itertools.product((0.0, 1.0), repeat=3)))
    for seed in range(4):
        S = _twins(seed, 1)
        d = vf.voronoi3d(S, vf.Convex(halfspaces=H))
        _check(d, S, _in_box)
        Sr = S @ R.T
        d = vf.voronoi3d(Sr, vf.Convex(points=cube @ R.T))
        _check(d, Sr, lambda V: (V @ R).min() >= -1e-12 and (V @ R).max() <= 1 + 1e-12)
        assert abs(d.volumes.sum() - 1.0) < 1e-12
        d = vf.voronoi3d(S, BOX, periodic=True)
        assert d.describe()["convex"]
        assert abs(d.volumes.sum() - 1.0) < 1e-14


def test_rotated_cube_centre_twins():
    """Twins 5.7e-17 apart at a rotated cube's centre with its corners: cells by symmetry."""
    R = np.linalg.qr(np.random.default_rng(2).normal(size=(3, 3)))[0]
    B = np.array(list(itertools.product((0.0, 1.0), repeat=3))) @ R.T
    c = B.mean(0)
    S = np.r_[
        B,
        [c + [-1.3877787807814457e-17, -5.551115123125783e-17, 0.0]],
        [c + [-1.3877787807814457e-17, 0, 0]],
    ]
    H = np.c_[R.T, np.ones(3)]  # x' = R^T x <= 1 in the cube's frame, and >= 0
    H = np.r_[H, np.c_[-R.T, np.zeros(3)]]
    for box in (vf.Convex(points=B), vf.Convex(halfspaces=H)):
        d = vf.voronoi3d(S, box)
        _check(d, S, lambda V: (V @ R).min() >= -1e-12 and (V @ R).max() <= 1 + 1e-12)
        # central symmetry: each corner's cell is 1/16, the twins' 1/4
        assert np.allclose(d.volumes, [1 / 16] * 8 + [1 / 4] * 2, rtol=0, atol=1e-14)


def test_ulp_lattice_neighbours_symmetric():
    """A 4x4x4 lattice moved by 1 ulp per coordinate: a face a few ulps wide is on both sides."""
    L = np.array(list(itertools.product(range(4), repeat=3)), float) * 0.25 + 0.125
    for seed in (5, 0, 1):
        J = L + np.random.default_rng(seed).integers(-1, 2, L.shape) * np.spacing(L)
        d = vf.voronoi3d(J, BOX)
        _check(d, J, _in_box)
