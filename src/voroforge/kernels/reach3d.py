"""How far a 3D power cell's search must go: the stop test, global and local (issue 12).

:func:`far` is the search's stop test (:mod:`kernels.cellcut3d`): no site farther than
``sqrt(g2)`` weighing at most ``wmax`` can cut a cell of radius ``sqrt(rmax2)``. With the
global heaviest weight one heavy site widened every cell's search to its power radius
(checker13 F4: quadratic). :func:`weight_reach` appends to the search grid ``g`` a max
pyramid of the weights per bucket (level 0 the buckets, each level up 2x2x2 of the one
below), and :func:`local_stop` then also stops where every pyramid node is either too far
to cut the cell with its own heaviest weight, or beyond ``g2`` and made so by it: a proven
bound like :func:`far`'s, local to the cell.

``g`` with a pyramid: ``g[9] = 0`` (no budget), ``g[10]`` the top level ``T``, ``g[11 + L]``
where level ``L``'s maxima start (``-inf``: an empty node), level ``L`` holding
``ceil(n_k / 2^L)`` nodes along axis ``k`` (x fastest).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT, REACH3D_BOX_RTOL, REACH3D_ROUND_TRIES, VORONOI3D_STOP_RTOL
from .grid3d import bucket3d

NJIT_INLINE = {**NJIT, "inline": "always"}
NJIT_NO_NRT = {**NJIT, "_nrt": False}


@njit(**NJIT_INLINE)
def far(g2, wi, wmax, rmax2):
    """No site at squared distance >= ``g2`` can cut or touch a cell of squared radius ``rmax2``.

    (Needs ``wmax >= wi``: then the test holds from one root of ``g2`` on, for all larger.)
    """
    lhs = g2 + wi - wmax
    return lhs > 0.0 and lhs * lhs > 4.0 * g2 * rmax2 * (1.0 + VORONOI3D_STOP_RTOL)


def weight_reach(P: np.ndarray, W: np.ndarray, g: np.ndarray) -> np.ndarray:
    """The grid ``g`` with the weights' max pyramid appended (unequal weights), else ``g``."""
    if len(W) == 0 or not float(W.max()) > float(W.min()) or g.shape[0] > 9:
        return g
    n = [int(g[6]), int(g[7]), int(g[8])]
    top = np.full(n[0] * n[1] * n[2], -np.inf)
    _bucket_max(np.ascontiguousarray(P, np.float64), np.asarray(W, np.float64), g, top)
    levels = [top.reshape(n[2], n[1], n[0])]
    while max(levels[-1].shape) > 1:
        a = levels[-1]
        pad = [(0, s % 2) for s in a.shape]
        a = np.pad(a, pad, constant_values=-np.inf)
        z, y, x = (s // 2 for s in a.shape)
        levels.append(a.reshape(z, 2, y, 2, x, 2).max(axis=(1, 3, 5)))
    head = 11 + len(levels)
    offs = np.cumsum([head] + [lv.size for lv in levels])[:-1]
    parts = [g[:9], [0.0, len(levels) - 1.0], offs.astype(np.float64)]
    return np.concatenate(parts + [lv.ravel() for lv in levels])


@njit(**NJIT)
def _bucket_max(P, W, g, out):
    """``out[bucket] = max(out[bucket], W[i])`` over the sites ``P`` (buckets of grid ``g``)."""
    nx = int(g[6])
    ny = int(g[7])
    for i in range(P.shape[0]):
        ix, iy, iz = bucket3d(P[i, 0], P[i, 1], P[i, 2], g)
        b = (iz * ny + iy) * nx + ix
        out[b] = max(out[b], W[i])


@njit(**NJIT_INLINE)
def _node_gap(p, o, h, n, a, L, eps):
    """Distance along one axis from ``p`` to level-``L`` node ``a``'s slab (widened)."""
    i0 = a << L
    i1 = min((a + 1) << L, n)
    lo = o + i0 * h - eps if i0 > 0 else -np.inf  # edge buckets hold the clamped sites
    hi = o + i1 * h + eps if i1 < n else np.inf
    return max(lo - p, 0.0, p - hi)


@njit(**NJIT_INLINE)
def _node_reach(d2, wi, wn, rmax2):
    """Least ``g2`` from which a node at squared distance ``d2``, heaviest ``wn``, cannot cut.

    0 when it cannot cut at all; else the closed-form root of :func:`far`, rounded up until
    the float test passes (``inf`` if it never does).
    """
    w = max(wn, wi)  # lighter sites are taken as heavy as the cell's (far needs wmax >= wi)
    if far(d2, wi, w, rmax2):
        return 0.0
    c = w - wi
    k = rmax2 * (1.0 + VORONOI3D_STOP_RTOL)
    t = (c + 2.0 * k + 2.0 * np.sqrt(k * k + c * k)) * (1.0 + 1e-12)
    step = 1e-12 * (abs(wi) + abs(w) + rmax2) + 1e-300
    for _ in range(REACH3D_ROUND_TRIES):
        if far(t, wi, w, rmax2):
            return t
        t = t * (1.0 + 1e-9) + step
        step *= 2.0
    return np.inf


@njit(**NJIT_NO_NRT)
def local_reach(px, py, pz, wi, rmax2, g):
    """Least ``g2`` from which no site beyond ``sqrt(g2)`` can cut the cell (pyramid ``g``).

    Each pyramid node needs ``g2`` at least its :func:`_node_reach`; a node needing no more
    than the best found so far is not opened (its sites weigh no more and lie no nearer),
    nodes are walked depth first without a stack (a child's place in its parent is the low
    bit of its indices).
    """
    top = int(g[10])
    n = (int(g[6]), int(g[7]), int(g[8]))
    eps = (
        REACH3D_BOX_RTOL * (abs(g[0]) + n[0] * g[3] + abs(px)) + VORONOI3D_STOP_RTOL * g[3],
        REACH3D_BOX_RTOL * (abs(g[1]) + n[1] * g[4] + abs(py)) + VORONOI3D_STOP_RTOL * g[4],
        REACH3D_BOX_RTOL * (abs(g[2]) + n[2] * g[5] + abs(pz)) + VORONOI3D_STOP_RTOL * g[5],
    )
    best = 0.0
    L = top
    a = 0
    b = 0
    c = 0
    while True:
        lx = ((n[0] - 1) >> L) + 1
        ly = ((n[1] - 1) >> L) + 1
        if a < lx and b < ly and c < ((n[2] - 1) >> L) + 1:
            wn = g[int(g[11 + L]) + (c * ly + b) * lx + a]
            if wn > -np.inf:
                gx = _node_gap(px, g[0], g[3], n[0], a, L, eps[0])
                gy = _node_gap(py, g[1], g[4], n[1], b, L, eps[1])
                gz = _node_gap(pz, g[2], g[5], n[2], c, L, eps[2])
                t = _node_reach(gx * gx + gy * gy + gz * gz, wi, wn, rmax2)
                if t > best:
                    if L == 0 or t == np.inf:
                        best = t
                    else:
                        L -= 1
                        a *= 2
                        b *= 2
                        c *= 2
                        continue
        while True:  # the next node: a sibling, or up
            if L == top:
                return best
            s = (a & 1) | ((b & 1) << 1) | ((c & 1) << 2)
            if s < 7:
                s += 1
                a = (a & ~1) | (s & 1)
                b = (b & ~1) | ((s >> 1) & 1)
                c = (c & ~1) | ((s >> 2) & 1)
                break
            L += 1
            a >>= 1
            b >>= 1
            c >>= 1


@njit(**NJIT_INLINE)
def local_stop(g2, wi, wmax, rmax2, px, py, pz, g, gs2, gr2):
    """Whether the search may stop at ``g2``: :func:`far`, or the local bound of ``g``'s pyramid.

    ``gs2`` is the local bound found at squared radius ``gr2`` (-1: none yet); it is found
    again when the cell has shrunk since, and only when the equal-weights test passes (the
    cell's own bucket needs that much). Returns ``(stop, gs2, gr2)``.
    """
    if far(g2, wi, wmax, rmax2):
        return True, gs2, gr2
    if g.shape[0] <= 10 or not far(g2, wi, wi, rmax2):
        return False, gs2, gr2
    if g2 < gs2 and rmax2 != gr2:
        gs2 = local_reach(px, py, pz, wi, rmax2, g)
        gr2 = rmax2
    return g2 >= gs2, gs2, gr2
