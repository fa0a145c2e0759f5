"""Voronoi vertices of a Delaunay triangulation: centres, and one vertex per cocircular class.

The Delaunay-dual cells (``kernels/cells``) and ``Triangulation.circumcenters`` take their
vertices from here:

- :func:`circumcenters` computes each triangle's centre as the Voronoi vertex named by its
  three sites (``kernels/vertex``), with its proven rounding bound, and flags the edges
  whose incircle the fast filter cannot decide.
- :func:`merge_cocircular` joins triangles into classes that must share one vertex: exactly
  cocircular ones (exact ``incircle`` == 0), ones whose centres agree to their rounding
  bounds, and the two ends of every Voronoi edge that rounding turned the wrong way (the
  fold test). Every member of a class gets the vertex of the class's canonical name.
- :func:`triangle_centers` is the same naming without the merge by distance, for
  ``Triangulation.circumcenters``.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..config import (
    FOLD_MAX_ROUNDS,
    FOLD_SPAN_ERRS,
    NJIT,
    NJIT_PARALLEL,
    VERTEX_SNAP_RTOL,
)
from .chainfit import fit_chains
from .classname import bound_ok, class_vertex
from .cocircular import canonical_flips
from .predicates import cross_diff, incircle, incircle_fast
from .refit import fit_classes, middle_member, rank_key
from .risky import mark_risky
from .vertex import (
    canonical_vertex_ranked,
    is_close,
    near_pair,
    same_vertex,
    voronoi_vertex,
    voronoi_vertex_and_error,
)

_U = 2.0**-53


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
        # int64 site numbers (the triangles are int32): one compile of the vertex kernels,
        # which the other callers reach with int64
        a = np.int64(tri[3 * k])
        b = np.int64(tri[3 * k + 1])
        c = np.int64(tri[3 * k + 2])
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
def _radius(xs, ys, tri, cx, cy, t, u):
    """The L1 radius the merge and fold tolerances of triangles ``t``, ``u`` scale with.

    The largest L1 distance from either centre to its triangle's sites: the same whichever
    of the two comes first and whichever site a halfedge starts at (an L1 distance differs
    from site to site on one circle, and which halfedge of an edge is the lower one depends
    on the builder's numbering: the sweep and the default then merged differently).
    """
    r = 0.0
    for k in (t, u):
        for j in range(3):
            v = tri[3 * k + j]
            r = max(r, abs(cx[k] - xs[v]) + abs(cy[k] - ys[v]))
    return r


@njit(**NJIT)
def _cc_close(xs, ys, tri, err, cx, cy, t, u):
    """Whether the centres of adjacent triangles ``t``, ``u`` are one point.

    They are when their distance is within both centres' rounding bounds
    (``vertex.center_error``: floats cannot tell them apart) and within ``CC_MERGE_RTOL`` of
    the circle's radius (a centre floats cannot place, a sliver's, merges with nothing by
    distance alone; :func:`_unfold` merges it if it swaps with a neighbour): the one merge
    rule, :func:`.vertex.same_vertex`, which the half-plane cells use too.
    """
    r = _radius(xs, ys, tri, cx, cy, t, u)
    return same_vertex(cx[t], cy[t], err[t], cx[u], cy[u], err[u], r)


@njit(**NJIT_PARALLEL)
def flag_close(xs, ys, tri, he, cx, cy, flag, err, box, fold, near):
    """Also flag interior halfedges whose two triangles have centres equal to rounding.

    On every other interior halfedge ``e < twin`` it marks in ``fold`` whether the Voronoi
    edge between the two centres runs backwards (:func:`_folds`): the first round of
    :func:`_unfold` takes that mark wherever naming left both centres as they are, so the
    edges are scanned once, here. Both triangles of a short edge are marked in ``near``
    (their vertices are among the only ones rounding can fold a cell's ring at; flagged
    edges and merged classes are marked after the merge, :func:`.risky.mark_risky`).
    """
    for e0 in prange(tri.shape[0]):
        # int64 halfedges (a prange index is uint64, the halfedges int32): the callees
        # (_short, _folds, _swapped, _next) are compiled once, for the other callers' types
        e = np.int64(e0)
        f = np.int64(he[e])
        if f < e:
            continue
        t = e // 3
        u = f // 3
        if flag[e] != 0:
            continue
        # both tests need the edge within what rounding and naming move its ends (_short;
        # _cc_close's bound is within it as FOLD_SPAN_ERRS >= 1): most edges end here
        if not _short(xs, ys, tri, e, err, cx, cy, t, u):
            continue
        near[t] = 1
        near[u] = 1
        if _cc_close(xs, ys, tri, err, cx, cy, t, u):
            flag[e] = 1
        elif _folds(xs, ys, tri, e, f, cx, cy, box, err):
            fold[e] = 1


@njit(**NJIT)
def _merge_exact(xs, ys, tri, he, cand, cx, cy, near, rank, err, box, fold):
    t = tri.shape[0] // 3
    parent = np.arange(t)
    changed = np.zeros(t, dtype=np.uint8)
    joined = np.zeros(cand.shape[0], dtype=np.uint8)
    merged = False
    for k in range(cand.shape[0]):
        e = cand[k]
        f = np.int64(he[e])
        a, b, c, d = _quad(tri, e, f)
        if (near and _cc_close(xs, ys, tri, err, cx, cy, e // 3, f // 3)) or (
            incircle(xs[a], ys[a], xs[b], ys[b], xs[c], ys[c], xs[d], ys[d]) == 0.0
        ):
            joined[k] = 1
            ra = _find(parent, e // 3)
            rb = _find(parent, f // 3)
            if ra != rb:
                parent[max(ra, rb)] = min(ra, rb)
                merged = True
    every = np.zeros(0, dtype=np.uint8)  # (``pick``: every class)
    if merged:
        for k in range(t):
            parent[k] = _find(parent, k)
        # the centres are still the triangles' own here: classes of two may reuse them
        _name_classes(xs, ys, tri, he, parent, cx, cy, rank, err, changed, np.bool_(True), every)
    if near:
        args = (fold, cand, joined, changed, every, np.bool_(False))
        _unfold(xs, ys, tri, he, parent, cx, cy, rank, box, err, *args)
    return parent


@njit(**NJIT)
def _in_box(x, y, box):
    return box[0] <= x <= box[2] and box[1] <= y <= box[3]


@njit(**NJIT)
def _next(e):
    return e - 2 if e % 3 == 2 else e + 1


@njit(**NJIT)
def _short(xs, ys, tri, e, err, cx, cy, t, u):
    """Whether the Voronoi edge between the centres of ``t``, ``u`` (halfedge ``e``) can fold.

    Only an edge within what rounding and naming can move its ends (the centres' bounds,
    an ulp of each, and a class's snap to its name, ``VERTEX_SNAP_RTOL`` of the radius) can;
    a longer one that breaks a turn test is a straight angle rounded, left alone. The radius
    is the L1 distance of the farther centre from the edge's lower site (by coordinates):
    the same whichever halfedge or triangle the builder's numbering puts first.
    """
    p = tri[e]
    q = tri[_next(e)]
    xp = xs[p]
    yp = ys[p]
    xq = xs[q]
    yq = ys[q]
    lower = (xq < xp) | ((xq == xp) & (yq < yp))
    sx = xq if lower else xp
    sy = yq if lower else yp
    r = max(abs(cx[t] - sx) + abs(cy[t] - sy), abs(cx[u] - sx) + abs(cy[u] - sy))
    d = abs(cx[t] - cx[u]) + abs(cy[t] - cy[u])
    return d <= FOLD_SPAN_ERRS * (err[t] + err[u] + VERTEX_SNAP_RTOL * r + _ulps(cx, cy, t, u))


@njit(**NJIT)
def _ulps(cx, cy, t, u):
    """An ulp of each centre's coordinates (both rounded to nearest: twice the half ulp).

    Rounding bounds count a centre's final addition exactly (0 where it is exact, an
    exact lattice far from the origin), so two centres a few ulps apart stay two vertices;
    a swap between them (a fold, proven by exact signs) may still be the representation
    of two vertices closer than the ulps, and the fold tests reach that far.
    """
    return 2.0 * _U * (abs(cx[t]) + abs(cy[t]) + abs(cx[u]) + abs(cy[u]))


@njit(**NJIT)
def short_edge(xs, ys, tri, err, cx, cy, t, u):
    """Whether the centres of triangles ``t``, ``u`` may be one vertex (rings' fold test).

    Within what rounding and naming move them, as :func:`_short`, with the radius of both
    triangles (:func:`_radius`; no halfedge at hand): the edges a fold may contract.
    """
    d = abs(cx[t] - cx[u]) + abs(cy[t] - cy[u])
    r = _radius(xs, ys, tri, cx, cy, t, u)
    return d <= FOLD_SPAN_ERRS * (err[t] + err[u] + VERTEX_SNAP_RTOL * r + _ulps(cx, cy, t, u))


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
    if not _short(xs, ys, tri, e, err, cx, cy, t, u):
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
            if parent[lo // 3] == parent[hi // 3]:
                continue  # one class (a shared parent is a shared root)
            if not _short(xs, ys, tri, lo, err, cx, cy, lo // 3, hi // 3):
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
def _unfold(
    xs, ys, tri, he, parent, cx, cy, rank, box, err, fold, cand, joined, changed, pick, middle
):
    """Merge swapped vertices (:func:`_folds`) until none is left; renames the classes.

    Each round joins the classes at both ends of every edge that folds, then names the
    joined classes. The result of a round does not depend on the order of its joins (the
    root of a class is its smallest triangle), so a round only tests the edges whose answer
    can have changed: edges whose two centres kept their bits since the last test keep its
    answer (a fold then was joined then). The first round takes :func:`flag_close`'s marks
    (``fold``) where naming kept both centres (``changed`` is 0), and tests the flagged
    ``cand`` edges and those at renamed centres (a ``cand`` edge ``joined`` by the exact
    merge has both ends in one class for good, and is skipped); later rounds test the edges
    at centres the last renaming changed. Each round merges classes, so this ends; every
    merge is a pair of vertices closer than their rounding, and the merged class gets its
    canonical vertex as any other. ``pick`` empty: every class is named again after each
    round; else only the classes a round joined (``pick`` is scratch, one entry a triangle).
    """
    merges = 0
    every = pick.shape[0] == 0
    old = parent.copy() if not every else parent
    for e in range(fold.shape[0]):
        if fold[e] != 0:
            f = he[e]
            if changed[e // 3] == 0 and changed[f // 3] == 0:
                merges += _link(parent, e // 3, f // 3)
    for k in range(cand.shape[0]):
        if joined[k] != 0:
            continue  # one class already
        e = cand[k]
        f = np.int64(he[e])
        if changed[e // 3] != 0 or changed[f // 3] != 0:
            continue  # tested below
        if _short(xs, ys, tri, e, err, cx, cy, e // 3, f // 3):
            if _find(parent, e // 3) != _find(parent, f // 3):
                if _folds(xs, ys, tri, e, f, cx, cy, box, err):
                    merges += _link(parent, e // 3, f // 3)
    merges += _refold(xs, ys, tri, he, parent, cx, cy, box, err, changed)
    for it in range(FOLD_MAX_ROUNDS):
        if it > 0:
            if not every:
                old[:] = parent
            merges = _refold(xs, ys, tri, he, parent, cx, cy, box, err, changed)
        if merges == 0:
            return
        for k in range(parent.shape[0]):
            parent[k] = _find(parent, k)
        if not every:
            pick[:] = 0
            for k in range(parent.shape[0]):
                if old[k] != parent[k]:
                    pick[parent[k]] = 1  # a class that took in another
        changed[:] = 0
        no = np.bool_(False)
        _name_classes_by(xs, ys, tri, he, parent, cx, cy, rank, err, changed, no, pick, middle)


@njit(**NJIT)
def _better_ref(t, u, err, tri, rank):
    """Whether triangle ``t`` is a better reference for its class's name than ``u``.

    The smaller rounding bound (the best-conditioned centre), ties to the lower rank key:
    never the triangles' numbering, which differs between builders (the sweep's and the
    default's classes then got different names where a class spans more than the snap).
    """
    if err.shape[0] == 0 or err[t] == err[u]:
        return rank_key(t, tri, rank) < rank_key(u, tri, rank)
    return err[t] < err[u]


@njit(**NJIT)
def _class_vertex(on, k, rank, r, xs, ys, tri, cx, cy, err):
    """``(found, x, y)``: the class's vertex (sites ``on[:k]``), named near ``r``'s centre.

    With bounds (``err``), the name is also the centre to ``r``'s bound, or the class exactly
    cocircular (:func:`.classname.class_vertex`).
    """
    a0 = tri[3 * r]
    if err.shape[0] == 0:
        return canonical_vertex_ranked(on, k, rank, cx[r], cy[r], xs[a0], ys[a0], xs, ys)
    a1 = tri[3 * r + 1]
    a2 = tri[3 * r + 2]
    return class_vertex(on, k, rank, cx[r], cy[r], err[r], xs[a0], ys[a0], a0, a1, a2, xs, ys)


@njit(**NJIT_PARALLEL)
def _name_pairs(xs, ys, tri, size, other, cx, cy, rank, err, changed):
    """:func:`_name_classes` for the classes of two triangles, while every centre is its own.

    Such a class (root ``r``, other member ``u``) has the root's three sites and, when the two
    share an edge, the one ``u`` adds. The name search (:func:`.vertex.first_named`) tries the
    three lowest-ranked of the four first, so that triple is tested here without the
    search: when it is one of the two triangles, its vertex is that triangle's centre, which
    :func:`circumcenters` computed by the same rule (same bits,
    ``vertex.voronoi_vertex_and_error``); else it is computed (``vertex.voronoi_vertex``: any
    argument order). Then the name's tests (no close pair, finite, near the reference
    centre: the better-conditioned of the two, :func:`_better_ref`).
    A class whose first triple fails one, or whose triangles do not share an edge, takes the
    full search (:func:`_class_vertex`), which tries the others. Each class reads and writes
    only its own two triangles' entries, so the classes are named in parallel.
    """
    for r0 in prange(size.shape[0]):
        r = np.int64(r0)  # (a prange index is uint64: see flag_close)
        if size[r] != 2:
            continue
        u = other[r]
        # the name must be near the better-conditioned centre (not the root's: the
        # numbering differs between builders)
        ref = u if _better_ref(u, r, err, tri, rank) else r
        # int64 site numbers: one compile of the vertex kernels (see circumcenters)
        a = np.int64(tri[3 * r])
        b = np.int64(tri[3 * r + 1])
        c = np.int64(tri[3 * r + 2])
        u0 = np.int64(tri[3 * u])
        u1 = np.int64(tri[3 * u + 1])
        u2 = np.int64(tri[3 * u + 2])
        new0 = u0 != a and u0 != b and u0 != c
        new1 = u1 != a and u1 != b and u1 != c
        new2 = u2 != a and u2 != b and u2 != c
        found = False
        wx = 0.0
        wy = 0.0
        if int(new0) + int(new1) + int(new2) == 1:
            d = u0 if new0 else (u1 if new1 else u2)
            # the highest-ranked site is the one the first triple leaves out
            top = a
            rt = rank[a]
            if rank[b] > rt:
                top = b
                rt = rank[b]
            if rank[c] > rt:
                top = c
                rt = rank[c]
            if rank[d] > rt:
                top = d
            p = a if top != a else d
            q = b if top != b else d
            w = c if top != c else d
            if top == d:
                wx = cx[r]  # the first triple is r's
                wy = cy[r]
            elif top != u0 and top != u1 and top != u2:
                wx = cx[u]  # the first triple is u's
                wy = cy[u]
            else:
                wx, wy = voronoi_vertex(p, q, w, xs, ys)
            if np.isfinite(wx) and np.isfinite(wy):
                sx = xs[tri[3 * ref]]
                sy = ys[tri[3 * ref]]
                vx = cx[ref]
                vy = cy[ref]
                r2 = (vx - sx) * (vx - sx) + (vy - sy) * (vy - sy)
                near = near_pair(p, q, r2, xs, ys) or near_pair(q, w, r2, xs, ys)
                if not (near or near_pair(p, w, r2, xs, ys)):
                    found = is_close(vx, vy, wx, wy, sx, sy, VERTEX_SNAP_RTOL)
                    if found and not bound_ok(vx, vy, err[ref], wx, wy, p, q, w, xs, ys):
                        # not the centre to the bounds: a name only where all four
                        # are exactly on one circle (:mod:`.classname`)
                        found = (
                            incircle(xs[a], ys[a], xs[b], ys[b], xs[c], ys[c], xs[d], ys[d]) == 0.0
                        )
        if not found:
            on = np.zeros(6, dtype=np.int64)
            on[0] = a
            on[1] = b
            on[2] = c
            k = np.int64(3)  # not a literal: one compile of the callees (see halfplane._cells)
            for v in (u0, u1, u2):
                if v != a and v != b and v != c:
                    on[k] = v
                    k += 1
            _, wx, wy = _class_vertex(on, k, rank, ref, xs, ys, tri, cx, cy, err)
        _set_vertex(cx, cy, r, wx, wy, changed)
        _set_vertex(cx, cy, u, wx, wy, changed)


@njit(**NJIT)
def _set_vertex(cx, cy, k, vx, vy, changed):
    """``(cx[k], cy[k]) = (vx, vy)``, noting in ``changed`` when the bits may differ."""
    if not (cx[k] == vx and cy[k] == vy) or vx == 0.0 or vy == 0.0:
        changed[k] = 1  # (a zero's sign is not seen by ==: counted as changed)
    cx[k] = vx
    cy[k] = vy


@njit(**NJIT)
def _name_classes(xs, ys, tri, he, parent, cx, cy, rank, err, changed, own, pick):
    """:func:`_name_classes_by`, every class named near its best-conditioned member."""
    no = np.bool_(False)
    _name_classes_by(xs, ys, tri, he, parent, cx, cy, rank, err, changed, own, pick, no)


@njit(**NJIT)
def _name_classes_by(xs, ys, tri, he, parent, cx, cy, rank, err, changed, own, pick, middle):
    """Give every triangle of a class (``parent`` its root) the vertex of the class's name.

    The name is the canonical triple of the class's sites (``kernels/vertex``), numbered by
    ``rank`` (their input indices), found near the reference centre: the member's with the
    smallest rounding bound ``err``, ties to the lowest rank key (:func:`_better_ref`; never
    the root, whose number depends on the builder), or, for a class whose members' own
    centres spread far and ``middle`` (the fold rounds' first try), the middle member's own
    centre (:func:`.refit.middle_member`); without a name that centre is used.
    Classes of two triangles (four cocircular
    sites: every square of a grid) are the common case and take a short path; larger ones
    are gathered by a counting sort. Triangles whose centre may have changed are marked
    in ``changed``. ``own`` says that every centre is still its triangle's own (the first
    naming), which lets a class of two reuse one (:func:`_name_pairs`). ``pick``: only the
    classes whose root it marks are named (empty: every class). A class of three or more
    whose sites' rings then turn wrong is renamed (:func:`.chainfit.fit_chains`).
    """
    t = parent.shape[0]
    size = np.zeros(t, dtype=np.int64)
    other = np.zeros(t, dtype=np.int64)
    most = 0
    for k in range(t):
        r = parent[k]
        size[r] += 1
        most = max(most, size[r])
        if k != r:
            other[r] = k
    if own:
        _name_pairs(xs, ys, tri, size, other, cx, cy, rank, err, changed)
        if most <= 2:
            return
    on = np.zeros(max(6, 3 * most), dtype=np.int64)
    big = 0
    every = pick.shape[0] == 0
    for r in range(t):
        if size[r] == 2 and own:
            continue  # named above
        if not every and pick[r] == 0:
            continue
        if size[r] == 2:
            # the root's three sites and the other triangle's new ones (one, when adjacent)
            a = tri[3 * r]
            b = tri[3 * r + 1]
            c = tri[3 * r + 2]
            on[0] = a
            on[1] = b
            on[2] = c
            k = np.int64(3)  # not a literal: one compile of the callees (see halfplane._cells)
            u = other[r]
            for j in range(3):
                v = tri[3 * u + j]
                if v != a and v != b and v != c and (k == 3 or v != on[3]):
                    on[k] = v
                    k += 1
            ref = u if _better_ref(u, r, err, tri, rank) else r
            _, vx, vy = _class_vertex(on, k, rank, ref, xs, ys, tri, cx, cy, err)
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
    chain = np.zeros(t, dtype=np.uint8)  # the classes of three or more named here
    for r in range(t):
        if size[r] < 3 or not (every or pick[r] != 0):
            continue
        chain[r] = 1
        k = np.int64(0)
        for u in range(start[r], start[r + 1]):
            for c in range(3):
                v = tri[3 * members[u] + c]
                if seen[v] != r:
                    seen[v] = r
                    on[k] = v
                    k += 1
        # the class's best-conditioned centre is the reference its name must match (the
        # root's may be a sliver's, which no triple's centre is near), unless the members'
        # centres spread far (a fold round's joins): then the middle member's own centre
        mid, px, py = -1, 0.0, 0.0
        if middle:
            mid, px, py = middle_member(xs, ys, tri, members[start[r] : start[r + 1]], rank)
        if mid >= 0:
            a0 = tri[3 * mid]
            _, vx, vy = canonical_vertex_ranked(on, k, rank, px, py, xs[a0], ys[a0], xs, ys)
        else:
            best = r
            if err.shape[0] > 0:
                for u in range(start[r], start[r + 1]):
                    if _better_ref(members[u], best, err, tri, rank):
                        best = members[u]
            # (the snap alone: a chain of joins, named as the fold rounds left it)
            none = np.zeros(0)
            _, vx, vy = _class_vertex(on, k, rank, best, xs, ys, tri, cx, cy, none)
        for u in range(start[r], start[r + 1]):
            _set_vertex(cx, cy, members[u], vx, vy, changed)
    # a chain's name where its sites' rings of centres turn right or miss a site: renamed
    if err.shape[0] > 0:  # (the cells' classes; not ``triangle_centers``)
        fit_chains(xs, ys, tri, he, parent, cx, cy, chain, changed)  # (:mod:`.chainfit`)


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

    Returns ``(cls, near)``: each triangle's class (its root) and whether it is on a
    Voronoi edge that rounding could turn: short for its ends' rounding bounds and naming
    moves, or flagged and not joined (:func:`.risky.mark_risky`). Those are the triangles whose
    centres can fold a cell's ring (``kernels/cells`` checks those cells).

    Where an edge is short (``near``: rounding can fold a ring there, and the classes then
    depend on the triangles' own centres), every exactly cocircular quad is first flipped
    to one diagonal, the same for every builder (:func:`.cocircular.canonical_flips`):
    ``tri``, ``he`` are changed in place and ``cx, cy, err, flag`` are those of the flipped
    triangles. (Exact grids have no short edge: their squares keep the builder's diagonals.)
    """
    fold = np.zeros(tri.shape[0], dtype=np.uint8)
    near = np.zeros(tri.shape[0] // 3, dtype=np.uint8)
    flag_close(xs, ys, tri, he, cx, cy, flag, err, box, fold, near)
    if near.any() and canonical_flips(xs, ys, tri, he, np.flatnonzero(flag)):
        cx[:], cy[:], err[:], flag[:] = circumcenters(xs, ys, tri, he)
        fold[:] = 0
        near[:] = 0
        flag_close(xs, ys, tri, he, cx, cy, flag, err, box, fold, near)
    cand = np.flatnonzero(flag)
    if cand.shape[0] == 0 and not fold.any():
        # nothing to merge or unfold (most uniform inputs): every triangle is its own class,
        # and flag_close marked the short edges
        return np.arange(tri.shape[0] // 3), near
    own_x = cx.copy()
    own_y = cy.copy()
    cls = _merge_exact(xs, ys, tri, he, cand, cx, cy, True, rank, err, box, fold)
    mark_risky(xs, ys, tri, he, cls, cx, cy, own_x, own_y, err, flag, near)
    return cls, near


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
def contract(xs, ys, tri, he, parent, cx, cy, rank, box, err, pa, pb, only):
    """:func:`contract_by`, every joined class named near its best-conditioned member."""
    no = np.bool_(False)
    return contract_by(xs, ys, tri, he, parent, cx, cy, rank, box, err, pa, pb, only, no)


@njit(**NJIT)
def contract_by(xs, ys, tri, he, parent, cx, cy, rank, box, err, pa, pb, only, middle):
    """Join the classes of triangles ``pa[k]`` and ``pb[k]``, name them, unfold; joins made.

    The cells' fold test (``kernels/folds.fold_pairs``) finds rings that rounding folded
    across edges that are not neighbours (the pairwise test of :func:`_folds` sees only one
    edge at a time) and gives the short Voronoi edges around the fold: their ends are one
    vertex to rounding. ``parent`` (compressed, as :func:`merge_cocircular` returns it) is
    updated in place; every member of a joined class gets the class's named vertex, and the
    edges at renamed centres are tested for swaps again (:func:`_unfold`). Pairs ``(t, t)``
    are a stalled fold test's request: when no pair joins, those classes are named afresh
    where their cells turn best (:func:`.refit.fit_classes`), and the count is of renamed
    classes (0: nothing changed). ``only``: name only the classes a join changed (every
    other keeps its vertex, one :func:`.refit.fit_classes` chose too); else all of them.
    ``middle``: a class whose members' centres spread far is named from its middle member
    (:func:`.refit.middle_member`), not its best-conditioned one.
    """
    merges = 0
    refit = False
    t = parent.shape[0]
    old = parent.copy()
    for k in range(pa.shape[0]):
        if pa[k] == pb[k]:
            refit = True  # a stalled fold test's request (:func:`.folds.fold_pairs`)
        else:
            merges += _link(parent, pa[k], pb[k])
    if merges == 0 and not refit:
        return 0
    for k in range(t):
        parent[k] = _find(parent, k)
    changed = np.zeros(t, dtype=np.uint8)
    pick = np.zeros(t if only else 0, dtype=np.uint8)  # (empty: every class)
    if only:
        for k in range(t):
            if old[k] != parent[k]:
                pick[parent[k]] = 1
    if merges > 0:
        no = np.bool_(False)
        _name_classes_by(xs, ys, tri, he, parent, cx, cy, rank, err, changed, no, pick, middle)
        if only:
            fit_classes(xs, ys, tri, he, parent, cx, cy, pick, changed)
    else:
        fresh = np.zeros(t, dtype=np.uint8)
        for k in range(pa.shape[0]):
            fresh[parent[pa[k]]] = 1
        merges = fit_classes(xs, ys, tri, he, parent, cx, cy, fresh, changed)
        if merges == 0:
            return 0
    fold = np.zeros(tri.shape[0], dtype=np.uint8)
    cand = np.zeros(0, dtype=np.int64)
    joined = np.zeros(0, dtype=np.uint8)
    args = (fold, cand, joined, changed, pick, middle)
    _unfold(xs, ys, tri, he, parent, cx, cy, rank, box, err, *args)
    return merges
