"""Insertion order for the sweep's fallback: exact convex hull, then a biased randomised order.

The circle sweep of :mod:`.delaunay` is quadratic on a few classes of input: points along
parallel lines (rows of a scanned grid, the images of a periodic diagram of sites on one
line) reach the sweep one line after another, and every point of the later line takes over
the fan of edges its predecessor held to the earlier line (``n`` flips per point). Randomised
incremental insertion makes an expected linear number of flips on any input; inserting in
rounds of doubling size, each round along a Hilbert curve (BRIO, Amenta, Choi and Rote
2003), keeps the point location walks short. The hull vertices are triangulated first, so
every later point lies inside or on the triangulation.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT
from .predicates import orient2d

#: Rounds smaller than this are not split further (one Hilbert-sorted run).
BRIO_MIN_ROUND = 64
#: Fixed seed: the fallback's triangulation, like the sweep's, depends only on the input.
BRIO_SEED = 20240615
#: Hilbert curve levels (a 2^16 x 2^16 grid over the bounding box).
HILBERT_LEVELS = 16


@njit(**NJIT)
def convex_hull(xs, ys, by_x):
    """Vertices of the convex hull, counter-clockwise, exact (Andrew's monotone chain).

    ``by_x`` lists the points sorted by x then y. Points on a hull edge between its two
    end vertices are not vertices. Needs at least three points, not all collinear.
    """
    n = by_x.shape[0]
    out = np.zeros(2 * n + 1, dtype=np.int64)
    h = 0
    low = 2  # the lower chain pops down to two points, the upper one down to the lower chain
    for k in range(2 * n - 1):  # left to right (lower chain), then back (upper chain)
        if k == n:
            low = h + 1
        p = by_x[k] if k < n else by_x[2 * n - 2 - k]
        while h >= low:
            a = out[h - 2]
            b = out[h - 1]
            if orient2d(xs[a], ys[a], xs[b], ys[b], xs[p], ys[p]) > 0.0:
                break
            h -= 1
        out[h] = p
        h += 1
    return out[: h - 1].copy()  # the last equals the first


def _hilbert_keys(xs: np.ndarray, ys: np.ndarray) -> np.ndarray:
    """Index along a Hilbert curve over the points' bounding box (vectorised xy2d)."""
    side = 1 << HILBERT_LEVELS
    x0, x1 = xs.min(), xs.max()
    y0, y1 = ys.min(), ys.max()
    sx = (side - 1) / (x1 - x0) if x1 > x0 else 0.0
    sy = (side - 1) / (y1 - y0) if y1 > y0 else 0.0
    x = np.clip(((xs - x0) * sx).astype(np.int64), 0, side - 1)
    y = np.clip(((ys - y0) * sy).astype(np.int64), 0, side - 1)
    d = np.zeros(xs.shape[0], dtype=np.int64)
    s = side >> 1
    while s > 0:
        rx = (x & s) > 0
        ry = (y & s) > 0
        d += s * s * ((3 * rx) ^ ry)
        flip = ~ry
        swap_x = np.where(flip & rx, side - 1 - x, x)
        swap_y = np.where(flip & rx, side - 1 - y, y)
        x, y = np.where(flip, swap_y, swap_x), np.where(flip, swap_x, swap_y)
        s >>= 1
    return d


def brio_order(xs: np.ndarray, ys: np.ndarray, idx: np.ndarray) -> np.ndarray:
    """``idx`` in biased randomised insertion order.

    Rounds of doubling size, each sorted along a Hilbert curve.
    """
    m = idx.shape[0]
    if m == 0:
        return idx
    rng = np.random.default_rng(BRIO_SEED)
    perm = idx[rng.permutation(m)]
    keys = _hilbert_keys(xs[perm], ys[perm])
    bounds = [m]
    while bounds[-1] > BRIO_MIN_ROUND:
        bounds.append(bounds[-1] // 2)
    bounds.append(0)
    bounds.reverse()
    parts = []
    for lo, hi in zip(bounds[:-1], bounds[1:], strict=True):
        if hi > lo:
            parts.append(perm[lo:hi][np.argsort(keys[lo:hi], kind="stable")])
    return np.concatenate(parts)
