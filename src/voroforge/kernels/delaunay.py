"""Sweep-hull Delaunay triangulation (after Delaunator) with exact predicates.

Points are inserted in order of distance from the circumcentre of a seed triangle; each new
point is joined to the hull edges it sees and the new edges are legalised with Lawson flips.
Visibility uses the adaptive exact orientation, so the triangulation is always valid. Flips
use the floating-point incircle filter alone, which keeps the large exact-arithmetic code out
of the hot loop; when the filter could not decide some test (nearly or exactly cocircular
points), one parallel pass lists every edge that is not locally Delaunay (exact incircle
where the filter cannot tell) and exact Lawson flips from those (strict incircle, so
cocircular input terminates) give the Delaunay triangulation. A point that sees no hull
edge (possible only when rounding of the sweep distances ties or inverts the order) is
deferred and inserted afterwards by point location and a 1-to-3 or edge split, so no point
is ever dropped.

Layout (Delaunator): ``triangles`` is a flat array, halfedge ``e`` goes from ``triangles[e]``
to ``triangles[_next(e)]`` and ``halfedges[e]`` is its twin or -1 on the hull. Triangles are
counter-clockwise (positive signed area). All kernels take distinct points: the engine removes
exact duplicates before calling them.
"""

from __future__ import annotations

import math

import numpy as np
from numba import literally, njit, prange

from ..config import NJIT, NJIT_PARALLEL, SEED_DET_RTOL
from .delaunay_brio import brio_order, convex_hull
from .predicates import incircle, incircle_fast, orient2d, orient2d_fast
from .vertex import circumcenter

#: The sweep gives up after FLIP_BUDGET_PER_POINT * n + FLIP_BUDGET_BASE flips, or as many hull
#: walk steps, and the points are inserted in a randomised order instead
#: (:func:`_triangulate_brio`). Uniform points make about 4 flips and 2 steps a point; points on
#: a few parallel lines make n / 30 flips a point, three lines of integer points n / 150 hull
#: steps (issue 15).
FLIP_BUDGET_PER_POINT = 16
FLIP_BUDGET_BASE = 1 << 16

#: The smallest helpers are inlined by numba itself: called as functions, each would be
#: compiled once for every mix of int32 entries, int64 indices and literal -1 its callers
#: pass (nine times for _add_triangle), for code LLVM inlines anyway.
_INLINE = {**NJIT, "inline": "always"}


@njit(**_INLINE)
def _next(e):
    return e - 2 if e % 3 == 2 else e + 1


@njit(**_INLINE)
def _prev(e):
    return e + 2 if e % 3 == 0 else e - 1


@njit(**_INLINE)
def link_halfedges(he, a, b):
    """Make halfedges ``a`` and ``b`` twins (``b = -1``: ``a`` is on the hull)."""
    he[a] = b
    if b != -1:
        he[b] = a


@njit(**NJIT)
def _orient(ax, ay, bx, by, cx, cy):
    """Filtered orientation, exact only when the filter cannot decide."""
    o = orient2d_fast(ax, ay, bx, by, cx, cy)
    if o != o:
        return orient2d(ax, ay, bx, by, cx, cy)
    return o


@njit(**NJIT)
def _incircle(exact, ax, ay, bx, by, cx, cy, dx, dy):
    """Exact incircle, or the filtered one (NaN when undecided) in the sweep's fast mode."""
    literally(exact)
    if exact:
        return incircle(ax, ay, bx, by, cx, cy, dx, dy)
    return incircle_fast(ax, ay, bx, by, cx, cy, dx, dy)


@njit(**_INLINE)
def _add_triangle(tri, he, t, i0, i1, i2, a, b, c):
    tri[t] = i0
    tri[t + 1] = i1
    tri[t + 2] = i2
    link_halfedges(he, t, a)
    link_halfedges(he, t + 1, b)
    link_halfedges(he, t + 2, c)


@njit(**NJIT)
def _flip(a, b, tri, he, hull_tri):
    """Flip the diagonal of the quad formed by twin halfedges ``a`` and ``b``.

    Afterwards ``a``'s triangle is ``(p1, pl, p0)`` and ``b``'s is ``(p0, pr, p1)``, where
    ``a`` ran ``pr -> pl``, ``p0`` was opposite ``a`` and ``p1`` opposite ``b``; the new
    diagonal is the pair ``prev(a)``, ``prev(b)``.
    """
    a0 = a - a % 3
    b0 = b - b % 3
    ar = a0 + (a + 2) % 3
    bl = b0 + (b + 2) % 3
    p0 = tri[ar]
    p1 = tri[bl]
    tri[a] = p1
    tri[b] = p0
    hbl = he[bl]
    har = he[ar]
    link_halfedges(he, a, hbl)
    if hbl == -1:
        hull_tri[p1] = a
    link_halfedges(he, b, har)
    if har == -1:
        hull_tri[p0] = b
    link_halfedges(he, ar, bl)


@njit(**NJIT)
def _legalize(a, xs, ys, tri, he, hull_tri, stack, exact, flips):
    """Flip edges opposite the newest point until all are locally Delaunay.

    ``a`` is a halfedge whose triangle's opposite corner is the new point. Whenever a flip moves
    a hull halfedge to a new index, ``hull_tri`` (hull halfedge by start vertex) follows it.
    With ``exact`` False an edge whose filtered incircle cannot decide is left unflipped
    (always a valid triangulation) and the function returns False; :func:`_repair` then
    settles such edges exactly after the sweep. Returns True when every test was decided.
    ``flips[0]`` counts the flips.
    """
    literally(exact)
    sp = 0
    decided = True
    while True:
        b = he[a]
        if b == -1:
            if sp == 0:
                return decided
            sp -= 1
            a = stack[sp]
            continue
        a0 = a - a % 3
        b0 = b - b % 3
        al = a0 + (a + 1) % 3
        ar = a0 + (a + 2) % 3
        bl = b0 + (b + 2) % 3
        br = b0 + (b + 1) % 3
        p0 = tri[ar]
        pr = tri[a]
        pl = tri[al]
        p1 = tri[bl]
        v = _incircle(exact, xs[pr], ys[pr], xs[pl], ys[pl], xs[p0], ys[p0], xs[p1], ys[p1])
        if v > 0.0:
            # the flip of _flip, written out: numba does not inline the call in this loop
            tri[a] = p1
            tri[b] = p0
            hbl = he[bl]
            har = he[ar]
            link_halfedges(he, a, hbl)
            if hbl == -1:
                hull_tri[p1] = a
            link_halfedges(he, b, har)
            if har == -1:
                hull_tri[p0] = b
            link_halfedges(he, ar, bl)
            flips[0] += 1
            if sp >= stack.shape[0]:
                return decided  # cannot happen: the stack is sized to the number of halfedges
            stack[sp] = br
            sp += 1
        else:
            if v != v:
                decided = False  # undecided filter: left for _repair
            if sp == 0:
                return decided
            sp -= 1
            a = stack[sp]


@njit(**NJIT)
def _pseudo_angle(dx, dy):
    s = abs(dx) + abs(dy)
    if s == 0.0:
        return 0.0
    p = dx / s
    return (3.0 - p) / 4.0 if dy > 0.0 else (1.0 + p) / 4.0


@njit(**NJIT)
def _hash_key(x, y, cx, cy, size):
    k = int(math.floor(_pseudo_angle(x - cx, y - cy) * size))
    return k % size


@njit(**NJIT)
def _seed(xs, ys):
    """Seed triangle: point nearest the bbox centre, its nearest neighbour, smallest circle."""
    n = xs.shape[0]
    minx = xs.min()
    maxx = xs.max()
    miny = ys.min()
    maxy = ys.max()
    mx = 0.5 * (minx + maxx)
    my = 0.5 * (miny + maxy)
    i0 = 0
    best = np.inf
    for i in range(n):
        d = (xs[i] - mx) ** 2 + (ys[i] - my) ** 2
        if d < best:
            best = d
            i0 = i
    i1 = -1
    best = np.inf
    for i in range(n):
        if i == i0:
            continue
        d = (xs[i] - xs[i0]) ** 2 + (ys[i] - ys[i0]) ** 2
        if d < best:
            best = d
            i1 = i
    i2 = -1
    best = np.inf
    x0 = xs[i0]
    y0 = ys[i0]
    dx = xs[i1] - x0
    dy = ys[i1] - y0
    bl = dx * dx + dy * dy
    for i in range(n):
        if i == i0 or i == i1:
            continue
        ex = xs[i] - x0
        ey = ys[i] - y0
        left = dx * ey
        right = dy * ex
        det = left - right
        if not abs(det) > SEED_DET_RTOL * (abs(left) + abs(right)):
            # nearly collinear: never the smallest circle unless nothing else is left
            if i2 != -1 or orient2d(x0, y0, xs[i1], ys[i1], xs[i], ys[i]) == 0.0:
                continue
            det = orient2d(x0, y0, xs[i1], ys[i1], xs[i], ys[i])
        cl = ex * ex + ey * ey
        ux = (ey * bl - dy * cl) / (2.0 * det)
        uy = (dx * cl - ex * bl) / (2.0 * det)
        r = ux * ux + uy * uy
        if not r < best and i2 != -1:
            continue
        best = r
        i2 = i
    if i2 == -1:
        return i0, i1, -1
    if orient2d(xs[i0], ys[i0], xs[i1], ys[i1], xs[i2], ys[i2]) < 0.0:
        i1, i2 = i2, i1
    return i0, i1, i2


@njit(**NJIT)
def _locate(xs, ys, tri, he, ntri, start, px, py):
    """Visibility walk to the triangle containing ``p`` (in or on); brute force as a fallback."""
    t = start
    came = -1
    for _ in range(4 * ntri + 16):
        moved = False
        for j in range(3):
            e = 3 * t + (j + t) % 3
            if e == came:
                continue
            a = tri[e]
            b = tri[_next(e)]
            if orient2d(xs[a], ys[a], xs[b], ys[b], px, py) < 0.0:
                if he[e] == -1:
                    break
                came = he[e]
                t = he[e] // 3
                moved = True
                break
        if not moved:
            if _contains(xs, ys, tri, t, px, py):
                return t
            break
    for t in range(ntri):
        if _contains(xs, ys, tri, t, px, py):
            return t
    return -1


@njit(**NJIT)
def _contains(xs, ys, tri, t, px, py):
    for j in range(3):
        a = tri[3 * t + j]
        b = tri[3 * t + (j + 1) % 3]
        if orient2d(xs[a], ys[a], xs[b], ys[b], px, py) < 0.0:
            return False
    return True


@njit(**NJIT)
def _insert_in_triangle(k, t, xs, ys, tri, he, hull_tri, stack, flips, tcount):
    """1-to-3 split of triangle ``t`` by point ``k`` strictly inside it."""
    t0 = 3 * t
    a = tri[t0]
    b = tri[t0 + 1]
    c = tri[t0 + 2]
    h0 = he[t0]
    h1 = he[t0 + 1]
    h2 = he[t0 + 2]
    t1 = tcount
    t2 = tcount + 3
    _add_triangle(tri, he, t0, a, b, k, h0, -1, -1)
    _add_triangle(tri, he, t1, b, c, k, h1, -1, t0 + 1)
    _add_triangle(tri, he, t2, c, a, k, h2, t0 + 2, t1 + 1)
    if h0 == -1:
        hull_tri[a] = t0
    if h1 == -1:
        hull_tri[b] = t1
    if h2 == -1:
        hull_tri[c] = t2
    _legalize(t0, xs, ys, tri, he, hull_tri, stack, True, flips)
    _legalize(t1, xs, ys, tri, he, hull_tri, stack, True, flips)
    _legalize(t2, xs, ys, tri, he, hull_tri, stack, True, flips)
    return tcount + 6


@njit(**NJIT)
def _insert_on_edge(k, e, xs, ys, tri, he, hull_tri, hull_next, hull_prev, stack, flips, tcount):
    """Split halfedge ``e`` (and its twin, if any) at point ``k`` lying on it."""
    a = tri[e]
    b = tri[_next(e)]
    c = tri[_prev(e)]
    h_bc = he[_next(e)]
    h_ca = he[_prev(e)]
    f = he[e]
    ta = e - e % 3
    tb = tcount
    tcount += 3
    # (c, a, k) reuses the first triangle, (b, c, k) is new
    _add_triangle(tri, he, ta, c, a, k, h_ca, -1, -1)
    _add_triangle(tri, he, tb, b, c, k, h_bc, ta + 2, -1)
    if h_ca == -1:
        hull_tri[c] = ta
    if h_bc == -1:
        hull_tri[b] = tb
    if f == -1:
        hull_tri[a] = ta + 1
        hull_tri[k] = tb + 2
        hull_next[a] = k
        hull_prev[k] = a
        hull_next[k] = b
        hull_prev[b] = k
    else:
        d = tri[_prev(f)]
        h_ad = he[_next(f)]
        h_db = he[_prev(f)]
        tc = f - f % 3
        td = tcount
        tcount += 3
        _add_triangle(tri, he, tc, a, d, k, h_ad, -1, ta + 1)
        _add_triangle(tri, he, td, d, b, k, h_db, tb + 2, tc + 1)
        if h_ad == -1:
            hull_tri[a] = tc
        if h_db == -1:
            hull_tri[d] = td
        _legalize(tc, xs, ys, tri, he, hull_tri, stack, True, flips)
        _legalize(td, xs, ys, tri, he, hull_tri, stack, True, flips)
    _legalize(ta, xs, ys, tri, he, hull_tri, stack, True, flips)
    _legalize(tb, xs, ys, tri, he, hull_tri, stack, True, flips)
    return tcount


@njit(**NJIT)
def _sweep(xs, ys, max_flips):
    """Sweep points renumbered so that the seed is 0, 1, 2 and the rest follow in sweep order.

    Hull visibility uses the exact (adaptive) orientation, so the triangulation is always
    valid. Flips use the filtered incircle alone, which keeps the large exact-arithmetic code
    out of the hot loop: an edge it cannot decide stays unflipped and :func:`_repair` makes
    the result Delaunay afterwards. Returns ``(clean, tri, he, tcount, hull_tri, hull_next,
    hull_prev, hull_start, deferred, work)``; ``clean`` is True when every incircle test was
    decided, so the sweep did exactly what an exact one would have done. ``work`` is the larger
    of the flips made and the hull walk's steps; the sweep stops (unfinished) as soon as it
    passes ``max_flips``.
    """
    n = xs.shape[0]
    max_tri = max(2 * n - 5, 1)
    tri = np.full(3 * max_tri, -1, dtype=np.int32)
    he = np.full(3 * max_tri, -1, dtype=np.int32)
    stack = np.zeros(3 * max_tri + 16, dtype=np.int32)
    hull_prev = np.zeros(n, dtype=np.int32)
    hull_next = np.zeros(n, dtype=np.int32)
    hull_tri = np.full(n, -1, dtype=np.int32)
    hash_size = max(int(math.ceil(math.sqrt(n))), 1)
    hull_hash = np.full(hash_size, -1, dtype=np.int32)
    deferred = np.zeros(n, dtype=np.int32)
    n_def = 0
    flips = np.zeros(2, dtype=np.int64)  # flips, hull walk steps

    cx, cy = circumcenter(xs[0], ys[0], xs[1], ys[1], xs[2], ys[2])
    hull_next[0] = 1
    hull_next[1] = 2
    hull_next[2] = 0
    hull_prev[0] = 2
    hull_prev[1] = 0
    hull_prev[2] = 1
    hull_tri[0] = 0
    hull_tri[1] = 1
    hull_tri[2] = 2
    for v in range(3):
        hull_hash[_hash_key(xs[v], ys[v], cx, cy, hash_size)] = v
    _add_triangle(tri, he, 0, 0, 1, 2, -1, -1, -1)
    tcount = 3
    hull_start = 0
    clean = True

    for k in range(3, n):
        if flips[0] > max_flips or flips[1] > max_flips:
            break
        x = xs[k]
        y = ys[k]
        key = _hash_key(x, y, cx, cy, hash_size)
        start = 0
        for j in range(hash_size):
            start = hull_hash[(key + j) % hash_size]
            if start != -1 and start != hull_next[start]:
                break
        start = hull_prev[start]
        e = start
        while True:
            flips[1] += 1
            q = hull_next[e]
            if _orient(xs[e], ys[e], xs[q], ys[q], x, y) < 0.0:
                break
            e = q
            if e == start:
                e = -1
                break
        if e == -1:
            deferred[n_def] = k
            n_def += 1
            continue

        q = hull_next[e]
        t = tcount
        _add_triangle(tri, he, t, e, k, q, -1, -1, hull_tri[e])
        tcount += 3
        hull_tri[e] = t
        hull_tri[k] = t + 1
        clean &= _legalize(t + 2, xs, ys, tri, he, hull_tri, stack, False, flips)

        nn = q
        while True:
            q = hull_next[nn]
            if not _orient(xs[nn], ys[nn], xs[q], ys[q], x, y) < 0.0:
                break
            t = tcount
            _add_triangle(tri, he, t, nn, k, q, hull_tri[k], -1, hull_tri[nn])
            tcount += 3
            hull_tri[k] = t + 1
            clean &= _legalize(t + 2, xs, ys, tri, he, hull_tri, stack, False, flips)
            hull_next[nn] = nn
            nn = q

        if e == start:
            while True:
                q = hull_prev[e]
                if not _orient(xs[q], ys[q], xs[e], ys[e], x, y) < 0.0:
                    break
                t = tcount
                _add_triangle(tri, he, t, q, k, e, -1, hull_tri[e], hull_tri[q])
                tcount += 3
                hull_tri[q] = t
                clean &= _legalize(t + 2, xs, ys, tri, he, hull_tri, stack, False, flips)
                hull_next[e] = e
                e = q

        hull_start = e
        hull_prev[k] = e
        hull_next[e] = k
        hull_prev[nn] = k
        hull_next[k] = nn
        hull_hash[_hash_key(x, y, cx, cy, hash_size)] = k
        hull_hash[_hash_key(xs[e], ys[e], cx, cy, hash_size)] = e

    deferred = deferred[:n_def]
    work = max(flips[0], flips[1])
    return clean, tri, he, tcount, hull_tri, hull_next, hull_prev, hull_start, deferred, work


@njit(**NJIT_PARALLEL)
def _suspect_edges(xs, ys, tri, he, tcount):
    """Halfedges (one per interior edge) that are not locally Delaunay (exact incircle).

    The filter settles most edges; the exact test runs, in parallel, only where it cannot.
    """
    flag = np.zeros(tcount, dtype=np.bool_)
    for e in prange(tcount):
        f = he[e]
        if f < e:
            continue  # hull edge, or the twin handles it
        p = tri[e]
        q = tri[_next(e)]
        r = tri[_prev(e)]
        s = tri[_prev(f)]
        v = incircle_fast(xs[p], ys[p], xs[q], ys[q], xs[r], ys[r], xs[s], ys[s])
        if v != v:
            v = incircle(xs[p], ys[p], xs[q], ys[q], xs[r], ys[r], xs[s], ys[s])
        if v > 0.0:
            flag[e] = True
    return np.flatnonzero(flag).astype(np.int32)


@njit(**NJIT)
def _repair(xs, ys, tri, he, hull_tri, suspects):
    """Lawson flips with exact incircle from the given edges until every edge is legal.

    Any triangulation reaches the Delaunay one this way; started from all illegal edges
    (:func:`_suspect_edges`) it ends Delaunay. Returns the number of flips.
    """
    stack = np.zeros(suspects.shape[0] + tri.shape[0] + 16, dtype=np.int32)
    sp = suspects.shape[0]
    stack[:sp] = suspects
    flips = 0
    while sp > 0:
        sp -= 1
        a = stack[sp]
        b = he[a]
        if b == -1:
            continue
        pr = tri[a]
        pl = tri[_next(a)]
        p0 = tri[_prev(a)]
        p1 = tri[_prev(b)]
        if incircle(xs[pr], ys[pr], xs[pl], ys[pl], xs[p0], ys[p0], xs[p1], ys[p1]) > 0.0:
            _flip(a, b, tri, he, hull_tri)
            flips += 1
            if sp + 4 > stack.shape[0]:
                grown = np.zeros(2 * stack.shape[0], dtype=np.int32)
                grown[:sp] = stack[:sp]
                stack = grown
            # the quad's four outer edges: a, next(a), b, next(b)
            stack[sp] = a
            stack[sp + 1] = _next(a)
            stack[sp + 2] = b
            stack[sp + 3] = _next(b)
            sp += 4
    return flips


@njit(**NJIT)
def _insert_deferred(xs, ys, tri, he, tcount, hull_tri, hull_next, hull_prev, deferred):
    """Insert points the sweep could not attach to the hull (they lie inside or on it).

    Returns the new triangle count and the number of flips made.
    """
    stack = np.zeros(tri.shape[0] + 16, dtype=np.int32)
    flips = np.zeros(1, dtype=np.int64)
    for j in range(deferred.shape[0]):
        k = deferred[j]
        t = _locate(xs, ys, tri, he, tcount // 3, (tcount // 3) - 1, xs[k], ys[k])
        if t == -1:
            continue  # unreachable for distinct points inside the hull
        zero = np.int64(-1)  # not a literal: numba would compile _insert_on_edge for it
        nzero = 0
        for m in range(3):
            e = 3 * t + m
            a = tri[e]
            b = tri[_next(e)]
            if orient2d(xs[a], ys[a], xs[b], ys[b], xs[k], ys[k]) == 0.0:
                zero = e
                nzero += 1
        if nzero == 0:
            tcount = _insert_in_triangle(k, t, xs, ys, tri, he, hull_tri, stack, flips, tcount)
        elif nzero == 1:
            tcount = _insert_on_edge(
                k, zero, xs, ys, tri, he, hull_tri, hull_next, hull_prev, stack, flips, tcount
            )
        # nzero == 2 would mean a duplicate point, which the engine removes beforehand
    return tcount, flips[0]


@njit(**NJIT)
def _hull_array(hull_next, start):
    h = 1
    v = hull_next[start]
    while v != start:
        h += 1
        v = hull_next[v]
    hull = np.zeros(h, dtype=np.int32)
    v = start
    for j in range(h):
        hull[j] = v
        v = hull_next[v]
    return hull


@njit(**NJIT_PARALLEL)
def _sweep_keys(xs, ys, i0, i1, i2):
    """Squared distance of every point from the seed's circumcentre; the seed gets -3, -2, -1."""
    n = xs.shape[0]
    cx, cy = circumcenter(xs[i0], ys[i0], xs[i1], ys[i1], xs[i2], ys[i2])
    d = np.zeros(n)
    for i in prange(n):
        d[i] = (xs[i] - cx) ** 2 + (ys[i] - cy) ** 2
    d[i0] = -3.0
    d[i1] = -2.0
    d[i2] = -1.0
    return d


def _sweep_order(xs, ys, i0, i1, i2):
    """Seed first, then the other points by distance from the seed's circumcentre.

    numpy's argsort (vectorised quicksort) beats a numba bucket sort by 4x at 1M points; the
    order of ties does not matter to the sweep.
    """
    return np.argsort(_sweep_keys(xs, ys, i0, i1, i2))


@njit(**NJIT)
def _gather(xs, ys, order):
    """Points in sweep order, x and y interleaved: one cache line holds both coordinates."""
    n = order.shape[0]
    sxy = np.zeros((n, 2))
    for i in range(n):
        sxy[i, 0] = xs[order[i]]
        sxy[i, 1] = ys[order[i]]
    return sxy


@njit(**NJIT)
def _relabel(tri, tcount, hull, order):
    out = np.zeros(tcount, dtype=np.int32)
    for j in range(tcount):
        out[j] = order[tri[j]]
    for j in range(hull.shape[0]):
        hull[j] = order[hull[j]]
    return out


@njit(**NJIT)
def _hull_links(tri, he, tcount, hull, n):
    """``hull_tri``, ``hull_next``, ``hull_prev`` (size ``n``) of a triangulation and its hull."""
    hull_tri = np.full(n, -1, dtype=np.int32)
    hull_next = np.zeros(n, dtype=np.int32)
    hull_prev = np.zeros(n, dtype=np.int32)
    for e in range(tcount):
        if he[e] == -1:
            hull_tri[tri[e]] = e
    h = hull.shape[0]
    for j in range(h):
        hull_next[hull[j]] = hull[(j + 1) % h]
        hull_prev[hull[(j + 1) % h]] = hull[j]
    return hull_tri, hull_next, hull_prev


def _triangulate_brio(sx, sy, order):
    """Fallback of :func:`triangulate_sorted` when the sweep makes too many flips.

    The exact convex hull's vertices are swept (without a budget), then every other point is
    located and inserted (1-to-3 or edge split, exact Lawson flips) in a biased randomised
    order, whose expected number of flips is linear whatever the input. Points are renumbered
    hull first, then in insertion order; returns what :func:`triangulate_sorted` does and the
    number of flips made.
    """
    n = sx.shape[0]
    hv = convex_hull(sx, sy, np.lexsort((sy, sx)))
    inner = np.ones(n, dtype=np.bool_)
    inner[hv] = False
    rest = brio_order(sx, sy, np.flatnonzero(inner))
    h_order, _, _, htri, hhe, hhull, _ = triangulate_sorted(sx[hv], sy[hv], max_flips=-1)
    new = np.concatenate([hv[h_order], rest])
    gxy = _gather(sx, sy, new)
    gx = gxy[:, 0]
    gy = gxy[:, 1]
    max_tri = max(2 * n - 5, 1)
    tri = np.full(3 * max_tri, -1, dtype=np.int32)
    he = np.full(3 * max_tri, -1, dtype=np.int32)
    tcount = htri.shape[0]
    tri[:tcount] = htri
    he[:tcount] = hhe
    hull_tri, hull_next, hull_prev = _hull_links(tri, he, tcount, hhull, n)
    todo = np.arange(hv.shape[0], n, dtype=np.int32)
    tcount, flips = _insert_deferred(gx, gy, tri, he, tcount, hull_tri, hull_next, hull_prev, todo)
    hull = _hull_array(hull_next, hhull[0])
    return (order[new], gx, gy, tri[:tcount], he[:tcount], hull, True), flips


def triangulate_sorted(xs: np.ndarray, ys: np.ndarray, *, max_flips: int | None = None):
    """Triangulate distinct points, returning the result in sweep order.

    Returns ``(order, sx, sy, tri, he, hull, ok)``: point ``k`` of the sweep-ordered arrays
    ``sx, sy`` is input point ``order[k]``; ``tri`` (flat), ``he`` and ``hull`` use sweep
    indices. Working in sweep order keeps each point's triangles close together in memory,
    which matters for everything that walks around points afterwards. ``ok`` is False when
    all points are collinear (then only ``order`` is meaningful). A sweep that makes more than
    ``max_flips`` flips (default: the budget above; -1: no limit) is abandoned for
    :func:`_triangulate_brio`, and then the order is the hull first, then insertion order.
    """
    n = xs.shape[0]
    empty = np.zeros(0, dtype=np.int32)
    if n < 3:
        return np.arange(n), xs, ys, empty, empty, empty, False
    i0, i1, i2 = _seed(xs, ys)
    if i2 == -1:
        return np.arange(n), xs, ys, empty, empty, empty, False
    order = _sweep_order(xs, ys, i0, i1, i2)
    sxy = _gather(xs, ys, order)
    sx = sxy[:, 0]  # strided views
    sy = sxy[:, 1]
    if max_flips is None:
        max_flips = FLIP_BUDGET_PER_POINT * n + FLIP_BUDGET_BASE
    elif max_flips < 0:
        max_flips = np.iinfo(np.int64).max
    swept = _sweep(sx, sy, max_flips)
    clean, tri, he, tcount, hull_tri, hull_next, hull_prev, hull_start, deferred, flips = swept
    if flips > max_flips:
        return _triangulate_brio(sx, sy, order)[0]
    if not clean:
        suspects = _suspect_edges(sx, sy, tri, he, tcount)
        if suspects.shape[0]:
            _repair(sx, sy, tri, he, hull_tri, suspects)
    if deferred.shape[0]:
        tcount, _ = _insert_deferred(
            sx, sy, tri, he, tcount, hull_tri, hull_next, hull_prev, deferred
        )
    hull = _hull_array(hull_next, hull_start)
    return order, sx, sy, tri[:tcount], he[:tcount], hull, True


def triangulate(xs: np.ndarray, ys: np.ndarray):
    """Delaunay triangulation of distinct points given as coordinate arrays.

    Returns ``(triangles (3t,) int32, halfedges (3t,) int32, hull (h,) int32, ok)`` in input
    indices; ``ok`` is False when all points are collinear (no triangles; the caller builds
    the hull).
    """
    order, _, _, tri, he, hull, ok = triangulate_sorted(xs, ys)
    if not ok:
        return tri, he, hull, False
    tri_out = _relabel(tri, tri.shape[0], hull, order)
    return tri_out, he.copy(), hull, True
