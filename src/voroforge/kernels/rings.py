"""Areas and centroids of ragged (GeoArrow multipolygon) cells, with holes and parts."""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..config import NJIT_PARALLEL


@njit(**NJIT_PARALLEL)
def area_centroid(coords, ring_offsets, polygon_offsets, geom_offsets):
    """Area and area centroid of each geometry.

    The first ring of every polygon is its exterior, the others are holes; ring orientation
    does not matter. Sums are taken relative to the geometry's first vertex, so coordinates
    like 500000/4000000 keep their precision. Empty geometries get area 0 and a NaN centroid.
    """
    n = geom_offsets.shape[0] - 1
    area = np.zeros(n)
    cen = np.full((n, 2), np.nan)
    for g in prange(n):
        p0 = geom_offsets[g]
        p1 = geom_offsets[g + 1]
        if p0 == p1:
            continue
        first = coords[ring_offsets[polygon_offsets[p0]]]
        ox = first[0]
        oy = first[1]
        a_tot = 0.0
        mx = 0.0
        my = 0.0
        for p in range(p0, p1):
            for r in range(polygon_offsets[p], polygon_offsets[p + 1]):
                a = 0.0
                sx = 0.0
                sy = 0.0
                for k in range(ring_offsets[r], ring_offsets[r + 1] - 1):
                    x0 = coords[k, 0] - ox
                    y0 = coords[k, 1] - oy
                    x1 = coords[k + 1, 0] - ox
                    y1 = coords[k + 1, 1] - oy
                    cr = x0 * y1 - x1 * y0
                    a += cr
                    sx += (x0 + x1) * cr
                    sy += (y0 + y1) * cr
                sign = 1.0 if a >= 0.0 else -1.0
                if r != polygon_offsets[p]:
                    sign = -sign  # holes subtract
                a_tot += sign * a
                mx += sign * sx
                my += sign * sy
        area[g] = 0.5 * a_tot
        if a_tot != 0.0:
            cen[g, 0] = ox + mx / (3.0 * a_tot)
            cen[g, 1] = oy + my / (3.0 * a_tot)
    return area, cen


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
