"""Issue 12: a plane's values found near it on a many-faced cell (kernels/climb3d): the full pass's.

``cellcut3d._cut_batch`` used to evaluate every vertex of the cell for each candidate plane;
:func:`climb3d.plane_local` climbs to the top vertex over the cell's edges and either proves
that every vertex lies below the filter's band (``MISS``) or floods the vertices near and
above the plane (``LOCAL``), else says ``FULL``. Against the full pass on cells of ~100-400
faces (a box cut by tangent planes of a sphere, as a helix's cells are), with random planes,
planes through a vertex, nearly missing and nearly touching: a ``MISS`` has no vertex within
the band, a ``LOCAL`` list holds every vertex within the band or above with the same bits,
and the cut made from it (``list_removed``, ``graph3d.cut_listed``) leaves the same graph,
array for array, as ``graph3d.cut_open``. End to end: many-faced diagrams against the
face-ring cut (full passes) and rational cells.
"""

from __future__ import annotations

import numpy as np
import pytest

import voroforge as vf
from catalogue3d import helix, three_lines
from reference3d_exact import exact_power_cell
from voroforge.engine.containers import box_template
from voroforge.kernels import climb3d, graph3d

CAP = 4096
BOX = (0.0, 0.0, 0.0, 1.0, 1.0, 1.0)


def _sphere_cell(n, seed):
    """The box [-1, 1]^3 cut by the bisectors of ``n`` sites at distance ~1.6 (site 0 at 0)."""
    rng = np.random.default_rng(seed)
    u = rng.normal(size=(n, 3))
    u /= np.linalg.norm(u, axis=1)[:, None]
    P = np.vstack([np.zeros(3), u * rng.uniform(1.5, 1.7, (n, 1))])
    W = np.zeros(n + 1)
    t = box_template(-np.ones(3), np.ones(3))
    V = np.zeros((CAP, 3))
    V[:8] = t.TV
    F = np.zeros((CAP, 3), np.int64)
    F[:6] = t.TF
    R = np.zeros(4 * CAP, np.int64)
    R[:24] = t.TR
    G = [np.zeros(CAP, np.int32)] + [np.zeros((CAP, 24), np.int32) for _ in range(3)]
    assert graph3d.from_rings(8, F, 6, R, *G)
    FL = np.zeros(CAP, np.bool_)
    CP = np.zeros((CAP, 3), np.int64)
    S = np.zeros(CAP)
    nv = 8
    for k in range(1, n + 1):
        a = P[k]
        h = 0.5 * float(a @ a)
        S[:nv] = V[:nv] @ a - h
        st, nv2, _ = graph3d.cut(V, nv, *G, FL, S, CP, k)
        assert st in (graph3d.GCUT_DONE, graph3d.GCUT_NONE)
        nv = nv2 if st == graph3d.GCUT_DONE else nv
    return P, W, t.WP, V, nv, G, FL


def _full(V, nv, a, h, S):
    S[:nv] = a[0] * V[:nv, 0] + a[1] * V[:nv, 1] + a[2] * V[:nv, 2] - h
    return S[:nv]


def _planes(rng, V, nv, count):
    """Candidate sites: random near ones, and ones whose plane passes through a vertex, just
    beyond the cell's top vertex or just inside it (by a few bands)."""
    out = []
    for k in range(count):
        u = rng.normal(size=3)
        u /= np.linalg.norm(u)
        kind = k % 4
        top = float((V[:nv] @ u).max())
        if kind == 0:
            d = rng.uniform(0.5, 1.2) * top
        elif kind == 1:
            d = float(V[rng.integers(nv)] @ u)
        else:
            d = top * (1.0 + (1 if kind == 2 else -1) * 10.0 ** rng.uniform(-13, -6))
        if d <= 0:
            continue
        out.append(2.0 * d * u)  # the bisector of 0 and q: u . x = d
    return out


@pytest.mark.parametrize("n, seed", [(120, 1), (400, 2)])
def test_local_values_are_the_full_pass(n, seed):
    P, W, WP, V, nv, G, FL = _sphere_cell(n, seed)
    assert nv > 150
    rng = np.random.default_rng(seed + 10)
    work = np.zeros((CAP, 4), np.int64)
    S = np.zeros(CAP)
    SF = np.zeros(CAP)
    modes = [0, 0, 0]
    r2 = float((V[:nv] ** 2).sum(axis=1).max())
    for q in _planes(rng, V, nv, 400):
        d2 = float(q @ q)
        h = 0.5 * d2
        tol = 1e-12 * (np.sqrt(d2 * r2) + abs(h))
        full = _full(V, nv, q, h, SF)
        S[:] = np.nan
        for hint in (0, int(rng.integers(nv))):
            mode, smax, low, nvis = climb3d.plane_local(
                V, nv, G[0], G[1], S, work, q[0], q[1], q[2], h, tol, hint
            )
            assert not work[:nv, 0].any() and not work[:nv, 3].any()  # marks cleared
            modes[mode] += 1
            if mode == climb3d.MISS:
                assert full.max() < -tol
            elif mode == climb3d.LOCAL:
                seen = work[:nvis, 1]
                assert len(set(seen.tolist())) == nvis
                assert (S[seen] == full[seen]).all()  # the same bits
                need = np.flatnonzero(full > -tol)
                assert np.isin(need, seen).all()
                assert (smax > 0) == (full.max() > 0) and (low <= tol) == (
                    np.abs(full).min() <= tol
                )
    assert modes[climb3d.FULL] <= 0.1 * sum(modes) and modes[climb3d.MISS] > 0
    assert modes[climb3d.LOCAL] > 0


def test_local_cut_is_the_full_cut():
    """Cut after cut, the graph cut from the local list leaves the same arrays as ``cut_open``."""
    P, W, WP, V, nv, G, FL = _sphere_cell(300, 5)
    rng = np.random.default_rng(7)
    A = [V.copy(), *[g.copy() for g in G], FL.copy()]
    B = [V.copy(), *[g.copy() for g in G], FL.copy()]
    nva = nvb = nv
    work = np.zeros((CAP, 4), np.int64)
    SA = np.zeros(CAP)
    SB = np.zeros(CAP)
    CA = np.zeros((CAP, 3), np.int64)
    CB = np.zeros((CAP, 3), np.int64)
    cuts = 0
    for step in range(300):
        u = rng.normal(size=3)
        u /= np.linalg.norm(u)
        top = float((A[0][:nva] @ u).max())
        q = 2.0 * top * rng.uniform(0.97, 1.0) * u
        d2 = float(q @ q)
        h = 0.5 * d2
        r2 = float((A[0][:nva] ** 2).sum(axis=1).max())
        tol = 1e-12 * (np.sqrt(d2 * r2) + abs(h))
        full = _full(B[0], nvb, q, h, SB)
        if np.abs(full).min() <= tol or full.max() <= 0:
            continue  # band decisions are the engine's (exact); here only clear cuts
        mode, smax, low, nvis = climb3d.plane_local(
            A[0], nva, A[1], A[2], SA, work, q[0], q[1], q[2], h, tol, step
        )
        assert mode == climb3d.LOCAL
        nup, down = climb3d.list_removed(nva, A[1], SA, work, nvis, CA)
        assert nup == (full > 0).sum() and down
        sa = graph3d.cut_listed(A[0], nva, *A[1:5], A[5], SA, CA, 1000 + step, nup, True)
        sb = graph3d.cut_open(B[0], nvb, *B[1:5], B[5], SB, CB, 1000 + step)
        assert sa == sb
        assert sa[0] == graph3d.GCUT_DONE
        ca = graph3d.cut_close(A[0], sa[1], *A[1:5], A[5], SA, CA, sa[3], False)
        cb = graph3d.cut_close(B[0], sb[1], *B[1:5], B[5], SB, CB, sb[3], False)
        assert ca == cb
        nva = nvb = ca[1]
        for x, y in zip(A, B, strict=True):
            assert np.array_equal(x[:nva], y[:nva])
        cuts += 1
    assert cuts > 100


@pytest.mark.parametrize("pts", [helix(600), three_lines(600)], ids=["helix", "lines3"])
def test_many_faced_diagrams(pts, monkeypatch):
    """Against the face-ring cut (every cut a full pass) and rational cells."""
    from voroforge.engine import build3d

    d = vf.voronoi3d(pts, BOX)
    assert d.unmatched_vertices == 0
    assert abs(d.volumes.sum() - 1.0) <= 1e-12
    monkeypatch.setattr(build3d, "CAPS", build3d.CAPS[:6] + (2,))  # no graph: face rings
    e = vf.voronoi3d(pts, BOX)
    monkeypatch.undo()
    assert np.abs(d.volumes - e.volumes).max() <= 1e-12 * d.volumes.max()
    for x, y in zip(d.neighbors, e.neighbors, strict=True):
        assert (x == y).all()
    assert np.array_equal(np.unique(d.vertices, axis=0), np.unique(e.vertices, axis=0))
    ptr, nb = d.neighbors
    assert max(np.diff(ptr)) >= 40
    for i in (0, len(pts) // 2):
        ex = exact_power_cell(pts, i, BOX)
        want = {int(j) for lab in ex.neighbour_sets() for j in lab if j >= 0}
        assert {int(j) for j in nb[ptr[i] : ptr[i + 1]] if j >= 0} == want
        assert abs(d.volumes[i] - float(ex.volume)) <= 1e-12 * max(1.0, float(ex.volume))
