"""The bucket grid of :mod:`kernels.grid` with a third axis: shells instead of rings.

``grid = (x0, y0, z0, hx, hy, hz, nx, ny, nz)`` as a float64 array (counts stored as
floats); bucket ``(ix, iy, iz)`` is number ``(iz * ny + iy) * nx + ix``. Sites are sorted
into buckets by ``engine.build3d.bucket_sort3d`` (numpy, stable: increasing index within a
bucket). Shell ``r`` around a bucket is the set of buckets at Chebyshev distance ``r``; the
stop test is :func:`shell_gap`, a lower bound on the distance from a point inside the block
of shells ``0..r`` to any site outside it (six slabs instead of four strips). The 3D
cell search's stop tests (:func:`far`, :func:`reach_box`, :func:`box_misses`, the k-d walk
:func:`next_leaf`) live here too (kernels.cellcut3d runs the search).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT, VORONOI3D_STOP_RTOL
from .grid import bucket_of, heap_pop, heap_push

#: the cell search's stop tests run inside its loop (numba's inliner; as kernels.cellcut3d)
_INLINE = {**NJIT, "inline": "always"}
_NO_NRT = {**NJIT, "_nrt": False}


@njit(**NJIT)
def bucket3d(x, y, z, g):
    """The bucket coordinates ``(ix, iy, iz)`` of a point (clamped into the grid)."""
    ix = bucket_of(x, g[0], g[3], int(g[6]))
    iy = bucket_of(y, g[1], g[4], int(g[7]))
    iz = bucket_of(z, g[2], g[5], int(g[8]))
    return ix, iy, iz


@njit(**NJIT)
def shell_gap(x, y, z, ci, cj, ck, r, g):
    """Lower bound on the distance from ``(x, y, z)`` to any bucket outside shells ``0..r``.

    ``inf`` once the block covers the whole grid.
    """
    gap = np.inf
    c = (ci, cj, ck)
    p = (x, y, z)
    for a in range(3):
        n = int(g[6 + a])
        if c[a] - r > 0:
            gap = min(gap, p[a] - (g[a] + (c[a] - r) * g[3 + a]))
        if c[a] + r < n - 1:
            gap = min(gap, (g[a] + (c[a] + r + 1) * g[3 + a]) - p[a])
    return max(gap, 0.0)


@njit(**NJIT)
def shell_buckets(ci, cj, ck, r, g, out):
    """Bucket numbers of shell ``r`` around ``(ci, cj, ck)`` into ``out``; returns the count."""
    nx = int(g[6])
    ny = int(g[7])
    nz = int(g[8])
    m = 0
    for kz in range(max(ck - r, 0), min(ck + r, nz - 1) + 1):
        for ky in range(max(cj - r, 0), min(cj + r, ny - 1) + 1):
            full = abs(kz - ck) == r or abs(ky - cj) == r
            row = (kz * ny + ky) * nx
            if full:
                for kx in range(max(ci - r, 0), min(ci + r, nx - 1) + 1):
                    out[m] = row + kx
                    m += 1
            else:
                if ci - r >= 0:
                    out[m] = row + ci - r
                    m += 1
                if r > 0 and ci + r <= nx - 1:
                    out[m] = row + ci + r
                    m += 1
    return m


@njit(**NJIT)
def shell_buckets_in(ci, cj, ck, r, ib, tb, bound, nx, ny, out):
    """:func:`shell_buckets` within an index box, only buckets whose lower bound passes.

    The box is ``ib = (ix0, iy0, iz0, ix1, iy1, iz1)`` (inclusive, inside the grid); bucket
    ``(ix, iy, iz)`` is kept when its separable lower bound ``tb[0, ix] + tb[1, iy] +
    tb[2, iz]`` is at most ``bound``.

    Returns the count, or -1 when shell ``r`` misses the box (so does every later one: the
    box holds ``(ci, cj, ck)``).
    """
    if (
        ci - r < ib[0]
        and ci + r > ib[3]
        and cj - r < ib[1]
        and cj + r > ib[4]
        and ck - r < ib[2]
        and ck + r > ib[5]
    ):
        return -1
    m = 0
    for kz in range(max(ck - r, ib[2]), min(ck + r, ib[5]) + 1):
        tz = tb[2, kz]
        if tz > bound:
            continue
        for ky in range(max(cj - r, ib[1]), min(cj + r, ib[4]) + 1):
            tyz = tz + tb[1, ky]
            if tyz > bound:
                continue
            row = (kz * ny + ky) * nx
            if abs(kz - ck) == r or abs(ky - cj) == r:
                for kx in range(max(ci - r, ib[0]), min(ci + r, ib[3]) + 1):
                    if tyz + tb[0, kx] <= bound:
                        out[m] = row + kx
                        m += 1
            else:
                if ci - r >= ib[0] and tyz + tb[0, ci - r] <= bound:
                    out[m] = row + ci - r
                    m += 1
                if r > 0 and ci + r <= ib[3] and tyz + tb[0, ci + r] <= bound:
                    out[m] = row + ci + r
                    m += 1
    return m


# -- k-d buckets: the grid's adaptive form for clustered sites (kernels.grid's, in 3D) ------
#
# Twenty tight clusters in a unit box put thousands of sites in one bucket of the uniform
# grid, and every cell there scans them all (680 us a cell at 40k sites, sd 0.02). The k-d
# buckets split the sites at the median of the longest side of their tight box until at
# most ``leaf`` remain; the cell search (kernels.cellcut3d) walks them depth first, nearer
# child first, skipping a node whose box is beyond the stop test.


@njit(**NJIT)
def _select3(S, perm, a, lo, hi, kth):
    """Reorder rows ``lo:hi`` of ``S`` (and ``perm``) so ``S[kth, a]`` is its ``kth`` smallest.

    Hoare's quickselect on axis ``a``, rows moving whole; the pivot is the median of three
    keys a third of the range apart from a start a hash of the range picks (as
    :func:`.grid._select`: the ends and the middle are quadratic on sorted runs).
    """
    while hi - lo > 1:
        span = hi - lo
        h = (lo * 2654435761 + span * 40503) % span
        x = S[lo + h, a]
        y = S[lo + (h + span // 3) % span, a]
        z = S[lo + (h + 2 * (span // 3)) % span, a]
        pivot = max(min(x, y), min(max(x, y), z))
        i = lo
        j = hi - 1
        while i <= j:
            while S[i, a] < pivot:
                i += 1
            while S[j, a] > pivot:
                j -= 1
            if i <= j:
                for c in range(3):
                    S[i, c], S[j, c] = S[j, c], S[i, c]
                perm[i], perm[j] = perm[j], perm[i]
                i += 1
                j -= 1
        if kth <= j:
            hi = j + 1
        elif kth >= i:
            lo = i
        else:
            return


@njit(**NJIT)
def _box3(S, lo, hi, nodes, v):
    for c in range(3):
        nodes[v, c] = np.inf
        nodes[v, 3 + c] = -np.inf
    for t in range(lo, hi):
        for c in range(3):
            nodes[v, c] = min(nodes[v, c], S[t, c])
            nodes[v, 3 + c] = max(nodes[v, 3 + c], S[t, c])


@njit(**NJIT)
def kd_buckets3d(P, leaf):
    """Sites ``P (n, 3)`` split into k-d buckets of at most ``leaf`` sites (``leaf >= 2``).

    Returns ``nodes (m, 8)``, ``start (nb + 1,)``, ``SP (n, 3)`` and ``sidx (n,)``: node
    ``v``'s tight box is ``nodes[v, :6]`` (lows, highs), its children ``left`` and ``left +
    1`` with ``left = nodes[v, 6]`` (-1 for a bucket), a bucket's number ``nodes[v, 7]``;
    bucket ``b`` holds the sorted sites ``SP[start[b]:start[b + 1]]`` (their numbers
    ``sidx``), buckets numbered in the order of their sites. Node 0 is the root.
    """
    n = P.shape[0]
    half = (leaf + 1) // 2
    cap = 2 * (n // half + 1) + 1
    nodes = np.zeros((cap, 8))
    lo = np.zeros(cap, np.int64)
    hi = np.zeros(cap, np.int64)
    perm = np.arange(n)
    S = P.copy()
    hi[0] = n
    nodes[0, 6] = -1.0
    _box3(S, np.int64(0), n, nodes, np.int64(0))  # not literals: one compile of _box3
    stack = np.zeros(128, np.int64)
    top = 1
    count = 1
    while top > 0:
        top -= 1
        v = stack[top]
        a = lo[v]
        b = hi[v]
        if b - a <= leaf:
            continue
        ax = np.int64(0)  # not a literal: one compile of _select3
        for c in range(1, 3):
            if nodes[v, 3 + c] - nodes[v, c] > nodes[v, 3 + ax] - nodes[v, ax]:
                ax = c
        mid = (a + b) // 2
        _select3(S, perm, ax, a, b, mid)
        c = count
        count += 2
        nodes[v, 6] = c
        lo[c] = a
        hi[c] = mid
        lo[c + 1] = mid
        hi[c + 1] = b
        for u in (c, c + 1):
            nodes[u, 6] = -1.0
            _box3(S, lo[u], hi[u], nodes, u)
        stack[top] = c
        stack[top + 1] = c + 1
        top += 2
    # buckets numbered in the order of their sites: depth first, left child first
    start = np.zeros(n + 1, np.int64)
    nb = 0
    stack[0] = 0
    top = 1
    while top > 0:
        top -= 1
        v = stack[top]
        left = int(nodes[v, 6])
        if left < 0:
            nodes[v, 7] = nb
            start[nb] = lo[v]
            nb += 1
        else:
            stack[top] = left + 1
            stack[top + 1] = left
            top += 2
    start[nb] = n
    return nodes[:count], start[: nb + 1], S, perm


@njit(**_INLINE)
def ordered_bucket(order, o, ci, cj, ck, px, py, pz, g, wi, wmax, rmax2):
    """The bucket of ordered entry ``o`` around ``(ci, cj, ck)``, or -1 (outside, or too far)."""
    ox = int(order[o, 0])
    oy = int(order[o, 1])
    oz = int(order[o, 2])
    bx = ci + ox
    by = cj + oy
    bz = ck + oz
    nx = int(g[6])
    ny = int(g[7])
    if bx < 0 or by < 0 or bz < 0 or bx >= nx or by >= ny or bz >= int(g[8]):
        return -1
    if order[o, 3] > 0.0:
        gx = axis_gap(px, g[0], g[3], bx, ox)
        gy = axis_gap(py, g[1], g[4], by, oy)
        gz = axis_gap(pz, g[2], g[5], bz, oz)
        if far(gx * gx + gy * gy + gz * gz, wi, wmax, rmax2):
            return -1
    return (bz * ny + by) * nx + bx


@njit(**_INLINE)
def far(g2, wi, wmax, rmax2):
    """No site at squared distance >= ``g2`` can cut or touch a cell of squared radius ``rmax2``."""
    lhs = g2 + wi - wmax
    return lhs > 0.0 and lhs * lhs > 4.0 * g2 * rmax2 * (1.0 + VORONOI3D_STOP_RTOL)


@njit(**_INLINE)
def axis_gap(p, origin, size, b, off):
    """Distance along one axis from coordinate ``p`` to bucket ``b`` (``off`` buckets away)."""
    if off > 0:
        return max(0.0, origin + b * size - p)
    if off < 0:
        return max(0.0, p - (origin + (b + 1) * size))
    return 0.0


@njit(**_INLINE)
def box_misses(px, py, pz, box, V, nv, wi, wmax, rmax2, eps):
    """No site in ``box = (x0, y0, z0, x1, y1, z1)`` can cut or touch the cell ``V[:nv]``.

    A plane cuts or touches a convex cell only if some vertex ``x`` is at least as near
    (in power) to the other site as to the cell's: the box misses when every vertex is
    farther from it, less the heaviest weight, than from the site, with slack
    (``VORONOI3D_STOP_RTOL`` of the cell's size; the box widened by ``eps``, the rounding
    of coordinates relative to the site). Long cells (a cluster's outer sites) meet few
    boxes this way, where the sphere of :func:`far` holds the whole cluster. ``V`` is
    relative to the site, ``box`` absolute.
    """
    lx = box[0] - px - eps
    ly = box[1] - py - eps
    lz = box[2] - pz - eps
    hx = box[3] - px + eps
    hy = box[4] - py + eps
    hz = box[5] - pz + eps
    slack = VORONOI3D_STOP_RTOL * (rmax2 + abs(wi) + abs(wmax)) + wmax - wi
    for k in range(nv):
        x = V[k, 0]
        y = V[k, 1]
        z = V[k, 2]
        gx = max(lx - x, 0.0, x - hx)
        gy = max(ly - y, 0.0, y - hy)
        gz = max(lz - z, 0.0, z - hz)
        if gx * gx + gy * gy + gz * gz <= x * x + y * y + z * z + slack:
            return False
    return True


@njit(**_NO_NRT)
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


@njit(**_INLINE)
def box_dist2(px, py, pz, tree, v):
    """Squared distance from the site to k-d node ``v``'s tight box (0 inside)."""
    dx = max(tree[v, 0] - px, 0.0, px - tree[v, 3])
    dy = max(tree[v, 1] - py, 0.0, py - tree[v, 4])
    dz = max(tree[v, 2] - pz, 0.0, pz - tree[v, 5])
    return dx * dx + dy * dy + dz * dz


@njit(**_NO_NRT)
def next_leaf(px, py, pz, tree, hk, hv, size, wi, wmax, rmax2, V, nv, eps):
    """Pop k-d nodes off the heap ``hk[:size], hv[:size]`` to the next bucket that may cut.

    Nearest box first (keys: squared distances from the site to the boxes); the walk ends
    at the first node beyond the stop test (:func:`far`: every later one is farther), a
    node whose box every vertex is nearer than (:func:`box_misses`) is dropped. Returns
    ``(bucket or -1, size)``. Kept out of line: :func:`.cellcut3d.one_cell`'s grid search compiles
    around a call, not around the walk (inlined, the walk cost uniform cells 4-7%).
    """
    while size > 0:
        key, v, size = heap_pop(hk, hv, size)
        if far(key, wi, wmax, rmax2):
            return -1, 0
        if box_misses(px, py, pz, tree[v], V, nv, wi, wmax, rmax2, eps):
            continue
        left = int(tree[v, 6])
        if left < 0:
            return int(tree[v, 7]), size
        for c in range(left, left + 2):
            d2 = box_dist2(px, py, pz, tree, c)
            if not far(d2, wi, wmax, rmax2):
                size = heap_push(hk, hv, size, d2, c)
    return -1, size
