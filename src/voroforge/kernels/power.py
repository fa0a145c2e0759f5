"""Power (Laguerre) cells by half-plane clipping of a box.

Cell ``i`` is ``{x : |x - p_i|^2 - w_i <= |x - p_j|^2 - w_j}`` for every neighbour ``j``. With
``u = x - p_i`` and ``d = p_j - p_i`` the constraint reads ``2 d.u <= |d|^2 + w_i - w_j``, so
every test is made relative to the cell's own site and large coordinates keep their precision.

Output contract (the same closed-ring layout the Voronoi assembly consumes):

``coords (K, 2) float64``
    Closed counter-clockwise rings (last vertex repeats the first), in site order.
``lengths (n + 1,) int64``
    Cell ``i`` is ``coords[lengths[i]:lengths[i + 1]]``; empty when the cell misses the box.
``owner (K,) int64``
    ``owner[k] = j`` when the edge from vertex ``k`` to ``k + 1`` lies on the power bisector of
    sites ``i`` and ``j``, -1 on the box, -2 on the closing vertex.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..config import NJIT, NJIT_PARALLEL
from .cells import _dedupe_ring


@njit(**NJIT)
def _crossing(ax, ay, sa, bx, by, sb):
    """Where the segment ``a -> b`` meets the clip line (signed values ``sa``, ``sb``).

    Interpolated from the endpoint nearer the line: ``a + 1.0 * (b - a)`` need not round to
    ``b``, and a crossing at a box corner then landed just past it (a self-intersecting
    spike in the ring).
    """
    if abs(sa) <= abs(sb):
        t = sa / (sa - sb)
        return ax + t * (bx - ax), ay + t * (by - ay)
    t = sb / (sb - sa)
    return bx + t * (ax - bx), by + t * (ay - by)


@njit(**NJIT)
def _clip(px, py, po, m, qx, qy, qo, dx, dy, c, ox, oy, j):
    """Keep the part of polygon ``p`` (``m`` vertices) where ``2 d.(x - o) <= c``; into ``q``."""
    out = 0
    if m == 0:
        return 0
    s_prev = 2.0 * (dx * (px[m - 1] - ox) + dy * (py[m - 1] - oy)) - c
    for k in range(m):
        if out + 2 > qx.shape[0]:
            break  # never reached for convex input; guards the buffers against noise
        # edge (k - 1) -> k, owner po[k - 1]
        kp = k - 1 if k > 0 else m - 1
        s = 2.0 * (dx * (px[k] - ox) + dy * (py[k] - oy)) - c
        if s_prev <= 0.0:
            if s > 0.0:
                # leaving: the crossing starts an edge on the clip line
                qx[out], qy[out] = _crossing(px[kp], py[kp], s_prev, px[k], py[k], s)
                qo[out] = j
                out += 1
        else:
            if s <= 0.0:
                # entering: the crossing continues the original edge
                qx[out], qy[out] = _crossing(px[kp], py[kp], s_prev, px[k], py[k], s)
                qo[out] = po[kp]
                out += 1
        if s <= 0.0:
            qx[out] = px[k]
            qy[out] = py[k]
            qo[out] = po[k]
            out += 1
        s_prev = s
    return out


@njit(**NJIT)
def _cell(i, xs, ys, ws, indptr, indices, box, px, py, po, qx, qy, qo):
    """Power cell of site ``i`` clipped to ``box``; returns its vertex count (in ``p``)."""
    px[0] = box[0]
    py[0] = box[1]
    px[1] = box[2]
    py[1] = box[1]
    px[2] = box[2]
    py[2] = box[3]
    px[3] = box[0]
    py[3] = box[3]
    for k in range(4):
        po[k] = -1
    m = 4
    ox = xs[i]
    oy = ys[i]
    for e in range(indptr[i], indptr[i + 1]):
        j = indices[e]
        dx = xs[j] - ox
        dy = ys[j] - oy
        # the weight difference first: |d|^2 + w_i would round |d|^2 away when the weights
        # are large, and sites i and j would then see two different bisectors (a gap)
        c = dx * dx + dy * dy + (ws[i] - ws[j])
        m = _clip(px, py, po, m, qx, qy, qo, dx, dy, c, ox, oy, j)
        for k in range(m):
            px[k] = qx[k]
            py[k] = qy[k]
            po[k] = qo[k]
        if m == 0:
            break
    r = _dedupe_ring(px, py, po, m)  # repeated vertices: a clip line through a vertex
    if r == 0:
        return 0
    area2 = 0.0
    for k in range(r):
        kn = k + 1 if k + 1 < r else 0
        area2 += (px[k] - ox) * (py[kn] - oy) - (px[kn] - ox) * (py[k] - oy)
    if not area2 > 0.0:
        return 0
    return r


@njit(**NJIT_PARALLEL)
def power_cells(xs, ys, ws, indptr, indices, box, active):
    """Closed rings of the power cells of all sites (see the module docstring).

    Parameters
    ----------
    xs, ys, ws : (n,) float64
        Sites and weights.
    indptr, indices : CSR int64
        Candidate neighbours of each site (a superset of its power neighbours).
    box : (4,) float64
        ``(xmin, ymin, xmax, ymax)``.
    active : (n,) bool
        Sites whose cell is computed; the others get an empty cell.
    """
    n = xs.shape[0]
    cap = np.zeros(n + 1, dtype=np.int64)
    for i in range(n):
        cap[i + 1] = cap[i] + 2 * (indptr[i + 1] - indptr[i]) + 9
    slab_x = np.zeros(cap[n])
    slab_y = np.zeros(cap[n])
    slab_o = np.zeros(cap[n], dtype=np.int64)
    counts = np.zeros(n + 1, dtype=np.int64)
    for i in prange(n):
        if not active[i]:
            continue
        size = cap[i + 1] - cap[i]
        px = np.zeros(size)
        py = np.zeros(size)
        po = np.zeros(size, dtype=np.int64)
        qx = np.zeros(size)
        qy = np.zeros(size)
        qo = np.zeros(size, dtype=np.int64)
        m = _cell(i, xs, ys, ws, indptr, indices, box, px, py, po, qx, qy, qo)
        if m > 0:
            b = cap[i]
            for k in range(m):
                slab_x[b + k] = px[k]
                slab_y[b + k] = py[k]
                slab_o[b + k] = po[k]
            slab_x[b + m] = px[0]
            slab_y[b + m] = py[0]
            slab_o[b + m] = -2
            counts[i + 1] = m + 1
    for i in range(n):
        counts[i + 1] += counts[i]
    coords = np.zeros((counts[n], 2))
    owner = np.zeros(counts[n], dtype=np.int64)
    for i in prange(n):
        b = cap[i]
        o = counts[i]
        for k in range(counts[i + 1] - o):
            coords[o + k, 0] = slab_x[b + k]
            coords[o + k, 1] = slab_y[b + k]
            owner[o + k] = slab_o[b + k]
    return coords, counts, owner
