"""Shared edges handed to an empty cell, given to the cell across them.

A builder names the cell across each ring edge from the bisector it cut. Where two bisectors
are one line (a power diagram whose lighter site lies exactly on its heavier neighbours'
radical line: a 4 x 4 lattice with weights 1 and 0 in a checkerboard), the site between them
has an empty cell (a segment or a point) and may be named across the edge of its two
neighbours: the pair ``(0, 1)`` with cell 1 empty where cells 0 and 2 share the edge
(checker35 F1). Such a pair is wrong whatever the builder, so it is mended here, once, on the
diagram's rings: the edge goes to the cell whose ring holds it reversed (bit for bit), or
else holds a segment on its line overlapping it (exact ``orient2d``).
"""

from __future__ import annotations

import numpy as np

from ..kernels.predicates import orient2d


def reown(edges, buffers, n: int):
    """``(coords, pairs)`` of ``edges`` with no pair naming a cell that has no ring.

    ``buffers``: the diagram's GeoArrow ``(coords, ring, poly, geom)``. Returns ``edges``
    itself when every pair names two cells with rings (the usual case: one pass over ``n``).
    """
    seg, pairs = edges
    coords, ring, poly, geom = buffers
    has = np.zeros(n, bool)
    if len(ring) > 1:
        # a cell has a ring when one of its polygons' exterior rings has 4+ points
        ext = poly[:-1]
        full = (ring[ext + 1] - ring[ext]) >= 4
        cell_of_poly = np.searchsorted(geom, np.arange(len(poly) - 1), side="right") - 1
        has[cell_of_poly[full]] = True
    bad = np.flatnonzero(~(has[pairs[:, 0]] & has[pairs[:, 1]]))
    if not len(bad):
        return edges
    # every directed ring edge: its start, end and cell
    starts = np.ones(len(coords), bool)
    starts[ring[1:] - 1] = False  # a ring's closing point starts no edge
    starts[len(coords) - 1 :] = False
    k = np.flatnonzero(starts)
    ring_of = np.searchsorted(ring, k, side="right") - 1
    poly_of = np.searchsorted(poly, ring_of, side="right") - 1
    cell_of = np.searchsorted(geom, poly_of, side="right") - 1
    a_all, b_all = coords[k], coords[k + 1]
    seg = np.array(seg, copy=True)
    pairs = np.array(pairs, copy=True)
    keep = np.ones(len(pairs), bool)
    for e in bad.tolist():
        i, j = (int(c) for c in pairs[e])
        c = i if has[i] else j if has[j] else -1
        if c < 0:
            keep[e] = False  # two empty cells share nothing
            continue
        d = _across(seg[e], c, a_all, b_all, cell_of, has)
        if d < 0:
            continue  # no ring holds it: left as built
        pairs[e] = (min(c, d), max(c, d))
    seg, pairs = seg[keep], pairs[keep]
    # a pair mended onto an edge the other cell's ring had given too: once
    a, b = seg[:, 0], seg[:, 1]
    swap = (b[:, 0] < a[:, 0]) | ((b[:, 0] == a[:, 0]) & (b[:, 1] < a[:, 1]))
    lo = np.where(swap[:, None], b, a)
    hi = np.where(swap[:, None], a, b)
    key = np.column_stack([pairs, lo, hi])
    _, first = np.unique(key, axis=0, return_index=True)
    first.sort()
    return seg[first], pairs[first]


def _across(s, c: int, a_all, b_all, cell_of, has) -> int:
    """The cell other than ``c`` whose ring holds the segment ``s`` (2, 2), or -1."""
    p, q = s
    other = (cell_of != c) & has[cell_of]
    exact = other & (a_all == q).all(axis=1) & (b_all == p).all(axis=1)
    if exact.any():
        return int(cell_of[np.flatnonzero(exact)[0]])
    # else a ring edge on the segment's line that overlaps it by more than a point
    d = q - p
    t0 = (a_all - p) @ d
    t1 = (b_all - p) @ d
    L = float(d @ d)
    near = other & (np.maximum(t0, t1) > 0) & (np.minimum(t0, t1) < L)
    for r in np.flatnonzero(near).tolist():
        a, b = a_all[r], b_all[r]
        if orient2d(p[0], p[1], q[0], q[1], a[0], a[1]) == 0 and (
            orient2d(p[0], p[1], q[0], q[1], b[0], b[1]) == 0
        ):
            return int(cell_of[r])
    return -1
