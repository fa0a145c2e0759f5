"""Sibson natural-neighbour weights from the Bowyer-Watson cavity of each query point.

Inserting a query point ``q`` into a Delaunay triangulation destroys the triangles whose
circumcircle contains ``q`` (the cavity). The new cell of ``q`` is made of the pieces it
steals from the cells of the cavity's vertices (the natural neighbours). The piece stolen
from vertex ``v`` is bounded by

* old Voronoi edges of ``v`` between circumcentres of two cavity triangles,
* half-edges from a cavity triangle's circumcentre to the new vertex ``circumcentre(x, y, q)``
  where the Delaunay edge ``(x, y)`` of ``v`` is on the cavity boundary (or the hull),
* one segment of the bisector of ``q`` and ``v``.

Shoelace sums are taken about the midpoint of ``q`` and ``v``, which lies on the line of that
bisector segment, so that segment contributes nothing and every other piece is a term local
to one (triangle, corner) pair: no ordering of the cavity is needed. Weights are the stolen
areas divided by their sum (the area of the new cell).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NATURAL_HULL_RTOL, NJIT
from .predicates import incircle, orient2d
from .vertex import circumcenter

#: Query status codes returned by :func:`sibson`.
INSIDE = 0
OUTSIDE = 1


@njit(**NJIT)
def _circumcentres(xs, ys, tri):
    t = len(tri) // 3
    cc = np.zeros((t, 2))
    for k in range(t):
        a = tri[3 * k]
        b = tri[3 * k + 1]
        c = tri[3 * k + 2]
        cx, cy = circumcenter(xs[a], ys[a], xs[b], ys[b], xs[c], ys[c])
        cc[k, 0] = cx
        cc[k, 1] = cy
    return cc


@njit(**NJIT)
def _conflicts(xs, ys, tri, k, qx, qy):
    a = tri[3 * k]
    b = tri[3 * k + 1]
    c = tri[3 * k + 2]
    return incircle(xs[a], ys[a], xs[b], ys[b], xs[c], ys[c], qx, qy) > 0.0


@njit(**NJIT)
def _seed(xs, ys, tri, he, start, s, qx, qy):
    """A triangle around vertex ``s`` whose circumcircle contains ``q``, or -1."""
    e = start[s]
    if e < 0:
        return -1
    cur = e
    while True:  # counter-clockwise around s
        k = cur // 3
        if _conflicts(xs, ys, tri, k, qx, qy):
            return k
        prev = 3 * k + (cur % 3 + 2) % 3
        twin = he[prev]
        if twin < 0:
            break
        cur = twin
        if cur == e:
            return -1
    cur = e
    while True:  # clockwise, when the walk above stopped at the hull
        twin = he[cur]
        if twin < 0:
            return -1
        cur = 3 * (twin // 3) + (twin % 3 + 1) % 3
        if cur == e:
            return -1
        if _conflicts(xs, ys, tri, cur // 3, qx, qy):
            return cur // 3


@njit(**NJIT)
def _blend(px, py, xs, ys, values, grads, v, lam, sums, acc, xi):
    """Accumulate site ``v`` with (unnormalised) Sibson weight ``lam``.

    ``sums`` holds ``(sum lam, sum lam r, sum lam / r, sum lam r**2)`` with ``r = |q - v|``;
    ``acc`` the weighted values, ``xi`` the ``lam / r`` weighted tangent-plane values.
    """
    dx = px - xs[v]
    dy = py - ys[v]
    r = np.sqrt(dx * dx + dy * dy)
    sums[0] += lam
    sums[1] += lam * r
    sums[2] += lam / r
    sums[3] += lam * r * r
    for j in range(len(acc)):
        acc[j] += lam * values[v, j]
        xi[j] += lam / r * (values[v, j] + grads[v, j, 0] * dx + grads[v, j, 1] * dy)


@njit(**NJIT)
def _finish(sums, acc, xi, smooth, out, q):
    total = sums[0]
    for j in range(len(acc)):
        z0 = acc[j] / total
        if smooth:
            # Sibson's Z1: blend that reproduces a + b.x + c |x|^2 given exact gradients
            alpha = sums[1] / sums[2]
            beta = sums[3] / total
            z1 = xi[j] / sums[2]
            out[q, j] = (alpha * z0 + beta * z1) / (alpha + beta)
        else:
            out[q, j] = z0


@njit(**NJIT)
def sibson(xs, ys, tri, he, values, grads, smooth, nearest, qx, qy, out):
    """Sibson interpolation of ``values`` at every query point.

    Parameters
    ----------
    xs, ys : (n,) float64
        Site coordinates (duplicates allowed: they appear in no triangle).
    tri : (3 t,) int32
        Triangles, counter-clockwise, flat.
    he : (3 t,) int32
        Opposite halfedges, -1 on the hull.
    values : (n, k) float64
        Data values per site.
    grads : (n, k, 2) float64
        Gradients of the data at the sites (used when ``smooth``).
    smooth : bool
        Sibson's C1 interpolant ``Z1`` (Sibson 1980) instead of the plain ``Z0``.
    nearest : (m,) int64
        A nearest site of each query point (one that appears in the triangulation).
    qx, qy : (m,) float64
        Query points.
    out : (m, k) float64
        Filled with the interpolated values where the status is ``INSIDE``.

    Returns
    -------
    status : (m,) int8
        ``INSIDE``, or ``OUTSIDE`` for points outside the convex hull of the sites.
    """
    n = len(xs)
    t = len(tri) // 3
    nq = len(qx)
    kdim = values.shape[1]
    status = np.full(nq, OUTSIDE, dtype=np.int8)
    start = np.full(n, -1, dtype=np.int64)
    for e in range(3 * t):
        start[tri[e]] = e
    cc = _circumcentres(xs, ys, tri)
    mark = np.full(t, -1, dtype=np.int64)  # 2 q: tested, outside; 2 q + 1: in the cavity
    cavity = np.zeros(max(t, 1), dtype=np.int64)
    acc = np.zeros(kdim)
    xi = np.zeros(kdim)
    sums = np.zeros(4)
    for q in range(nq):
        px = qx[q]
        py = qy[q]
        s = nearest[q]
        if xs[s] == px and ys[s] == py:
            for j in range(kdim):
                out[q, j] = values[s, j]
            status[q] = INSIDE
            continue
        k0 = _seed(xs, ys, tri, he, start, s, px, py)
        if k0 < 0:
            continue
        inside = 2 * q + 1
        mark[k0] = inside
        cavity[0] = k0
        size = 1
        head = 0
        outside = False
        on_hull = -1
        near = NATURAL_HULL_RTOL  # q's distance to the nearest hull edge / its length
        while head < size and not outside:
            k = cavity[head]
            head += 1
            for j in range(3):
                e = 3 * k + j
                twin = he[e]
                if twin < 0:
                    a = tri[e]
                    b = tri[3 * k + (j + 1) % 3]
                    o = orient2d(xs[a], ys[a], xs[b], ys[b], px, py)
                    if o < 0.0:
                        outside = True
                        break
                    if o == 0.0:
                        on_hull = e
                        near = 0.0
                        continue
                    # o is twice the triangle's area: o / |ab|^2 is q's distance to the
                    # line over |ab|; the nearest such edge that q projects onto
                    lx = xs[b] - xs[a]
                    ly = ys[b] - ys[a]
                    ll = lx * lx + ly * ly
                    tp = (px - xs[a]) * lx + (py - ys[a]) * ly
                    if o <= near * ll and 0.0 <= tp <= ll:
                        on_hull = e
                        near = o / ll
                    continue
                k2 = twin // 3
                if mark[k2] >= 2 * q:
                    continue
                if _conflicts(xs, ys, tri, k2, px, py):
                    mark[k2] = inside
                    cavity[size] = k2
                    size += 1
                else:
                    mark[k2] = 2 * q
        if outside:
            continue
        status[q] = INSIDE
        if on_hull >= 0:
            # on a hull edge (the new cell is unbounded): Sibson's limit is linear along it.
            # Within NATURAL_HULL_RTOL of its length from it the cell is bounded but so long
            # that its areas cancel to garbage (values far outside the data's range): the
            # limit is used there too (off by about that fraction)
            k = on_hull // 3
            a = tri[on_hull]
            b = tri[3 * k + (on_hull % 3 + 1) % 3]
            lx = xs[b] - xs[a]
            ly = ys[b] - ys[a]
            u = ((px - xs[a]) * lx + (py - ys[a]) * ly) / (lx * lx + ly * ly)
            if not 0.0 <= u <= 1.0:
                if near == 0.0:  # on the hull edge's line, beyond it: outside
                    status[q] = OUTSIDE
                    continue
                u = min(max(u, 0.0), 1.0)  # (rounding of u only)
            sums[:] = 0.0
            acc[:] = 0.0
            xi[:] = 0.0
            if u > 0.0:
                _blend(px, py, xs, ys, values, grads, b, u, sums, acc, xi)
            if u < 1.0:
                _blend(px, py, xs, ys, values, grads, a, 1.0 - u, sums, acc, xi)
            _finish(sums, acc, xi, smooth, out, q)
            continue
        sums[:] = 0.0
        acc[:] = 0.0
        xi[:] = 0.0
        for i in range(size):
            k = cavity[i]
            cx = cc[k, 0]
            cy = cc[k, 1]
            for c in range(3):
                v = tri[3 * k + c]
                w = tri[3 * k + (c + 1) % 3]
                u = tri[3 * k + (c + 2) % 3]
                mx = 0.5 * (px + xs[v])
                my = 0.5 * (py + ys[v])
                ax = cx - mx
                ay = cy - my
                area = 0.0
                # incoming edge u -> v: from this circumcentre towards the next one
                twin = he[3 * k + (c + 2) % 3]
                if twin >= 0 and mark[twin // 3] == inside:
                    bx = cc[twin // 3, 0] - mx
                    by = cc[twin // 3, 1] - my
                else:
                    nx, ny = circumcenter(xs[u], ys[u], xs[v], ys[v], px, py)
                    bx = nx - mx
                    by = ny - my
                area += ax * by - ay * bx
                # outgoing edge v -> w on the cavity boundary: from the new vertex to here
                twin = he[3 * k + c]
                if twin < 0 or mark[twin // 3] != inside:
                    nx, ny = circumcenter(xs[v], ys[v], xs[w], ys[w], px, py)
                    bx = nx - mx
                    by = ny - my
                    area += bx * ay - by * ax
                _blend(px, py, xs, ys, values, grads, v, 0.5 * area, sums, acc, xi)
        _finish(sums, acc, xi, smooth, out, q)
    return status
