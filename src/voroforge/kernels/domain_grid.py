"""A coarse grid that tells which convex cells can touch a polygon domain's boundary.

Grid squares crossed by any boundary segment (with a one-square margin) are marked. A cell
whose bounding box covers only unmarked squares contains no boundary point, so it lies wholly
inside or wholly outside the domain, which one square's centre decides. Only the remaining
cells need a polygon intersection.

The squares are indexed as the buckets of :mod:`.grid` (:func:`.grid.bucket_of`), but the
grid holds segments, not points: a segment marks every square it may cross (with a margin),
so there is no counting sort and no ring search here.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from ..config import NJIT, NJIT_PARALLEL
from .grid import bucket_of


@njit(**NJIT)
def mark_segments(segs, x0, y0, h, gx, gy):
    """Boolean (gy, gx) grid of squares that a segment ``(x1, y1, x2, y2)`` may touch."""
    marked = np.zeros((gy, gx), dtype=np.bool_)
    for s in range(segs.shape[0]):
        ax = (segs[s, 0] - x0) / h
        ay = (segs[s, 1] - y0) / h
        bx = (segs[s, 2] - x0) / h
        by = (segs[s, 3] - y0) / h
        if ax > bx:
            ax, bx = bx, ax
            ay, by = by, ay
        c0 = max(int(math.floor(ax)) - 1, 0)
        c1 = min(int(math.floor(bx)) + 1, gx - 1)
        for c in range(c0, c1 + 1):
            # the segment's y-range over column c widened by one square on each side
            lo = max(float(c - 1), ax)
            hi = min(float(c + 2), bx)
            if lo > hi:
                continue
            if bx > ax:
                ya = ay + (by - ay) * ((lo - ax) / (bx - ax))
                yb = ay + (by - ay) * ((hi - ax) / (bx - ax))
            else:
                ya = ay
                yb = by
            r0 = max(int(math.floor(min(ya, yb))) - 1, 0)
            r1 = min(int(math.floor(max(ya, yb))) + 1, gy - 1)
            for r in range(r0, r1 + 1):
                marked[r, c] = True
    return marked


@njit(**NJIT_PARALLEL)
def classify(coords, offsets, marked, inside, x0, y0, h):
    """Per ring: 1 wholly inside, 0 wholly outside (or empty), 2 may cross the boundary."""
    n = offsets.shape[0] - 1
    gy, gx = marked.shape
    status = np.zeros(n, dtype=np.int8)
    for i in prange(n):
        a = offsets[i]
        b = offsets[i + 1]
        if a == b:
            continue
        xmn = np.inf
        xmx = -np.inf
        ymn = np.inf
        ymx = -np.inf
        for k in range(a, b):
            xmn = min(xmn, coords[k, 0])
            xmx = max(xmx, coords[k, 0])
            ymn = min(ymn, coords[k, 1])
            ymx = max(ymx, coords[k, 1])
        c0 = bucket_of(xmn, x0, h, gx)
        c1 = bucket_of(xmx, x0, h, gx)
        r0 = bucket_of(ymn, y0, h, gy)
        r1 = bucket_of(ymx, y0, h, gy)
        hit = False
        for r in range(r0, r1 + 1):
            for c in range(c0, c1 + 1):
                if marked[r, c]:
                    hit = True
                    break
            if hit:
                break
        if hit:
            status[i] = 2
        else:
            status[i] = 1 if inside[r0, c0] else 0
    return status


@njit(**NJIT)
def _row_range(ya, yb, y0, h, gy):
    lo = min(ya, yb)
    hi = max(ya, yb)
    r0 = max(int(math.floor((lo - y0) / h)) - 1, 0)
    r1 = min(int(math.ceil((hi - y0) / h)) + 1, gy - 1)
    return r0, r1


@njit(**NJIT_PARALLEL)
def scanline_inside(segs, cx, cy, y0, h):
    """Even-odd inside test of every grid centre ``(cx[c], cy[r])`` against closed rings.

    ``segs`` (k, 4) are all ring segments ``(xa, ya, xb, yb)``. A segment crosses row ``r``
    when exactly one end lies above ``cy[r]`` (half-open, so a vertex on the row counts once);
    each row's crossings are sorted and the centres between odd and even ones are inside.
    O(crossings + squares), rows in parallel. Only squares away from the boundary rely on
    the answer, so rounding in the crossings cannot matter.
    """
    gy = cy.shape[0]
    gx = cx.shape[0]
    counts = np.zeros(gy + 1, dtype=np.int64)
    for s in range(segs.shape[0]):
        ya = segs[s, 1]
        yb = segs[s, 3]
        r0, r1 = _row_range(ya, yb, y0, h, gy)
        for r in range(r0, r1 + 1):
            if (ya > cy[r]) != (yb > cy[r]):
                counts[r + 1] += 1
    for r in range(gy):
        counts[r + 1] += counts[r]
    xs = np.zeros(counts[gy])
    fill = counts[:-1].copy()
    for s in range(segs.shape[0]):
        xa = segs[s, 0]
        ya = segs[s, 1]
        xb = segs[s, 2]
        yb = segs[s, 3]
        r0, r1 = _row_range(ya, yb, y0, h, gy)
        for r in range(r0, r1 + 1):
            y = cy[r]
            if (ya > y) != (yb > y):
                xs[fill[r]] = xa + (y - ya) * (xb - xa) / (yb - ya)
                fill[r] += 1
    inside = np.zeros((gy, gx), dtype=np.bool_)
    for r in prange(gy):
        row = np.sort(xs[counts[r] : counts[r + 1]])
        k = 0
        m = row.shape[0]
        for c in range(gx):
            while k < m and row[k] < cx[c]:
                k += 1
            inside[r, c] = k % 2 == 1
    return inside
