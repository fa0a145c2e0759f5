"""Numba kernels of the solids: the hull lattice's pair tests, the implicit route's smoothing."""

from __future__ import annotations

import numpy as np
from numba import njit

from .. import config

__all__ = ["box_pairs", "near_classes", "separated", "taubin", "two_nearest"]


@njit(**config.NJIT)
def _grid_pairs(lo, hi, o, h, dim, start, members, out_i, out_j, fill):
    """Count (or write) the overlapping pairs, bucket by bucket.

    A pair is reported only in the bucket holding the larger of its two low corners: once.
    """
    m = 0
    nb = start.shape[0] - 1
    for cell in range(nb):
        s0, s1 = start[cell], start[cell + 1]
        for a in range(s0, s1):
            i = members[a]
            for b in range(a + 1, s1):
                j = members[b]
                if lo[j, 0] > hi[i, 0] or lo[i, 0] > hi[j, 0]:
                    continue
                if lo[j, 1] > hi[i, 1] or lo[i, 1] > hi[j, 1]:
                    continue
                if lo[j, 2] > hi[i, 2] or lo[i, 2] > hi[j, 2]:
                    continue
                key = 0
                for c in range(2, -1, -1):
                    t = int(np.floor((max(lo[i, c], lo[j, c]) - o[c]) / h))
                    t = min(max(t, 0), dim[c] - 1)
                    key = key * dim[c] + t
                if key != cell:
                    continue
                if fill:
                    out_i[m] = min(i, j)
                    out_j[m] = max(i, j)
                m += 1
    return m


def box_pairs(lo, hi) -> np.ndarray:
    """Index pairs ``(i < j)`` of overlapping closed axis-aligned boxes, sorted.

    Boxes go into the buckets of a uniform grid (twice the median box size, at most 128 a
    side) they overlap;
    pairs are tested within buckets and each reported once, in the bucket of the larger of
    their low corners.
    """
    lo = np.ascontiguousarray(lo, dtype=np.float64)
    hi = np.ascontiguousarray(hi, dtype=np.float64)
    n = len(lo)
    if n < 2:
        return np.zeros((0, 2), dtype=np.int64)
    o = lo.min(axis=0)
    span = float((hi.max(axis=0) - o).max())
    # twice the median box, at most 128 buckets a side (points and tiny boxes: 1 if all equal)
    h = max(2.0 * float(np.median((hi - lo).max(axis=1))), span / 128.0) or 1.0
    c0 = np.floor((lo - o) / h).astype(np.int64)
    c1 = np.floor((hi - o) / h).astype(np.int64)
    dim = c1.max(axis=0) + 1
    nx = c1 - c0 + 1
    cnt = nx.prod(axis=1)
    owner = np.repeat(np.arange(n), cnt)
    local = np.arange(int(cnt.sum())) - np.repeat(np.cumsum(cnt) - cnt, cnt)
    nxo = nx[owner]
    ix = c0[owner, 0] + local % nxo[:, 0]
    iy = c0[owner, 1] + (local // nxo[:, 0]) % nxo[:, 1]
    iz = c0[owner, 2] + local // (nxo[:, 0] * nxo[:, 1])
    key = (iz * dim[1] + iy) * dim[0] + ix
    order = np.argsort(key, kind="stable")
    members = owner[order]
    start = np.searchsorted(key[order], np.arange(int(dim.prod()) + 1))
    z = np.zeros(0, dtype=np.int64)
    args = (lo, hi, o, h, dim.astype(np.int64), start.astype(np.int64), members)
    m = _grid_pairs(*args, z, z, False)
    pi = np.zeros(m, dtype=np.int64)
    pj = np.zeros(m, dtype=np.int64)
    _grid_pairs(*args, pi, pj, True)
    o_ = np.lexsort((pj, pi))
    return np.stack([pi[o_], pj[o_]], axis=1)


@njit(**config.NJIT)
def _separated(vp, V, qp, Q, x, y, margin, out):
    for p in range(x.shape[0]):
        a, b = x[p], y[p]
        for q in range(qp[b], qp[b + 1]):
            nx, ny, nz, off = Q[q, 0], Q[q, 1], Q[q, 2], Q[q, 3]
            ok = True
            for v in range(vp[a], vp[a + 1]):
                if nx * V[v, 0] + ny * V[v, 1] + nz * V[v, 2] + off <= margin:
                    ok = False
                    break
            if ok:
                out[p] = True
                break


def separated(vp, V, qp, Q, x, y, margin: float) -> np.ndarray:
    """Per pair ``(x[p], y[p])``: whether polytope ``x`` lies wholly outside a facet of ``y``.

    Every vertex of ``x`` more than ``margin`` outside one facet plane of ``y``: a sufficient
    test that the two convex bodies are apart. Polytope ``t`` has vertices
    ``V[vp[t]:vp[t + 1]]`` and facet planes ``Q[qp[t]:qp[t + 1]]`` (outward unit normal,
    offset: ``n . v + offset > 0`` outside).
    """
    out = np.zeros(len(x), dtype=bool)
    _separated(
        np.ascontiguousarray(vp, dtype=np.int64),
        np.ascontiguousarray(V, dtype=np.float64),
        np.ascontiguousarray(qp, dtype=np.int64),
        np.ascontiguousarray(Q, dtype=np.float64),
        np.ascontiguousarray(x, dtype=np.int64),
        np.ascontiguousarray(y, dtype=np.int64),
        float(margin),
        out,
    )
    return out


@njit(**config.NJIT)
def _taubin(v, f, inv_deg, steps):
    acc = np.zeros(v.shape)
    for s in steps:
        acc[:] = 0.0
        for t in range(f.shape[0]):
            a, b, c = f[t, 0], f[t, 1], f[t, 2]
            for k in range(3):
                acc[a, k] += v[b, k]
                acc[b, k] += v[c, k]
                acc[c, k] += v[a, k]
        for i in range(v.shape[0]):
            if inv_deg[i] > 0.0:
                for k in range(3):
                    v[i, k] += s * (acc[i, k] * inv_deg[i] - v[i, k])


def taubin(vertices, faces, iterations: int, lamb: float = 0.5, nu: float = 0.5) -> np.ndarray:
    """Taubin-smoothed copy of ``vertices`` (``trimesh.smoothing.filter_taubin``'s filter).

    The operator is trimesh's equal-weight umbrella: each vertex moves towards the mean of
    the vertices its faces' edges lead to (``a -> b, b -> c, c -> a``: on a closed oriented
    mesh, each neighbour once), by ``lamb`` on even iterations and back by ``nu`` on odd
    ones. The same arithmetic up to the order of the sums (rounding); built from the faces
    in one pass instead of trimesh's sparse matrix, which costs more to set up than the
    smoothing itself (0.4 s of a lattice's 555k triangles).
    """
    v = np.array(vertices, dtype=np.float64, order="C")
    f = np.ascontiguousarray(faces, dtype=np.int64)
    deg = np.bincount(f.ravel(), minlength=len(v)).astype(np.float64)
    inv_deg = np.divide(1.0, deg, out=np.zeros_like(deg), where=deg > 0)
    steps = np.where(np.arange(int(iterations)) % 2 == 0, float(lamb), -float(nu))
    _taubin(v, f, inv_deg, steps)
    return v


@njit(**config.NJIT)
def _two_nearest(p, s, d1, d2):
    for i in range(p.shape[0]):
        x, y, z = p[i, 0], p[i, 1], p[i, 2]
        a = np.inf
        b = np.inf
        for j in range(s.shape[0]):
            dx = s[j, 0] - x
            dy = s[j, 1] - y
            dz = s[j, 2] - z
            q = dx * dx + dy * dy + dz * dz
            if q < b:
                if q < a:
                    b = a
                    a = q
                else:
                    b = q
        d1[i] = np.sqrt(a)
        d2[i] = np.sqrt(b)


def two_nearest(points, seeds) -> tuple[np.ndarray, np.ndarray]:
    """Distances from each point to its nearest and second-nearest seed, by brute force.

    For the few seeds of a shell's openings (tens to hundreds) against many grid samples, a
    scan of every seed costs half the CPU of a KD-tree's two-neighbour query (the lamp-shade
    example: 0.9M samples, 90 seeds, 0.17 s against 0.34 s); the distances there are
    identical to the KD-tree's. Needs at least two seeds.
    """
    p = np.ascontiguousarray(points, dtype=np.float64)
    s = np.ascontiguousarray(seeds, dtype=np.float64)
    if len(s) < 2:
        raise ValueError("two_nearest needs at least two seeds")
    d1 = np.zeros(len(p))
    d2 = np.zeros(len(p))
    _two_nearest(p, s, d1, d2)
    return d1, d2


@njit(**config.NJIT)
def _near_classes(p, order, tol2, parent):
    """Union every pair within ``sqrt(tol2)`` (a sweep along x in ``order``); roots = minima."""
    n = order.shape[0]
    tol = np.sqrt(tol2)
    for a in range(n):
        i = order[a]
        for b in range(a + 1, n):
            j = order[b]
            dx = p[j, 0] - p[i, 0]
            if dx > tol:
                break
            dy = p[j, 1] - p[i, 1]
            dz = p[j, 2] - p[i, 2]
            if dx * dx + dy * dy + dz * dz <= tol2:
                ri = i
                while parent[ri] != ri:
                    ri = parent[ri]
                rj = j
                while parent[rj] != rj:
                    rj = parent[rj]
                if ri < rj:
                    parent[rj] = ri
                elif rj < ri:
                    parent[ri] = rj
    for i in range(parent.shape[0]):  # each to its class's lowest index (roots come first)
        parent[i] = parent[parent[i]]


def near_classes(points, tol: float) -> np.ndarray:
    """Classes of the points closer than ``tol`` (chains joined), numbered by lowest member.

    What ``scipy.sparse.csgraph.connected_components`` labels on the graph of
    ``cKDTree(points).query_pairs(tol)`` (distance <= tol), without scipy: class ``c`` is
    the ``c``-th class by its lowest point index.

    Parameters
    ----------
    points : (n, 3) float64
    tol : float

    Returns
    -------
    (n,) int64
    """
    p = np.ascontiguousarray(points, dtype=np.float64)
    parent = np.arange(len(p), dtype=np.int64)
    if len(p) > 1 and tol >= 0:
        order = np.argsort(p[:, 0], kind="stable").astype(np.int64)
        _near_classes(p, order, float(tol) * float(tol), parent)
    roots = np.flatnonzero(parent == np.arange(len(p)))
    label = np.zeros(len(p), dtype=np.int64)
    label[roots] = np.arange(len(roots))
    return label[parent]
