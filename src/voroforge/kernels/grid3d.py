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
