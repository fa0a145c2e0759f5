"""Fortune's sweep-line algorithm, returning the Delaunay dual of the Voronoi diagram it sweeps.

Conventions. The sweep line ``y = L`` moves upward; sites are processed in ``(y, x)`` order.
The beach line is the sequence of parabolic arcs, left to right; each arc is a node of a
treap (random priorities, in-order = left to right, so its expected depth is O(log m)) and
of a doubly linked list for O(1) neighbours. Breakpoints are never stored: the search for
the arc above a new site decides on which side of each breakpoint the site lies at its
``L``, exactly (a float filter, expansions when it cannot decide; :func:`_right_of`).

Three consecutive arcs ``a, b, c`` (distinct sites ``a != c``) have converging breakpoints
exactly when ``orient2d(a, b, c) > 0`` (exact); their circle event is keyed by the top of
the circumcircle, ``cy + r``, in an indexed binary heap (one event per middle arc, removed
when the triple changes). Site events come from the pre-sorted site order. When a circle
event fires, arc ``b`` vanishes and the counter-clockwise triangle ``(a, b, c)`` is emitted:
one Voronoi vertex, one Delaunay triangle.

Halfedges are built during the sweep: every breakpoint carries an *edge record* (one per
Delaunay edge). The first triangle closing an edge parks its halfedge in the record, the
second links the pair; a third would be a topological error, which is counted (``bad``)
and must stay zero. The sites of the lowest horizontal line start the beach line together
(their breakpoints are vertical). Floating-point event order can only misplace events among
(nearly) cocircular sites, so a final Lawson pass with the exact ``incircle`` makes the
result exactly Delaunay; its flip count is ~0 on ordinary input.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..config import NJIT
from .delaunay import link_halfedges
from .expansion import two_diff
from .predicates import incircle, incircle_fast, orient2d, parabola_gap
from .vertex import center_offset

#: Small helpers of the sweep are inlined at the numba level: as separate functions every call
#: would pay a reference-count round trip on each array argument.
_INLINE = {**NJIT, "inline": "always"}
#: The sweep's event loop runs without numba's reference counting (see :func:`_sweep_loop`).
_NO_NRT = {**NJIT, "_nrt": False}

# stats slots returned by the debug helper
_S_FLIPS = 0
_S_BAD = 1
_S_MAX_BEACH = 2
_S_CIRCLE = 3
_S_TRI_SWEEP = 4
_NSTATS = 5


# ---------------------------------------------------------------------------------------------
# site order
# ---------------------------------------------------------------------------------------------


@njit(**NJIT)
def _sort_ties(xs, ys, order):
    """Within runs of equal ``y`` in ``order`` (sorted by ``y``), sort by ``x``, in place."""
    n = order.shape[0]
    i = 0
    while i < n:
        y = ys[order[i]]
        j = i + 1
        while j < n and ys[order[j]] == y:
            j += 1
        if j - i > 1:
            seg = order[i:j].copy()
            order[i:j] = seg[np.argsort(xs[seg])]
        i = j


def _site_order(xs, ys):
    """Indices sorted by ``(y, x)``: numpy's (vectorised) argsort on ``y``, then the ties."""
    order = np.argsort(ys)
    _sort_ties(xs, ys, order)
    return order


# ---------------------------------------------------------------------------------------------
# geometry in floating point (only used to order events and locate arcs)
# ---------------------------------------------------------------------------------------------


@njit(**NJIT)
def _breakpoint(px, py, qx, qy, sweep):
    """X of the breakpoint between the arc of ``p`` (left) and the arc of ``q`` (right).

    Both parabolas are taken at the sweep line ``y = sweep >= py, qy``. With
    ``hp = sweep - py``, ``hq = sweep - qy``, ``dx = qx - px`` and ``a = qy - py`` the
    offset ``u = x - px`` solves ``a u^2 - 2 hp dx u + hp (dx^2 - a hq) = 0`` and the
    breakpoint is the root ``(hp dx - sqrt(hp hq |pq|^2)) / a``, evaluated in the form that
    avoids cancellation.
    """
    if py == qy:
        return 0.5 * (px + qx)
    hp = sweep - py
    if hp <= 0.0:
        return px
    hq = sweep - qy
    if hq <= 0.0:
        return qx
    dx = qx - px
    a = qy - py
    s = math.sqrt(hp * hq * (dx * dx + a * a))
    if dx > 0.0:
        return px + hp * (dx * dx - hq * a) / (hp * dx + s)
    return px + (hp * dx - s) / a


@njit(**_INLINE)
def _right_of(sx, px, py, qx, qy, sweep):
    """``sx > _breakpoint(px, py, qx, qy, sweep)``, decided exactly.

    With ``u = sx - px`` the breakpoint is the root ``u*`` of
    ``f(u) = a u^2 - 2 hp dx u + hp (dx^2 - a hq)`` named in :func:`_breakpoint`; the other
    root lies beyond the vertex ``hp dx / a``, so the sign of ``f`` and the side of the
    vertex decide. Both are taken exactly: the side of the vertex is
    ``orient2d(p, q, (sx, sweep))`` and the sign of ``f`` is ``parabola_gap``'s (both
    parabolas' heights above ``sx`` compared). Sites a few ulps apart otherwise put a new
    site into the wrong arc, and the sweep's triangulation leaves part of the hull uncovered.
    """
    if py == qy:
        # sx against the midpoint, without rounding px + qx: float differences are
        # monotone, so only equal rounded differences need their exact remainders
        lo, lo_err = two_diff(sx, px)
        hi, hi_err = two_diff(qx, sx)
        if lo != hi:
            return lo > hi
        return lo_err > hi_err
    hp = sweep - py
    if hp <= 0.0:
        return sx > px
    hq = sweep - qy
    if hq <= 0.0:
        return sx > qx
    side = orient2d(px, py, qx, qy, sx, sweep)  # hp dx - a u, sign-exact
    if qy > py:
        if side <= 0.0:
            return True
    elif side <= 0.0:
        return False
    return parabola_gap(sx, px, py, qx, qy, sweep) < 0.0


@njit(**_INLINE)
def _event_y(ax, ay, bx, by, cx, cy):
    """Top of the circumcircle of the counter-clockwise ``a, b, c``; +inf when it overflows.

    The circle comes from the one vertex routine (``kernels/vertex.center_offset``): its
    centre as an offset ``u`` from the point opposite the longest edge, a point on the
    circle. When the centre lies below that point the top is ``oy + ux^2 / (r - uy)``
    rather than ``oy + uy + r``, which would cancel catastrophically for the huge circles of
    nearly collinear triples.
    """
    _, oy, ux, uy = center_offset(ax, ay, 0.0, bx, by, 0.0, cx, cy, 0.0)
    r = math.sqrt(ux * ux + uy * uy)
    if uy >= 0.0:
        y = oy + (uy + r)
    else:
        y = oy + ux * ux / (r - uy)
    if y != y or y == np.inf or y == -np.inf:
        return np.inf
    return y


# ---------------------------------------------------------------------------------------------
# indexed binary heap of circle events (one per middle arc; key[node] is its event y)
# ---------------------------------------------------------------------------------------------


@njit(**_INLINE)
def _sift_up(heap, hpos, key, i):
    node = heap[i]
    k = key[node]
    while i > 0:
        par = (i - 1) >> 1
        pn = heap[par]
        if key[pn] <= k:
            break
        heap[i] = pn
        hpos[pn] = i
        i = par
    heap[i] = node
    hpos[node] = i


@njit(**_INLINE)
def _sift_down(heap, hpos, key, size, i):
    node = heap[i]
    k = key[node]
    while True:
        c = 2 * i + 1
        if c >= size:
            break
        if c + 1 < size and key[heap[c + 1]] < key[heap[c]]:
            c += 1
        cn = heap[c]
        if key[cn] >= k:
            break
        heap[i] = cn
        hpos[cn] = i
        i = c
    heap[i] = node
    hpos[node] = i


@njit(**_INLINE)
def _heap_remove(heap, hpos, key, size, node):
    """Remove ``node``'s event if it has one; returns the new heap size."""
    i = hpos[node]
    if i < 0:
        return size
    hpos[node] = -1
    size -= 1
    if i != size:
        last = heap[size]
        heap[i] = last
        hpos[last] = i
        _sift_down(heap, hpos, key, size, i)
        if hpos[last] == i:
            _sift_up(heap, hpos, key, i)
    return size


# ---------------------------------------------------------------------------------------------
# beach line: treap with implicit (in-order) keys and parent pointers
# ---------------------------------------------------------------------------------------------


@njit(**_INLINE)
def _rotate_up(x, left, right, parent, root):
    """Rotate ``x`` above its parent; returns the (possibly new) root."""
    p = parent[x]
    g = parent[p]
    if left[p] == x:
        b = right[x]
        left[p] = b
        right[x] = p
    else:
        b = left[x]
        right[p] = b
        left[x] = p
    if b != -1:
        parent[b] = p
    parent[p] = x
    parent[x] = g
    if g == -1:
        return x
    if left[g] == p:
        left[g] = x
    else:
        right[g] = x
    return root


@njit(**_INLINE)
def _insert_after(v, x, left, right, parent, tprio, root):
    """Insert leaf ``x`` right after node ``v`` in order, then restore the heap on priorities."""
    left[x] = -1
    right[x] = -1
    u = right[v]
    if u == -1:
        right[v] = x
        parent[x] = v
    else:
        while left[u] != -1:
            u = left[u]
        left[u] = x
        parent[x] = u
    while parent[x] != -1 and tprio[x] < tprio[parent[x]]:
        root = _rotate_up(x, left, right, parent, root)
    return root


@njit(**_INLINE)
def _delete(x, left, right, parent, tprio, root):
    """Remove node ``x`` from the treap; returns the new root."""
    while left[x] != -1 and right[x] != -1:
        lc = left[x]
        rc = right[x]
        c = lc if tprio[lc] < tprio[rc] else rc
        root = _rotate_up(c, left, right, parent, root)
    c = left[x] if left[x] != -1 else right[x]
    p = parent[x]
    if c != -1:
        parent[c] = p
    if p == -1:
        root = c
    elif left[p] == x:
        left[p] = c
    else:
        right[p] = c
    left[x] = -1
    right[x] = -1
    parent[x] = -1
    return root


@njit(**_INLINE)
def _locate(root, sx, sweep, left, right, nxt, arcx, arcy):
    """Leftmost arc whose right breakpoint is at or right of ``sx`` (lower-bound descent)."""
    v = root
    cand = -1
    while v != -1:
        w = nxt[v]
        if w == -1:
            cand = v
            v = left[v]
            continue
        if _right_of(sx, arcx[v], arcy[v], arcx[w], arcy[w], sweep):
            v = right[v]
        else:
            cand = v
            v = left[v]
    return cand


# ---------------------------------------------------------------------------------------------
# the sweep
# ---------------------------------------------------------------------------------------------


@njit(**_INLINE)
def _push_event(node, prv, nxt, site, arcx, arcy, key, heap, hpos, size):
    """Schedule the circle event of the triple centred on ``node`` if its breakpoints converge."""
    a = prv[node]
    c = nxt[node]
    if a == -1 or c == -1:
        return size
    if site[a] == site[c]:
        return size
    ax = arcx[a]
    ay = arcy[a]
    bx = arcx[node]
    by = arcy[node]
    cx = arcx[c]
    cy = arcy[c]
    # orient2d's value is the leading component of its exact expansion when the filter fails,
    # so it is correct to full relative precision, which the circumcentre below needs
    det = orient2d(ax, ay, bx, by, cx, cy)
    if det <= 0.0:
        return size
    key[node] = _event_y(ax, ay, bx, by, cx, cy)
    heap[size] = node
    _sift_up(heap, hpos, key, size)
    return size + 1


@njit(**_INLINE)
def _alloc(free, nfree, nnodes, tprio, hpos, rng):
    """A fresh arc node (recycled when possible) with a new random treap priority."""
    if nfree > 0:
        nfree -= 1
        w = free[nfree]
    else:
        w = nnodes
        nnodes += 1
    rng ^= rng << np.uint64(13)
    rng ^= rng >> np.uint64(7)
    rng ^= rng << np.uint64(17)
    tprio[w] = np.uint32(rng >> np.uint64(32))
    hpos[w] = -1
    return w, nfree, nnodes, rng


@njit(**_INLINE)
def _attach(rec_he, rec, h, he, stats):
    """Give halfedge ``h`` to edge record ``rec``: park it, or link it with the parked twin."""
    o = rec_he[rec]
    if o == -1:
        rec_he[rec] = h
    elif o >= 0:
        he[h] = o
        he[o] = h
        rec_he[rec] = -2
    else:
        stats[_S_BAD] += 1  # a third triangle on one Delaunay edge: never happens


@njit(**NJIT)
def _sweep(xs, ys, order, stats):
    """Run Fortune's sweep; returns ``(tri (3t,), he (3t,))`` with halfedges linked."""
    n = order.shape[0]
    cap = 2 * n + 2
    left = np.full(cap, -1, dtype=np.int32)
    right = np.full(cap, -1, dtype=np.int32)
    parent = np.full(cap, -1, dtype=np.int32)
    prv = np.full(cap, -1, dtype=np.int32)
    nxt = np.full(cap, -1, dtype=np.int32)
    site = np.zeros(cap, dtype=np.int32)
    arcx = np.zeros(cap)  # the arc's site coordinates, next to the tree (one load less)
    arcy = np.zeros(cap)
    edge = np.full(cap, -1, dtype=np.int32)
    tprio = np.zeros(cap, dtype=np.uint32)
    hpos = np.full(cap, -1, dtype=np.int32)
    heap = np.zeros(cap, dtype=np.int32)
    key = np.zeros(cap, dtype=np.float64)
    free = np.zeros(cap, dtype=np.int32)
    tmax = max(2 * n - 4, 1)
    tri = np.zeros(3 * tmax, dtype=np.int32)
    he = np.full(3 * tmax, -1, dtype=np.int32)
    rec_he = np.full(3 * n + 3, -1, dtype=np.int32)
    tree = (left, right, parent, prv, nxt, site, edge, tprio, hpos, heap, free)
    ntri = _sweep_loop(xs, ys, order, stats, tree, arcx, arcy, key, tri, he, rec_he)
    return tri[: 3 * ntri], he[: 3 * ntri]


@njit(**_NO_NRT)
def _sweep_loop(xs, ys, order, stats, tree, arcx, arcy, key, tri, he, rec_he):
    """The event loop over preallocated arrays; returns the number of triangles.

    Compiled without reference counting: the small helpers inlined into the loop take a
    dozen arrays each, and their atomic reference-count updates cost as much as the rest
    of the sweep. Nothing here allocates, so nothing needs counting.
    """
    left, right, parent, prv, nxt, site, edge, tprio, hpos, heap, free = tree
    n = order.shape[0]
    nfree = 0
    nnodes = 0
    nrec = 0
    ntri = 0
    size = 0
    rng = np.uint64(88172645463325252)
    root = -1
    beach = 0

    # the lowest sites: one arc each, left to right, separated by vertical breakpoints
    y0 = ys[order[0]]
    i = 0
    last = -1
    while i < n and ys[order[i]] == y0:
        v, nfree, nnodes, rng = _alloc(free, nfree, nnodes, tprio, hpos, rng)
        site[v] = order[i]
        arcx[v] = xs[order[i]]
        arcy[v] = ys[order[i]]
        if last == -1:
            root = v
        else:
            prv[v] = last
            nxt[last] = v
            edge[last] = nrec
            nrec += 1
            root = _insert_after(last, v, left, right, parent, tprio, root)
        last = v
        beach += 1
        i += 1
    stats[_S_MAX_BEACH] = beach

    while True:
        if size > 0 and (i >= n or key[heap[0]] <= ys[order[i]]):
            # circle event: arc b vanishes, triangle (a, b, c) is born
            b = heap[0]
            size = _heap_remove(heap, hpos, key, size, b)
            a = prv[b]
            c = nxt[b]
            t3 = 3 * ntri
            tri[t3] = site[a]
            tri[t3 + 1] = site[b]
            tri[t3 + 2] = site[c]
            ntri += 1
            _attach(rec_he, edge[a], t3, he, stats)
            _attach(rec_he, edge[b], t3 + 1, he, stats)
            rec_he[nrec] = t3 + 2
            edge[a] = nrec
            nrec += 1
            nxt[a] = c
            prv[c] = a
            root = _delete(b, left, right, parent, tprio, root)
            free[nfree] = b
            nfree += 1
            beach -= 1
            stats[_S_CIRCLE] += 1
            size = _heap_remove(heap, hpos, key, size, a)
            size = _heap_remove(heap, hpos, key, size, c)
            size = _push_event(a, prv, nxt, site, arcx, arcy, key, heap, hpos, size)
            size = _push_event(c, prv, nxt, site, arcx, arcy, key, heap, hpos, size)
        elif i < n:
            # site event: split the arc above the site into p, s, p
            s = order[i]
            i += 1
            sx = xs[s]
            v = _locate(root, sx, ys[s], left, right, nxt, arcx, arcy)
            size = _heap_remove(heap, hpos, key, size, v)
            ns, nfree, nnodes, rng = _alloc(free, nfree, nnodes, tprio, hpos, rng)
            v2, nfree, nnodes, rng = _alloc(free, nfree, nnodes, tprio, hpos, rng)
            site[ns] = s
            site[v2] = site[v]
            arcx[ns] = sx
            arcy[ns] = ys[s]
            arcx[v2] = arcx[v]
            arcy[v2] = arcy[v]
            edge[v2] = edge[v]
            edge[v] = nrec
            edge[ns] = nrec
            nrec += 1
            after = nxt[v]
            nxt[v] = ns
            prv[ns] = v
            nxt[ns] = v2
            prv[v2] = ns
            nxt[v2] = after
            if after != -1:
                prv[after] = v2
            root = _insert_after(v, ns, left, right, parent, tprio, root)
            root = _insert_after(ns, v2, left, right, parent, tprio, root)
            beach += 2
            if beach > stats[_S_MAX_BEACH]:
                stats[_S_MAX_BEACH] = beach
            size = _push_event(v, prv, nxt, site, arcx, arcy, key, heap, hpos, size)
            size = _push_event(v2, prv, nxt, site, arcx, arcy, key, heap, hpos, size)
        else:
            break
    stats[_S_TRI_SWEEP] = ntri
    return ntri


# ---------------------------------------------------------------------------------------------
# exact Delaunay repair (Lawson flips)
# ---------------------------------------------------------------------------------------------


@njit(**NJIT)
def _legalize_all(xs, ys, tri, he, stats):
    """Flip every edge whose opposite vertex lies strictly inside the neighbour's circumcircle.

    A stack of halfedges to check (each at most once at a time); a flip re-queues the four
    outer edges of its quadrilateral. Strict ``incircle`` makes cocircular input terminate.
    """
    m = tri.shape[0]
    stack = np.zeros(m + 1, dtype=np.int32)
    queued = np.zeros(m, dtype=np.uint8)
    sp = 0
    for e in range(m):
        if he[e] > e:
            stack[sp] = e
            sp += 1
            queued[e] = 1
    limit = 10 * m + 1000  # a valid triangulation needs far fewer; guards a broken one
    flips = 0
    while sp > 0:
        sp -= 1
        a = stack[sp]
        queued[a] = 0
        b = he[a]
        if b == -1:
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
        v = incircle_fast(xs[p0], ys[p0], xs[pr], ys[pr], xs[pl], ys[pl], xs[p1], ys[p1])
        if v != v:
            v = incircle(xs[p0], ys[p0], xs[pr], ys[pr], xs[pl], ys[pl], xs[p1], ys[p1])
        if v <= 0.0 or flips >= limit:
            continue
        flips += 1
        tri[a] = p1
        tri[b] = p0
        hbl = he[bl]
        har = he[ar]
        link_halfedges(he, a, hbl)
        link_halfedges(he, b, har)
        link_halfedges(he, ar, bl)
        for k in range(4):
            e = a if k == 0 else (al if k == 1 else (b if k == 2 else br))
            if queued[e] == 0 and he[e] != -1:
                queued[e] = 1
                stack[sp] = e
                sp += 1
    stats[_S_FLIPS] = flips


def _fortune(xs, ys, stats):
    """Triangles (input numbering) and halfedges of the sweep over ``xs, ys``."""
    order = _site_order(xs, ys)
    _compile_callees()
    tri, he = _fortune_sorted(
        np.ascontiguousarray(xs[order]), np.ascontiguousarray(ys[order]), stats
    )
    return order[tri].astype(np.int32), he


def _prepare(points: np.ndarray) -> np.ndarray:
    pts = np.ascontiguousarray(points, dtype=np.float64)
    if pts.ndim != 2 or pts.shape[1] != 2:
        raise ValueError(f"points must have shape (n, 2), got {pts.shape}")
    return pts


def _exact_shift(v: np.ndarray) -> float:
    """A shift ``c`` with ``v - c`` exact for every value (0.0 when none is found).

    Moving the points next to the origin changes no predicate (exact translation) but makes
    the floating-point event keys resolve features far below the coordinates' own ulp.
    """
    lo = float(v.min())
    hi = float(v.max())
    for c in (0.5 * (lo + hi), lo, hi):
        t = v - c
        bv = v - t
        err = (v - (t + bv)) + (bv - c)  # Knuth's two-diff error of v - c
        if not np.any(err):
            return c
    return 0.0


def _normalised(xs: np.ndarray, ys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Coordinate arrays translated and scaled by a power of two, both exactly."""
    xs = xs - _exact_shift(xs)
    ys = ys - _exact_shift(ys)
    m = max(float(np.abs(xs).max()), float(np.abs(ys).max()))
    if m > 0.0 and np.isfinite(m):
        s = 2.0 ** -math.frexp(m)[1]
        sx = xs * s
        sy = ys * s
        if np.array_equal(sx / s, xs) and np.array_equal(sy / s, ys):
            xs, ys = sx, sy
    return np.ascontiguousarray(xs), np.ascontiguousarray(ys)


@njit(**NJIT)
def _fortune_sorted(xs, ys, stats):
    """The sweep and its exact repair on sites already in ``(y, x)`` order."""
    order = np.arange(xs.shape[0])
    tri, he = _sweep(xs, ys, order, stats)
    _legalize_all(xs, ys, tri, he, stats)
    return tri, he


def fortune_delaunay(xs: np.ndarray, ys: np.ndarray):
    """Delaunay triangulation of distinct sites by the sweep, in sweep order.

    The engine's entry point: it feeds the result to the same cell builder as the default
    algorithm, so the Voronoi cells are the dual of the sweep's triangulation.

    Parameters
    ----------
    xs, ys : (u,) float64
        Distinct sites.

    Returns
    -------
    order : (u,) int64
        ``order[k]`` is the input index of sweep site ``k`` (sites sorted by ``(y, x)``).
    sx, sy : (u,) float64
        The sites in sweep order (``xs[order]``, ``ys[order]``).
    tri, he : (3 t,) int32
        Flat counter-clockwise triangles and their halfedges (-1 on the hull) in sweep
        numbering (Delaunator layout).
    ok : bool
        False when there is no triangle (fewer than three sites, or all collinear).
    """
    n = xs.shape[0]
    empty = np.zeros(0, dtype=np.int32)
    if n < 3:
        return np.arange(n), xs, ys, empty, empty, False
    order = _site_order(xs, ys)
    # interleaved like the default triangulation's output: the cell builder then sees the
    # same array types (strided views) and numba compiles it once for both
    sxy = np.zeros((n, 2))
    sxy[:, 0] = xs[order]
    sxy[:, 1] = ys[order]
    sx = sxy[:, 0]
    sy = sxy[:, 1]
    stats = np.zeros(_NSTATS, dtype=np.int64)
    _compile_callees()
    tri, he = _fortune_sorted(*_normalised(sx, sy), stats)
    return order, sx, sy, tri, he, tri.shape[0] > 0


def _compile_callees() -> None:
    """Compile (or load) the predicates the event loop calls, with their own options.

    :func:`_sweep_loop` runs without reference counting; a callee compiled for the first
    time inside its compilation inherits that, and the exact predicates' stage allocates
    (numba refuses: a ``TypingError`` on a fresh cache when the sweep is the first user of
    ``orient2d`` or of the breakpoint's exact stage). Compiled on their own first, they keep
    their counting; the calls are cheap once cached.
    """
    orient2d(0.0, 0.0, 1.0, 0.0, 0.0, 1.0)
    parabola_gap(0.0, 0.0, 0.0, 1.0, 1.0, 2.0)
    incircle(0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0)
    incircle_fast(0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0)
    center_offset(0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0)


def fortune_debug(points: np.ndarray) -> dict:
    """Run the sweep and return its triangles, halfedges and counters.

    Parameters
    ----------
    points : (n, 2) float64
        Distinct points.

    Returns
    -------
    dict
        ``triangles (t, 3) int32``, ``halfedges (3 t,) int32`` (Delaunator layout, -1 on the
        hull), ``flips`` (Lawson flips after the sweep; ~0 on ordinary input), ``bad``
        (edges claimed by a third triangle during the sweep; always 0), ``max_beach`` (most
        arcs at once), ``circle_events`` and ``sweep_triangles``.
    """
    pts = _prepare(points)
    stats = np.zeros(_NSTATS, dtype=np.int64)
    if pts.shape[0] < 3:
        tri = np.zeros(0, dtype=np.int32)
        he = np.zeros(0, dtype=np.int32)
    else:
        tri, he = _fortune(*_normalised(pts[:, 0], pts[:, 1]), stats)
    return {
        "triangles": tri.reshape(-1, 3),
        "halfedges": he,
        "flips": int(stats[_S_FLIPS]),
        "bad": int(stats[_S_BAD]),
        "max_beach": int(stats[_S_MAX_BEACH]),
        "circle_events": int(stats[_S_CIRCLE]),
        "sweep_triangles": int(stats[_S_TRI_SWEEP]),
    }


def fortune_triangles(points: np.ndarray) -> np.ndarray:
    """Delaunay triangles of distinct points by Fortune's sweep (the dual of its Voronoi).

    Parameters
    ----------
    points : (n, 2) float64
        Distinct points (the engine removes exact duplicates first); ``n >= 0``.

    Returns
    -------
    (t, 3) int32
        Counter-clockwise triangles forming a Delaunay triangulation; ``(0, 3)`` when the
        points are fewer than three or all collinear.

    Examples
    --------
    >>> import numpy as np
    >>> fortune_triangles(np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])).tolist()
    [[1, 0, 2]]
    """
    pts = _prepare(points)
    if pts.shape[0] < 3:
        return np.zeros((0, 3), dtype=np.int32)
    stats = np.zeros(_NSTATS, dtype=np.int64)
    tri, _ = _fortune(*_normalised(pts[:, 0], pts[:, 1]), stats)
    return tri.reshape(-1, 3)
