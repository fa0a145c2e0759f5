"""T-junctions of periodic cells, for :func:`.describe.describe`'s count on a torus.

On a torus every ring side of an edge has a partner: the ring on the other side passes the
same two vertices the other way. Rounding cells tens of ulps wide can put a Voronoi vertex
exactly on the edge of a cell whose ring does not have it (20,000 sites in a 3 x 2 box at
4e12: two vertices an ulp apart, one rounded onto the straight edge of the fourth cell
around them). The cells still tile the torus, but that edge is one ring side against two:
the count of edges as half the ring sides came out short (Euler 1). :func:`split` puts such
a vertex into the ring whose side it lies on, exactly, so both sides count alike.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np


def split(coords, ring, idx, nxt, ids, lo, size):
    """The rings with the vertices that lie exactly inside another ring's side put in it.

    Parameters
    ----------
    coords : (m, 2) float64
        Closed rings' points; ``ring`` their offsets.
    idx, nxt : (k,) int64
        The open ring vertices (indices into ``coords``) and, for each, the position in
        ``idx`` of the next one along its ring.
    ids : (k,) int64
        Vertex ids modulo the box (copies of one vertex share an id).
    lo, size : (2,) float64
        The box.

    Returns
    -------
    (coords, ring) or None
        None where every side (between two points) has a partner, or no vertex lies on a
        side without one. Only sides without a partner are searched (few), in rationals.
    """
    a = ids
    b = ids[nxt]
    step = coords[idx[nxt]] - coords[idx] + 0.0  # -0.0 made 0.0
    live = (step != 0).any(axis=1)
    if not live.any():
        return None
    # a side and its partner: the same two vertices the other way, the step's signs
    # opposite (a side can join a vertex to its own image; two sides the same two vertices
    # apart by different steps, on a torus of few cells, are told apart by the signs)
    m = int(ids.max()) + 1
    sign = np.sign(step).astype(np.int64) + 1
    fwd = (a * m + b) * 9 + sign[:, 0] * 3 + sign[:, 1]
    back = (b * m + a) * 9 + (2 - sign[:, 0]) * 3 + (2 - sign[:, 1])
    keys, count = np.unique(fwd[live], return_counts=True)

    def times(k):
        at = np.minimum(np.searchsorted(keys, k), len(keys) - 1)
        return np.where(keys[at] == k, count[at], 0)

    odd = np.flatnonzero(live & (times(fwd) != times(back)))
    if not len(odd):
        return None
    cand = np.unique(np.concatenate((a[odd], b[odd])))
    first = np.full(int(ids.max()) + 1, -1, dtype=np.int64)
    seen, at_first = np.unique(ids, return_index=True)
    first[seen] = at_first
    w = [Fraction(float(s)) for s in size]
    inserts = {}
    for j in odd:
        p = [Fraction(float(t)) for t in coords[idx[j]]]
        q = [Fraction(float(t)) for t in coords[idx[nxt[j]]]]
        mid = [(p[k] + q[k]) / 2 for k in (0, 1)]
        for v in cand:
            if v == a[j] or v == b[j]:
                continue  # (a vertex whose own image lies on the side: not a junction)
            r = [Fraction(float(t)) for t in coords[idx[first[v]]]]
            # the copy of v nearest the side's middle
            r = [r[k] + w[k] * math.floor((mid[k] - r[k]) / w[k] + Fraction(1, 2)) for k in (0, 1)]
            dpq = (q[0] - p[0], q[1] - p[1])
            dpr = (r[0] - p[0], r[1] - p[1])
            if dpq[0] * dpr[1] != dpq[1] * dpr[0]:
                continue
            along = dpq[0] * dpr[0] + dpq[1] * dpr[1]
            if not 0 < along < dpq[0] ** 2 + dpq[1] ** 2:
                continue
            xy = (float(r[0]), float(r[1]))
            if Fraction(xy[0]) != r[0] or Fraction(xy[1]) != r[1]:
                continue  # the copy there is no float: not a point of these cells
            inserts.setdefault(int(idx[j]), []).append((along, xy))
    if not inserts:
        return None
    at = np.array(sorted(inserts), dtype=np.int64)
    pts = [np.array([xy for _, xy in sorted(inserts[i])]) for i in at]
    extra = np.array([len(t) for t in pts], dtype=np.int64)
    # each inserted run goes after its side's start point
    new = np.insert(coords, np.repeat(at + 1, extra), np.concatenate(pts), axis=0)
    added = np.searchsorted(at, ring, side="left")  # inserts before each ring's start
    shift = np.concatenate(([0], np.cumsum(extra)))
    return new, ring + shift[added]
