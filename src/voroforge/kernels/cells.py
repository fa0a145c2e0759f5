"""Voronoi cells from a Delaunay triangulation, clipped to an axis-aligned box.

Output contract (shared with the half-plane kernel):

``coords (K, 2) float64``
    Vertices of every cell's convex polygon (cell intersected with the box), counter-clockwise,
    without a repeated closing vertex and without consecutive duplicates.
``offsets (n + 1,) int64``
    Cell ``i`` is ``coords[offsets[i]:offsets[i + 1]]`` (empty when it misses the box).
``owner (K,) int32``
    ``owner[k] = j`` when the polygon edge from vertex ``k`` to the next vertex lies on the
    bisector of sites ``i`` and ``j``; -1 when it lies on the box.

Interior cells are rings of circumcentres. Triangles whose circumcircles coincide (exactly
cocircular sites, decided with the exact ``incircle``) share one circumcentre, so cocircular
grids give clean cells without zero-length edges. Cells of hull sites (unbounded before
clipping) are cut out of the box by the bisectors of their Delaunay neighbours.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..config import (
    CC_MERGE_RTOL,
    FOLD_MAX_ROUNDS,
    FOLD_SPAN_ERRS,
    NJIT,
    NJIT_PARALLEL,
    RELABEL_RTOL,
    VERTEX_SNAP_RTOL,
)
from .clip import dedupe_ring
from .power import box_cell
from .predicates import cross_diff, incircle, incircle_fast
from .vertex import box_crossing, canonical_vertex_ranked, voronoi_vertex_and_error

_U = 2.0**-53

_CHUNK = 2048


@njit(**NJIT)
def _find(parent, a):
    while parent[a] != a:
        parent[a] = parent[parent[a]]
        a = parent[a]
    return a


@njit(**NJIT_PARALLEL)
def circumcenters(xs, ys, tri, he):
    """Circumcentres of all triangles, their rounding bounds, and flags on undecided edges.

    Each centre is the Voronoi vertex named by the triangle's sites (``kernels/vertex``),
    computed together with its proven rounding-error bound (``vertex.center_error``, from
    the same set-up: ``voronoi_vertex_and_error``).

    A halfedge ``e < twin`` is flagged when the fast incircle filter cannot call its
    quadrilateral; those are the candidates for exact cocircularity. Returns
    ``(cx, cy, err, flag)``.
    """
    t = tri.shape[0] // 3
    cx = np.zeros(t)
    cy = np.zeros(t)
    err = np.zeros(t)
    flag = np.zeros(tri.shape[0], dtype=np.uint8)
    for k in prange(t):
        a = tri[3 * k]
        b = tri[3 * k + 1]
        c = tri[3 * k + 2]
        ux, uy, err[k] = voronoi_vertex_and_error(a, b, c, xs, ys)
        if not (np.isfinite(ux) and np.isfinite(uy)):
            # a sliver whose centre overflows: far outside any box, so its cells get cut
            ux = np.inf
            uy = np.inf
        cx[k] = ux
        cy[k] = uy
        for j in range(3):
            e = 3 * k + j
            f = he[e]
            if f > e:
                d = tri[f - f % 3 + (f + 2) % 3]
                v = incircle_fast(xs[a], ys[a], xs[b], ys[b], xs[c], ys[c], xs[d], ys[d])
                if v != v:
                    flag[e] = 1
    return cx, cy, err, flag


@njit(**NJIT)
def _quad(tri, e, f):
    a = tri[e]
    b = tri[e - e % 3 + (e + 1) % 3]
    c = tri[e - e % 3 + (e + 2) % 3]
    d = tri[f - f % 3 + (f + 2) % 3]
    return a, b, c, d


@njit(**NJIT)
def _cc_close(xs, ys, a, err, cx, cy, t, u):
    """Whether the centres of triangles ``t``, ``u`` (site ``a`` on both) are one point.

    They are when their distance is within both centres' rounding bounds
    (``vertex.center_error``: floats cannot tell them apart) and within ``CC_MERGE_RTOL`` of
    the circle's radius (a centre floats cannot place, a sliver's, merges with nothing by
    distance alone; :func:`_unfold` merges it if it swaps with a neighbour). Both scale
    with the local spacing: the coordinates' magnitude enters only through its ulps.
    """
    d = abs(cx[t] - cx[u]) + abs(cy[t] - cy[u])
    if not d <= err[t] + err[u]:
        return False
    r = abs(cx[t] - xs[a]) + abs(cy[t] - ys[a])
    return d <= CC_MERGE_RTOL * r + 4.0 * _U * (abs(cx[t]) + abs(cy[t]))


@njit(**NJIT_PARALLEL)
def flag_close(xs, ys, tri, he, cx, cy, flag, err, box, fold):
    """Also flag interior halfedges whose two triangles have centres equal to rounding.

    On every other interior halfedge ``e < twin`` it marks in ``fold`` whether the Voronoi
    edge between the two centres runs backwards (:func:`_folds`): the first round of
    :func:`_unfold` takes that mark wherever naming left both centres as they are, so the
    edges are scanned once, here.
    """
    for e in prange(tri.shape[0]):
        f = he[e]
        if f < e or flag[e] != 0:
            continue
        t = e // 3
        u = f // 3
        # both tests need the edge within what rounding and naming move its ends (_short;
        # _cc_close's bound is within it as FOLD_SPAN_ERRS >= 1): most edges end here
        if not _short(xs, ys, tri[e], err, cx, cy, t, u):
            continue
        if _cc_close(xs, ys, tri[e], err, cx, cy, t, u):
            flag[e] = 1
        elif _folds(xs, ys, tri, e, f, cx, cy, box, err):
            fold[e] = 1


@njit(**NJIT)
def _merge_exact(xs, ys, tri, he, cand, cx, cy, near, rank, err, box, fold):
    t = tri.shape[0] // 3
    parent = np.arange(t)
    changed = np.zeros(t, dtype=np.uint8)
    merged = False
    for k in range(cand.shape[0]):
        e = cand[k]
        f = he[e]
        a, b, c, d = _quad(tri, e, f)
        if (near and _cc_close(xs, ys, a, err, cx, cy, e // 3, f // 3)) or (
            incircle(xs[a], ys[a], xs[b], ys[b], xs[c], ys[c], xs[d], ys[d]) == 0.0
        ):
            ra = _find(parent, e // 3)
            rb = _find(parent, f // 3)
            if ra != rb:
                parent[max(ra, rb)] = min(ra, rb)
                merged = True
    if merged:
        for k in range(t):
            parent[k] = _find(parent, k)
        _name_classes(xs, ys, tri, parent, cx, cy, rank, err, changed)
    if near:
        _unfold(xs, ys, tri, he, parent, cx, cy, rank, box, err, fold, cand, changed)
    return parent


@njit(**NJIT)
def _in_box(x, y, box):
    return box[0] <= x <= box[2] and box[1] <= y <= box[3]


@njit(**NJIT)
def _next(e):
    return e - 2 if e % 3 == 2 else e + 1


@njit(**NJIT)
def _short(xs, ys, a, err, cx, cy, t, u):
    """Whether the Voronoi edge between the centres of ``t``, ``u`` (site ``a``) can fold.

    Only an edge within what rounding and naming can move its ends (the centres' bounds,
    and a class's snap to its name, ``VERTEX_SNAP_RTOL`` of the radius) can; a longer one
    that breaks a turn test is a straight angle rounded, left alone.
    """
    d = abs(cx[t] - cx[u]) + abs(cy[t] - cy[u])
    r = abs(cx[t] - xs[a]) + abs(cy[t] - ys[a])
    return d <= FOLD_SPAN_ERRS * (err[t] + err[u] + VERTEX_SNAP_RTOL * r)


@njit(**NJIT)
def _folds(xs, ys, tri, e, f, cx, cy, box, err):
    """Whether the Voronoi edge dual to halfedge ``e`` (``f`` its twin, ``e < f``) folds.

    The Voronoi edge dual to Delaunay edge ``i -> j`` runs from the centre of the triangle
    right of it to the centre of the one left of it, along ``j - i`` turned left, by the
    empty-circle property (its exact length is >= 0). When the computed vertices run the
    other way (decided exactly, :func:`.predicates.cross_diff`), rounding has swapped them:
    their exact distance is below their rounding, and keeping both folds the ring.
    """
    t = e // 3
    u = f // 3
    if not _short(xs, ys, tri[e], err, cx, cy, t, u):
        return False
    if not (_in_box(cx[t], cy[t], box) and _in_box(cx[u], cy[u], box)):
        return False  # a vertex outside the box is never output: its cells are cut
    return _swapped(xs, ys, tri, e, f, cx[u], cy[u], cx[t], cy[t])


@njit(**NJIT)
def _link(parent, t, u):
    """Join the classes of triangles ``t`` and ``u`` (the smaller root wins); 1 if they were two."""
    rt = _find(parent, t)
    ru = _find(parent, u)
    if rt == ru:
        return 0
    parent[max(rt, ru)] = min(rt, ru)
    return 1


@njit(**NJIT)
def _refold(xs, ys, tri, he, parent, cx, cy, box, err, changed):
    """Join across every edge at a ``changed`` triangle that folds now; the number of joins."""
    merges = 0
    for t in range(changed.shape[0]):
        if changed[t] == 0:
            continue
        for j in range(3):
            e = 3 * t + j
            f = he[e]
            if f < 0:
                continue
            lo = min(e, f)
            hi = max(e, f)
            if not _short(xs, ys, tri[lo], err, cx, cy, lo // 3, hi // 3):
                continue  # the cheap test first: most edges are long
            if _find(parent, lo // 3) == _find(parent, hi // 3):
                continue
            if _folds(xs, ys, tri, lo, hi, cx, cy, box, err):
                merges += _link(parent, lo // 3, hi // 3)
    return merges


@njit(**NJIT)
def _dot_sign(ax, ay, bx, by, cx, cy, dx, dy):
    """Sign-exact ``(b - a) . (d - c)`` (the cross product with ``d - c`` turned right)."""
    return -cross_diff(ax, ay, bx, by, cy, dx, dy, cx)


@njit(**NJIT)
def _swapped(xs, ys, tri, e, f, ux, uy, tx, ty):
    """Whether the computed Voronoi edge ``u -> t`` dual to halfedge ``e`` cannot be right.

    With ``i -> k`` the halfedge, ``q`` the third site of the triangle left of it and ``j``
    that of the one right of it, the exact edge runs along ``k - i`` turned left (``q`` and
    ``j`` are its next and previous neighbours around ``i``, in reverse around ``k``), so it
    makes a left turn with the neighbouring edges of both cells: ``(j - i).e <= 0``,
    ``(q - i).e >= 0``, ``(j - k).e <= 0``, ``(q - k).e >= 0``. A computed edge ``e`` that
    breaks one (exact signs) has swapped or turned ends: rounding moved them by more than
    their distance.
    """
    i = tri[e]
    k = tri[_next(e)]
    q = tri[_next(_next(e))]
    j = tri[_next(_next(f))]
    if cross_diff(xs[i], ys[i], xs[k], ys[k], ux, uy, tx, ty) < 0.0:
        return True
    if _dot_sign(xs[i], ys[i], xs[j], ys[j], ux, uy, tx, ty) > 0.0:
        return True
    if _dot_sign(xs[i], ys[i], xs[q], ys[q], ux, uy, tx, ty) < 0.0:
        return True
    if _dot_sign(xs[k], ys[k], xs[j], ys[j], ux, uy, tx, ty) > 0.0:
        return True
    return _dot_sign(xs[k], ys[k], xs[q], ys[q], ux, uy, tx, ty) < 0.0


@njit(**NJIT)
def _unfold(xs, ys, tri, he, parent, cx, cy, rank, box, err, fold, cand, changed):
    """Merge swapped vertices (:func:`_folds`) until none is left; renames the classes.

    Each round joins the classes at both ends of every edge that folds, then names the
    joined classes. The result of a round does not depend on the order of its joins (the
    root of a class is its smallest triangle), so a round only tests the edges whose answer
    can have changed: edges whose two centres kept their bits since the last test keep its
    answer (a fold then was joined then). The first round takes :func:`flag_close`'s marks
    (``fold``) where naming kept both centres (``changed`` is 0), and tests the flagged
    ``cand`` edges and those at renamed centres; later rounds test the edges at centres the
    last renaming changed. Each round merges classes, so this ends; every merge is a pair of
    vertices closer than their rounding, and the merged class gets its canonical vertex as
    any other.
    """
    merges = 0
    for e in range(fold.shape[0]):
        if fold[e] != 0:
            f = he[e]
            if changed[e // 3] == 0 and changed[f // 3] == 0:
                merges += _link(parent, e // 3, f // 3)
    for k in range(cand.shape[0]):
        e = cand[k]
        f = he[e]
        if changed[e // 3] != 0 or changed[f // 3] != 0:
            continue  # tested below
        if _short(xs, ys, tri[e], err, cx, cy, e // 3, f // 3):
            if _find(parent, e // 3) != _find(parent, f // 3):
                if _folds(xs, ys, tri, e, f, cx, cy, box, err):
                    merges += _link(parent, e // 3, f // 3)
    merges += _refold(xs, ys, tri, he, parent, cx, cy, box, err, changed)
    for it in range(FOLD_MAX_ROUNDS):
        if it > 0:
            merges = _refold(xs, ys, tri, he, parent, cx, cy, box, err, changed)
        if merges == 0:
            return
        for k in range(parent.shape[0]):
            parent[k] = _find(parent, k)
        changed[:] = 0
        _name_classes(xs, ys, tri, parent, cx, cy, rank, err, changed)


@njit(**NJIT)
def _class_vertex(on, k, rank, r, xs, ys, tri, cx, cy):
    """Vertex of the class rooted at triangle ``r`` with sites ``on[:k]`` (see below)."""
    a0 = tri[3 * r]
    _, vx, vy = canonical_vertex_ranked(on, k, rank, cx[r], cy[r], xs[a0], ys[a0], xs, ys)
    return vx, vy


@njit(**NJIT)
def _set_vertex(cx, cy, k, vx, vy, changed):
    """``(cx[k], cy[k]) = (vx, vy)``, noting in ``changed`` when the bits may differ."""
    if not (cx[k] == vx and cy[k] == vy) or vx == 0.0 or vy == 0.0:
        changed[k] = 1  # (a zero's sign is not seen by ==: counted as changed)
    cx[k] = vx
    cy[k] = vy


@njit(**NJIT)
def _name_classes(xs, ys, tri, parent, cx, cy, rank, err, changed):
    """Give every triangle of a class (``parent`` its root) the vertex of the class's name.

    The name is the canonical triple of the class's sites (``kernels/vertex``), numbered by
    ``rank`` (their input indices), found near the root's centre; without one the root's
    centre is used (for classes of three or more, the member centre with the smallest
    rounding bound ``err`` is the reference). Classes of two triangles (four cocircular
    sites: every square of a grid) are the common case and take a short path; larger ones
    are gathered by a counting sort. Triangles whose centre may have changed are marked
    in ``changed``.
    """
    t = parent.shape[0]
    size = np.zeros(t, dtype=np.int64)
    other = np.zeros(t, dtype=np.int64)
    for k in range(t):
        r = parent[k]
        size[r] += 1
        if k != r:
            other[r] = k
    on = np.zeros(max(6, 3 * int(size.max())), dtype=np.int64)
    big = 0
    for r in range(t):
        if size[r] == 2:
            # the root's three sites and the other triangle's new ones (one, when adjacent)
            a = tri[3 * r]
            b = tri[3 * r + 1]
            c = tri[3 * r + 2]
            on[0] = a
            on[1] = b
            on[2] = c
            k = 3
            u = other[r]
            for j in range(3):
                v = tri[3 * u + j]
                if v != a and v != b and v != c and (k == 3 or v != on[3]):
                    on[k] = v
                    k += 1
            vx, vy = _class_vertex(on, k, rank, r, xs, ys, tri, cx, cy)
            _set_vertex(cx, cy, r, vx, vy, changed)
            _set_vertex(cx, cy, u, vx, vy, changed)
        elif size[r] > 2:
            big += 1
    if big == 0:
        return
    # members of every class of three or more, grouped by root in triangle order (a
    # counting sort: linear, where a sort of all triangles cost more than the rest)
    start = np.zeros(t + 1, dtype=np.int64)
    for r in range(t):
        start[r + 1] = start[r] + (size[r] if size[r] > 2 else 0)
    fill = start[:-1].copy()
    members = np.zeros(start[t], dtype=np.int64)
    for k in range(t):
        r = parent[k]
        if size[r] > 2:
            members[fill[r]] = k
            fill[r] += 1
    seen = np.full(xs.shape[0], -1, dtype=np.int64)
    for r in range(t):
        if size[r] < 3:
            continue
        k = 0
        for u in range(start[r], start[r + 1]):
            for c in range(3):
                v = tri[3 * members[u] + c]
                if seen[v] != r:
                    seen[v] = r
                    on[k] = v
                    k += 1
        # the class's best-conditioned centre is the reference its name must match (the
        # root's may be a sliver's, which no triple's centre is near)
        best = r
        if err.shape[0] > 0:
            for u in range(start[r], start[r + 1]):
                if err[members[u]] < err[best]:
                    best = members[u]
        vx, vy = _class_vertex(on, k, rank, best, xs, ys, tri, cx, cy)
        for u in range(start[r], start[r + 1]):
            _set_vertex(cx, cy, members[u], vx, vy, changed)


def merge_cocircular(xs, ys, tri, he, cx, cy, err, flag, rank, box):
    """Give triangles with the same circumcircle one circumcentre; return each one's class.

    Two triangles sharing an edge have the same circumcircle exactly when the fourth point is
    on the first one's circle (exact incircle == 0); triangles whose computed centres agree
    to their rounding bounds (:func:`_cc_close`) are merged too, and so are the ends of every
    Voronoi edge that rounding turned the wrong way (:func:`_unfold`, exact signs: keeping
    them would fold the ring). Classes are the connected components of that relation;
    every member gets the vertex named by the class's canonical triple (the vertex rule of
    ``kernels/vertex``, which the half-plane kernel follows too). The exact code runs only
    on the halfedges flagged by :func:`circumcenters`. ``rank[v]`` is site ``v``'s input
    index (names are chosen in the input's numbering, as every algorithm does).
    """
    fold = np.zeros(tri.shape[0], dtype=np.uint8)
    flag_close(xs, ys, tri, he, cx, cy, flag, err, box, fold)
    cand = np.flatnonzero(flag)
    return _merge_exact(xs, ys, tri, he, cand, cx, cy, True, rank, err, box, fold)


def triangle_centers(xs, ys, tri, he):
    """Circumcentres of all triangles, named as the Voronoi vertices are.

    Each is the vertex named by its triangle's sites, and exactly cocircular triangles
    (exact ``incircle`` == 0) share the vertex of their canonical name, as in the cells. The
    merge of merely close centres (``CC_MERGE_RTOL``) is left out: each centre stays its own
    triangle's, to its conditioning. Returns ``(cx, cy)``.
    """
    cx, cy, _, flag = circumcenters(xs, ys, tri, he)
    cand = np.flatnonzero(flag)
    if cand.shape[0]:
        none = np.zeros(0)
        fold = np.zeros(0, dtype=np.uint8)
        _merge_exact(xs, ys, tri, he, cand, cx, cy, False, np.arange(xs.shape[0]), none, none, fold)
    return cx, cy


@njit(**NJIT)
def _outgoing(tri, he, cx, cy, box, n):
    """Per point: one outgoing halfedge, its degree, and whether its cell must be cut.

    Hull points get their outgoing hull halfedge. A cell is cut when its point is on the hull
    or one of its circumcentres lies outside the box.
    """
    out = np.full(n, -1, dtype=np.int64)
    deg = np.zeros(n, dtype=np.int64)
    cut = np.zeros(n, dtype=np.bool_)
    for e in range(tri.shape[0]):
        v = tri[e]
        out[v] = e
        deg[v] += 1
    for e in range(tri.shape[0]):
        if he[e] == -1:
            out[tri[e]] = e
            cut[tri[e]] = True
    for t in range(tri.shape[0] // 3):
        if not (box[0] <= cx[t] <= box[2] and box[1] <= cy[t] <= box[3]):
            cut[tri[3 * t]] = True
            cut[tri[3 * t + 1]] = True
            cut[tri[3 * t + 2]] = True
    return out, deg, cut


@njit(**NJIT)
def _index_of(nbrs, nn, a):
    for k in range(nn):
        if nbrs[k] == a:
            return k
    return -1


@njit(**NJIT)
def _chain(nbrs, tris, nn, a, b):
    """Where neighbour ``a`` is, and how many Delaunay triangles lead from it to ``b``.

    Returns ``(ka, steps)`` in rotation order; ``steps`` is -1 when either is missing, ``b``
    does not follow ``a``, or a triangle between them does not exist (past a hull end).
    """
    ka = _index_of(nbrs, nn, a)
    kb = _index_of(nbrs, nn, b)
    if ka < 0 or kb < 0:
        return ka, -1
    steps = (kb - ka) % nn if tris[nn - 1] >= 0 else kb - ka
    for s in range(max(steps, 0)):
        if tris[(ka + s) % nn] < 0:
            return ka, -1
    return ka, steps if steps >= 1 else -1


@njit(**NJIT)
def _emit_chain(nbrs, tris, nn, ka, steps, cx, cy, qx, qy, qw, out):
    """Write the circumcentres of the ``steps`` triangles after neighbour ``ka`` to ``q``.

    Each is followed by the edge of the next neighbour; returns the new vertex count.
    """
    for s in range(steps):
        k = (ka + s) % nn
        t = tris[k]
        qx[out] = cx[t]
        qy[out] = cy[t]
        qw[out] = nbrs[(k + 1) % nn]
        out += 1
    return out


@njit(**NJIT)
def _canonical_vertices(i, xs, ys, px, py, pw, m, nbrs, tris, nn, cx, cy, box, qx, qy, qw):
    """Replace computed vertices by values every cell sharing them computes identically.

    A vertex between the bisectors with neighbours ``a`` then ``b`` is the circumcentre of
    the Delaunay triangle ``(i, a, b)``. When ``a`` and ``b`` are not consecutive neighbours
    the clip lost edges too short for floats to separate (neighbours whose bisectors coincide
    in floating point); the chain of circumcentres between them is put back from the
    triangulation. A vertex on a box side is the canonical crossing of the bisector with that
    side; two box sides meet at an exact corner. Owners of box sides (-1..-4) become -1.
    """
    out = 0
    for v in range(m):
        a = pw[v - 1] if v > 0 else pw[m - 1]
        b = pw[v]
        x = px[v]
        y = py[v]
        if a >= 0 and b >= 0:
            ka, steps = _chain(nbrs, tris, nn, a, b)
            # the chain's vertices are in order: swapped ones were merged (cells._unfold)
            ok = steps >= 1 and out + steps + (m - v) <= qx.shape[0]
            if ok:
                out = _emit_chain(nbrs, tris, nn, ka, steps, cx, cy, qx, qy, qw, out)
                continue
        elif a >= 0 or b >= 0:
            j = a if a >= 0 else b
            side = b if a >= 0 else a
            bx, by = box_crossing(i, j, xs, ys, side, box)
            if bx == bx and box[0] <= bx <= box[2] and box[1] <= by <= box[3]:
                x = bx
                y = by
        else:
            vert = a if (a == -1 or a == -3) else b
            horz = b if vert == a else a
            if (vert == -1 or vert == -3) and (horz == -2 or horz == -4):
                x = box[0] if vert == -1 else box[2]
                y = box[1] if horz == -2 else box[3]
        qx[out] = x
        qy[out] = y
        qw[out] = b
        out += 1
    for v in range(out):
        px[v] = qx[v]
        py[v] = qy[v]
        pw[v] = qw[v] if qw[v] >= 0 else -1
    return dedupe_ring(px, py, pw, out)


@njit(**NJIT)
def _nearest_label(xs, ys, x, y, b, nbrs, nn):
    """The neighbour nearest to ``(x, y)``, starting from ``b``.

    It moves only on a decisive comparison: the point must be clearly (``RELABEL_RTOL`` of
    the coordinates' size) off the bisector of the two candidates.
    """
    for k in range(nn):
        j = nbrs[k]
        if j == b:
            continue
        # |P - s_j|^2 - |P - s_b|^2 = (s_j - s_b) . (s_j + s_b - 2P)
        dx = xs[j] - xs[b]
        dy = ys[j] - ys[b]
        # in the frame of P: the local spacing, not the coordinates' magnitude, sets the
        # tolerance; P's own representation error adds a few ulps of its magnitude
        jx = xs[j] - x
        jy = ys[j] - y
        bx = xs[b] - x
        by = ys[b] - y
        d = dx * (jx + bx) + dy * (jy + by)
        size = abs(jx) + abs(bx) + abs(jy) + abs(by)
        tol = (RELABEL_RTOL * size + 16.0 * _U * (abs(x) + abs(y))) * (abs(dx) + abs(dy))
        if d < -tol:
            b = j
    return b


@njit(**NJIT)
def _relabel_edges(xs, ys, px, py, pw, m, nbrs, tris, nn, cx, cy, qx, qy, qw):
    """Fix the owners of bisector edges that floats could not separate; result in ``p``.

    Neighbours closer to each other than the float resolution of their bisectors (sites
    1e-17 of the extent apart, say) cut the cell along the same float line, and the clip
    labels the whole edge with whichever came last. Each end of the edge is given its
    nearest neighbour; when the ends disagree, the Delaunay chain of circumcentres between
    the two neighbours is inserted, so the edge is split where the true vertices are.
    """
    out = 0
    for v in range(m):
        b = pw[v]
        qx[out] = px[v]
        qy[out] = py[v]
        qw[out] = b
        out += 1
        if b < 0:
            continue
        w = v + 1 if v + 1 < m else 0
        lp = _nearest_label(xs, ys, px[v], py[v], b, nbrs, nn)
        lq = _nearest_label(xs, ys, px[w], py[w], b, nbrs, nn)
        if lp == lq:
            qw[out - 1] = lp
            continue
        kp, steps = _chain(nbrs, tris, nn, lp, lq)
        if not (steps >= 1 and out + steps + (m - v) <= qx.shape[0]):
            qw[out - 1] = _nearest_label(
                xs, ys, 0.5 * (px[v] + px[w]), 0.5 * (py[v] + py[w]), b, nbrs, nn
            )
            continue
        qw[out - 1] = lp
        out = _emit_chain(nbrs, tris, nn, kp, steps, cx, cy, qx, qy, qw, out)
    for v in range(out):
        px[v] = qx[v]
        py[v] = qy[v]
        pw[v] = qw[v]
    return out


@njit(**NJIT)
def _cut_cell(i, xs, ys, ws, nbrs, tris, nn, box, cx, cy, px, py, pw, qx, qy, qw, ss):
    """Cell of site ``i`` as the box cut by the bisectors with ``nbrs[:nn]``; result in ``p``.

    The cut is the power cell's (``kernels/power.box_cell``) with the zero weights ``ws``:
    Voronoi is the equal-weight case. ``tris[k]`` is the Delaunay triangle between
    neighbours ``k`` and ``k + 1`` (or -1); it lets :func:`_canonical_vertices` make shared
    vertices bit-identical across cells. ``ss`` is scratch.
    """
    m = box_cell(i, xs, ys, ws, nbrs, nn, box, px, py, pw, qx, qy, qw, ss)
    if m == 0:
        return 0
    m = _relabel_edges(xs, ys, px, py, pw, m, nbrs, tris, nn, cx, cy, qx, qy, qw)
    return _canonical_vertices(i, xs, ys, px, py, pw, m, nbrs, tris, nn, cx, cy, box, qx, qy, qw)


@njit(**NJIT)
def _cell(i, xs, ys, ws, tri, he, cx, cy, cls, out, box, bufs, nbrs, cl, tb, ss):
    """Polygon of site ``i`` into ``p``; returns the vertex count.

    A cell whose ring of circumcentres lies inside the box is that ring. Any other cell
    (hull sites, cells reaching past the box) is cut out of the box by the bisectors of its
    Delaunay neighbours: this never relies on far-away, ill-conditioned circumcentres of
    nearly flat triangles.
    """
    px, py, pw, qx, qy, qw = bufs
    o0 = out[i]
    if o0 == -1:
        return 0
    hull = he[o0] == -1
    o = o0
    m = 0
    k = 0
    inside = not hull
    while True:
        t = o // 3
        p = o - o % 3 + (o + 2) % 3  # previous halfedge: y -> i
        y = tri[p]
        nbrs[k] = tri[o - o % 3 + (o + 1) % 3]
        tb[k] = t
        k += 1
        if inside:
            if m > 0 and cls[t] == cl[m - 1]:
                pw[m - 1] = y  # same circumcentre as the previous vertex: no 0-length edge
            else:
                vx = cx[t]
                vy = cy[t]
                px[m] = vx
                py[m] = vy
                pw[m] = y
                cl[m] = cls[t]
                m += 1
                if not (box[0] <= vx <= box[2] and box[1] <= vy <= box[3]):
                    inside = False
        o = he[p]
        if o == -1:
            nbrs[k] = y
            tb[k] = -1
            k += 1
            break
        if o == o0:
            break
    if not inside:
        return _cut_cell(i, xs, ys, ws, nbrs, tb, k, box, cx, cy, px, py, pw, qx, qy, qw, ss)
    if m > 1 and cl[m - 1] == cl[0]:
        m -= 1
    return m if m >= 3 else 0


@njit(**NJIT)
def _scratch(cap):
    """Per-chunk scratch of one cell: rings ``p``, ``q`` with owners, neighbour ring, values."""
    bufs = (
        np.zeros(cap),
        np.zeros(cap),
        np.zeros(cap, dtype=np.int64),
        np.zeros(cap),
        np.zeros(cap),
        np.zeros(cap, dtype=np.int64),
    )
    nbrs = np.zeros(cap, dtype=np.int64)
    cl = np.zeros(cap, dtype=np.int64)
    tb = np.zeros(cap, dtype=np.int64)
    return bufs, nbrs, cl, tb, np.zeros(cap)


@njit(**NJIT_PARALLEL)
def _count(xs, ys, ws, tri, he, cx, cy, cls, out, box, cap, deg, cut, merged):
    """Vertex count of every cell.

    Without cocircular merges an uncut cell has one vertex per incident triangle, so only cut
    cells need the full construction.
    """
    n = xs.shape[0]
    counts = np.zeros(n, dtype=np.int64)
    if not merged:
        for i in prange(n):
            counts[i] = deg[i] if deg[i] >= 3 else 0
    nchunks = (n + _CHUNK - 1) // _CHUNK
    for ch in prange(nchunks):
        bufs, nbrs, cl, tb, ss = _scratch(cap)
        for i in range(ch * _CHUNK, min(n, (ch + 1) * _CHUNK)):
            if not merged and not cut[i]:
                continue
            counts[i] = _cell(i, xs, ys, ws, tri, he, cx, cy, cls, out, box, bufs, nbrs, cl, tb, ss)
    return counts


@njit(**NJIT)
def _write_ring(i, tri, he, cx, cy, out, base, coords, owner, kmap):
    """The ring of uncut, unmerged cell ``i`` at ``coords[base:]``, closed (see :func:`_fill`)."""
    o0 = out[i]
    if o0 == -1:
        return
    o = o0
    m = 0
    while True:
        p = o - o % 3 + (o + 2) % 3  # previous halfedge: y -> i
        t = o // 3
        coords[base + m, 0] = cx[t]
        coords[base + m, 1] = cy[t]
        owner[base + m] = kmap[tri[p]]
        m += 1
        o = he[p]
        if o == o0 or o == -1:
            break
    if m < 3:
        return  # (not reached for an interior site: its count is its degree, >= 3)
    coords[base + m, 0] = cx[o0 // 3]
    coords[base + m, 1] = cy[o0 // 3]
    owner[base + m] = -2


@njit(**NJIT_PARALLEL)
def _fill(xs, ys, ws, tri, he, cx, cy, cls, out, box, cap, start, coords, owner, kmap, cut, merged):
    """Write every cell as a closed ring at ``start[i]``; owners go through ``kmap``.

    Without cocircular merges an uncut cell is its ring of circumcentres, one per incident
    triangle (what :func:`_cell` builds then, see :func:`_count`): it is written straight
    from the halfedge walk.
    """
    n = xs.shape[0]
    nchunks = (n + _CHUNK - 1) // _CHUNK
    for ch in prange(nchunks):
        bufs, nbrs, cl, tb, ss = _scratch(cap)
        px, py, pw = bufs[0], bufs[1], bufs[2]
        for i in range(ch * _CHUNK, min(n, (ch + 1) * _CHUNK)):
            if not merged and not cut[i]:
                _write_ring(i, tri, he, cx, cy, out, start[i], coords, owner, kmap)
                continue
            m = _cell(i, xs, ys, ws, tri, he, cx, cy, cls, out, box, bufs, nbrs, cl, tb, ss)
            if m == 0:
                continue
            base = start[i]
            for k in range(m):
                coords[base + k, 0] = px[k]
                coords[base + k, 1] = py[k]
                w = pw[k]
                owner[base + k] = kmap[w] if w >= 0 else w
            coords[base + m, 0] = px[0]
            coords[base + m, 1] = py[0]
            owner[base + m] = -2


def cells_from_triangulation(xs, ys, tri, he, box, order, kmap):
    """Clipped Voronoi cells of distinct sites from their Delaunay triangulation.

    Parameters
    ----------
    xs, ys : (u,) float64
        Sites in the kernel's numbering (for locality, the sweep order of the triangulation).
    tri, he : (3 t,) int32
        Flat triangles and halfedges in that numbering.
    box : (4,) float64
        ``(xmin, ymin, xmax, ymax)`` every cell is clipped to.
    order : (u,) int64
        ``order[k]`` is the output position of kernel site ``k``.
    kmap : (u,) int64
        Output owner id of kernel site ``k``.

    Returns
    -------
    coords : (K, 2) float64
        Closed rings (last vertex repeats the first) in output order.
    lengths : (u + 1,) int64
        Output cell ``j`` is ``coords[lengths[j]:lengths[j + 1]]`` (empty when equal).
    owner : (K,) int64
        ``owner[v]`` is the site across the edge from vertex ``v`` to ``v + 1``, -1 on the box,
        -2 on each closing vertex.
    """
    n = xs.shape[0]
    box = np.asarray(box, dtype=np.float64)
    cx, cy, err, flag = circumcenters(xs, ys, tri, he)
    cls = merge_cocircular(xs, ys, tri, he, cx, cy, err, flag, kmap, box)
    out, deg, cut = _outgoing(tri, he, cx, cy, box, n)
    cap = int(deg.max()) + 16
    merged = bool(flag.any()) or bool((cls != np.arange(cls.shape[0])).any())
    ws = np.zeros(n)
    counts = _count(xs, ys, ws, tri, he, cx, cy, cls, out, box, cap, deg, cut, merged)
    closed = np.where(counts > 0, counts + 1, 0)
    lengths = np.zeros(n + 1, dtype=np.int64)
    lengths[1:][order] = closed
    np.cumsum(lengths, out=lengths)
    start = lengths[:-1][order]
    total = int(lengths[-1])
    coords = np.zeros((total, 2))
    owner = np.zeros(total, dtype=np.int64)
    _fill(xs, ys, ws, tri, he, cx, cy, cls, out, box, cap, start, coords, owner, kmap, cut, merged)
    return coords, lengths, owner


@njit(**NJIT_PARALLEL)
def _cut_all(xs, ys, indptr, indices, box, cap, counts, offsets, coords, owner, fill):
    """Cut cells of all sites from their neighbour lists (count pass, then ``fill`` pass)."""
    n = xs.shape[0]
    ws = np.zeros(n)
    nchunks = (n + _CHUNK - 1) // _CHUNK
    for ch in prange(nchunks):
        px = np.zeros(cap)
        py = np.zeros(cap)
        pw = np.zeros(cap, dtype=np.int64)
        qx = np.zeros(cap)
        qy = np.zeros(cap)
        qw = np.zeros(cap, dtype=np.int64)
        no_tris = np.full(cap, -1, dtype=np.int64)
        none = np.zeros(0)
        ss = np.zeros(cap)
        for i in range(ch * _CHUNK, min(n, (ch + 1) * _CHUNK)):
            nb = indices[indptr[i] : indptr[i + 1]]
            m = _cut_cell(
                i, xs, ys, ws, nb, no_tris, nb.shape[0], box, none, none, px, py, pw, qx, qy, qw, ss
            )
            if not fill:
                counts[i] = m
                continue
            base = offsets[i]
            for k in range(m):
                coords[base + k, 0] = px[k]
                coords[base + k, 1] = py[k]
                owner[base + k] = pw[k]


def cells_from_neighbors(xs, ys, indptr, indices, box):
    """Clipped cells when the neighbours are known but there are no triangles (collinear)."""
    n = xs.shape[0]
    box = np.asarray(box, dtype=np.float64)
    deg = np.diff(indptr)
    cap = int(deg.max() if n else 0) + 16
    counts = np.zeros(n, dtype=np.int64)
    dummy_c = np.zeros((0, 2))
    dummy_o = np.zeros(0, dtype=np.int32)
    offsets = np.zeros(n + 1, dtype=np.int64)
    _cut_all(xs, ys, indptr, indices, box, cap, counts, offsets, dummy_c, dummy_o, False)
    np.cumsum(counts, out=offsets[1:])
    coords = np.zeros((int(offsets[-1]), 2))
    owner = np.zeros(int(offsets[-1]), dtype=np.int32)
    _cut_all(xs, ys, indptr, indices, box, cap, counts, offsets, coords, owner, True)
    return coords, offsets, owner
