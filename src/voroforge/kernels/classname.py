"""The name of a merged pair of triangles: a triple whose centre is the members' vertex.

A class of the Delaunay dual (``kernels/centers``) is named by the first well-conditioned
triple of its sites in rank order whose centre is the reference member's to rounding
(:func:`.vertex.canonical_vertex_ranked`: ``VERTEX_SNAP_RTOL`` of the radius plus 16 ulps of
the magnitude). Far from the origin that snap reaches many ulps (sites on a circle of 1e-7
at (5e5, 4e6): 137 units of x's ulp), where the exact vertices of a float circle lie a few
ulps apart; a class of two triangles whose exact centres are 9 units apart was named by a
third triple's centre 28 units past both (an ulp past the box's top side), and its cells
folded and were dropped. :func:`class_vertex` adds the test that the name is the vertex
to the proven bounds: within the reference's rounding bound (plus half an ulp of each
coordinate of both), or within both bounds where the name is no worse conditioned than
the reference, or the class's sites are exactly cocircular (then every triple has the
one exact centre, and the snap alone decides, as before). ``centers`` applies it to
classes of two; larger classes (chains of fold joins, whose members' exact centres lie
many bounds apart) keep the snap alone: named by their best member's bound, they moved
vertices further (a float circle of 1000 at phase 0.95: 8.56 ulps past a cell).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NAME_MAX_TRIES, NJIT, VERTEX_SNAP_RTOL
from .predicates import incircle
from .vertex import (
    is_close,
    near_pair,
    sort_by_rank,
    voronoi_vertex,
    voronoi_vertex_and_error,
)

_U = 2.0**-53


@njit(**NJIT)
def within_bounds(vx, vy, ev, wx, wy, ew):
    """Whether the name's centre ``(wx, wy)`` (bound ``ew``) is the vertex ``(vx, vy)`` (``ev``).

    Within ``ev`` of it, or, where the name is no worse conditioned (``ew <= ev``), within
    both bounds; either plus half an ulp of each coordinate of both (the representation).
    """
    d = abs(vx - wx) + abs(vy - wy)
    slack = _U * (abs(vx) + abs(vy) + abs(wx) + abs(wy))
    if d <= ev + slack:
        return True
    return ew <= ev and d <= ev + ew + slack


@njit(**NJIT)
def exactly_cocircular(on, k, a, b, c, xs, ys):
    """Whether every site of ``on[:k]`` is exactly on the circle through ``a, b, c``."""
    for p in range(k):
        x = on[p]
        if x == a or x == b or x == c:
            continue
        if incircle(xs[a], ys[a], xs[b], ys[b], xs[c], ys[c], xs[x], ys[x]) != 0.0:
            return False
    return True


@njit(**NJIT)
def bound_ok(vx, vy, ev, wx, wy, x0, x1, x2, xs, ys):
    """:func:`within_bounds` for triple ``x0, x1, x2`` with centre ``(wx, wy)``.

    The triple's own bound is computed only where the reference's alone does not decide.
    """
    d = abs(vx - wx) + abs(vy - wy)
    if d <= ev + _U * (abs(vx) + abs(vy) + abs(wx) + abs(wy)):
        return True
    _, _, ew = voronoi_vertex_and_error(x0, x1, x2, xs, ys)
    return within_bounds(vx, vy, ev, wx, wy, ew)


@njit(**NJIT)
def name_ok(vx, vy, ev, wx, wy, x0, x1, x2, on, k, a, b, c, xs, ys, exact):
    """Whether triple ``x0, x1, x2`` with centre ``(wx, wy)`` names the vertex ``(vx, vy)``.

    :func:`bound_ok`, else exact cocircularity of the class (``on[:k]`` on the circle of
    ``a, b, c``), decided once: ``exact[0]`` is -1 until then, then 0 or 1. The snap
    (``vertex.is_close``) is the caller's.
    """
    if bound_ok(vx, vy, ev, wx, wy, x0, x1, x2, xs, ys):
        return True
    if exact[0] < 0:
        exact[0] = 1 if exactly_cocircular(on, k, a, b, c, xs, ys) else 0
    return exact[0] == 1


@njit(**NJIT)
def class_vertex(on, k, rank, vx, vy, ev, sx, sy, a, b, c, xs, ys):
    """``vertex.canonical_vertex_ranked`` whose name is also the vertex to the bounds.

    ``(vx, vy)`` is the reference member's centre, ``ev`` its rounding bound, ``(sx, sy)``
    one of its sites and ``a, b, c`` its triple. Triples of ``on[:k]`` in rank order, as
    there (repeats, close pairs and non-finite centres skipped, the snap tested), the first
    that passes :func:`name_ok` names it. Returns ``(found, x, y)``; ``(vx, vy)`` if none.
    """
    sort_by_rank(on, k, rank)
    r2 = (vx - sx) * (vx - sx) + (vy - sy) * (vy - sy)
    exact = np.full(1, -1, dtype=np.int64)
    tries = 0
    for p in range(k):
        for q in range(p + 1, k):
            for r in range(q + 1, k):
                tries += 1
                if tries > NAME_MAX_TRIES:
                    return False, vx, vy
                x0, x1, x2 = on[p], on[q], on[r]
                if x0 == x1 or x1 == x2:
                    continue
                if near_pair(x0, x1, r2, xs, ys) or near_pair(x1, x2, r2, xs, ys):
                    continue
                if near_pair(x0, x2, r2, xs, ys):
                    continue
                wx, wy = voronoi_vertex(x0, x1, x2, xs, ys)
                if not (np.isfinite(wx) and np.isfinite(wy)):
                    continue
                if not is_close(vx, vy, wx, wy, sx, sy, VERTEX_SNAP_RTOL):
                    continue
                if name_ok(vx, vy, ev, wx, wy, x0, x1, x2, on, k, a, b, c, xs, ys, exact):
                    return True, wx, wy
    return False, vx, vy
