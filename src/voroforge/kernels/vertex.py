"""One vertex rule: a Voronoi (or power) vertex is named by its owners and computed once.

A vertex of a 2D diagram is where the cells of three sites meet; its *name* is that set of
three owner sites. Every cell builder (Delaunay-dual cells, half-plane cells, power cells,
the triangulation's ``circumcenters``) computes a vertex only from its name, through
:func:`voronoi_vertex` or :func:`power_vertex`: the owners are put in their canonical order
(lexicographic by coordinates, ``x`` then ``y``; the index breaks ties between equal
points) and :func:`center` runs on them in that order. So every caller, whatever its own
numbering of the sites or the order it meets the owners in, gets the same bits, and
neighbouring cells share their vertices exactly. (The sort itself is skipped where the
order provably cannot change a bit, which is almost everywhere: see
:func:`_center_if_order_free`.)

:func:`center` is the power centre of three weighted points; with zero or equal weights it
is the circumcentre, bit for bit (the weight differences are exact zeros). It works relative
to the point opposite the longest edge, so both edge vectors are the short ones (a sliver
with one tiny edge keeps its precision), and uses the adaptive ``orient2d`` as denominator
when the float one cannot be trusted.

Where four or more sites are cocircular, several triples name one vertex;
:func:`canonical_triple` picks the name (the first well-conditioned triple of the
lowest-numbered sites, in the input's numbering), so every cell around the vertex uses the
same one. The order of the computation and the choice of the name are kept apart on
purpose: coordinates do not depend on any numbering (the Triangulation, the sweep-ordered
Delaunay cells and the half-plane cells all get the same bits for a triple), while the
lowest-numbered choice is the one that keeps the half-plane cells consistent around
near-duplicate sites (measured: a coordinate-ordered choice broke Euler's formula there).

A bisector's crossing with a side of the box is named by its pair and the side
(:func:`box_crossing`, :func:`power_box_crossing`), computed from the pair in canonical order.

3D extends this unchanged in shape: a vertex is named by its sorted owner quadruple and
computed once, from that name, by one circumsphere (power-sphere) routine; the canonical
choice among cospherical sites is the first well-conditioned quadruple.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import (
    CC_MERGE_RTOL,
    CORNER_CROSSING_ULPS,
    NAME_MAX_TRIES,
    NJIT,
    VERTEX_DET_RTOL,
    VERTEX_PAIR_RTOL,
    VERTEX_REFINE_RTOL,
    VERTEX_SNAP_RTOL,
)
from .expansion import exact_circumcenter, two_sum
from .predicates import orient2d
from .sidecross import nearest_crossing


@njit(**NJIT)
def _frame(ax, ay, aw, bx, by, bw, cx, cy, cw):
    """The set-up shared by :func:`center_offset`, :func:`center_error` and the order test.

    The origin ``o`` is the point opposite the longest edge (the first such in argument
    order); ``d = p - o`` and ``e = q - o`` are the two short edges, ``bl``, ``cl`` the
    right-hand sides of ``2 d.u = |d|^2 + (w_o - w_p)`` (same for ``e``), ``left - right``
    the float determinant. ``det`` is that determinant when it can be trusted, else the
    adaptive ``orient2d`` (``trusted`` says which). ``tie`` is whether the longest edge was
    tied, so that the argument order chose the origin.
    Returns ``(ox, oy, ow, pw, qw, dx, dy, ex, ey, bl, cl, left, right, det, trusted, tie)``.
    """
    la = (bx - cx) * (bx - cx) + (by - cy) * (by - cy)
    lb = (cx - ax) * (cx - ax) + (cy - ay) * (cy - ay)
    lc = (ax - bx) * (ax - bx) + (ay - by) * (ay - by)
    if lb >= la and lb >= lc:
        ox, oy, ow, px, py, pw, qx, qy, qw = bx, by, bw, cx, cy, cw, ax, ay, aw
        tie = lb == la or lb == lc
    elif lc >= la:
        ox, oy, ow, px, py, pw, qx, qy, qw = cx, cy, cw, ax, ay, aw, bx, by, bw
        tie = lc == la  # lc > lb here
    else:
        ox, oy, ow, px, py, pw, qx, qy, qw = ax, ay, aw, bx, by, bw, cx, cy, cw
        tie = False  # la > lb and la > lc here
    dx = px - ox
    dy = py - oy
    ex = qx - ox
    ey = qy - oy
    # |u - d|^2 - w_p = |u|^2 - w_o  <=>  2 d.u = |d|^2 + (w_o - w_p); the weight
    # difference is an exact 0 for equal weights, so this is then the circumcentre's bits
    bl = dx * dx + dy * dy + (ow - pw)
    cl = ex * ex + ey * ey + (ow - qw)
    left = dx * ey
    right = dy * ex
    det = left - right
    trusted = abs(det) >= VERTEX_DET_RTOL * (abs(left) + abs(right)) and det != 0.0
    if not trusted:
        det = orient2d(ox, oy, px, py, qx, qy)
    return ox, oy, ow, pw, qw, dx, dy, ex, ey, bl, cl, left, right, det, trusted, tie


@njit(**NJIT)
def center_offset(ax, ay, aw, bx, by, bw, cx, cy, cw):
    """Power centre of three weighted points as an origin point and an offset from it.

    Returns ``(ox, oy, ux, uy)``: the origin is the point opposite the longest edge, and the
    centre is ``(ox + ux, oy + uy)``. The offset is what a caller needing the circle itself
    wants (with zero weights ``|u|`` is the circumradius; Fortune's sweep takes the circle's
    top from it). Exactly collinear points give non-finite offsets.
    """
    ox, oy, _, _, _, dx, dy, ex, ey, bl, cl, _, _, det, _, _ = _frame(
        ax, ay, aw, bx, by, bw, cx, cy, cw
    )
    d = 0.5 / det
    return ox, oy, (ey * bl - dy * cl) * d, (dx * cl - ex * bl) * d


_U = 2.0**-53  # unit roundoff of float64


@njit(**NJIT)
def _error_of(ox, oy, ow, pw, qw, dx, dy, ex, ey, bl, cl, left, right, det):
    """:func:`center_error` from :func:`_frame`'s values (the offset recomputed from them)."""
    ad = abs(det)
    rel_det = 4.0 * _U * (abs(left) + abs(right)) / ad if ad > 0.0 else np.inf
    if not rel_det < 0.5:
        return np.inf
    # |bl|, |cl| carry the weights' own magnitude: their rounding is relative to it
    abl = dx * dx + dy * dy + abs(ow) + abs(pw)
    acl = ex * ex + ey * ey + abs(ow) + abs(qw)
    ux = (ey * bl - dy * cl) * (0.5 / det)
    uy = (dx * cl - ex * bl) * (0.5 / det)
    if not (abs(ux) < np.inf and abs(uy) < np.inf):
        return np.inf
    nx = 7.0 * _U * (abs(ey) * abl + abs(dy) * acl) * (0.5 / ad)
    ny = 7.0 * _U * (abs(dx) * acl + abs(ex) * abl) * (0.5 / ad)
    err = nx + ny + (abs(ux) + abs(uy)) * (2.0 * _U + rel_det)
    # the final addition o + u: its rounding error exactly (two_sum's residual), which is 0
    # where the sum is representable (an exact lattice far from the origin), not half an
    # ulp of the magnitude (that merged vertices a few ulps apart there)
    err += abs(two_sum(ox, ux)[1]) + abs(two_sum(oy, uy)[1])
    return 2.0 * err + 4.0 * _U * _U * (abs(ox) + abs(oy))


@njit(**NJIT)
def center_error(ax, ay, aw, bx, by, bw, cx, cy, cw):
    """A bound on the L1 rounding error of :func:`center` (same arguments).

    A first-order running error bound of :func:`center_offset`'s arithmetic, doubled to
    cover the second-order terms: the exact power centre of the three (exact) inputs lies
    within this L1 distance of the computed one. Infinite when the denominator cannot be
    trusted to a factor of two (a sliver whose centre floats cannot place).
    """
    ox, oy, ow, pw, qw, dx, dy, ex, ey, bl, cl, left, right, det, _, _ = _frame(
        ax, ay, aw, bx, by, bw, cx, cy, cw
    )
    return _error_of(ox, oy, ow, pw, qw, dx, dy, ex, ey, bl, cl, left, right, det)


@njit(**NJIT)
def voronoi_vertex_error(a, b, c, xs, ys):
    """A bound on the L1 rounding error of :func:`voronoi_vertex` (same arguments).

    :func:`center_error` of the owners in canonical order, or, for a centre computed from
    exact expansions, a few ulps of its own magnitude (:func:`voronoi_vertex_and_error`).
    """
    return voronoi_vertex_and_error(a, b, c, xs, ys)[2]


@njit(**NJIT)
def voronoi_vertex_and_error(a, b, c, xs, ys):
    """:func:`voronoi_vertex` and :func:`voronoi_vertex_error` of one triple, bit for bit.

    Returns ``(x, y, err)`` from one :func:`_frame`. Where the centre's bits cannot depend on
    the argument order (:func:`_center_if_order_free`) neither can the bound's: reordering
    the owners only swaps ``p`` and ``q``, which swaps the terms of every sum in
    :func:`_error_of` (addition is commutative in floats) and negates the determinant and
    both numerators exactly. Elsewhere both come from the owners in canonical order.
    """
    x, y, err, _ = _vertex_and_bounds(a, b, c, xs, ys, np.bool_(False))
    return x, y, err


@njit(**NJIT)
def _sorted_vertex_and_error(a, b, c, xs, ys):
    """:func:`voronoi_vertex_and_error` where the order could matter: owners sorted first."""
    a, b, c = sorted_triple(a, b, c, xs, ys)
    ox, oy, ow, pw, qw, dx, dy, ex, ey, bl, cl, left, right, det, _, _ = _frame(
        xs[a], ys[a], 0.0, xs[b], ys[b], 0.0, xs[c], ys[c], 0.0
    )
    d = 0.5 / det
    x = ox + (ey * bl - dy * cl) * d
    y = oy + (dx * cl - ex * bl) * d
    err = _error_of(ox, oy, ow, pw, qw, dx, dy, ex, ey, bl, cl, left, right, det)
    if err > VERTEX_REFINE_RTOL * (abs(x) + abs(y)) and det != 0.0:
        # a sliver: the float formula loses the centre to cancellation; the exact one
        # keeps it to a few ulps of its own magnitude (``expansion.exact_circumcenter``)
        rx, ry = exact_circumcenter(xs[a], ys[a], xs[b], ys[b], xs[c], ys[c])
        if np.isfinite(rx) and np.isfinite(ry):
            return rx, ry, 8.0 * _U * (abs(rx) + abs(ry))
    return x, y, err


@njit(**NJIT)
def voronoi_vertex_lazy(a, b, c, xs, ys):
    """:func:`voronoi_vertex_and_error`'s bits, the bound computed only where it is needed.

    Returns ``(x, y, err, low)``; ``err`` is -1 (not computed) in the easy case, almost every
    vertex: the float formula in argument order gives the canonical bits (no tied longest
    edge, a trusted determinant, offsets neither zero nor infinite) and an upper bound of
    the rounding bound of :func:`_error_of` is below the refinement threshold, so that
    :func:`voronoi_vertex_and_error` returns these very bits. The upper bound uses the
    centre's one division (``0.5 / det``) where the full bound has three, and ``u |x|`` for
    the final addition's rounding error (its exact residual there): each term is at least
    its counterpart, and rounding is monotone. Where it fails, the full bound decides, and
    the rest is :func:`voronoi_vertex_and_error`'s own path. ``low`` is a lower bound of the
    rounding bound (``err`` itself where computed): in the easy case twice the final
    addition's exact rounding errors, one of :func:`_error_of`'s non-negative terms (a
    rounded sum of non-negative terms is at least each of them), so that a caller can prove
    two centres within their bounds of each other without computing the bounds.
    """
    return _vertex_and_bounds(a, b, c, xs, ys, np.bool_(True))


@njit(**{**NJIT, "inline": "always"})
def voronoi_vertex_lazy_inline(a, b, c, xs, ys):
    """:func:`voronoi_vertex_lazy` inlined into its caller's code (numba IR).

    For hot loops (the half-plane settling): a call between compiled functions updates the
    reference count of each array argument, two per vertex here.
    """
    return _vertex_and_bounds(a, b, c, xs, ys, np.bool_(True))


@njit(**{**NJIT, "inline": "always"})  # as a call: half-plane grid 1e5 ~13% slower
def _vertex_and_bounds(a, b, c, xs, ys, lazy):
    """One copy of the float path behind two entries: ``lazy`` False or True.

    :func:`voronoi_vertex_and_error` (False) and :func:`voronoi_vertex_lazy` (True) share the
    formula, so the lazy proof and the full bound always see the same bits. Returns
    ``(x, y, err, low)``.
    """
    ox, oy, ow, pw, qw, dx, dy, ex, ey, bl, cl, left, right, det, trusted, tie = _frame(
        xs[a], ys[a], 0.0, xs[b], ys[b], 0.0, xs[c], ys[c], 0.0
    )
    if trusted and not tie:
        d = 0.5 / det
        ux = (ey * bl - dy * cl) * d
        uy = (dx * cl - ex * bl) * d
        if 0.0 < abs(ux) < np.inf and 0.0 < abs(uy) < np.inf:
            x = ox + ux
            y = oy + uy
            lim = VERTEX_REFINE_RTOL * (abs(x) + abs(y))
            h = abs(d)  # 0.5 / |det|, bit for bit
            rel = 8.0 * _U * (abs(left) + abs(right)) * h * (1.0 + 2.0**-40)
            if lazy and rel < 0.5:
                ub = 7.0 * _U * (abs(ey) * bl + abs(dy) * cl) * h
                ub += 7.0 * _U * (abs(dx) * cl + abs(ex) * bl) * h
                ub += (abs(ux) + abs(uy)) * (2.0 * _U + rel)
                ub += _U * abs(x) + _U * abs(y)
                ub = 2.0 * ub + 4.0 * _U * _U * (abs(ox) + abs(oy))
                if ub <= lim:
                    low = 2.0 * (abs(two_sum(ox, ux)[1]) + abs(two_sum(oy, uy)[1]))
                    return x, y, -1.0, low
            err = _error_of(ox, oy, ow, pw, qw, dx, dy, ex, ey, bl, cl, left, right, det)
            if not err > lim:
                return x, y, err, err
    x, y, err = _sorted_vertex_and_error(a, b, c, xs, ys)
    return x, y, err, err


@njit(**NJIT)
def center(ax, ay, aw, bx, by, bw, cx, cy, cw):
    """Power centre of weighted points ``a, b, c`` (the circumcentre for equal weights).

    The point whose power distance ``|x - p|^2 - w`` is the same to all three. The result
    depends on the argument order only through ties of edge lengths; callers that need
    canonical bits use :func:`voronoi_vertex` / :func:`power_vertex`.
    """
    ox, oy, ux, uy = center_offset(ax, ay, aw, bx, by, bw, cx, cy, cw)
    return ox + ux, oy + uy


@njit(**NJIT)
def circumcenter(ax, ay, bx, by, cx, cy):
    """Circumcentre of a triangle: :func:`center` with zero weights."""
    return center(ax, ay, 0.0, bx, by, 0.0, cx, cy, 0.0)


@njit(**NJIT)
def before(a, b, xs, ys):
    """Whether site ``a`` comes before site ``b`` in canonical order (``x``, ``y``, index)."""
    if xs[a] != xs[b]:
        return xs[a] < xs[b]
    if ys[a] != ys[b]:
        return ys[a] < ys[b]
    return a < b


@njit(**NJIT)
def sorted_triple(a, b, c, xs, ys):
    """The owners ``a, b, c`` in canonical order (see :func:`before`)."""
    # one integer type for the swaps (a prange index is unsigned: mixed, numba unifies to float)
    a = np.int64(a)
    b = np.int64(b)
    c = np.int64(c)
    if before(b, a, xs, ys):
        a, b = b, a
    if before(c, b, xs, ys):
        b, c = c, b
        if before(b, a, xs, ys):
            a, b = b, a
    return a, b, c


@njit(**NJIT)
def _center_if_order_free(ax, ay, aw, bx, by, bw, cx, cy, cw):
    """:func:`center` when its bits cannot depend on the argument order; else ``ok`` False.

    Returns ``(x, y, ok)``. :func:`center` uses the order in two places only: the origin
    when the longest edge is tied, and the ``orient2d`` fallback. Otherwise the origin is
    the point opposite the strictly longest edge in every order, and the other two differ
    between orders at most by a swap ``p <-> q``, which negates the determinant and both
    numerators exactly (``fl(u) - fl(v) = -(fl(v) - fl(u))``): the quotients, and so the
    centre, keep their bits. The exception is a numerator that cancels to an exact zero
    (``+0`` in both orders, so the offset's sign of zero would follow the order); a zero
    or non-finite offset is therefore not ``ok`` either. Callers then sort the owners.
    """
    ox, oy, _, _, _, dx, dy, ex, ey, bl, cl, _, _, det, trusted, tie = _frame(
        ax, ay, aw, bx, by, bw, cx, cy, cw
    )
    if tie or not trusted:
        return 0.0, 0.0, False
    d = 0.5 / det
    ux = (ey * bl - dy * cl) * d
    uy = (dx * cl - ex * bl) * d
    if not (0.0 < abs(ux) < np.inf and 0.0 < abs(uy) < np.inf):
        return 0.0, 0.0, False
    return ox + ux, oy + uy, True


@njit(**NJIT)
def voronoi_vertex(a, b, c, xs, ys):
    """The Voronoi vertex named by sites ``a, b, c``: the same bits in any argument order.

    That of :func:`center` on the owners in canonical order; they are sorted only where the
    order could change a bit (:func:`_center_if_order_free`). A sliver's centre, which the
    float formula loses to cancellation, is computed from exact expansions
    (:func:`voronoi_vertex_and_error`), the same bits as there; the rounding bound is
    computed only where the easy case is not proven (:func:`voronoi_vertex_lazy`).
    """
    x, y, _, _ = voronoi_vertex_lazy(a, b, c, xs, ys)
    return x, y


@njit(**NJIT)
def power_vertex(a, b, c, xs, ys, ws):
    """The power vertex named by weighted sites ``a, b, c`` (any argument order).

    With equal weights it is :func:`voronoi_vertex`, bit for bit (slivers included).
    """
    if ws[a] == ws[b] and ws[b] == ws[c]:
        return voronoi_vertex(a, b, c, xs, ys)
    x, y, ok = _center_if_order_free(xs[a], ys[a], ws[a], xs[b], ys[b], ws[b], xs[c], ys[c], ws[c])
    if ok:
        return x, y
    a, b, c = sorted_triple(a, b, c, xs, ys)
    return center(xs[a], ys[a], ws[a], xs[b], ys[b], ws[b], xs[c], ys[c], ws[c])


@njit(**NJIT)
def _side_crossing(ax, ay, dx, dy, t, side, box):
    """Where the line through ``a + t d`` normal to ``d`` meets box side ``side`` (-1..-4).

    Sides are -1 left, -2 bottom, -3 right, -4 top. NaN when the line is parallel to it.
    """
    mx = ax + t * dx
    my = ay + t * dy
    if side == -1 or side == -3:
        x = box[0] if side == -1 else box[2]
        if dy == 0.0:
            return np.nan, np.nan
        return x, my - dx * (x - mx) / dy
    y = box[1] if side == -2 else box[3]
    if dx == 0.0:
        return np.nan, np.nan
    return mx - dy * (y - my) / dx, y


@njit(**NJIT)
def box_crossing(a, b, xs, ys, side, box):
    """Where the bisector of sites ``a`` and ``b`` crosses box side ``side`` (-1..-4).

    Computed from the pair in canonical order, so both cells of the pair get the same bits;
    for sites a few ulps apart the double nearest the exact crossing
    (:func:`.sidecross.nearest_crossing`: their crossings of one side stay in order, issue
    15). A crossing within ``CORNER_CROSSING_ULPS`` ulps of the sites of a box corner is
    the nearest double too: a float circle's Voronoi vertices all within 1e-14 of the
    corner on its centre, sites 100 away, had crossings off by ~1e-14, past one another
    (issue 15). NaN when the bisector is parallel to the side.
    """
    a = np.int64(a)
    b = np.int64(b)
    if before(b, a, xs, ys):
        a, b = b, a
    x, y = _side_crossing(xs[a], ys[a], xs[b] - xs[a], ys[b] - ys[a], 0.5, side, box)
    big = max(max(abs(xs[a]), abs(ys[a])), max(abs(xs[b]), abs(ys[b])))
    if side == -1 or side == -3:
        u = min(abs(y - box[1]), abs(y - box[3]))
    else:
        u = min(abs(x - box[0]), abs(x - box[2]))
    if u <= CORNER_CROSSING_ULPS * np.spacing(big):
        # nearest_crossing refines where the box is under an ulp of the sites: a box of
        # no extent asks for it (it reads the box for its extent only)
        return nearest_crossing(xs[a], ys[a], xs[b], ys[b], side, np.zeros(4), x, y)
    return nearest_crossing(xs[a], ys[a], xs[b], ys[b], side, box, x, y)


@njit(**NJIT)
def power_box_crossing(a, b, xs, ys, ws, side, box):
    """Where the power bisector of ``a`` and ``b`` crosses box side ``side`` (-1..-4).

    The bisector ``|x - a|^2 - w_a = |x - b|^2 - w_b`` passes through ``a + t (b - a)`` with
    ``t = 1/2 + (w_a - w_b) / (2 |b - a|^2)``: for equal weights ``t`` is exactly 1/2 and
    the result is :func:`box_crossing`'s, bit for bit (the nearest double: equal weights
    go through it).
    """
    a = np.int64(a)
    b = np.int64(b)
    if before(b, a, xs, ys):
        a, b = b, a
    if ws[a] == ws[b]:
        return box_crossing(a, b, xs, ys, side, box)
    dx = xs[b] - xs[a]
    dy = ys[b] - ys[a]
    t = 0.5 + 0.5 * (ws[a] - ws[b]) / (dx * dx + dy * dy)
    return _side_crossing(xs[a], ys[a], dx, dy, t, side, box)


@njit(**NJIT)
def near_pair(a, b, r2, xs, ys):
    """Whether sites ``a, b`` on a circle of squared radius ``r2`` are too close for a name.

    Their triple's centre is then ill-conditioned (it lies far along their bisector).
    """
    dx = xs[a] - xs[b]
    dy = ys[a] - ys[b]
    return dx * dx + dy * dy <= VERTEX_PAIR_RTOL * r2


@njit(**NJIT)
def is_close(x, y, px, py, sx, sy, rtol):
    """Whether ``(px, py)`` is within ``rtol`` of vertex ``(x, y)`` of site ``(sx, sy)``.

    L1 distance relative to the vertex's distance from the site (the local spacing), plus a
    few ulps of the vertex's magnitude (its representation error): a fixed fraction of the
    magnitude would merge whole cells far from the origin.
    """
    scale = abs(x - sx) + abs(y - sy)
    return abs(px - x) + abs(py - y) <= rtol * scale + 16.0 * _U * (abs(x) + abs(y))


@njit(**NJIT)
def same_vertex(x1, y1, e1, x2, y2, e2, r):
    """Whether two computed vertices with rounding bounds ``e1``, ``e2`` are one point.

    The one merge rule of every cell builder (the Delaunay-dual cells' adjacent centres,
    the half-plane cells' sites on a circle): the two are within their rounding bounds of
    each other (floats cannot tell them apart; an exact lattice's distinct vertices, whose
    bounds are ~0, never merge however far from the origin) and within ``CC_MERGE_RTOL`` of
    ``r`` (the L1 distance from the vertex to a site on its circle) plus a few ulps of
    their magnitude (a sliver's centre, which floats cannot place, merges with nothing by
    distance alone). Symmetric in the two, so no caller's order can change the answer.
    """
    d = abs(x1 - x2) + abs(y1 - y2)
    if not d <= e1 + e2:
        return False
    return d <= CC_MERGE_RTOL * r + 4.0 * _U * max(abs(x1) + abs(y1), abs(x2) + abs(y2))


@njit(**NJIT)
def _named(on, k, vx, vy, sx, sy, xs, ys):
    """:func:`first_named`, and the coordinates of the name's vertex (``(vx, vy)`` if none).

    The coordinates are those the test computed, so a caller needing them does not compute
    the vertex twice.
    """
    r2 = (vx - sx) * (vx - sx) + (vy - sy) * (vy - sy)
    tries = 0
    for p in range(k):
        for q in range(p + 1, k):
            for r in range(q + 1, k):
                tries += 1
                if tries > NAME_MAX_TRIES:
                    return -1, -1, -1, vx, vy  # the same bound for every caller
                x0, x1, x2 = on[p], on[q], on[r]
                if x0 == x1 or x1 == x2:
                    continue
                if near_pair(x0, x1, r2, xs, ys) or near_pair(x1, x2, r2, xs, ys):
                    continue
                if near_pair(x0, x2, r2, xs, ys):
                    continue
                cx, cy = voronoi_vertex(x0, x1, x2, xs, ys)
                if np.isfinite(cx) and np.isfinite(cy):
                    if is_close(vx, vy, cx, cy, sx, sy, VERTEX_SNAP_RTOL):
                        return x0, x1, x2, cx, cy
    return -1, -1, -1, vx, vy


@njit(**NJIT)
def first_named(on, k, vx, vy, sx, sy, xs, ys):
    """The first triple of ``on[:k]`` (already in name order) that names vertex ``(vx, vy)``.

    ``(sx, sy)`` is one site on the vertex's circle. Triples are tried in lexicographic
    order of their positions in ``on``; repeats are skipped, and so are ill-conditioned
    triples (two sites a few ulps apart, see :func:`near_pair`) and those whose centre is
    not the vertex to rounding (``VERTEX_SNAP_RTOL``). ``(-1, -1, -1)`` when none names it.
    """
    a, b, c, _, _ = _named(on, k, vx, vy, sx, sy, xs, ys)
    return a, b, c


@njit(**NJIT)
def _sort_by_index(on, k):
    for p in range(1, k):  # insertion sort: few sites are on one circle
        x = on[p]
        q = p
        while q > 0 and x < on[q - 1]:
            on[q] = on[q - 1]
            q -= 1
        on[q] = x


@njit(**NJIT)
def sort_by_rank(on, k, rank):
    """Insertion sort of ``on[:k]`` by ``rank[on[p]]`` (few sites are on one circle)."""
    for p in range(1, k):
        x = on[p]
        q = p
        while q > 0 and rank[x] < rank[on[q - 1]]:
            on[q] = on[q - 1]
            q -= 1
        on[q] = x


@njit(**NJIT)
def canonical_triple(on, k, vx, vy, sx, sy, xs, ys):
    """The name of the vertex ``(vx, vy)`` where sites ``on[:k]`` are cocircular.

    The first well-conditioned, lowest-numbered triple (:func:`first_named` after sorting
    ``on[:k]`` by site number; repeats allowed). Callers numbering the sites as the input
    does agree on it; one with its own numbering uses :func:`canonical_vertex_ranked`.
    """
    _sort_by_index(on, k)
    return first_named(on, k, vx, vy, sx, sy, xs, ys)


@njit(**NJIT)
def canonical_vertex(on, k, vx, vy, sx, sy, xs, ys):
    """Coordinates of the vertex named by :func:`canonical_triple` (``(vx, vy)`` if none)."""
    _sort_by_index(on, k)
    _, _, _, x, y = _named(on, k, vx, vy, sx, sy, xs, ys)
    return x, y


@njit(**NJIT)
def canonical_vertex_ranked(on, k, rank, vx, vy, sx, sy, xs, ys):
    """:func:`canonical_vertex` with site ``v`` numbered ``rank[v]`` (its input index).

    Returns ``(found, x, y)``: whether a triple names the vertex, and its coordinates.
    """
    sort_by_rank(on, k, rank)
    a, _, _, x, y = _named(on, k, vx, vy, sx, sy, xs, ys)
    return a >= 0, x, y


@njit(**NJIT)
def canonical_vertex4(p0, p1, p2, p3, vx, vy, c1x, c1y, c2x, c2y, xs, ys):
    """:func:`canonical_vertex` where four sites are on the circle, three centres known.

    The sites are ``p0..p3``, ``(vx, vy)`` the vertex (the centre of the triple without
    ``p0``), ``c1``, ``c2`` the centres of the triples without ``p1`` and ``p2`` (from
    :func:`voronoi_vertex`: any order, the same bits), and ``p3`` the vertex's site. The
    same triples are tried in the same order with the same tests as :func:`canonical_vertex`
    on ``[p0, p1, p2, p3]``, so the result is its bits; only the triple without ``p3`` has
    its centre computed, if it is tried. Returns ``(x, y)``.
    """
    sx = xs[p3]
    sy = ys[p3]
    r2 = (vx - sx) * (vx - sx) + (vy - sy) * (vy - sy)
    s0, s1, s2, s3 = np.int64(p0), np.int64(p1), np.int64(p2), np.int64(p3)
    s0, s1 = min(s0, s1), max(s0, s1)  # the sites by index (a sorting network)
    s2, s3 = min(s2, s3), max(s2, s3)
    s0, s2 = min(s0, s2), max(s0, s2)
    s1, s3 = min(s1, s3), max(s1, s3)
    s1, s2 = min(s1, s2), max(s1, s2)
    for t in range(4):  # lexicographic triples leave out s3, s2, s1, s0 in turn
        if t > NAME_MAX_TRIES - 1:
            return vx, vy
        omit = s3 if t == 0 else (s2 if t == 1 else (s1 if t == 2 else s0))
        x0 = s0 if t < 3 else s1
        x1 = s1 if t < 2 else s2
        x2 = s2 if t == 0 else s3
        if x0 == x1 or x1 == x2:
            continue
        if near_pair(x0, x1, r2, xs, ys) or near_pair(x1, x2, r2, xs, ys):
            continue
        if near_pair(x0, x2, r2, xs, ys):
            continue
        if omit == p0:
            cx, cy = vx, vy
        elif omit == p1:
            cx, cy = c1x, c1y
        elif omit == p2:
            cx, cy = c2x, c2y
        else:
            cx, cy = voronoi_vertex(x0, x1, x2, xs, ys)
        if np.isfinite(cx) and np.isfinite(cy):
            if is_close(vx, vy, cx, cy, sx, sy, VERTEX_SNAP_RTOL):
                return cx, cy
    return vx, vy
