"""The bucket grid of :mod:`kernels.grid` with a third axis: shells instead of rings.

``grid = (x0, y0, z0, hx, hy, hz, nx, ny, nz)`` as a float64 array (counts stored as
floats); bucket ``(ix, iy, iz)`` is number ``(iz * ny + iy) * nx + ix``. Sites are sorted
into buckets by ``engine.build3d.bucket_sort3d`` (numpy, stable: increasing index within a
bucket). Shell ``r`` around a bucket is the set of buckets at Chebyshev distance ``r``; the
stop test is :func:`shell_gap`, a lower bound on the distance from a point inside the block
of shells ``0..r`` to any site outside it (six slabs instead of four strips).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT
from .grid import bucket_of


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
