"""How far a 3D power cell's search must go: the stop test, global and local (issue 12).

:func:`far` is the search's stop test (:mod:`kernels.cellcut3d`): no site farther than
``sqrt(g2)`` weighing at most ``wmax`` can cut a cell of radius ``sqrt(rmax2)``. With the
global heaviest weight one heavy site widened every cell's search to its power radius
(checker13 F4: quadratic). :func:`weight_reach` appends to the search grid ``g`` a max
pyramid of the weights per bucket (level 0 the buckets, each level up 2x2x2 of the one
below), and :func:`local_stop` then also stops where every pyramid node is either too far
to cut the cell with its own heaviest weight, or beyond ``g2`` and made so by it: a proven
bound like :func:`far`'s, local to the cell.

A few heavy sites among light ones (one site of weight 1 among 80,000 of weight 0: the
cells of its light neighbours are empty, and each searched up to it past O(n) nearer
sites) are taken out of the pyramid instead (:func:`heavy_sites`): the search then bounds
the light sites alone (their heaviest weight ``wl``, the pyramid of theirs) and the cell
is cut by every heavy site that can reach it when that search stops
(:func:`.cellcut3d.one_cell`); the cell only shrinks, so the stop stays proven. (The
shells' reach by the cell's bounding box, :func:`reach_box`, is here too.)

``g`` with a pyramid: ``g[9] = 0`` (no budget), ``g[10]`` the top level ``T``, ``g[11 + L]``
where level ``L``'s maxima start (``-inf``: an empty node), level ``L`` holding
``ceil(n_k / 2^L)`` nodes along axis ``k`` (x fastest); then at ``b = 12 + T``: ``g[b]``
the number ``h`` of heavy sites, ``g[b + 1]`` the light sites' heaviest weight ``wl`` and
``g[b + 2:b + 2 + h]`` the heavy sites' positions in the search's bucket order.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import (
    NJIT,
    REACH3D_BOX_RTOL,
    REACH3D_HEAVY_GAP,
    REACH3D_HEAVY_MOST,
    REACH3D_ROUND_TRIES,
    VORONOI3D_STOP_RTOL,
)
from .grid import bucket_of
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


def heavy_sites(W: np.ndarray, g: np.ndarray) -> np.ndarray:
    """The heavy sites of weights ``W`` on grid ``g``, sorted (none when there are too many).

    Heavy: above the lightest weight by more than ``REACH3D_HEAVY_GAP`` squared bucket sides
    (the grid's largest), at most ``REACH3D_HEAVY_MOST`` of them.
    """
    side = float(np.max(g[3:6]))
    heavy = np.flatnonzero(W > float(W.min()) + REACH3D_HEAVY_GAP * side * side)
    if len(heavy) > REACH3D_HEAVY_MOST:
        return heavy[:0]
    return heavy


def weight_reach(P: np.ndarray, W: np.ndarray, g: np.ndarray, sidx=None) -> np.ndarray:
    """The grid ``g`` with the weights' max pyramid appended (unequal weights), else ``g``.

    With ``sidx`` (the search's bucket order of the sites) the heavy sites
    (:func:`heavy_sites`) are left out of the pyramid and listed after it, by position in
    that order; without it none are.
    """
    if len(W) == 0 or not float(W.max()) > float(W.min()) or g.shape[0] > 9:
        return g
    heavy = heavy_sites(W, g) if sidx is not None else np.zeros(0, np.int64)
    WL = np.asarray(W, np.float64)
    if len(heavy):
        WL = WL.copy()
        WL[heavy] = -np.inf
        rank = np.zeros(len(W), np.int64)
        rank[sidx] = np.arange(len(W))
        heavy = np.sort(rank[heavy])
    n = [int(g[6]), int(g[7]), int(g[8])]
    top = np.full(n[0] * n[1] * n[2], -np.inf)
    _bucket_max(np.ascontiguousarray(P, np.float64), WL, g, top)
    levels = [top.reshape(n[2], n[1], n[0])]
    while max(levels[-1].shape) > 1:
        a = levels[-1]
        pad = [(0, s % 2) for s in a.shape]
        a = np.pad(a, pad, constant_values=-np.inf)
        z, y, x = (s // 2 for s in a.shape)
        levels.append(a.reshape(z, 2, y, 2, x, 2).max(axis=(1, 3, 5)))
    hb = [float(len(heavy)), float(WL.max())] + heavy.astype(np.float64).tolist()
    head = 11 + len(levels) + len(hb)
    offs = np.cumsum([head] + [lv.size for lv in levels])[:-1]
    parts = [g[:9], [0.0, len(levels) - 1.0], offs.astype(np.float64), hb]
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


@njit(**NJIT_INLINE)
def heavy_header(g, wi, wmax):
    """``(hb, hn, wmax)``: where ``g``'s heavy sites are listed, how many, the weight to bound.

    The heavy sites are at ``g[hb + 2:hb + 2 + hn]`` (:func:`weight_reach`); with some, the
    search of a cell of weight ``wi`` bounds the light sites: ``max(wl, wi)``.
    """
    if g.shape[0] <= 10:
        return 0, 0, wmax
    hb = 12 + int(g[10])
    hn = int(g[hb])
    return hb, hn, (max(g[hb + 1], wi) if hn > 0 else wmax)


@njit(**NJIT_INLINE)
def gather_heavy(g, hb, hn, i, px, py, pz, wi, SP, SW, sidx, cand, cd2, rmax2):
    """The ``hn`` heavy sites listed in ``g`` from ``hb + 2`` that can reach the cell, as a batch.

    The test is :func:`.cellcut3d._gather`'s (the site itself and its duplicates skipped).
    Returns how many were kept (at most ``REACH3D_HEAVY_MOST``, within the batch's room).
    """
    reach = rmax2 * (1.0 + 2.0 * VORONOI3D_STOP_RTOL)
    m = 0
    for q in range(hn):
        t = int(g[hb + 2 + q])
        dx = SP[t, 0] - px
        dy = SP[t, 1] - py
        dz = SP[t, 2] - pz
        d2 = dx * dx + dy * dy + dz * dz
        h = 0.5 * (d2 + (wi - SW[t]))
        if sidx[t] == i or d2 == 0.0 or (h > 0.0 and h * h > reach * d2):
            continue
        cand[m] = t
        cd2[m] = d2
        m += 1
    return m


@njit(**NJIT_NO_NRT)
def reach_box(px, py, pz, V, nv, wi, wmax, rmax2, g, ib, tb):
    """Where a site that can still cut the cell ``V[:nv]`` may lie, bucket by bucket.

    Site ``q`` (``d = q - p``) cuts or touches the cell only if some vertex ``x`` has
    ``|d|^2 - 2 x . d <= w_q - w_i``; over the cell's bounding box ``[lo, hi]`` (relative to
    the site) that least value is separable, a sum over the axes of ``T(d_k) = min over e
    in (lo_k, hi_k) of (d_k - e)^2 - e^2``. So a bucket can hold such a site only if the sum
    of its slabs' least ``T`` (``tb[k, index]``) is at most the returned bound (``wmax - wi``
    with slack), and only buckets in the index box ``ib`` can (each axis on its own, the
    others at their least, ``-max(lo^2, hi^2)``). Each row of ``tb`` is shifted to least 0
    (the bound with it), so that a partial sum over the axes is a lower bound too. For long
    cells (sites near the default container's padded walls) the box is far smaller than the
    stop sphere of :func:`far` (twice the cell's radius), and ``tb`` drops most of it.
    """
    allow = wmax - wi + VORONOI3D_STOP_RTOL * (rmax2 + abs(wi) + abs(wmax))
    bound = allow
    lo0 = np.inf
    lo1 = np.inf
    lo2 = np.inf
    hi0 = -np.inf
    hi1 = -np.inf
    hi2 = -np.inf
    for v in range(nv):
        lo0 = min(lo0, V[v, 0])
        hi0 = max(hi0, V[v, 0])
        lo1 = min(lo1, V[v, 1])
        hi1 = max(hi1, V[v, 1])
        lo2 = min(lo2, V[v, 2])
        hi2 = max(hi2, V[v, 2])
    lo = (lo0, lo1, lo2)
    hi = (hi0, hi1, hi2)
    p = (px, py, pz)
    most = 0.0
    for k in range(3):
        most += max(lo[k] * lo[k], hi[k] * hi[k])
    for k in range(3):
        n = int(g[6 + k])
        o = g[k]
        h = g[3 + k]
        # the slabs' rounding relative to the site
        eps = 1e-15 * (abs(o) + n * h + abs(p[k])) + VORONOI3D_STOP_RTOL * h
        a = lo[k]
        b = hi[k]
        bk = allow + most - max(a * a, b * b)  # this axis alone
        ra = np.sqrt(bk + a * a)
        rb = np.sqrt(bk + b * b)
        d0 = min(a - ra, b - rb) - eps
        d1 = max(a + ra, b + rb) + eps
        i0 = bucket_of(p[k] + d0, o, h, n)
        i1 = bucket_of(p[k] + d1, o, h, n)
        ib[k] = i0
        ib[3 + k] = i1
        least = np.inf
        for i in range(i0, i1 + 1):
            s0 = o + i * h - p[k] - eps if i > 0 else -np.inf
            s1 = o + (i + 1) * h - p[k] + eps if i < n - 1 else np.inf
            ca = min(max(a, s0), s1) - a
            cb = min(max(b, s0), s1) - b
            t = min(ca * ca - a * a, cb * cb - b * b)
            tb[k, i] = t
            least = min(least, t)
        for i in range(i0, i1 + 1):  # each row's least 0: a partial sum is a lower bound
            tb[k, i] -= least
        bound -= least
    return bound


@njit(**NJIT_INLINE)
def _slab(p, o, h, n, a):
    """``(least, most)`` squared distance along one axis from ``p`` to bucket ``a``'s slab."""
    lo = o + a * h - p if a > 0 else -np.inf  # edge buckets hold the clamped sites
    hi = o + (a + 1) * h - p if a < n - 1 else np.inf
    gap = max(lo, -hi, 0.0)
    return gap * gap, max(lo * lo, hi * hi)


@njit(**NJIT_INLINE)
def shell_hit(b, px, py, pz, g, rs2, box):
    """Whether bucket ``b`` is in :func:`shell_range`'s index ``box`` and meets its sphere.

    The sphere is ``|x - p|^2 = rs2``; both tests are those of the first cut and of the
    search that skips its buckets, so each bucket is taken by exactly one of them.
    """
    nx = int(g[6])
    ny = int(g[7])
    a0 = b % nx
    a1 = (b // nx) % ny
    a2 = b // (nx * ny)
    if a0 < box[0] or a0 > box[3] or a1 < box[1] or a1 > box[4] or a2 < box[2] or a2 > box[5]:
        return False
    l0, h0 = _slab(px, g[0], g[3], nx, a0)
    l1, h1 = _slab(py, g[1], g[4], ny, a1)
    l2, h2 = _slab(pz, g[2], g[5], int(g[8]), a2)
    return l0 + l1 + l2 <= rs2 <= h0 + h1 + h2


@njit(**NJIT_INLINE)
def shell_range(px, py, pz, g, rs2):
    """The index box ``(x0, y0, z0, x1, y1, z1)`` of the buckets within ``sqrt(rs2)`` of ``p``.

    A cell heavier than every light site by ``c`` (:func:`heavy_header`) is cut by no light
    plane nearer than ``rs = sqrt(c)`` to its site (a plane at ``(d^2 + c) / 2d`` from the
    site), and by the nearest ones at sites that far: :func:`.cellcut3d.one_cell` cuts it
    by the sites of the buckets meeting that sphere first (:func:`shell_hit`), so that its
    search, which visits every light site, keeps few (one site of weight 1 among n of
    weight 0: the heavy cell's scan kept most of the n sites, each tested against its
    thousands of vertices, while its far corners were still uncut). The box is one bucket
    wider than ``bucket_of`` finds (rounding), clamped to the grid.
    """
    rs = np.sqrt(rs2)
    n0 = int(g[6])
    n1 = int(g[7])
    n2 = int(g[8])
    x0 = max(bucket_of(px - rs, g[0], g[3], n0) - 1, 0)
    y0 = max(bucket_of(py - rs, g[1], g[4], n1) - 1, 0)
    z0 = max(bucket_of(pz - rs, g[2], g[5], n2) - 1, 0)
    x1 = min(bucket_of(px + rs, g[0], g[3], n0) + 1, n0 - 1)
    y1 = min(bucket_of(py + rs, g[1], g[4], n1) + 1, n1 - 1)
    z1 = min(bucket_of(pz + rs, g[2], g[5], n2) + 1, n2 - 1)
    return x0, y0, z0, x1, y1, z1


#: :func:`box_near` tests the vertices in blocks of this many, with no branch inside a block
#: (the compiler runs a block's tests side by side; a box missed reads every vertex)
BOX_BLOCK = 8


@njit(**NJIT_INLINE)
def _near(x, y, z, lx, ly, lz, hx, hy, hz, slack):
    """Whether the vertex ``(x, y, z)`` is at most as far from the box as from the site."""
    gx = lx - x
    t = x - hx
    gx = t if t > gx else gx
    gx = 0.0 if gx < 0.0 else gx
    gy = ly - y
    t = y - hy
    gy = t if t > gy else gy
    gy = 0.0 if gy < 0.0 else gy
    gz = lz - z
    t = z - hz
    gz = t if t > gz else gz
    gz = 0.0 if gz < 0.0 else gz
    return gx * gx + gy * gy + gz * gz <= x * x + y * y + z * z + slack


@njit(**NJIT_INLINE)
def box_near(px, py, pz, box, V, nv, wi, wmax, rmax2, eps, first):
    """A vertex of the cell ``V[:nv]`` that a site in ``box`` (lows, highs) may reach, or -1.

    -1: no site in the box can cut or touch the cell (the box misses it). A plane cuts or
    touches a convex cell only if some vertex ``x`` is at least as near (in power) to the
    other site as to the cell's: the box misses when every vertex is farther from it, less
    the heaviest weight, than from the site, with slack (``VORONOI3D_STOP_RTOL`` of the
    cell's size; the box widened by ``eps``, the rounding of coordinates relative to the
    site). Long cells (a cluster's outer sites) meet few boxes this way, where the sphere of
    :func:`far` holds the whole cluster. ``V`` is relative to the site, ``box`` absolute.

    The vertices are read from ``first`` on, then from 0 (any start gives the same answer:
    whether one is near; a box's near vertices are near its enclosing boxes too, so the
    caller starts a k-d child at its parent's). A many-faced cell's near vertices are few
    and bunched in its numbering (three lines of 500 sites: 150 of ~1,000, found after
    ~360 from 0, ~29 from the parent's).
    """
    lx = box[0] - px - eps
    ly = box[1] - py - eps
    lz = box[2] - pz - eps
    hx = box[3] - px + eps
    hy = box[4] - py + eps
    hz = box[5] - pz + eps
    slack = VORONOI3D_STOP_RTOL * (rmax2 + abs(wi) + abs(wmax)) + wmax - wi
    if not 0 <= first < nv:
        first = 0
    k0 = first
    end = nv
    for _ in range(2):
        while k0 < end:
            k1 = min(k0 + BOX_BLOCK, end)
            hit = False
            for k in range(k0, k1):
                hit |= _near(V[k, 0], V[k, 1], V[k, 2], lx, ly, lz, hx, hy, hz, slack)
            if hit:
                for k in range(k0, k1):
                    if _near(V[k, 0], V[k, 1], V[k, 2], lx, ly, lz, hx, hy, hz, slack):
                        return k
            k0 = k1
        k0 = 0
        end = first
    return -1


@njit(**NJIT_INLINE)
def box_dist2(px, py, pz, tree, v):
    """Squared distance from the site to k-d node ``v``'s tight box (0 inside)."""
    dx = max(tree[v, 0] - px, 0.0, px - tree[v, 3])
    dy = max(tree[v, 1] - py, 0.0, py - tree[v, 4])
    dz = max(tree[v, 2] - pz, 0.0, pz - tree[v, 5])
    return dx * dx + dy * dy + dz * dz


@njit(**NJIT_INLINE)
def axis_gap(p, origin, size, b, off):
    """Distance along one axis from coordinate ``p`` to bucket ``b`` (``off`` buckets away)."""
    if off > 0:
        return max(0.0, origin + b * size - p)
    if off < 0:
        return max(0.0, p - (origin + (b + 1) * size))
    return 0.0
