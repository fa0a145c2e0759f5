"""Ring bookkeeping of cell builders: closing rings in output order, shared edges per pair.

Areas, centroids and moments of rings are in ``kernels/moments``.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..config import NJIT, NJIT_PARALLEL


@njit(**NJIT_PARALLEL)
def close_rings(coords, offsets, owner, perm, kmap):
    """Reorder open convex rings and close them.

    Ring ``k`` of the output is kernel ring ``perm[k]`` with its first vertex repeated at the
    end. Owners are mapped through ``kmap`` (kernel index -> output site index); the closing
    vertex gets owner -2. Returns ``(coords, ring_offsets over all k, owner)``; empty rings stay
    empty (length 0).
    """
    m = perm.shape[0]
    lengths = np.zeros(m + 1, dtype=np.int64)
    for k in range(m):
        c = offsets[perm[k] + 1] - offsets[perm[k]]
        lengths[k + 1] = c + 1 if c > 0 else 0
    for k in range(m):
        lengths[k + 1] += lengths[k]
    total = lengths[m]
    out = np.zeros((total, 2))
    own = np.full(total, -2, dtype=np.int64)
    for k in prange(m):
        a = offsets[perm[k]]
        b = offsets[perm[k] + 1]
        o = lengths[k]
        for v in range(a, b):
            out[o + v - a, 0] = coords[v, 0]
            out[o + v - a, 1] = coords[v, 1]
            w = owner[v]
            own[o + v - a] = kmap[w] if w >= 0 else w
        if b > a:
            out[o + b - a, 0] = coords[a, 0]
            out[o + b - a, 1] = coords[a, 1]
    return out, lengths, own


@njit(**NJIT_PARALLEL)
def shared_edges(coords, ring_offsets, ring_cell, owner, tol):
    """Edges ``k -> k + 1`` of closed rings whose owner is a higher-numbered cell.

    Returns ``(segments (m, 2, 2), pairs (m, 2))`` in ring order; edges not longer than
    ``tol`` are skipped.
    """
    nr = ring_cell.shape[0]
    tol2 = tol * tol
    per = np.zeros(nr + 1, dtype=np.int64)
    for r in prange(nr):
        c = ring_cell[r]
        cnt = 0
        for k in range(ring_offsets[r], ring_offsets[r + 1] - 1):
            if owner[k] > c:
                dx = coords[k + 1, 0] - coords[k, 0]
                dy = coords[k + 1, 1] - coords[k, 1]
                if dx * dx + dy * dy > tol2:
                    cnt += 1
        per[r + 1] = cnt
    for r in range(nr):
        per[r + 1] += per[r]
    seg = np.zeros((per[nr], 2, 2))
    pairs = np.zeros((per[nr], 2), dtype=np.int64)
    for r in prange(nr):
        c = ring_cell[r]
        j = per[r]
        for k in range(ring_offsets[r], ring_offsets[r + 1] - 1):
            if owner[k] > c:
                dx = coords[k + 1, 0] - coords[k, 0]
                dy = coords[k + 1, 1] - coords[k, 1]
                if dx * dx + dy * dy > tol2:
                    seg[j, 0, 0] = coords[k, 0]
                    seg[j, 0, 1] = coords[k, 1]
                    seg[j, 1, 0] = coords[k + 1, 0]
                    seg[j, 1, 1] = coords[k + 1, 1]
                    pairs[j, 0] = c
                    pairs[j, 1] = owner[k]
                    j += 1
    return seg, pairs


@njit(**NJIT)
def boundary_cycle(tri, he, n):
    """The boundary of a triangulation as one cycle of vertices, or an empty array.

    ``tri``, ``he`` in the Delaunator layout (halfedge ``e`` runs from ``tri[e]`` to the next
    corner of its triangle; ``he[e] == -1`` on the boundary). Empty when the boundary
    halfedges do not form exactly one cycle (a vertex met twice, an open chain, two loops).
    """
    after = np.full(n, -1, np.int64)
    first = -1
    count = 0
    for e in range(he.shape[0]):
        if he[e] >= 0:
            continue
        a = tri[e]
        if after[a] >= 0:
            return np.zeros(0, np.int64)  # a vertex the boundary passes twice
        after[a] = tri[e - e % 3 + (e + 1) % 3]
        first = a if first < 0 else first
        count += 1
    ring = np.zeros(count, np.int64)
    if count == 0:
        return ring
    ring[0] = first
    for k in range(1, count):
        ring[k] = after[ring[k - 1]]
        if ring[k] < 0 or ring[k] == first:
            return np.zeros(0, np.int64)
    if after[ring[count - 1]] != first:
        return np.zeros(0, np.int64)
    return ring
