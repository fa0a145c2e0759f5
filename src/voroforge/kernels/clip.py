"""One convex cut: a ring against a half-space given by signed values at its vertices.

Every cell builder in the package (Delaunay-dual hull cells, half-plane cells, power cells)
cuts a convex ring by a line and keeps the side where the line's signed function is
``<= 0``. The caller computes the signed values ``ss`` (one per vertex, in any frame it
likes: relative to the cell's site, with or without weights), and :func:`cut_ring` does the
rest the same way for all of them:

- a vertex with ``s <= 0`` is kept as it is (a vertex exactly on the line is not moved, so no
  near-duplicate is created there);
- an edge that crosses the line gets one new vertex, interpolated from the endpoint
  **nearer the line** (:func:`crossing`): ``a + 1.0 * (b - a)`` need not round to ``b``, and
  a crossing next to a box corner then rounded past it, a self-intersecting spike;
- owners are carried per edge: ``owner[k]`` labels the edge from vertex ``k`` to ``k + 1``;
  the new edge along the line gets the caller's ``label``, the edge entering the kept side
  keeps its old label;
- consecutive equal vertices are merged (the later edge's owner is kept) and trailing
  vertices equal to the first are dropped.

The 3D cut of a polyhedron has the same shape: signed values per vertex, owners per face,
a new face carrying the label.

Source and destination are given as arrays plus offsets, so a caller may keep both rings in
one buffer (the half-plane kernel does) or in two (the others do).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT
from .moments import neumaier_add, ring_sums
from .predicates import orient2d


@njit(inline="always", **NJIT)
def plane_values_inline(px, py, a, m, nx, ny, ox, oy, h, ss):
    """:func:`plane_values` inlined into its caller's code (numba IR).

    For hot loops (the half-plane cells' search): a call between compiled functions updates
    the reference count of each array argument, and a cut is a few dozen flops.
    """
    smax = -np.inf
    for u in range(m):
        s = nx * (px[a + u] - ox) + ny * (py[a + u] - oy) - h
        ss[u] = s
        smax = max(smax, s)
    return smax


@njit(**NJIT)
def plane_values(px, py, a, m, nx, ny, ox, oy, h, ss):
    """Signed values ``n . (p - o) - h`` of vertices ``a:a + m`` into ``ss[:m]``.

    Returns the largest value: the ring is cut exactly when it is positive.
    """
    return plane_values_inline(px, py, a, m, nx, ny, ox, oy, h, ss)


@njit(inline="always", **NJIT)
def crossing(ax, ay, sa, bx, by, sb):
    """Where segment ``a -> b`` (signed values ``sa``, ``sb`` of opposite sign) meets the line.

    Interpolated from the endpoint nearer the line, so a crossing near a vertex stays on the
    segment's side of it.
    """
    if abs(sa) <= abs(sb):
        t = sa / (sa - sb)
        return ax + t * (bx - ax), ay + t * (by - ay)
    t = sb / (sb - sa)
    return bx + t * (ax - bx), by + t * (ay - by)


@njit(inline="always", **NJIT)
def _push(qx, qy, qo, b, c, x, y, o):
    """Append ``(x, y)`` with edge owner ``o`` at slot ``c`` of the ring starting at ``b``.

    A vertex equal to the previous one is merged into it (the zero-length edge goes, the
    later edge keeps its owner). Returns the next free slot.
    """
    if c > b and qx[c - 1] == x and qy[c - 1] == y:
        qo[c - 1] = o
        return c
    qx[c] = x
    qy[c] = y
    qo[c] = o
    return c + 1


@njit(**NJIT)
def cut_ring(px, py, po, a, m, ss, qx, qy, qo, b, label):
    """Keep the part of ring ``p[a:a + m]`` where ``ss <= 0``; write it to ``q[b:]``.

    ``ss[k]`` is the signed value of vertex ``a + k``. The new edge along the line gets owner
    ``label``. Returns the vertex count of the result (0 when nothing is left; a result may
    have fewer than 3 vertices when the ring only touches the line, and callers that need a
    polygon test for that). ``q`` may be the same arrays as ``p`` when ``b >= a + m``.
    The destination needs room for ``m + 1`` vertices.
    """
    return cut_ring_inline(px, py, po, a, m, ss, qx, qy, qo, b, label)


@njit(inline="always", **NJIT)
def cut_ring_inline(px, py, po, a, m, ss, qx, qy, qo, b, label):
    """:func:`cut_ring` inlined into its caller's code (numba IR).

    For the half-plane cells' search, as :func:`plane_values_inline`; :func:`cut_ring` is
    this body compiled once, for the other cell builders.
    """
    c = b
    for k in range(m):
        kn = k + 1 if k + 1 < m else 0
        sa = ss[k]
        sb = ss[kn]
        ax = px[a + k]
        ay = py[a + k]
        if sa <= 0.0:
            # a kept vertex on the line starts the new edge when the next one is cut off
            o = label if (sa == 0.0 and sb > 0.0) else po[a + k]
            c = _push(qx, qy, qo, b, c, ax, ay, o)
            if sa < 0.0 and sb > 0.0:  # leaving: the crossing starts the new edge
                x, y = crossing(ax, ay, sa, px[a + kn], py[a + kn], sb)
                c = _push(qx, qy, qo, b, c, x, y, label)
        elif sb < 0.0:  # entering: the crossing continues the old edge
            x, y = crossing(ax, ay, sa, px[a + kn], py[a + kn], sb)
            c = _push(qx, qy, qo, b, c, x, y, po[a + k])
    while c > b + 1 and qx[c - 1] == qx[b] and qy[c - 1] == qy[b]:
        c -= 1  # trailing vertices equal to the first: the edge into the first keeps its owner
    return c - b


@njit(**NJIT)
def dedupe_ring(qx, qy, qo, m):
    """Drop consecutive equal vertices of ``q[:m]`` (keeping the later edge owner).

    Returns the new count, 0 when fewer than 3 vertices are left.
    """
    out = 0
    for k in range(m):
        if out > 0 and qx[k] == qx[out - 1] and qy[k] == qy[out - 1]:
            qo[out - 1] = qo[k]
            continue
        qx[out] = qx[k]
        qy[out] = qy[k]
        qo[out] = qo[k]
        out += 1
    while out > 1 and qx[out - 1] == qx[0] and qy[out - 1] == qy[0]:
        out -= 1
    return out if out >= 3 else 0


@njit(**NJIT)
def _upper(x, y):
    """Whether direction ``(x, y)`` has its angle in ``[0, pi)`` (exact: signs only)."""
    return y > 0.0 or (y == 0.0 and x > 0.0)


@njit(**NJIT)
def ring_convex(xy, a, b):
    """Whether the closed ring ``xy[a:b]`` (last vertex repeating the first) is convex.

    Decided exactly on the float vertices: at least three distinct vertices, no zero edge,
    every turn left or straight on (``orient2d >= 0``, no reversal), and the edge directions
    wind once (counted by the turns from the lower to the upper half-plane of directions).
    Such a ring is a simple convex polygon, so valid. Rounding may also leave a tiny
    concavity in a valid ring; callers use this as a certificate, not as a validity test.
    """
    return open_ring_convex(xy[a : b - 1, 0], xy[a : b - 1, 1], b - a - 1)


@njit(inline="always", **NJIT)
def ring_corner(px, py, m, k):
    """Vertex ``k`` of the open ring ``p[:m]``: ``(k0, k2, ex, ey, fx, fy)``.

    ``k0`` and ``k2`` are the previous and next vertices (wrapping around), ``e`` the edge
    into vertex ``k`` and ``f`` the edge out of it.
    """
    k0 = k - 1 if k > 0 else m - 1
    k2 = k + 1 if k + 1 < m else 0
    return k0, k2, px[k] - px[k0], py[k] - py[k0], px[k2] - px[k], py[k2] - py[k]


@njit(**NJIT)
def open_ring_convex(px, py, m):
    """:func:`ring_convex` of the open ring ``p[:m]`` (no repeated closing vertex)."""
    if m < 3:
        return False
    wraps = 0
    for k in range(m):
        k0, k2, ex, ey, fx, fy = ring_corner(px, py, m, k)
        if (ex == 0.0 and ey == 0.0) or (fx == 0.0 and fy == 0.0):
            return False
        o = orient2d(px[k0], py[k0], px[k], py[k], px[k2], py[k2])
        if o < 0.0:
            return False
        if o == 0.0 and (_upper(ex, ey) != _upper(fx, fy)):
            return False  # straight on keeps the half; a reversal flips it
        if not _upper(ex, ey) and _upper(fx, fy):
            wraps += 1
    return wraps == 1


@njit(**NJIT)
def rings_convex(xy, lengths):
    """:func:`ring_convex` of every ring ``xy[lengths[i]:lengths[i + 1]]`` (empty ones pass)."""
    n = lengths.shape[0] - 1
    ok = np.ones(n, dtype=np.bool_)
    for i in range(n):
        if lengths[i + 1] > lengths[i]:
            ok[i] = ring_convex(xy, lengths[i], lengths[i + 1])
    return ok


@njit(**NJIT)
def rings_convex_area(xy, lengths):
    """Whether every ring ``xy[lengths[i]:lengths[i + 1]]`` is convex, and their total area.

    The half-plane cells' certificate (:func:`voroforge.engine.planar._certified`) in one
    pass: each closed ring gets :func:`ring_convex`'s exact test (empty rings pass, as in
    :func:`rings_convex`) and its signed area from :func:`.moments.ring_sums` relative to its
    first vertex, so coordinates far from the origin keep their precision; the areas are
    added with Neumaier's compensation (:func:`.moments.neumaier_add`: a million small cells
    sum to the box's area to a few ulps). Returns ``(convex, area)``; stops at the first ring
    that is not convex (area then NaN).
    """
    xs = xy[:, 0]
    ys = xy[:, 1]
    total = 0.0
    comp = 0.0
    for i in range(lengths.shape[0] - 1):
        a = lengths[i]
        b = lengths[i + 1]
        if b == a:
            continue
        if not open_ring_convex(xs[a : b - 1], ys[a : b - 1], b - a - 1):
            return False, np.nan
        if b - a < 2:
            continue
        ring = ring_sums(xs, ys, a, b, xs[a], ys[a], True)[0]
        total, comp = neumaier_add(total, comp, ring)
    return True, 0.5 * (total + comp)


@njit(**NJIT)
def _width(xy, a, b):
    """Width of the closed ring ``xy[a:b]`` (0 when all its vertices are on one line).

    The least, over its edges, of the farthest vertex from the edge's line (coordinates
    relative to the first vertex).
    """
    w = np.inf
    x0 = xy[a, 0]
    y0 = xy[a, 1]
    for k in range(a, b - 1):
        ex = xy[k + 1, 0] - xy[k, 0]
        ey = xy[k + 1, 1] - xy[k, 1]
        e = np.sqrt(ex * ex + ey * ey)
        if e == 0.0:
            continue
        far = 0.0
        for j in range(a, b - 1):
            dx = (xy[j, 0] - x0) - (xy[k, 0] - x0)
            dy = (xy[j, 1] - y0) - (xy[k, 1] - y0)
            far = max(far, abs(ex * dy - ey * dx) / e)
        w = min(w, far)
    return w


@njit(**NJIT)
def tiny_folded(xy, lengths, ulps):
    """Rings that fail :func:`ring_convex` and are at most ``ulps`` ulps across or wide.

    Cells floats cannot represent (sites a few ulps apart far from the origin; ulps of the
    ring's largest coordinate). Returns a code per ring: 1 for a ring at most ``ulps`` ulps
    across in both directions (its vertices a few ulps apart), 2 for a longer one at most
    that wide (a strip beside a cluster a few ulps across, whose vertices all rounded onto
    one line), 0 otherwise. The cheap tests come first (spans, then the area against
    width times span), so the width and the exact test run on those rings only.
    """
    n = lengths.shape[0] - 1
    bad = np.zeros(n, dtype=np.uint8)
    for i in range(n):
        a = lengths[i]
        b = lengths[i + 1]
        if b - a < 2:
            continue
        x0 = x1 = xy[a, 0]
        y0 = y1 = xy[a, 1]
        area2 = 0.0
        for k in range(a + 1, b):
            x0 = min(x0, xy[k, 0])
            x1 = max(x1, xy[k, 0])
            y0 = min(y0, xy[k, 1])
            y1 = max(y1, xy[k, 1])
            if k + 1 < b:
                area2 += (xy[k, 0] - xy[a, 0]) * (xy[k + 1, 1] - xy[a, 1]) - (
                    xy[k, 1] - xy[a, 1]
                ) * (xy[k + 1, 0] - xy[a, 0])
        big = max(abs(x0), abs(x1), abs(y0), abs(y1))
        thin = ulps * 2.0**-52 * big
        span = max(x1 - x0, y1 - y0)
        if span <= thin:
            bad[i] = 0 if ring_convex(xy, a, b) else 1
        elif abs(area2) <= 4.0 * thin * span and _width(xy, a, b) <= thin:
            # (twice the area of a ring at most w wide is at most 2 w span)
            bad[i] = 0 if ring_convex(xy, a, b) else 2
    return bad
