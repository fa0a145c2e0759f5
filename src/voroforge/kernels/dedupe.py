"""Exact duplicate detection with an open-addressing hash table on the coordinate bits."""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT


@njit(**NJIT)
def duplicate_of(xs, ys):
    """For each point, -1 if its coordinates are new, else the index of their first occurrence.

    ``-0.0`` and ``0.0`` count as equal. Expected O(n).
    """
    n = xs.shape[0]
    out = np.full(n, -1, dtype=np.int64)
    size = 1
    while size < 2 * n:
        size *= 2
    mask = size - 1
    table = np.full(size, -1, dtype=np.int64)
    bx = np.zeros(1, dtype=np.float64)
    for i in range(n):
        x = xs[i] + 0.0
        y = ys[i] + 0.0
        bx[0] = x
        hx = bx.view(np.uint64)[0]
        bx[0] = y
        hy = bx.view(np.uint64)[0]
        # both words through murmur3's 64-bit finaliser: every input bit reaches the low bits
        # the slot takes (a grid's coordinates differ in a few mantissa bits only, and a
        # weaker mix piled them into long probe runs: 15x slower on a 316 x 316 grid)
        h = (hx * np.uint64(0x9E3779B97F4A7C15)) ^ hy
        h ^= h >> np.uint64(33)
        h *= np.uint64(0xFF51AFD7ED558CCD)
        h ^= h >> np.uint64(33)
        h *= np.uint64(0xC4CEB9FE1A85EC53)
        h ^= h >> np.uint64(33)
        slot = np.int64(h & np.uint64(mask))
        while True:
            j = table[slot]
            if j == -1:
                table[slot] = i
                break
            if xs[j] == x and ys[j] == y:
                out[i] = j
                break
            slot = (slot + 1) & mask
    return out
