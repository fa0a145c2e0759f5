"""Whether neighbouring rings share every edge, end points bit for bit (one pass, parallel).

A ring's edge on the bisector with site ``j`` must be in ``j``'s ring too, running the other
way between the same two points. The Delaunay dual names every vertex once, so its rings
always agree; rings settled cell by cell (the half-plane cells, which the planar build keeps
where the dual lost a site a few ulps from others) decide alone which edges an ulp or two
long exist, and can disagree there (issue 15). :func:`rings_disagree` finds the rings that
do; :mod:`voroforge.engine.agree` makes them agree.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..config import NJIT, NJIT_PARALLEL


@njit(**NJIT)
def _matched(coords, lengths, owner, inv, me, v, j):
    """Whether cell ``j``'s ring has edge ``v`` of cell ``me``'s ring, reversed.

    That is an edge owned by ``me`` running from where edge ``v`` (owned by ``j``) ends to
    where it starts, in the same bits.
    """
    s = inv[j]
    if s < 0:
        return False
    px = coords[v, 0]
    py = coords[v, 1]
    qx = coords[v + 1, 0]
    qy = coords[v + 1, 1]
    for u in range(lengths[s], lengths[s + 1] - 1):
        if owner[u] != me:
            continue
        if (
            coords[u, 0] == qx
            and coords[u, 1] == qy
            and coords[u + 1, 0] == px
            and coords[u + 1, 1] == py
        ):
            return True
    return False


@njit(**NJIT)
def _has_short(coords, a, b, short, sx, sy):
    """Whether the closed ring ``coords[a:b]`` of site ``(sx, sy)`` is a few dozen ulps wide.

    An edge, or a vertex's distance from the site, shorter than ``short`` times the L1
    magnitude of the vertex.
    """
    for v in range(a, b - 1):
        x = coords[v, 0]
        y = coords[v, 1]
        lim = short * (abs(x) + abs(y))
        if abs(coords[v + 1, 0] - x) + abs(coords[v + 1, 1] - y) <= lim:
            return True
        if abs(x - sx) + abs(y - sy) <= lim:
            return True
    return False


@njit(**NJIT_PARALLEL)
def rings_disagree(coords, lengths, owner, inv, ring_id, short, sites):
    """Per ring: True where it is a few ulps wide and has an edge its neighbour lacks.

    A few ulps wide: an edge, or a vertex's distance from the ring's site (``sites`` by
    cell id), shorter than ``short`` of the vertex's magnitude (:func:`_has_short`); an
    edge the neighbour lacks: a bisector edge that is not in the neighbour's ring,
    reversed, in the same bits.

    Rings are closed (``coords[lengths[r]:lengths[r + 1]]``, the last vertex repeating the
    first); ``owner[k]`` is the cell across the edge from vertex ``k`` (negative: the box,
    or the closing vertex); ``inv[c]`` is the ring of cell ``c`` (-1: none) and
    ``ring_id[r]`` the cell of ring ``r``, the id owners use. Only such rings can disagree
    (cells that decided alone which edges an ulp long exist are at sites ulps apart); the
    others cost one pass over their vertices (no neighbour is read).
    """
    n = lengths.shape[0] - 1
    bad = np.zeros(n, dtype=np.bool_)
    for r in prange(n):
        me = ring_id[r]
        if not _has_short(coords, lengths[r], lengths[r + 1], short, sites[me, 0], sites[me, 1]):
            continue
        for v in range(lengths[r], lengths[r + 1] - 1):
            j = owner[v]
            if j < 0:
                continue
            if not _matched(coords, lengths, owner, inv, me, v, j):
                bad[r] = True
                break
    return bad


@njit(**NJIT)
def rings_disagree_at(coords, lengths, owner, inv, ring_id, which):
    """:func:`rings_disagree` of the rings ``which`` (indices), each checked whole."""
    bad = np.zeros(which.shape[0], dtype=np.bool_)
    for k in range(which.shape[0]):
        r = which[k]
        me = ring_id[r]
        for v in range(lengths[r], lengths[r + 1] - 1):
            j = owner[v]
            if j >= 0 and not _matched(coords, lengths, owner, inv, me, v, j):
                bad[k] = True
                break
    return bad
