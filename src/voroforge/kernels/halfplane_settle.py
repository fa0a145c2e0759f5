"""Exact finishing of a half-plane cell: its ring of neighbours made exact, then emitted.

The float cut (:mod:`.halfplane`) leaves a ring of neighbour labels that is right up to
rounding. This module makes it exactly right and writes the cell with vertices that every
cell sharing them computes identically:

1. :func:`settle_ring` checks the ring with the exact ``orient2d``/``incircle`` against every
   site met within the cell's reach (zero-length edges of cocircular sites go, neighbours
   lost to coinciding float bisectors come back) and names every vertex by its owners:
   :func:`.vertex.voronoi_vertex` of the triple, or, where more sites are on the circle to
   rounding, the triple :func:`.vertex.canonical_triple` picks. A site counts as on a circle
   by rounding only if the four sites' centres are one vertex to rounding, decided once
   for the four whichever cell asks (:func:`_joins`): near-duplicate sites make a tiny
   incircle value but long edges.
2. :func:`emit_exact` writes the ring: bisector-bisector vertices from step 1, a bisector's
   crossing with a box side by :func:`.vertex.box_crossing` (or the canonical vertex there
   when the crossing is one), box corners exactly.
3. :func:`emit_float` writes the float cut as it is, the fallback when step 1 fails.

Labels are site indices (``>= 0``) and box sides ``LEFT, BOTTOM, RIGHT, TOP`` (-1..-4, the
side codes of :func:`.vertex.box_crossing`); all box sides are written as owner -1.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import (
    HALFPLANE_MERGE_RTOL,
    HALFPLANE_NEAR_RTOL,
    HALFPLANE_SHADOW_RTOL,
    HALFPLANE_SNAP_PRE,
    NAME_MAX_TRIES,
    NJIT,
)
from ..config import (
    HALFPLANE_MERGE_WIDE_MAX as MERGE_WIDE_MAX,
)
from .cellcut import near_sides, onto_sides, side_reach
from .clip import dedupe_ring
from .predicates import incircle, orient2d
from .vertex import (
    box_crossing,
    canonical_vertex,
    canonical_vertex4,
    near_pair,
    same_vertex,
    voronoi_vertex_error,
    voronoi_vertex_lazy,
    voronoi_vertex_lazy_inline,
)

#: Box sides as ring labels (those of :func:`.vertex.box_crossing`); all become owner -1.
LEFT, BOTTOM, RIGHT, TOP = -1, -2, -3, -4
_U = 2.0**-53
_MAX_FIX = 64  # rounds of exact repair per cell before the float cut is kept as it is
# Work units of the settling, in the search's unit (a vertex or a site visited, ~1-2 ns):
_W_TEST = 8  # a filtered exact test (incircle, orient2d: ~10-20 ns)
_W_VERTEX = 32  # a vertex from its name (voronoi_vertex: ~30-50 ns)
_W_EXACT = 1024  # one from exact expansions (~5-10 us; a centre near the origin, see below)
_W_ADAPT = 512  # an incircle whose float filter fails: its exact stage (~1-3 us)
_SLOW_RTOL = 2.0**-20  # centres nearer the origin than this of their scale take that path


@njit(**NJIT)
def _merge_tol(r, vx, vy):
    """|d| below which a site is on the circle of radius ``r`` about vertex ``(vx, vy)``.

    Relative to the circle (the local spacing), plus the rounding of ``d`` that the
    vertex's representation error (ulps of its magnitude) causes: never a fixed fraction
    of the magnitude, which merged whole cells of lattices far from the origin.
    """
    return HALFPLANE_MERGE_RTOL * r * r + 16.0 * _U * r * (abs(vx) + abs(vy))


@njit(**NJIT)
def _edge_ok(i, j, p, q, xs, ys):
    """Whether neighbour ``j`` between ``p`` (before) and ``q`` (after) has an edge of length > 0.

    Around site ``i`` counter-clockwise, ``p`` lies right of ``i -> j`` and ``q`` left of it;
    the edge's ends are the circumcentres of ``(i, p, j)`` and ``(i, j, q)``, in that order
    exactly when ``p`` is strictly outside the circle through ``i, j, q`` (exact predicates).
    """
    ix = xs[i]
    iy = ys[i]
    jx = xs[j]
    jy = ys[j]
    if orient2d(ix, iy, jx, jy, xs[p], ys[p]) >= 0.0:
        return False
    if orient2d(ix, iy, jx, jy, xs[q], ys[q]) <= 0.0:
        return False
    if _rectangle(ix, iy, jx, jy, xs[q], ys[q], xs[p], ys[p]):
        return False  # cocircular: incircle is exactly 0 (its exact stage costs ~0.5 us)
    return incircle(ix, iy, jx, jy, xs[q], ys[q], xs[p], ys[p]) < 0.0


@njit(**NJIT)
def _rectangle(ax, ay, bx, by, cx, cy, dx, dy):
    """Whether the four points are the corners of an axis-aligned rectangle (in any order).

    Such corners are exactly cocircular (a rectangle's diagonals are diameters of one
    circle), so their ``incircle`` is exactly 0: an exact grid's squares, where the float
    filter always fails and the exact stage would run for every edge at them. The test:
    ``a`` shares its x with exactly one other point and its y with exactly one other, two
    different ones, and the fourth point has the x of the second and the y of the first.
    """
    nx = int(bx == ax) + int(cx == ax) + int(dx == ax)
    ny = int(by == ay) + int(cy == ay) + int(dy == ay)
    if nx != 1 or ny != 1:
        return False
    kp = 0 if bx == ax else (1 if cx == ax else 2)  # the point with a's x
    kr = 0 if by == ay else (1 if cy == ay else 2)  # the point with a's y
    if kp == kr:
        return False  # one point with both: not four corners
    ks = 3 - kp - kr  # the other one: the opposite corner
    xs3 = (bx, cx, dx)
    ys3 = (by, cy, dy)
    rx = xs3[kr]
    py = ys3[kp]
    return xs3[ks] == rx and ys3[ks] == py and rx != ax and py != ay


@njit(**NJIT)
def _shadowed_at_box(i, j, k, side, xs, ys, box):
    """Whether neighbour ``j`` between box side ``side`` and site ``k`` has no edge.

    Only for ``k`` a few ulps from ``j`` (their bisectors with ``i`` are nearly parallel,
    their crossing and the float cut are ill-conditioned): ``j``'s edge starts where its
    bisector meets the side, and is empty when ``k`` is nearer there than ``j``, i.e.
    ``|c - j|^2 - |c - k|^2 = (k - j) . (2 c - j - k) > 0`` (``k - j`` is exact).
    """
    dx = xs[k] - xs[j]
    dy = ys[k] - ys[j]
    ex = xs[j] - xs[i]
    ey = ys[j] - ys[i]
    if dx * dx + dy * dy > HALFPLANE_SHADOW_RTOL * (ex * ex + ey * ey):
        return False
    cx, cy = box_crossing(i, j, xs, ys, side, box)
    if not (np.isfinite(cx) and np.isfinite(cy)):
        return False
    return dx * (2.0 * cx - xs[j] - xs[k]) + dy * (2.0 * cy - ys[j] - ys[k]) > 0.0


@njit(**NJIT)
def _behind(i, j, k, xs, ys):
    """Whether site ``k`` lies strictly between sites ``i`` and ``j`` on one line (exact).

    Then the bisector of ``i, k`` is parallel to that of ``i, j`` and nearer ``i``: ``j``
    has no edge in ``i``'s cell (sites an ulp apart on a line: the float cut made the two
    parallel bisectors cross, and the ring kept a vertex of three collinear sites).
    """
    if orient2d(xs[i], ys[i], xs[j], ys[j], xs[k], ys[k]) != 0.0:
        return False
    # on the line i-j: strictly between along each axis where they differ (exact compares)
    for a, b, c in ((xs[i], xs[j], xs[k]), (ys[i], ys[j], ys[k])):
        if a != b and not (min(a, b) < c < max(a, b)):
            return False
    return (xs[k], ys[k]) != (xs[i], ys[i]) and (xs[k], ys[k]) != (xs[j], ys[j])


@njit(**NJIT)
def _shadowing(i, j, side, cand, nc, sidx, xs, ys, box):
    """A site among ``cand[:nc]`` a few ulps from ``j`` and nearer than it at ``j``'s box end.

    That is where the bisector of ``i, j`` meets box side ``side``
    (:func:`_shadowed_at_box`), or anywhere: a site strictly between ``i`` and ``j`` on
    their line (:func:`_behind`, exact; three sites an ulp apart on a line, where the two
    outer ones' float bisectors coincide and the cut lost the middle one). -1 when there
    is none.
    """
    for c in range(nc):
        x = sidx[cand[c]]
        if x != j and x != i:
            if _shadowed_at_box(i, j, x, side, xs, ys, box) or _behind(i, j, x, xs, ys):
                return x
    return -1


@njit(**NJIT)
def _remove(lab, m, u):
    for k in range(u, m - 1):
        lab[k] = lab[k + 1]
    return m - 1


@njit(**NJIT)
def _insert(lab, m, u, x):
    """Put label ``x`` at ring position ``u`` (the rest move up one); the new length."""
    for k in range(m, u, -1):
        lab[k] = lab[k - 1]
    lab[u] = x
    return m + 1


@njit(inline="always", **NJIT)
def _drop_invalid(i, lab, m, xs, ys, sure, trust, box):
    """Remove repeated labels and neighbours whose edge has no positive length.

    With ``trust``, labels whose float edge is long (``sure[u]``) are kept without the exact
    test: the float cut is off by rounding only, so such an edge exists. A label next to a
    box side and to a site a few ulps from its own goes when the other one is nearer where
    its bisector meets the box (:func:`_shadowed_at_box`).
    """
    u = np.int64(0)  # not a literal: see halfplane._cells
    while u < m and m >= 3:
        j = lab[u]
        p = lab[u - 1] if u > 0 else lab[m - 1]
        q = lab[u + 1] if u + 1 < m else lab[0]
        check = j >= 0 and p >= 0 and q >= 0 and p != q and not (trust and sure[u] > 0.0)
        shadowed = j >= 0 and (p < 0) != (q < 0)
        if shadowed:
            k = q if p < 0 else p
            shadowed = _shadowed_at_box(i, j, k, p if p < 0 else q, xs, ys, box)
            shadowed = shadowed or _behind(i, j, k, xs, ys)
        if j == p or shadowed or (check and not _edge_ok(i, j, p, q, xs, ys)):
            m = _remove(lab, m, u)
            u = max(u - 1, 0)
            trust = False  # sure[] is indexed by the ring as it was: no longer aligned
            continue
        u += 1
    return m


@njit(inline="always", **NJIT)
def settle_ring(i, lab, m, sure, cand, nc, sidx, xs, ys, vx, vy, on, box, budget):
    """Make the ring of neighbour labels ``lab[:m]`` exactly right.

    Returns ``(length, work)``: the settled ring's length, and the work units it cost
    (``_W_TEST`` an exact test, ``_W_VERTEX`` a vertex computed from its name, one a
    candidate looked at). The length is -2, and the ring unsettled, as soon as the work
    would pass ``budget``: the cell's vertices have many sites on their circles to rounding
    (sites on one circle), whose names alone cost up to ``NAME_MAX_TRIES`` vertices each,
    and the caller leaves the cell to the Delaunay dual (also for a four, below).

    Float cutting can keep an edge of zero length (cocircular sites), or lose a neighbour
    whose bisector coincides with another one in floating point. Labels without a positive
    edge are dropped (:func:`_edge_ok`); then each vertex between neighbours ``a, b`` is
    checked against every candidate site: one strictly inside the circle through ``i, a, b``
    is inserted between them (float filter, exact ``incircle`` near the circle). Candidates
    exactly on the circle are cocircular: the vertex is then the one named by the canonical
    triple of the sites on it, which every cell around the vertex finds the same.
    Returns -1 when the ring cannot be settled (the caller keeps the float cut).

    A site in the merge band (:func:`_merge_tol`) is on the circle only if its vertices
    with the circle's sites are the vertex to rounding (:func:`_joins`); else the dual's
    classes decide (-2), but a site ulps from ``i``, ``a``, ``b`` (or a band past
    ``MERGE_WIDE_MAX`` of the circle) gets the exact test. The canonical centre is that
    of the first well-conditioned triple of the sites on the circle
    (:func:`.vertex.canonical_vertex`). ``on`` is scratch for those sites (int64, any size).

    ``sure[u]`` flags labels whose float edge is long; until the ring changes they skip the
    exact tests (their edge and the orientation at its ends are beyond rounding).
    """
    cap = lab.shape[0]
    trust = True
    work = 0
    for _ in range(_MAX_FIX):
        m0 = m
        m = _drop_invalid(i, lab, m, xs, ys, sure, trust, box)
        work += _W_TEST * m
        if m < 3:
            return -1, work
        trust = trust and m == m0
        inserted = False
        for u in range(m):
            a = lab[u - 1] if u > 0 else lab[m - 1]
            b = lab[u]
            if (a < 0) != (b < 0) and m < cap:
                # a site's edge meeting a box side: a site a few ulps from it that is
                # nearer there owns the edge's end (their bisectors with i coincide in
                # floats, and the cut kept one of them)
                work += nc
                x = _shadowing(i, b if a < 0 else a, b if b < 0 else a, cand, nc, sidx, xs, ys, box)
                if x >= 0 and not _has(lab, m, x):
                    m = _insert(lab, m, u, x)
                    inserted = True
                    break
            if a < 0 or b < 0:
                continue
            ix = xs[i]
            iy = ys[i]
            both = trust and sure[u] > 0.0 and sure[u - 1 if u > 0 else m - 1] > 0.0
            if not both and orient2d(ix, iy, xs[a], ys[a], xs[b], ys[b]) <= 0.0:
                return -1, work
            work += _W_VERTEX + nc
            if work > budget:
                return -2, work
            # voronoi_vertex_lazy inlined: a call costs reference counts of xs, ys
            vx_, vy_, ev_, lv_ = voronoi_vertex_lazy_inline(i, a, b, xs, ys)
            r2 = (ix - vx_) * (ix - vx_) + (iy - vy_) * (iy - vy_)
            tol = HALFPLANE_NEAR_RTOL * r2
            # a site this close to the circle is on it: the edge it would add or keep is
            # shorter than floats can order (the default algorithm merges such vertices too)
            r = np.sqrt(r2)
            merge = _merge_tol(r, vx_, vy_)
            wide = merge <= MERGE_WIDE_MAX * r2
            nxt = lab[u + 1] if u + 1 < m else lab[0]
            prv = lab[u - 2] if u >= 2 else lab[u - 2 + m]
            non = np.int64(0)  # other sites on the circle, to rounding
            charged = False
            jsite = np.int64(-1)  # the last joined site, and its two centres (_joins)
            doubt = False  # a site on the circle to rounding that does not join
            j1x = j1y = j2x = j2y = 0.0
            for c in range(nc):
                x = sidx[cand[c]]
                if x == a or x == b:
                    continue
                dx = xs[x] - vx_
                dy = ys[x] - vy_
                d = dx * dx + dy * dy - r2
                if d > tol and (d > merge or not wide):
                    # (far out the merge band, ulps of the vertex's magnitude, is the wider:
                    # a site within it is tested for joining, never skipped as outside by
                    # the float test, unless the band is most of the circle: sites ulps
                    # apart, which the exact tests decide)
                    continue
                if not charged and d >= -tol:
                    # the first site near the circle: charge all of them at once, so a
                    # vertex with hundreds (sites on one circle) stops before the first
                    # exact test (random sites never get here: none is near)
                    work += _near_cost(a, b, c, cand, nc, sidx, xs, ys, vx_, vy_, r2, tol, merge)
                    charged = True
                    if work > budget:
                        return -2, work
                joined = False
                if abs(d) <= merge:
                    joined, ev_, q1x, q1y, q2x, q2y = _joins(i, a, b, x, vx_, vy_, ev_, lv_, xs, ys)
                    doubt = doubt or not joined
                    if not joined and wide and not _near_any(x, i, a, b, r2, xs, ys):
                        # on the circle to rounding, yet its four centres are not one point
                        # pair by pair: the Delaunay dual may still join them (adjacent
                        # centres within their bounds, chained classes) or keep the edge
                        # (a float-rotated lattice at 1e3: an edge of 3.4e-13 it merges),
                        # which no local test can tell; the dual builds the cell, and its
                        # seams with the others are checked (engine.planar). Where the band
                        # is most of the circle, or the site is a few ulps from i, a or b
                        # (sites ulps apart, whose cells the default takes from here when
                        # its own lose sites) the exact test decides
                        return -2, work
                if joined:
                    if x == nxt or x == prv:
                        # the edge of b (or a) between this vertex and x's is noise: drop it
                        m = _remove(lab, m, u if x == nxt else (u - 1 if u > 0 else m - 1))
                        inserted = True
                        break
                    s = 0.0
                    jsite = x
                    j1x, j1y, j2x, j2y = q1x, q1y, q2x, q2y
                elif d < -tol and abs(d) > merge:
                    s = 1.0
                else:
                    if abs(d) <= merge:
                        # not joined, yet on the circle to rounding: the float filter
                        # cannot call it, the exact stage runs (a far circle's centre)
                        work += _W_ADAPT
                        if work > budget:
                            return -2, work
                    s = incircle(ix, iy, xs[a], ys[a], xs[b], ys[b], xs[x], ys[x])
                if s > 0.0:
                    # x strictly inside the circle and on the line through i and a (or b)
                    # lies between them: a's bisector is beyond x's, so x replaces a
                    ua = u - 1 if u > 0 else m - 1
                    oa = orient2d(ix, iy, xs[a], ys[a], xs[x], ys[x])
                    if oa == 0.0:
                        if not _has(lab, m, x):
                            lab[ua] = x
                            inserted = True
                            break
                    ob = orient2d(ix, iy, xs[b], ys[b], xs[x], ys[x])
                    if ob == 0.0:
                        if not _has(lab, m, x):
                            lab[u] = x
                            inserted = True
                            break
                    if m < cap and not _has(lab, m, x):
                        # x goes where its direction from i is in the ring: between a and
                        # b, or just past b (before a) when the float ring put b (a) on
                        # the wrong side of it; that neighbour's edge then fails
                        # _edge_ok. Inserted between them, x would fail it instead, and
                        # come back every round (a 1e-9 cluster in a 1e6 box: the float
                        # cut's crossings are off by ulps of the box, 10% of the cell)
                        at = u
                        if ob > 0.0 and oa > 0.0:
                            at = u + 1
                        elif oa < 0.0 and ob < 0.0:
                            at = ua
                        m = _insert(lab, m, at, x)
                        inserted = True
                        break
                elif s == 0.0 and non + 3 < on.shape[0]:
                    on[non] = x  # on the circle, or on the vertex by rounding (joined)
                    non += 1
            if inserted:
                break
            if non > 1:
                work += non * non  # a pair test each (sites on one circle: many)
                if work > budget:
                    return -2, work
                non = _drop_shadowed(i, a, b, on, non, r2, xs, ys)
                if non > 1 and jsite >= 0 and doubt:
                    # two or more other sites on the vertex to rounding, some joined and
                    # some near it refused: joining is decided per quadruple (_joins), so
                    # the cells around such a vertex can join different sites and name it
                    # differently (350 sites on a circle of 1e-4 at (-2e5, 5e5): two
                    # vertices an ulp apart, one cell took the other's). The Delaunay dual
                    # decides them for the whole diagram, and its seams with the other
                    # cells are checked (engine.planar). Where every site near the circle
                    # joins (a lattice's cocircular sites scaled by 1/6), every cell finds
                    # the same set: those vertices stay here
                    return -2, work
            if non == 0:
                vx[u] = vx_  # no other site on the circle: the centre computed above
                vy[u] = vy_
            else:
                # the name is searched among the triples of the non + 3 sites on the circle
                k = non + 3
                tries = min(k * (k - 1) * (k - 2) // 6, NAME_MAX_TRIES)
                work += tries * _vertex_cost(vx_, vy_, r, ix, iy)
                if work > budget:
                    return -2, work
                if non == 1 and on[0] == jsite:
                    # four sites (a grid's square): three of the four triples' centres
                    # are known, the vertex's and the two _joins computed
                    vx[u], vy[u] = canonical_vertex4(
                        jsite, b, a, i, vx_, vy_, j1x, j1y, j2x, j2y, xs, ys
                    )
                else:
                    on[non] = i
                    on[non + 1] = a
                    on[non + 2] = b
                    vx[u], vy[u] = canonical_vertex(on, non + 3, vx_, vy_, ix, iy, xs, ys)
        if not inserted:
            return m, work
        trust = False  # the ring changed: every label gets the exact tests from now on
    return -1, work


@njit(**NJIT)
def _vertex_cost(vx, vy, r, sx, sy):
    """Work units of a vertex near ``(vx, vy)`` named by sites at distance ``r`` (one ``s``).

    Those vertices come from exact expansions when the centre is near the origin against
    its circle and sites (its rounding bound is then past ``VERTEX_REFINE_RTOL`` of its
    magnitude: sites on a circle about the origin), and cost ``_W_EXACT`` each.
    """
    if abs(vx) + abs(vy) < _SLOW_RTOL * (r + abs(sx) + abs(sy)):
        return _W_EXACT
    return _W_VERTEX


@njit(**NJIT)
def _near_cost(a, b, c0, cand, nc, sidx, xs, ys, vx, vy, r2, tol, merge):
    """Work units of the sites among ``cand[c0:nc]`` (but ``a``, ``b``) near the circle at ``v``.

    A site within ``merge`` of the circle costs two vertices (:func:`_joins`), one within
    ``tol`` an exact test.
    """
    join = 2 * _vertex_cost(vx, vy, np.sqrt(r2), xs[a], ys[a])
    work = 0
    for c in range(c0, nc):
        x = sidx[cand[c]]
        if x == a or x == b:
            continue
        dx = xs[x] - vx
        dy = ys[x] - vy
        d = abs(dx * dx + dy * dy - r2)
        if d <= merge:
            work += join
        elif d <= tol:
            work += _W_TEST
    return work


@njit(**NJIT)
def _joins(i, a, b, x, vx, vy, ev, lv, xs, ys):
    """Whether site ``x`` near the circle of ``i, a, b`` (centre ``vx, vy``) is on its vertex.

    Decided for the four sites once, the same from each of their cells: True when the
    four centres of their triples are one point by the one merge rule
    (:func:`.vertex.same_vertex`) pair by pair, at the scale :func:`_quad_scale`, or when
    the four are a rectangle's corners (exactly cocircular: one exact centre). The merge
    rule is not transitive, so a test from the asking cell's own vertex would let two
    cells at one group decide it differently: one merged an edge an ulp long that its
    neighbour kept, one vertex at two points (sites 1-3 ulps apart, issue 15). Each
    centre's bits and bounds do not depend on the order of its sites, so neither does the
    answer. The pairs are tried with lower bounds first (``lv`` the vertex's,
    :func:`.vertex.voronoi_vertex_lazy`): passing with them passes with the bounds, which
    are computed only where that fails. A collinear triple (no centre) never joins.
    Returns ``(joined, ev, x1, y1, x2, y2)``: ``ev`` is -1 on entry when not yet computed,
    and comes back computed if it was needed; when joined, the two centres (of ``i, a, x``
    and of ``i, x, b``), which may name the vertex.
    """
    x1, y1, e1, l1 = voronoi_vertex_lazy(i, a, x, xs, ys)
    x2, y2, e2, l2 = voronoi_vertex_lazy(i, x, b, xs, ys)
    fin = np.isfinite(x1) and np.isfinite(y1) and np.isfinite(x2) and np.isfinite(y2)
    if not fin:
        return False, ev, 0.0, 0.0, 0.0, 0.0
    if _rectangle(xs[i], ys[i], xs[a], ys[a], xs[b], ys[b], xs[x], ys[x]):
        return True, ev, x1, y1, x2, y2  # (a grid's squares: no bound needed)
    x3, y3, e3, l3 = voronoi_vertex_lazy(a, x, b, xs, ys)
    if not (np.isfinite(x3) and np.isfinite(y3)):
        return False, ev, 0.0, 0.0, 0.0, 0.0
    cx = (vx, x1, x2, x3)
    cy = (vy, y1, y2, y3)
    r = _quad_scale(i, a, b, x, cx, cy, xs, ys)
    if _one_point(cx, cy, (lv, l1, l2, l3), r):
        return True, ev, x1, y1, x2, y2
    if ev < 0.0:
        ev = voronoi_vertex_error(i, a, b, xs, ys)
    e1 = e1 if e1 >= 0.0 else voronoi_vertex_error(i, a, x, xs, ys)
    e2 = e2 if e2 >= 0.0 else voronoi_vertex_error(i, x, b, xs, ys)
    e3 = e3 if e3 >= 0.0 else voronoi_vertex_error(a, x, b, xs, ys)
    if _one_point(cx, cy, (ev, e1, e2, e3), r):
        return True, ev, x1, y1, x2, y2
    return False, ev, 0.0, 0.0, 0.0, 0.0


@njit(**NJIT)
def _near_any(x, i, a, b, r2, xs, ys):
    """Whether site ``x`` is a few ulps from ``i``, ``a`` or ``b`` (:func:`.vertex.near_pair`)."""
    return near_pair(x, i, r2, xs, ys) or near_pair(x, a, r2, xs, ys) or near_pair(x, b, r2, xs, ys)


@njit(**NJIT)
def _quad_scale(i, a, b, x, cx, cy, xs, ys):
    """The smallest L1 distance from one of four centres to one of the four sites.

    The merge rule's ``r`` for the group (a distance from a vertex to a site on its
    circle), the same whichever cell asks: the asking cell's own distance differs by
    rounding between the cells.
    """
    r = np.inf
    for s in (i, a, b, x):
        for k in range(4):
            r = min(r, abs(cx[k] - xs[s]) + abs(cy[k] - ys[s]))
    return r


@njit(**NJIT)
def _one_point(cx, cy, e, r):
    """Whether the four centres ``(cx[k], cy[k])`` with bounds ``e[k]`` are one vertex.

    Every pair by :func:`.vertex.same_vertex` (not transitive: all six are tested).
    """
    for p in range(4):
        for q in range(p + 1, 4):
            if not same_vertex(cx[p], cy[p], e[p], cx[q], cy[q], e[q], r):
                return False
    return True


@njit(**NJIT)
def _drop_shadowed(i, a, b, on, non, r2, xs, ys):
    """Drop from ``on[:non]`` each site a few ulps from another that is nearer the vertex.

    Of two sites on the circle of ``i, a, b`` to rounding whose bisector floats cannot
    place (:func:`.vertex.near_pair`), the one strictly inside the circle (exact
    ``incircle``) shadows the other, as in the Delaunay dual, where the farther one is in
    none of the vertex's triangles and so not in its name. Returns the new count.
    """
    ix = xs[i]
    iy = ys[i]
    kept = 0
    for c in range(non):
        x = on[c]
        drop = False
        for e in range(non):
            y = on[e]
            if y == x or not near_pair(x, y, r2, xs, ys):
                continue
            sy = incircle(ix, iy, xs[a], ys[a], xs[b], ys[b], xs[y], ys[y])
            sx = incircle(ix, iy, xs[a], ys[a], xs[b], ys[b], xs[x], ys[x])
            if sy > 0.0 >= sx:
                drop = True
                break
        if not drop:
            on[kept] = x
            kept += 1
    return kept


@njit(**NJIT)
def _has(lab, m, x):
    for k in range(m):
        if lab[k] == x:
            return True
    return False


@njit(**NJIT)
def _snap_crossing(i, j, x, y, xs, ys, near, nn, sidx, on):
    """The canonical vertex at box crossing ``(x, y)`` of the bisector of ``i, j``, if any.

    When other sites are as far from the crossing as ``i`` and ``j`` (to the merge
    tolerance), the crossing is a Voronoi vertex lying on the box: it becomes the
    canonical centre of those sites (:func:`.vertex.canonical_vertex`), as in
    :func:`settle_ring`. ``on`` is scratch (int64, any size).
    """
    r2 = (xs[i] - x) * (xs[i] - x) + (ys[i] - y) * (ys[i] - y)
    r = np.sqrt(r2)
    merge = _merge_tol(r, x, y)
    on[0] = i
    on[1] = j
    k = np.int64(2)
    for c in range(nn):
        q = sidx[near[c]]
        if q == i or q == j:
            continue
        dx = xs[q] - x
        dy = ys[q] - y
        if abs(dx * dx + dy * dy - r2) <= merge and k < on.shape[0]:
            on[k] = q
            k += 1
    if k == 2:
        return x, y
    return canonical_vertex(on, k, x, y, xs[i], ys[i], xs, ys)


@njit(**NJIT)
def _side_snap(i, a, b, x, y, xs, ys, box):
    """Vertex ``(x, y)`` of sites ``i, a, b`` put on the box sides within its reach.

    As the Delaunay dual's cells put it (:func:`.cellcut.side_reaches`,
    :func:`.cellcut.on_sides`): within four times its rounding bound and an ulp of a side
    it is on that side to rounding, and each cell's own cut would decide alone where it
    is (a gap an ulp wide along the side between the cells at it). It stays where it is
    when one of its sites lies within that reach of the side, or two of them within twice
    of each other. Returns ``(x, y, hit)``.
    """
    # the reach is at most 4 VERTEX_REFINE_RTOL (2**-30) of |x| + |y| plus an ulp: a
    # vertex farther inside than this needs no bound (almost all of them)
    pre = HALFPLANE_SNAP_PRE * (abs(x) + abs(y))
    if box[0] + pre < x < box[2] - pre and box[1] + pre < y < box[3] - pre:
        return x, y, False
    e = side_reach(x, y, voronoi_vertex_error(i, a, b, xs, ys))
    bits = near_sides(x, y, e, box)
    if bits == 0:
        return x, y, False
    for s, t in ((i, a), (a, b), (b, i)):
        if near_sides(xs[s], ys[s], e, box) & bits:
            return x, y, False
        if abs(xs[s] - xs[t]) <= 2.0 * e and abs(ys[s] - ys[t]) <= 2.0 * e:
            return x, y, False
    x, y = onto_sides(x, y, bits, box)
    return x, y, True


@njit(**NJIT)
def _on_side(x, y, side, box):
    """Whether ``(x, y)`` lies on box side ``side`` (``LEFT`` .. ``TOP``), exactly."""
    if side == LEFT:
        return x == box[0]
    if side == BOTTOM:
        return y == box[1]
    if side == RIGHT:
        return x == box[2]
    return y == box[3]


@njit(**NJIT)
def _crossing_at_end(i, u, lab, m, ox, oy, oo, xs, ys, box, near, nn, sidx, x, y):
    """Crossing ``(x, y)`` at ring position ``u`` (a site and a side), or its edge's end there.

    The site's edge ends at a vertex inside the ring (the next site label, ``ox, oy`` with
    ``oo`` 1 where :func:`_side_snap` put it on a side) and at one past the side, shared
    with a site of ``near[:nn]`` (sorted indices, ``sidx`` maps them) that the ring may
    lack (its part of the cell lies past the side: a vertex on the side or an ulp past
    it). An end put on this side by :func:`_side_snap` is the crossing, the nearer one
    when both are (:func:`.cellcut._crossing_at_vertex`, the dual's cells).
    """
    a = lab[u - 1] if u > 0 else lab[m - 1]
    b = lab[u]
    side = b if a >= 0 else a
    j = a if a >= 0 else b
    best = np.inf
    bx = x
    by = y
    # the end inside the ring: the vertex between j and its neighbour there
    w = u - 1 if a >= 0 else u + 1
    w = (w + m) % m
    pa = lab[w - 1] if w > 0 else lab[m - 1]
    if pa >= 0 and lab[w] >= 0 and oo[w] == 1 and _on_side(ox[w], oy[w], side, box):
        best = abs(ox[w] - x) + abs(oy[w] - y)
        bx = ox[w]
        by = oy[w]
    # the end past the side, shared with a site the ring may lack (its part of the cell
    # is past the side): a watched site whose vertex with i and j on j's bisector lies
    # within _side_snap's screen of the side. Along the bisector from the crossing the
    # difference f of squared distances from k and i is linear, and the vertex (f = 0)
    # is |f| un / (2 |cross|) from the side (un: the bisector's slope against it)
    ix = xs[i]
    iy = ys[i]
    r2 = (ix - x) * (ix - x) + (iy - y) * (iy - y)
    un = abs(xs[j] - ix) if side == BOTTOM or side == TOP else abs(ys[j] - iy)
    # (the vertex lies along the side, within the box's extent: its magnitude is the box's)
    pre = 4.0 * HALFPLANE_SNAP_PRE * (max(abs(box[0]), abs(box[2])) + max(abs(box[1]), abs(box[3])))
    for c in range(nn):
        k = sidx[near[c]]
        if k == i or k == j:
            continue
        dx = xs[k] - x
        dy = ys[k] - y
        f = abs(dx * dx + dy * dy - r2) - 8.0 * _U * (dx * dx + dy * dy + r2)
        cross = (iy - ys[k]) * (xs[j] - ix) - (ix - xs[k]) * (ys[j] - iy)
        if f * un > pre * abs(cross):
            continue
        vx, vy, _, _ = voronoi_vertex_lazy(i, j, k, xs, ys)
        vx, vy, hit = _side_snap(i, j, k, vx, vy, xs, ys, box)
        if hit and _on_side(vx, vy, side, box) and abs(vx - x) + abs(vy - y) < best:
            best = abs(vx - x) + abs(vy - y)
            bx = vx
            by = vy
    return bx, by


@njit(inline="always", **NJIT)
def emit_exact(i, lab, m, vx, vy, xs, ys, box, near, nn, sidx, ox, oy, oo, on):
    """Write the settled ring with canonical vertices to ``o``; -1 when one is undefined.

    Bisector-bisector vertices come from :func:`settle_ring`; a bisector meets a box side at
    the crossing named by the pair and the side (:func:`.vertex.box_crossing`), and two
    box sides meet at the exact corner. A crossing that is also a Voronoi vertex (a site
    among ``near[:nn]`` as far from it as the pair, to rounding) is that vertex's canonical
    circumcentre instead, which the cells meeting there inside compute too. A vertex within
    reach of a box side is put on it, with the crossings of that side by its edges
    (:func:`_side_snap`, :func:`_crossing_at_end`), as the dual's cells put it. ``on`` is
    scratch (int64, any size).
    """
    for u in range(m):
        a = lab[u - 1] if u > 0 else lab[m - 1]
        b = lab[u]
        oo[u] = 0
        if a >= 0 and b >= 0:
            x, y, hit = _side_snap(i, a, b, vx[u], vy[u], xs, ys, box)
            ox[u] = x
            oy[u] = y
            oo[u] = 1 if hit else 0
    for u in range(m):
        a = lab[u - 1] if u > 0 else lab[m - 1]
        b = lab[u]
        if a >= 0 and b >= 0:
            continue
        elif a >= 0 or b >= 0:
            j = a if a >= 0 else b
            side = b if a >= 0 else a
            x, y = box_crossing(i, j, xs, ys, side, box)
            if np.isfinite(x) and np.isfinite(y):
                # the vertex takes the crossing's place only on the side: one off it (beyond
                # the side snap's reach) keeps its edge to the side, as in the dual's cells
                sx, sy = _snap_crossing(i, j, x, y, xs, ys, near, nn, sidx, on)
                if _on_side(sx, sy, side, box):
                    x, y = sx, sy
                x, y = _crossing_at_end(i, u, lab, m, ox, oy, oo, xs, ys, box, near, nn, sidx, x, y)
        else:
            vert = a if (a == LEFT or a == RIGHT) else b
            horz = b if vert == a else a
            if not ((vert == LEFT or vert == RIGHT) and (horz == BOTTOM or horz == TOP)):
                return -1
            x = box[0] if vert == LEFT else box[2]
            y = box[1] if horz == BOTTOM else box[3]
        ox[u] = x
        oy[u] = y
    for u in range(m):
        x = ox[u]
        y = oy[u]
        if not (np.isfinite(x) and np.isfinite(y)):
            return -1
        ox[u] = min(max(x, box[0]), box[2])
        oy[u] = min(max(y, box[1]), box[3])
        oo[u] = lab[u] if lab[u] >= 0 else -1
    return dedupe_ring(ox, oy, oo, m)


@njit(**NJIT)
def emit_float(px, py, po, a, m, cx, cy, box, ox, oy, oo):
    """Write the float cell at ``a:a + m`` around site ``(cx, cy)`` to ``ox, oy, oo``.

    The fallback when the exact ring cannot be settled. Coordinates become absolute and
    vertices on box edges are snapped onto the box. Returns the length written (0 when
    rounding left fewer than three distinct vertices).
    """
    xmin, ymin, xmax, ymax = box[0], box[1], box[2], box[3]
    for t in range(a, a + m):
        x = min(max(px[t] + cx, xmin), xmax)
        y = min(max(py[t] + cy, ymin), ymax)
        o = po[t]
        op = po[t - 1] if t > a else po[a + m - 1]
        if o == BOTTOM or op == BOTTOM:
            y = ymin
        if o == TOP or op == TOP:
            y = ymax
        if o == LEFT or op == LEFT:
            x = xmin
        if o == RIGHT or op == RIGHT:
            x = xmax
        ox[t - a] = x
        oy[t - a] = y
        oo[t - a] = max(o, -1)
    return dedupe_ring(ox, oy, oo, m)
