"""Tiles: a k-d split of the plane placed on a sample of the sites, balanced by count.

The tiles partition the whole plane (outer tiles reach to infinity), so every site has
exactly one owning tile, decided by its coordinates alone: copies of one site always share
a tile, and a rerun places every site where the first run did. A tile's *loaded region* is
its rectangle grown by a halo; the sites in it are what the tile computes with.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from ..config import NJIT

__all__ = ["Tiling", "kd_tiling"]


@njit(**NJIT)
def _descend(xy, axis, value, left, right):  # pragma: no cover
    """The leaf (tile) of each point: down the tree from the root, left when below."""
    out = np.zeros(len(xy), dtype=np.int64)
    for i in range(len(xy)):
        k = 0
        while k >= 0:
            k = left[k] if xy[i, axis[k]] < value[k] else right[k]
        out[i] = -1 - k
    return out


@dataclass(frozen=True)
class Tiling:
    """A k-d tree of axis-aligned splits and its leaves, the tiles.

    Attributes
    ----------
    axis, value : (m,) int64, float64
        Internal node ``k`` sends a point left when ``xy[axis[k]] < value[k]``.
    left, right : (m,) int64
        Children: ``>= 0`` an internal node, ``< 0`` the tile ``-1 - child``.
    rects : (t, 4) float64
        Each tile's ``xmin, ymin, xmax, ymax`` (infinite on the outside).
    """

    axis: np.ndarray
    value: np.ndarray
    left: np.ndarray
    right: np.ndarray
    rects: np.ndarray

    def __len__(self) -> int:
        return len(self.rects)

    def assign(self, xy: np.ndarray) -> np.ndarray:
        """The tile owning each point of ``xy`` ``(n, 2)``, as ``(n,) int64``."""
        xy = np.ascontiguousarray(xy, dtype=np.float64).reshape(-1, 2)
        if len(self.axis) == 0:
            return np.zeros(len(xy), dtype=np.int64)
        return _descend(xy, self.axis, self.value, self.left, self.right)

    def touching(self, rect) -> np.ndarray:
        """Tiles whose closed rectangle meets the closed rectangle ``rect``."""
        r = self.rects
        x0, y0, x1, y1 = rect
        hit = (r[:, 0] <= x1) & (r[:, 2] >= x0) & (r[:, 1] <= y1) & (r[:, 3] >= y0)
        return np.flatnonzero(hit)

    def to_json(self) -> dict:
        """The splits as plain lists (for a job manifest; ``inf`` written as None)."""

        def clean(a):
            return [None if not np.isfinite(v) else float(v) for v in np.ravel(a)]

        return {
            "axis": self.axis.tolist(),
            "value": [float(v) for v in self.value],
            "left": self.left.tolist(),
            "right": self.right.tolist(),
            "rects": clean(self.rects),
        }


def kd_tiling(sample: np.ndarray, tiles: int) -> Tiling:
    """Split the plane into ``tiles`` rectangles holding about equal shares of ``sample``.

    Each node splits its longer side (measured on its sample) at the quantile that gives its
    two children ``floor(k / 2)`` and ``ceil(k / 2)`` of its ``k`` tiles.

    Parameters
    ----------
    sample : (s, 2) float64
        Sites sampled from the input.
    tiles : int
        Number of tiles, at least 1.

    Returns
    -------
    Tiling
    """
    axis, value, left, right, rects = [], [], [], [], []

    def build(idx, k, rect):
        if k == 1 or len(idx) < 2:
            rects.append(rect)
            return -len(rects)
        pts = sample[idx]
        span = pts.max(axis=0) - pts.min(axis=0)
        ax = int(span[1] > span[0])
        k_lo = k // 2
        vals = np.sort(pts[:, ax])
        cut = vals[min(len(vals) - 1, max(1, round(len(vals) * k_lo / k)))]
        if not cut > vals[0]:  # a heavy repeated value: split above it instead
            above = vals[vals > vals[0]]
            if not len(above):
                rects.append(rect)
                return -len(rects)
            cut = above[0]
        me = len(axis)
        axis.append(ax)
        value.append(float(cut))
        left.append(0)
        right.append(0)
        lo_rect = list(rect)
        hi_rect = list(rect)
        lo_rect[2 + ax] = cut
        hi_rect[ax] = cut
        mask = pts[:, ax] < cut
        left[me] = build(idx[mask], k_lo, tuple(lo_rect))
        right[me] = build(idx[~mask], k - k_lo, tuple(hi_rect))
        return me

    inf = float("inf")
    build(np.arange(len(sample)), max(int(tiles), 1), (-inf, -inf, inf, inf))
    return Tiling(
        np.array(axis, dtype=np.int64),
        np.array(value, dtype=np.float64),
        np.array(left, dtype=np.int64),
        np.array(right, dtype=np.int64),
        np.array(rects, dtype=np.float64).reshape(-1, 4),
    )
