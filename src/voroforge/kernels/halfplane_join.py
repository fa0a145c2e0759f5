"""Whether a site near a vertex's circle joins the vertex, and the name of the four.

Helpers of :func:`.halfplane_settle.settle_ring`. Floats cannot order the vertices of sites
an ulp or two apart: a site within rounding of a vertex's circle is taken as on it when its
centres with the circle's sites are one point by the merge rule (:func:`joins`, decided
for the four sites once, whichever cell asks), unless floats hold the exact topology there
(:func:`floats_hold`: the edge the join would drop or keep out runs the exact way round in
floats, so every cell keeps it, as the cells that do not ask about it do). A joined four is
named by one of its exact vertices (:func:`name4`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT
from .predicates import cross_diff, incircle, orient2d
from .vertex import (
    near_pair,
    same_vertex,
    voronoi_vertex,
    voronoi_vertex_error,
    voronoi_vertex_lazy,
)


@njit(**NJIT)
def rectangle(ax, ay, bx, by, cx, cy, dx, dy):
    """Whether the four points are the corners of an axis-aligned rectangle (in any order).

    Such corners are exactly cocircular (a rectangle's diagonals are diameters of one
    circle), so their ``incircle`` is exactly 0: an exact grid's squares, where the float
    filter always fails and the exact stage would run for every edge at them. The test:
    ``a`` shares its x with exactly one other point and its y with exactly one other, two
    different ones, and the fourth point has the x of the second and the y of the first.
    """
    nx = int(bx == ax) + int(cx == ax) + int(dx == ax)
    ny = int(by == ay) + int(cy == ay) + int(dy == ay)
    if nx != 1 or ny != 1:
        return False
    kp = 0 if bx == ax else (1 if cx == ax else 2)  # the point with a's x
    kr = 0 if by == ay else (1 if cy == ay else 2)  # the point with a's y
    if kp == kr:
        return False  # one point with both: not four corners
    ks = 3 - kp - kr  # the other one: the opposite corner
    xs3 = (bx, cx, dx)
    ys3 = (by, cy, dy)
    rx = xs3[kr]
    py = ys3[kp]
    return xs3[ks] == rx and ys3[ks] == py and rx != ax and py != ay


@njit(**NJIT)
def joins(i, a, b, x, vx, vy, ev, lv, xs, ys):
    """Whether site ``x`` near the circle of ``i, a, b`` (centre ``vx, vy``) is on its vertex.

    Decided for the four sites once, the same from each of their cells: True when the
    four centres of their triples are one point by the one merge rule
    (:func:`.vertex.same_vertex`) pair by pair, at the scale :func:`_quad_scale`, or when
    the four are a rectangle's corners (exactly cocircular: one exact centre). The merge
    rule is not transitive, so a test from the asking cell's own vertex would let two
    cells at one group decide it differently: one merged an edge an ulp long that its
    neighbour kept, one vertex at two points (sites 1-3 ulps apart, issue 15). Each
    centre's bits and bounds do not depend on the order of its sites, so neither does the
    answer. The pairs are tried with lower bounds first (``lv`` the vertex's,
    :func:`.vertex.voronoi_vertex_lazy`): passing with them passes with the bounds, which
    are computed only where that fails. A collinear triple (no centre) never joins.
    Returns ``(joined, ev, x1, y1, x2, y2)``: ``ev`` is -1 on entry when not yet computed,
    and comes back computed if it was needed; when joined, the two centres (of ``i, a, x``
    and of ``i, x, b``), which may name the vertex.
    """
    x1, y1, e1, l1 = voronoi_vertex_lazy(i, a, x, xs, ys)
    x2, y2, e2, l2 = voronoi_vertex_lazy(i, x, b, xs, ys)
    fin = np.isfinite(x1) and np.isfinite(y1) and np.isfinite(x2) and np.isfinite(y2)
    if not fin:
        return False, ev, 0.0, 0.0, 0.0, 0.0
    if rectangle(xs[i], ys[i], xs[a], ys[a], xs[b], ys[b], xs[x], ys[x]):
        return True, ev, x1, y1, x2, y2  # (a grid's squares: no bound needed)
    x3, y3, e3, l3 = voronoi_vertex_lazy(a, x, b, xs, ys)
    if not (np.isfinite(x3) and np.isfinite(y3)):
        return False, ev, 0.0, 0.0, 0.0, 0.0
    cx = (vx, x1, x2, x3)
    cy = (vy, y1, y2, y3)
    r = _quad_scale(i, a, b, x, cx, cy, xs, ys)
    if _one_point(cx, cy, (lv, l1, l2, l3), r):
        return True, ev, x1, y1, x2, y2
    if ev < 0.0:
        ev = voronoi_vertex_error(i, a, b, xs, ys)
    e1 = e1 if e1 >= 0.0 else voronoi_vertex_error(i, a, x, xs, ys)
    e2 = e2 if e2 >= 0.0 else voronoi_vertex_error(i, x, b, xs, ys)
    e3 = e3 if e3 >= 0.0 else voronoi_vertex_error(a, x, b, xs, ys)
    if _one_point(cx, cy, (ev, e1, e2, e3), r):
        return True, ev, x1, y1, x2, y2
    return False, ev, 0.0, 0.0, 0.0, 0.0


@njit(**NJIT)
def name4(p0, p1, p2, p3, vx, vy, c1x, c1y, c2x, c2y, xs, ys):
    """The name of four joined sites (:func:`joins`): a vertex of their exact diagram.

    :func:`.vertex.canonical_vertex4`'s arguments and search, but a triple is taken only
    where the fourth site is not strictly inside its circle (exact), with no distance test
    (the four centres are one point by the merge rule). Another's centre is no exact cell's
    vertex, so a neighbour keeping the two vertices apart shared neither (issue 15, c236).
    """
    s = sorted((np.int64(p0), np.int64(p1), np.int64(p2), np.int64(p3)))
    r2 = (vx - xs[p3]) * (vx - xs[p3]) + (vy - ys[p3]) * (vy - ys[p3])
    for t in range(4):  # the triples leave out s[3], s[2], s[1], s[0] in turn
        w = s[3 - t]
        x0, x1, x2 = (
            s[0] if t < 3 else s[1],
            s[1] if t < 2 else s[2],
            s[2] if t == 0 else s[3],
        )
        if near_pair(x0, x1, r2, xs, ys) or near_pair(x1, x2, r2, xs, ys):
            continue
        o = orient2d(xs[x0], ys[x0], xs[x1], ys[x1], xs[x2], ys[x2])
        if near_pair(x0, x2, r2, xs, ys) or o == 0.0:
            continue
        ic = incircle(xs[x0], ys[x0], xs[x1], ys[x1], xs[x2], ys[x2], xs[w], ys[w])
        if ic != 0.0 and (ic > 0.0) == (o > 0.0):
            continue  # the fourth strictly inside: no vertex of the four's exact diagram
        if w == p0 or w == p1 or w == p2:
            return (vx, vy) if w == p0 else ((c1x, c1y) if w == p1 else (c2x, c2y))
        return voronoi_vertex(x0, x1, x2, xs, ys)
    return vx, vy


@njit(**NJIT)
def _quad_scale(i, a, b, x, cx, cy, xs, ys):
    """The smallest L1 distance from one of four centres to one of the four sites.

    The merge rule's ``r`` for the group (a distance from a vertex to a site on its
    circle), the same whichever cell asks: the asking cell's own distance differs by
    rounding between the cells.
    """
    r = np.inf
    for s in (i, a, b, x):
        for k in range(4):
            r = min(r, abs(cx[k] - xs[s]) + abs(cy[k] - ys[s]))
    return r


@njit(**NJIT)
def _one_point(cx, cy, e, r):
    """Whether the four centres ``(cx[k], cy[k])`` with bounds ``e[k]`` are one vertex.

    Every pair by :func:`.vertex.same_vertex` (not transitive: all six are tested).
    """
    for p in range(4):
        for q in range(p + 1, 4):
            if not same_vertex(cx[p], cy[p], e[p], cx[q], cy[q], e[q], r):
                return False
    return True


@njit(**NJIT)
def _holds(p, q, s1, s2, v1x, v1y, v2x, v2y, xs, ys):
    """Whether an edge of ``p, q`` runs the exact way round in floats (a positive length).

    The edge from their vertex with ``s1`` (``v1``) to the one with ``s2`` (``v2``); ``s1``
    and ``s2`` must be on opposite sides of the line ``p q`` (else False). Along the
    bisector, turned left of ``p -> q``, the vertex with the site on the left comes last.
    """
    o1 = orient2d(xs[p], ys[p], xs[q], ys[q], xs[s1], ys[s1])
    o2 = orient2d(xs[p], ys[p], xs[q], ys[q], xs[s2], ys[s2])
    if o1 == 0.0 or o2 == 0.0 or (o1 > 0.0) == (o2 > 0.0):
        return False
    if o1 > 0.0:
        return cross_diff(xs[p], ys[p], xs[q], ys[q], v2x, v2y, v1x, v1y) > 0.0
    return cross_diff(xs[p], ys[p], xs[q], ys[q], v1x, v1y, v2x, v2y) > 0.0


@njit(**NJIT)
def floats_hold(i, a, b, x, nxt, prv, vx, vy, q1x, q1y, q2x, q2y, xs, ys):
    """Whether joined site ``x`` at vertex ``(vx, vy)`` of ``i, a, b`` (CCW) stays apart.

    ``q1``, ``q2`` are the centres of ``i, a, x`` and ``i, x, b`` (:func:`joins`). Exactly
    cocircular: no (one vertex). ``x`` strictly inside the circle: its edge in ``i``'s
    ring goes in if floats hold it. Outside: the vertex is exact; the edge the join would
    drop (of ``b`` when ``x`` is next in the ring, of ``a`` when it is before) stays if
    floats hold it; where ``x`` is beyond ``a b``, the vertex keeps its bits if floats hold
    the edge of ``a, b`` (their cells keep it: the same test there); else ``x`` belongs to
    another vertex of the ring. A pair of cells asks the same question of one edge.
    """
    ix, iy = xs[i], ys[i]
    if rectangle(ix, iy, xs[a], ys[a], xs[b], ys[b], xs[x], ys[x]):
        return False  # cocircular (a grid's squares: incircle's exact stage at every vertex)
    s = incircle(ix, iy, xs[a], ys[a], xs[b], ys[b], xs[x], ys[x])
    if s == 0.0:
        return False
    if s > 0.0:
        return _holds(i, x, a, b, q1x, q1y, q2x, q2y, xs, ys)
    if x == nxt:
        return _holds(i, b, a, x, vx, vy, q2x, q2y, xs, ys)
    if x == prv:
        return _holds(i, a, x, b, q1x, q1y, vx, vy, xs, ys)
    ox = orient2d(xs[a], ys[a], xs[b], ys[b], xs[x], ys[x])
    oi = orient2d(xs[a], ys[a], xs[b], ys[b], ix, iy)
    if ox == 0.0 or (ox > 0.0) == (oi > 0.0):
        return True
    x3, y3, _, _ = voronoi_vertex_lazy(a, x, b, xs, ys)
    return _holds(a, b, i, x, vx, vy, x3, y3, xs, ys)
