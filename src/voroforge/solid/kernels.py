"""Numba kernels of the hull lattice: box overlaps and convex separation over many pairs."""

from __future__ import annotations

import numpy as np
from numba import njit

from .. import config

__all__ = ["box_pairs", "separated"]


@njit(**config.NJIT)
def _sweep(lo, hi, order, out_i, out_j, fill):
    """Sweep along x over boxes sorted by ``lo[:, 0]``; count (or write) overlapping pairs."""
    n = order.shape[0]
    m = 0
    for s in range(n):
        i = order[s]
        for t in range(s + 1, n):
            j = order[t]
            if lo[j, 0] > hi[i, 0]:
                break
            if lo[j, 1] > hi[i, 1] or lo[i, 1] > hi[j, 1]:
                continue
            if lo[j, 2] > hi[i, 2] or lo[i, 2] > hi[j, 2]:
                continue
            if fill:
                out_i[m] = min(i, j)
                out_j[m] = max(i, j)
            m += 1
    return m


def box_pairs(lo, hi) -> np.ndarray:
    """Index pairs ``(i < j)`` of overlapping closed axis-aligned boxes, sorted.

    Sweep and prune along x (boxes sorted by their low x, each compared with the boxes that
    start before it ends), then y and z.
    """
    lo = np.ascontiguousarray(lo, dtype=np.float64)
    hi = np.ascontiguousarray(hi, dtype=np.float64)
    order = np.argsort(lo[:, 0], kind="stable")
    z = np.zeros(0, dtype=np.int64)
    m = _sweep(lo, hi, order, z, z, False)
    pi = np.zeros(m, dtype=np.int64)
    pj = np.zeros(m, dtype=np.int64)
    _sweep(lo, hi, order, pi, pj, True)
    o = np.lexsort((pj, pi))
    return np.stack([pi[o], pj[o]], axis=1)


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
