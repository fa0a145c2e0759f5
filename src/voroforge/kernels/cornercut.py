"""A cut cell at a box corner that its Voronoi vertices crowd closer than floats cut.

The cut cells (:mod:`kernels.cellcut`) cut the box by float bisector values, which are off
by ulps of the sites' distance. Where a cell's Voronoi vertices lie within that of a box
corner (a float circle's centre on the corner: every triangle's centre within 1e-14 of it,
sites 100 away, issue 15), each cell's cut decides alone which of its edges reach which
side, and the cells no longer tile the corner (non-convex rings, Euler, invalid cells).

There the cell is cut exactly instead (:func:`corner_cut`): each ring vertex's side of a
bisector is an exact sign (a float filter, then :func:`.distance_exact.compare`), and each
new vertex is the point named by its owners: a box side's crossing
(:func:`.vertex.box_crossing`, the double nearest the exact one near a corner) or the
Voronoi vertex of three sites (:func:`.vertex.voronoi_vertex`). Every cell at the corner
then decides each vertex and corner the one exact way; :mod:`kernels.cellcut` names the
result as it names any cut.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import CORNER_CUT_RTOL, NJIT
from .clip import dedupe_ring
from .distance_exact import compare
from .vertex import box_crossing, voronoi_vertex

_U = 2.0**-53


@njit(**NJIT)
def near_corner(i, xs, ys, tris, nn, cx, cy, box):
    """Whether a centre of site ``i``'s triangles ``tris[:nn]`` crowds a box corner.

    Within ``CORNER_CUT_RTOL`` of its L1 distance from the site in both coordinates.
    """
    for k in range(nn):
        t = tris[k]
        if t < 0:
            continue
        x = cx[t]
        y = cy[t]
        d = CORNER_CUT_RTOL * (abs(x - xs[i]) + abs(y - ys[i]))
        if (
            min(abs(x - box[0]), abs(x - box[2])) <= d
            and min(abs(y - box[1]), abs(y - box[3])) <= d
        ):
            return True
    return False


@njit(**NJIT)
def _sign(i, j, x, y, xs, ys, w):
    """Exact side of ``(x, y)`` of the bisector of ``i, j``: 1 nearer ``j``, -1 nearer ``i``."""
    dx = xs[j] - xs[i]
    dy = ys[j] - ys[i]
    ux = x - xs[i]
    uy = y - ys[i]
    h = 0.5 * (dx * dx + dy * dy)
    s = dx * ux + dy * uy - h
    e = 16.0 * _U * (abs(dx * ux) + abs(dy * uy) + abs(h))
    if s > e:
        return 1.0, w
    if s < -e:
        return -1.0, w
    if w.shape[0] == 0:
        w = np.empty((9, 64))  # noqa: TID251  (every slot read is written first)
    return float(compare(x, y, xs[i], ys[i], xs[j], ys[j], np.int64(0), w)), w


@njit(**NJIT)
def _named(i, j, o, xs, ys, box, ax, ay, bx, by):
    """The point where the bisector of ``i, j`` meets edge ``a -> b`` owned by ``o``, by name."""
    if o < 0:
        x, y = box_crossing(i, j, xs, ys, o, box)
        if x == x and y == y:
            return min(max(x, box[0]), box[2]), min(max(y, box[1]), box[3])
        return 0.5 * (ax + bx), 0.5 * (ay + by)
    return voronoi_vertex(i, j, o, xs, ys)


@njit(**NJIT)
def corner_cut(i, xs, ys, nbrs, nn, box, px, py, pw, qx, qy, qw, sg):
    """The box cut exactly by the bisectors of site ``i`` with ``nbrs[:nn]``; ring in ``p``.

    Owners as ``kernels.power.box_cell`` writes them (neighbours; -1..-4 on the box
    sides); returns the vertex count, 0 when less than a polygon is left. Buffers need
    room for ``nn + 5`` vertices; ``q`` and ``sg`` are scratch.
    """
    px[0], py[0], pw[0] = box[0], box[1], -2
    px[1], py[1], pw[1] = box[2], box[1], -3
    px[2], py[2], pw[2] = box[2], box[3], -4
    px[3], py[3], pw[3] = box[0], box[3], -1
    m = np.int64(4)
    ax, ay, ao = px, py, pw
    bx, by, bo = qx, qy, qw
    w = np.empty((0, 0))  # noqa: TID251  (scratch of the exact signs, made when needed)
    swapped = False
    for k in range(nn):
        j = nbrs[k]
        out = False
        inn = False
        for v in range(m):
            s, w = _sign(i, j, ax[v], ay[v], xs, ys, w)
            sg[v] = s
            out = out or s > 0.0
            inn = inn or s < 0.0
        if not out:
            continue
        if not inn:
            return 0
        c = np.int64(0)
        for v in range(m):
            vn = v + 1 if v + 1 < m else 0
            sa = sg[v]
            sb = sg[vn]
            if sa <= 0.0:
                bx[c] = ax[v]
                by[c] = ay[v]
                bo[c] = j if (sa == 0.0 and sb > 0.0) else ao[v]
                c += 1
                if sa < 0.0 and sb > 0.0:  # leaving: the crossing starts the new edge
                    bx[c], by[c] = _named(i, j, ao[v], xs, ys, box, ax[v], ay[v], ax[vn], ay[vn])
                    bo[c] = j
                    c += 1
            elif sb < 0.0:  # entering: the crossing continues the old edge
                bx[c], by[c] = _named(i, j, ao[v], xs, ys, box, ax[v], ay[v], ax[vn], ay[vn])
                bo[c] = ao[v]
                c += 1
        # named points of one vertex coincide: drop repeats (the later edge's owner kept)
        m = dedupe_ring(bx, by, bo, c)
        if m == 0:
            return 0
        ax, ay, ao, bx, by, bo = bx, by, bo, ax, ay, ao
        swapped = not swapped
    if swapped:
        for v in range(m):
            px[v] = ax[v]
            py[v] = ay[v]
            pw[v] = ao[v]
    return m
