"""Which triangles of the Delaunay dual sit on a Voronoi edge that rounding could fold.

Split off ``kernels/centers`` (its last pass after the merge): :func:`mark_risky`.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import FOLD_SPAN_ERRS, NJIT, VERTEX_SNAP_RTOL


@njit(**NJIT)
def mark_risky(xs, ys, tri, he, cls, cx, cy, own_x, own_y, err, flag, near):
    """Mark in ``near`` both triangles of every edge between two classes that can fold.

    Within a class every triangle has the one named vertex (no edge). Between two classes,
    an edge :func:`.centers.flag_close` could not decide (flagged, not joined) is marked;
    so is one at a class of two or more whose vertices are within ``FOLD_SPAN_ERRS`` times
    their proven distance from their triangles' exact centres (rounding bound plus the
    naming move, as ``folds._moved``; ``own_x, own_y`` are the centres before naming) and
    the snap tolerance: the short-edge test (``centers.short_edge``) with the naming moves
    added. Edges between two single triangles kept their centres: ``flag_close`` marked the
    short ones. A class whose vertex is far from every other vertex (an exact grid's
    squares) cannot fold a ring, so its cells are not checked.
    """
    t_count = cls.shape[0]
    multi = np.zeros(t_count, dtype=np.uint8)
    for t in range(t_count):
        if cls[t] != t:
            multi[cls[t]] = 1
    for e in range(tri.shape[0]):
        f = he[e]
        if f < e:
            continue
        t = e // 3
        u = f // 3
        if cls[t] == cls[u]:
            continue
        if flag[e] != 0:
            near[t] = 1
            near[u] = 1
            continue
        if multi[cls[t]] == 0 and multi[cls[u]] == 0:
            continue
        d = abs(cx[t] - cx[u]) + abs(cy[t] - cy[u])
        r = abs(cx[t] - xs[tri[e]]) + abs(cy[t] - ys[tri[e]])
        mt = err[t] + abs(cx[t] - own_x[t]) + abs(cy[t] - own_y[t])
        mu = err[u] + abs(cx[u] - own_x[u]) + abs(cy[u] - own_y[u])
        if not d > FOLD_SPAN_ERRS * (mt + mu + VERTEX_SNAP_RTOL * r):
            near[t] = 1  # (also where a bound is not finite)
            near[u] = 1
