"""Wrapped periodic edges ending on the box's sides at their cells' own vertices.

A wrapped cell that crosses a side of the box is the copy's cell cut to the box by GEOS
(:func:`.periodic._box_pieces`); its edges are the copies' edges cut to the box by
Liang-Barsky (:func:`.periodic._clip_segments`). The two compute the crossing with a side
in different arithmetic, and can differ by an ulp or two (checker35 F2: 15 random sites in
the unit box, an edge ended at ``0.07498485648544659`` on ``y = 0``, its cells' pieces at
``...656``: 2 ulps off one cell's boundary). :func:`snap_ends` moves each end that the clip
put on a side onto the nearest vertex on that side of the pieces of the edge's two copies,
where one is within rounding.
"""

from __future__ import annotations

import numpy as np
import shapely


def snap_ends(seg, pairs, clipped, pieces, box, tol):
    """``seg`` with the clipped ends moved onto their copies' pieces' vertices on the sides.

    Parameters
    ----------
    seg : (m, 2, 2) float64
        The edges cut to the box (changed in place and returned).
    pairs : (m, 2) int
        Each edge's two copies.
    clipped : (m, 2) bool
        Which ends the cut moved (those lie on a side, to rounding).
    pieces : (inside, cross, cut)
        :func:`.periodic._box_pieces`: the copies crossing the box and their cells cut to it.
    box : (xmin, ymin, xmax, ymax)
    tol : float
        How far an end may be from the vertex it is moved to (rounding of the box).

    Returns
    -------
    (m, 2, 2) float64
    """
    _, cross, cut = pieces
    if not clipped.any() or not len(cross):
        return seg
    w, k = shapely.get_coordinates(cut, return_index=True)
    copy = np.asarray(cross)[k]
    x0, y0, x1, y1 = box
    sides = ((0, x0), (0, x1), (1, y0), (1, y1))
    # the pieces' vertices on each side, keyed by (copy, side)
    keys, pts = [], []
    for s, (axis, at) in enumerate(sides):
        on = w[:, axis] == at
        keys.append(copy[on] * 4 + s)
        pts.append(w[on])
    keys = np.concatenate(keys)
    pts = np.concatenate(pts)
    if not len(keys):
        return seg
    order = np.argsort(keys, kind="stable")
    keys, pts = keys[order], pts[order]
    row, end = np.nonzero(clipped)
    p = seg[row, end]
    # the side each clipped end lies on: the nearest
    dist = np.column_stack([np.abs(p[:, axis] - at) for axis, at in sides])
    side = np.argmin(dist, axis=1)
    best = np.full(len(row), np.inf)
    to = p.copy()
    for c in (0, 1):
        key = pairs[row, c].astype(np.int64) * 4 + side
        lo = np.searchsorted(keys, key, side="left")
        hi = np.searchsorted(keys, key, side="right")
        for j in range(int((hi - lo).max(initial=0))):  # a piece has few there
            at = lo + j
            ok = at < hi
            q = pts[np.minimum(at, len(pts) - 1)]
            gap = np.abs(q - p).max(axis=1)
            take = ok & (gap < best) & (gap <= tol)
            best = np.where(take, gap, best)
            to[take] = q[take]
    seg[row, end] = to
    return seg
