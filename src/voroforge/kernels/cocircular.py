"""One triangulation of exactly cocircular sites, whichever builder made it.

Four or more sites on one circle have several Delaunay triangulations, all valid, and the
sweep and the default pick different ones (issue 15: every one of the 29 float circles of
the neighbour scan on which the two algorithms' cells differed had triangulations that
differed only across exactly cocircular quads). The cells name a cocircular set's vertex
from its sites alone, but the merge, unfold and fold tests compare the triangles' own
centres, which depend on the diagonal: the two algorithms then formed different classes
(350 sites of radius 1e-6 at (2e3, -7e3): a class of 195 triangles against 180 and
singletons, 37 cells apart).

:func:`canonical_flips` flips each exactly cocircular quad (exact ``incircle`` == 0) to its
lower diagonal (``(min, max)`` of its ends by coordinates, lexicographically). Every flip
makes the sorted list of diagonals smaller, so it ends; where it ends, every triangle of a
set of triangles on one circle holds that set's lowest site (else the triangle beside it
across a diagonal without that site would flip): the fan from the lowest site, one
triangulation for every builder.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT
from .delaunay import link_halfedges
from .predicates import incircle


@njit(**NJIT)
def _lower(xs, ys, p, q):
    """Whether site ``p`` comes before site ``q`` by coordinates (``x``, then ``y``)."""
    return xs[p] < xs[q] or (xs[p] == xs[q] and ys[p] < ys[q])


@njit(**NJIT)
def _lower_pair(xs, ys, c, d, a, b):
    """Whether the diagonal ``{c, d}`` comes before ``{a, b}`` (their ends, lower first)."""
    c0, c1 = (c, d) if _lower(xs, ys, c, d) else (d, c)
    a0, a1 = (a, b) if _lower(xs, ys, a, b) else (b, a)
    if c0 != a0:
        return _lower(xs, ys, c0, a0)
    return _lower(xs, ys, c1, a1)


@njit(**NJIT)
def canonical_flips(xs, ys, tri, he, cand):
    """Flip every exactly cocircular quad to its lower diagonal, in place; flips made.

    ``tri``, ``he``: flat triangles (counter-clockwise) and halfedges (-1 on the hull),
    updated as a Delaunay flip does (delaunator's ``_legalize``: every triangle stays
    counter-clockwise). ``cand``: the halfedges to look at first (an exactly cocircular
    edge is one the fast incircle filter left undecided: ``centers.circumcenters`` flags);
    the edges of every flipped quad are looked at again.
    """
    stack = [np.int64(e) for e in cand]
    flips = 0
    while len(stack):
        a = stack.pop()
        b = np.int64(he[a])
        if b < 0:
            continue
        a0 = a - a % 3
        b0 = b - b % 3
        al = a0 + (a + 1) % 3
        ar = a0 + (a + 2) % 3
        bl = b0 + (b + 2) % 3
        br = b0 + (b + 1) % 3
        p0, pr, pl, p1 = tri[ar], tri[a], tri[al], tri[bl]
        if not _lower_pair(xs, ys, p0, p1, pr, pl):
            continue
        if incircle(xs[p0], ys[p0], xs[pr], ys[pr], xs[pl], ys[pl], xs[p1], ys[p1]) != 0.0:
            continue
        tri[a] = p1
        tri[b] = p0
        link_halfedges(he, a, he[bl])
        link_halfedges(he, b, he[ar])
        link_halfedges(he, ar, bl)
        flips += 1
        for e in (a, b, al, ar, bl, br):
            if he[e] >= 0:
                stack.append(e)
    return flips
