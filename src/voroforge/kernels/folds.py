"""The cells' fold test: rings that rounding folded, and the vertices to join to unfold them.

Every cell ring of :func:`.cells.cells_from_triangulation` is certified convex with exact
turns (:func:`.clip.ring_convex`). A ring can still come out folded where the vertices of a
nearly cocircular cluster (a float circle far from the origin: its vertices are spaced like
the ulps there) round across each other. This module finds those rings and the pairs of
triangles whose classes must join (:func:`.centers.contract` joins them, and the cells are
built again):

- :func:`risky_sites`: the only sites whose rings can fold (a vertex of a short or undecided
  edge, :func:`.centers.merge_cocircular`); most inputs have none.
- :func:`folded_rings`: which of those rings fail the exact convexity test.
- :func:`fold_pairs`: for each folded ring, the pairs of triangles to join (the run of edges
  through a bad turn whose ends are one vertex to rounding, or, at a straight angle rounded
  into a bad turn, the edge :func:`_straight_fold` picks), within a reach of
  ``FOLD_REACH_RTOL`` of the vertex's distance from its site, doubled while no folded ring
  gives a join (a stall: small float circles far from the origin); a test that still
  stalls asks for the classes at the bad turns to be named afresh (:func:`.refit.fit_classes`).
- :func:`unfold_cells`: the rounds (test, join, build again), kept to the best round by
  :func:`_score` (rings not simple, then folded; once a ring folds, every cell of the first
  build is tested): where joins score worse, moves from the best round (:func:`_refine`:
  the classes at the bad turns named afresh, the joins of the rings not simple, every join,
  each joined class named afresh and no other renamed), then the same from the first build.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..config import (
    FOLD_MAX_ROUNDS,
    FOLD_REACH_ERRS,
    FOLD_REACH_RTOL,
    FOLD_SIMPLE_MAX,
    FOLD_SORT_TURNS,
    FOLD_SPAN_ERRS,
    FOLD_STALL_DOUBLINGS,
    FOLD_STALL_SPACING,
    NJIT,
    NJIT_PARALLEL,
)
from .cellcut import class_err, side_reaches
from .centers import contract_by, short_edge
from .clip import ring_convex
from .predicates import orient2d
from .vertex import voronoi_vertex

_U = 2.0**-53


@njit(**NJIT)
def risky_sites(tri, near, n):
    """Sites with a triangle marked in ``near`` (:func:`.centers.merge_cocircular`)."""
    risk = np.zeros(n, dtype=np.bool_)
    for t in range(near.shape[0]):
        if near[t] != 0:
            risk[tri[3 * t]] = True
            risk[tri[3 * t + 1]] = True
            risk[tri[3 * t + 2]] = True
    return risk


@njit(**NJIT_PARALLEL)
def folded_rings(coords, lengths, order, risk):
    """Whether each kernel site's ring (where ``risk``) fails :func:`.clip.ring_convex`."""
    n = order.shape[0]
    bad = np.zeros(n, dtype=np.bool_)
    for i in prange(n):
        if not risk[i]:
            continue
        a = lengths[order[i]]
        b = lengths[order[i] + 1]
        if b > a:
            bad[i] = not ring_convex(coords, a, b)
    return bad


@njit(**NJIT)
def _fan(i, tri, he, out, fan):
    """Triangles around site ``i`` in rotation order (the cells' walk) into ``fan``; count."""
    o0 = out[i]
    if o0 == -1:
        return 0
    o = o0
    k = 0
    while True:
        fan[k] = o // 3
        k += 1
        o = he[o - o % 3 + (o + 2) % 3]
        if o == -1 or o == o0:
            return k


@njit(**NJIT)
def _bad_turn(coords, a, b, c):
    """Whether ring vertices ``a -> b -> c`` turn right or reverse (exact on the floats)."""
    o = orient2d(coords[a, 0], coords[a, 1], coords[b, 0], coords[b, 1], coords[c, 0], coords[c, 1])
    if o < 0.0:
        return True
    if o > 0.0:
        return False
    # collinear: a reversal has opposite signs in a component (signs of differences are exact)
    ex = coords[b, 0] - coords[a, 0]
    ey = coords[b, 1] - coords[a, 1]
    fx = coords[c, 0] - coords[b, 0]
    fy = coords[c, 1] - coords[b, 1]
    return (ex != 0.0 and fx != 0.0 and (ex < 0.0) != (fx < 0.0)) or (
        ey != 0.0 and fy != 0.0 and (ey < 0.0) != (fy < 0.0)
    )


@njit(**NJIT)
def _moved(t, xs, ys, tri, err, cx, cy):
    """How far triangle ``t``'s exact centre can be from its vertex in the cells (L1).

    Its own centre is within ``err[t]`` of the exact one; its class's named vertex is where
    the cells put it, which a class joined by a chain of merges can carry further than the
    snap tolerance. Infinite (no bound) when its own centre is not finite.
    """
    # int64 site numbers (the triangles are int32): the vertex kernels' one signature
    a, b, c = np.int64(tri[3 * t]), np.int64(tri[3 * t + 1]), np.int64(tri[3 * t + 2])
    ox, oy = voronoi_vertex(a, b, c, xs, ys)
    # plus an ulp of the vertex (the fold tests' reach, as ``centers._ulps``)
    ulp = 2.0 * _U * (abs(cx[t]) + abs(cy[t]))
    return err[t] + abs(cx[t] - ox) + abs(cy[t] - oy) + ulp


@njit(**NJIT)
def _one_vertex(i, xs, ys, tri, err, cx, cy, t, u, rtol):
    """Whether the vertices of triangles ``t``, ``u`` (site ``i`` on both) are one to rounding.

    They are within what rounding and naming move them (:func:`.centers.short_edge`), or
    within ``FOLD_SPAN_ERRS`` times the proven distance of each from its exact centre (and
    ``rtol`` of their distance from the site: :func:`fold_pairs`' reach).
    """
    d = abs(cx[t] - cx[u]) + abs(cy[t] - cy[u])
    r = max(abs(cx[t] - xs[i]) + abs(cy[t] - ys[i]), abs(cx[u] - xs[i]) + abs(cy[u] - ys[i]))
    if not d <= rtol * r:
        return False  # (a centre's bound may reach 2**-30 of its magnitude: not the spacing)
    if short_edge(xs, ys, tri, err, cx, cy, t, u):
        return True
    bound = _moved(t, xs, ys, tri, err, cx, cy) + _moved(u, xs, ys, tri, err, cx, cy)
    return d <= FOLD_SPAN_ERRS * bound < np.inf


@njit(**NJIT)
def fold_pairs(sites, xs, ys, tri, he, out, cx, cy, err, cls, coords, lengths, order):
    """Pairs of triangles whose classes a folded ring asks to join: ``(pa, pb)``.

    For each site's ring, every vertex is matched to the triangle of the site's fan that
    holds its bits (box crossings match none). At a turn that is right or reverses (exact),
    the run of consecutive edges through it whose two ends are one vertex to rounding
    (:func:`.centers.short_edge`) is the folded cluster: each of its edges is a pair. A ring
    folded only by long edges (a straight angle rounded) gives none.

    The fans, the matches and the bad turns are found once (:func:`_matched`); each reach
    then visits only the bad turns (a ring of ``n`` vertices folded at a few: a sloped float
    line's site off it, whose reach doubled 6 times, each reading the whole ring again).
    """
    fit = _matched(sites, tri, he, out, cx, cy, cls, coords, lengths, order)
    mv = np.full(fit[2].shape[0], -1.0)  # each vertex's naming move, once (:func:`_moved_at`)
    args = (sites, xs, ys, tri, err, cx, cy, cls, coords, lengths, order, fit, mv)
    rtol = FOLD_REACH_RTOL
    pa, pb = _pairs_within(*args, rtol, False)
    # a stall: folded rings, and no join within the reach. Where a float circle's exact
    # vertices scatter over more than the reach (its sites' rounding moves the centres
    # of neighbouring triples by ~ulp * n**2 / 20: 600 sites of radius 1e-5 at 3e4,
    # 6e-3 of the radius) the contractions grow classes up to the reach and stop there,
    # with rings folded and even self-intersecting. The reach doubles until a ring gives
    # a join (the least that unfolds anything), at most FOLD_STALL_DOUBLINGS times, and
    # such joins keep their ends within FOLD_STALL_SPACING of the site's spacing of their
    # exact centres (unbounded, contractions carried vertices across sites: 333 sites of
    # radius 1e-5 at (1e6, 3e5) put 36 sites outside their cells)
    for _ in range(FOLD_STALL_DOUBLINGS):
        if pa.shape[0]:
            break
        rtol *= 2.0
        pa, pb = _pairs_within(*args, rtol, True)
    if pa.shape[0] == 0:
        # still none: the classes at the bad turns are to be named afresh, each at the
        # centre of one of its triples that leaves its cells the fewest bad turns (pairs
        # (t, t): :func:`.centers.contract`); a function of the rings and classes alone
        pa = _stalled_at(sites, cx, cy, coords, lengths, order, fit)
        pb = pa
    return pa, pb


@njit(**NJIT)
def _matched(sites, tri, he, out, cx, cy, cls, coords, lengths, order):
    """The sites' fans, their rings' vertices matched to them, and the turns to visit.

    Returns ``(fans, fan_at, tk, hk, flag)``: site ``sites[s]``'s fan (:func:`_fan`) is
    ``fans[fan_at[s]:fan_at[s + 1]]``; its ring vertex ``k`` (at ``coords[lengths[order[i]]
    + k]``) is the ``r = lengths[order[i]] + k``-th slot of ``tk`` (the first triangle of the
    fan from the previous match on that holds its bits, -1 for none), ``hk`` (its place in
    the fan) and ``flag`` (bit 1: a right or reversing turn, exact; bit 2: its edge to the
    next vertex joins two classes of one name). Slots of rings of under 3 vertices are
    unused.
    """
    size = coords.shape[0]
    tk = np.full(size, -1, dtype=np.int64)
    hk = np.zeros(size, dtype=np.int64)
    flag = np.zeros(size, dtype=np.uint8)
    fan_at = np.zeros(sites.shape[0] + 1, dtype=np.int64)
    fans = np.zeros(tri.shape[0] + 1, dtype=np.int64)  # (distinct sites: 3 per triangle)
    for s in range(sites.shape[0]):
        i = sites[s]
        b = lengths[order[i]]
        m = lengths[order[i] + 1] - b - 1
        fan_at[s + 1] = fan_at[s]
        if m < 3:
            continue
        if fans.shape[0] - fan_at[s] <= tri.shape[0] // 3:  # (a site listed twice)
            fans = np.concatenate((fans, np.zeros(tri.shape[0] // 3 + 1, dtype=np.int64)))
        fan = fans[fan_at[s] :]
        nf = _fan(i, tri, he, out, fan)
        fan_at[s + 1] = fan_at[s] + nf
        h = 0
        for k in range(m):
            for d in range(nf):
                t = fan[(h + d) % nf]
                if cx[t] == coords[b + k, 0] and cy[t] == coords[b + k, 1]:
                    tk[b + k] = t
                    h = (h + d) % nf
                    hk[b + k] = h
                    break
        for k in range(m):
            kp = k - 1 if k > 0 else m - 1
            kn = k + 1 if k + 1 < m else 0
            t = tk[b + k]
            u = tk[b + kn]
            if t >= 0 and u >= 0 and cls[t] != cls[u]:
                if cx[t] == cx[u] and cy[t] == cy[u]:
                    flag[b + k] |= 2
            if _bad_turn(coords, b + kp, b + k, b + kn):
                flag[b + k] |= 1
    return fans, fan_at, tk, hk, flag


@njit(**NJIT)
def _stalled(sites, tri, he, out, cx, cy, cls, coords, lengths, order):
    """Every triangle of the rings' fans at a bad turn or its two neighbours (by bits).

    All triangles holding a vertex's bits, so every class there, whatever triangle the
    builder's numbering puts first (two classes may share a name).
    """
    fit = _matched(sites, tri, he, out, cx, cy, cls, coords, lengths, order)
    return _stalled_at(sites, cx, cy, coords, lengths, order, fit)


@njit(**NJIT)
def _stalled_at(sites, cx, cy, coords, lengths, order, fit):
    """:func:`_stalled` on :func:`_matched`'s fans and turns.

    In fan order at each vertex; a fan of many bad turns (a sloped float line's site off
    it: ~n**2 of its n vertices' turns fold) is searched through its triangles sorted by
    their bits (:func:`_bits_range`) instead of read whole at each.
    """
    fans, fan_at, _, _, flag = fit
    got = np.zeros(64, dtype=np.int64)
    ng = 0
    for s in range(sites.shape[0]):
        i = sites[s]
        b = lengths[order[i]]
        m = lengths[order[i] + 1] - b - 1
        if m < 3:
            continue
        fan = fans[fan_at[s] : fan_at[s + 1]]
        nf = fan.shape[0]
        nbad = 0
        for k in range(m):
            nbad += flag[b + k] & 1
        if nbad == 0:
            continue
        by = _sorted_by_bits(fan, cx, cy) if nbad > FOLD_SORT_TURNS else np.zeros(0, np.int64)
        for k in range(m):
            if not flag[b + k] & 1:
                continue
            kp = k - 1 if k > 0 else m - 1
            kn = k + 1 if k + 1 < m else 0
            for j in (kp, k, kn):
                x, y = coords[b + j, 0], coords[b + j, 1]
                lo, hi = 0, nf  # every class at the vertex (two may share its bits)
                if by.shape[0]:
                    lo, hi = _bits_range(by, fan, cx, cy, x, y)
                for q in range(lo, hi):
                    t = fan[by[q]] if by.shape[0] else fan[q]
                    if cx[t] == x and cy[t] == y:
                        if ng == got.shape[0]:
                            got = np.concatenate((got, got))
                        got[ng] = t
                        ng += 1
    return got[:ng]


@njit(**NJIT)
def _sorted_by_bits(fan, cx, cy):
    """Places in ``fan`` sorted by their triangles' ``cx``, then ``cy``, then place."""
    fx = np.zeros(fan.shape[0])
    fy = np.zeros(fan.shape[0])
    for d in range(fan.shape[0]):
        fx[d] = cx[fan[d]]
        fy[d] = cy[fan[d]]
    by = np.argsort(fy, kind="mergesort")
    return by[np.argsort(fx[by], kind="mergesort")]


@njit(**NJIT)
def _bits_range(by, fan, cx, cy, x, y):
    """The run of ``by`` (:func:`_sorted_by_bits`) whose triangles' centres equal ``(x, y)``.

    ``==`` on floats, as the direct search (0 and -0 equal, NaN equal to nothing; NaNs sort
    last, so "below" and "at most" stay monotone along ``by``).
    """
    if x != x or y != y:
        return 0, 0
    lo, hi = 0, by.shape[0]
    while lo < hi:  # the first place not below (x, y)
        mid = (lo + hi) // 2
        t = fan[by[mid]]
        if cx[t] < x or (cx[t] == x and cy[t] < y):
            lo = mid + 1
        else:
            hi = mid
    first = lo
    hi = by.shape[0]
    while lo < hi:  # the first place past (x, y)
        mid = (lo + hi) // 2
        t = fan[by[mid]]
        if cx[t] < x or (cx[t] == x and cy[t] <= y):
            lo = mid + 1
        else:
            hi = mid
    return first, lo


@njit(**NJIT)
def _pairs_within(
    sites, xs, ys, tri, err, cx, cy, cls, coords, lengths, order, fit, mv, rtol, near
):
    """:func:`fold_pairs` with the reach ``rtol`` of a vertex's distance from its site.

    ``fit``: :func:`_matched`'s fans, matches and turns; ``mv``: the naming moves found so
    far (:func:`_moved_at`). ``near``: also keep every join's ends within
    ``FOLD_STALL_SPACING`` of the site's distance to its nearest neighbour of their exact
    centres (what the join and the earlier ones move them), so that no stalled contraction
    carries a vertex across the sites.
    """
    fans, fan_at, tk, hk, flag = fit
    total = 0
    for s in range(sites.shape[0]):
        i = sites[s]
        total += lengths[order[i] + 1] - lengths[order[i]]
    pa = np.zeros(total, dtype=np.int64)
    pb = np.zeros(total, dtype=np.int64)
    used = np.zeros(coords.shape[0], dtype=np.uint8)
    np_ = 0
    for s in range(sites.shape[0]):
        i = sites[s]
        b = lengths[order[i]]
        m = lengths[order[i] + 1] - b - 1
        if m < 3:
            continue
        fan = fans[fan_at[s] : fan_at[s + 1]]
        nf = fan.shape[0]
        lim = np.inf
        if near:
            sp = np.inf
            for d in range(nf):
                for j in range(3):
                    v = tri[3 * fan[d] + j]
                    if v != i:
                        sp = min(sp, abs(xs[v] - xs[i]) + abs(ys[v] - ys[i]))
            lim = FOLD_STALL_SPACING * sp
        for k in range(m):
            if flag[b + k] == 0:
                continue
            kp = k - 1 if k > 0 else m - 1
            kn = k + 1 if k + 1 < m else 0
            if flag[b + k] & 2 and used[b + k] == 0:
                used[b + k] = 1  # two classes with one name: one vertex already
                pa[np_] = tk[b + k]
                pb[np_] = tk[b + kn]
                np_ += 1
            if not flag[b + k] & 1:
                continue
            before = np_
            for step in (-1, 1):
                j = k
                for _ in range(m):
                    jn = j + step
                    if jn < 0:
                        jn += m
                    elif jn >= m:
                        jn -= m
                    e = j if step == 1 else jn  # edge e runs from vertex e to e + 1
                    t = tk[b + j]
                    u = tk[b + jn]
                    if t < 0 or u < 0 or cls[t] == cls[u]:
                        break
                    if not _one_vertex(i, xs, ys, tri, err, cx, cy, t, u, rtol):
                        break
                    if near and not _within(xs, ys, tri, err, cx, cy, t, u, lim):
                        break
                    if used[b + e] == 0:
                        used[b + e] = 1
                        pa[np_] = t
                        pb[np_] = u
                        np_ += 1
                    j = jn
                    if j == k:
                        break
            if np_ == before:
                rk, rm = tk[b : b + m], mv[b : b + m]
                for j in (kp, k, kn):
                    _moved_at(j, xs, ys, tri, err, cx, cy, cls, coords, b, fan, rk, hk[b:], rm)
                e = _straight_fold(xs[i], ys[i], cls, coords, b, rk, rm, kp, k, kn, rtol)
                en = e + 1 if e + 1 < m else 0
                if near and e >= 0 and not _within(xs, ys, tri, err, cx, cy, rk[e], rk[en], lim):
                    e = -1
                if e >= 0 and used[b + e] == 0:
                    used[b + e] = 1
                    pa[np_] = rk[e]
                    pb[np_] = rk[en]
                    np_ += 1
    return pa[:np_], pb[:np_]


@njit(**NJIT)
def _moved_at(k, xs, ys, tri, err, cx, cy, cls, coords, b, fan, tk, hk, mv):
    """``mv[k]``: how far ring vertex ``k``'s class can have moved (:func:`_moved`), once.

    The most any member of its class in the fan moved (they follow the member ``tk[k]``
    at fan place ``hk[k]``); a few ulps for a box crossing (no member). Computed only
    where a bad turn asks (a ring of ``n`` vertices may fold at a few).
    """
    if mv[k] >= 0.0:
        return
    t = tk[k]
    if t < 0:
        mv[k] = 8.0 * _U * (abs(coords[b + k, 0]) + abs(coords[b + k, 1]))  # a crossing
        return
    nf = fan.shape[0]
    h = hk[k]
    got = _moved(t, xs, ys, tri, err, cx, cy)
    for d2 in range(1, nf):
        u = fan[(h + d2) % nf]
        if cls[u] != cls[t]:
            break
        got = max(got, _moved(u, xs, ys, tri, err, cx, cy))
    mv[k] = got


@njit(**NJIT)
def _within(xs, ys, tri, err, cx, cy, t, u, lim):
    """Whether joining triangles ``t``, ``u`` keeps both within ``lim`` of their exact centres."""
    d = abs(cx[t] - cx[u]) + abs(cy[t] - cy[u])
    return d + _moved(t, xs, ys, tri, err, cx, cy) + _moved(u, xs, ys, tri, err, cx, cy) <= lim


@njit(**NJIT)
def _straight_fold(sx, sy, cls, coords, b, tk, mv, kp, k, kn, rtol):
    """The edge to contract at a bad turn ``kp -> k -> kn`` whose edges are not short; -1.

    The exact turn is left, so a computed right turn puts vertex ``k`` within what rounding
    and naming moved the three (:func:`_moved`; a box crossing, a few ulps) of the line
    through its neighbours: to rounding, it lies on that line. When it does, it joins the
    nearer neighbour that is a centre, if that one is within ``FOLD_REACH_ERRS`` times the
    same bound (a vertex of a nearly cocircular cluster, whose exact spread follows the
    input's rounding; never a long edge of a well-conditioned diagram).
    """
    t = tk[k]
    if t < 0:
        return -1
    px, py = coords[b + kp, 0], coords[b + kp, 1]
    vx, vy = coords[b + k, 0], coords[b + k, 1]
    qx, qy = coords[b + kn, 0], coords[b + kn, 1]
    moved = mv[kp] + mv[k] + mv[kn]
    ex = qx - px
    ey = qy - py
    base = np.sqrt(ex * ex + ey * ey)
    h = abs(ex * (vy - py) - ey * (vx - px))
    if not h <= FOLD_SPAN_ERRS * moved * base:
        return -1
    dp = abs(vx - px) + abs(vy - py) if tk[kp] >= 0 and cls[tk[kp]] != cls[t] else np.inf
    dq = abs(vx - qx) + abs(vy - qy) if tk[kn] >= 0 and cls[tk[kn]] != cls[t] else np.inf
    # never further than ``rtol`` of the cell's size: a class's naming move grows with
    # every join, and must not carry a vertex across the sites' spacing
    reach = min(FOLD_REACH_ERRS * moved, rtol * (abs(vx - sx) + abs(vy - sy)))
    if dp <= dq and dp <= reach:
        return kp  # the edge kp -> k
    if dq < dp and dq <= reach:
        return k  # the edge k -> kn
    return -1


@njit(**NJIT)
def _meet(coords, a, b, c, d):
    """Whether closed segments ``a-b`` and ``c-d`` (rows of ``coords``) share a point (exact)."""
    ax, ay, bx, by = coords[a, 0], coords[a, 1], coords[b, 0], coords[b, 1]
    qx, qy, rx, ry = coords[c, 0], coords[c, 1], coords[d, 0], coords[d, 1]
    o1 = orient2d(ax, ay, bx, by, qx, qy)
    o2 = orient2d(ax, ay, bx, by, rx, ry)
    if (o1 > 0.0 and o2 > 0.0) or (o1 < 0.0 and o2 < 0.0):
        return False
    o3 = orient2d(qx, qy, rx, ry, ax, ay)
    o4 = orient2d(qx, qy, rx, ry, bx, by)
    if (o3 > 0.0 and o4 > 0.0) or (o3 < 0.0 and o4 < 0.0):
        return False
    if o1 == 0.0 and o2 == 0.0:  # on one line: they meet only where their boxes overlap
        return (
            min(ax, bx) <= max(qx, rx)
            and min(qx, rx) <= max(ax, bx)
            and min(ay, by) <= max(qy, ry)
            and min(qy, ry) <= max(ay, by)
        )
    return True


@njit(**NJIT)
def _ring_simple(coords, a, b):
    """Whether the closed ring ``coords[a:b]`` (last row repeats the first) is simple.

    No edge meets an edge that is not its neighbour, and no two neighbours fold back onto
    each other (a reversal: a spike GEOS calls a self-intersection).
    """
    m = b - a - 1
    if m > FOLD_SIMPLE_MAX:
        return False
    for k in range(m):
        kp = k - 1 if k > 0 else m - 1
        kn = k + 1 if k + 1 < m else 0
        if (
            _bad_turn(coords, a + kp, a + k, a + kn)
            and orient2d(
                coords[a + kp, 0],
                coords[a + kp, 1],
                coords[a + k, 0],
                coords[a + k, 1],
                coords[a + kn, 0],
                coords[a + kn, 1],
            )
            == 0.0
        ):
            return False
    for p in range(m):
        for q in range(p + 2, m):
            if p == 0 and q == m - 1:
                continue  # neighbours across the closing vertex
            if _meet(coords, a + p, a + p + 1, a + q, a + q + 1):
                return False
    return True


@njit(**NJIT_PARALLEL)
def _tangled(coords, lengths, order, bad):
    """Which of the kernel sites' rings marked in ``bad`` are not simple."""
    n = order.shape[0]
    got = np.zeros(n, dtype=np.bool_)
    for i in prange(n):
        if bad[i]:
            got[i] = not _ring_simple(coords, lengths[order[i]], lengths[order[i] + 1])
    return got


def _not_simple(coords, lengths, order, bad):
    """How many of the kernel sites' rings marked in ``bad`` are not simple."""
    return int(_tangled(coords, lengths, order, bad).sum())


def _score(cells, bad, order):
    """``(rings not simple, rings folded)`` among those marked in ``bad`` (the folded ones)."""
    return (int(_not_simple(cells[0], cells[1], order, bad)), int(bad.sum()))


def unfold_cells(state, out, cells, rebuild):
    """The fold rounds of :func:`.cells.cells_from_triangulation`: ``(cells, tested)``.

    ``state`` is :func:`.cells.dual_prepare`'s (its centres and classes change in place),
    ``out, cells`` the first build, ``rebuild`` :func:`.cells.rebuild_cells`. Each round
    tests the rings that can fold, joins the classes :func:`fold_pairs` gives and builds the
    changed cells again, until no ring folds. Joins can fold more rings than they unfold
    (the phase-0.3 circle of 600 sites of radius 1e-5 at (3e4, 1e4): 6 self-intersecting
    rings before the first round, 33 after the twelfth, one class of 555 of its 598
    triangles named thousands of ulps from its members), so the best round is returned
    (:func:`_score`; a later round wins ties, so rounds that end with no ring folded
    return their last, as before). Where rings stay folded, :func:`_refine` goes on from
    the best round (classes at the bad turns named afresh, :func:`.refit.fit_classes`, as a
    stalled test asks; joins that name only the classes they join, each afresh), and where
    that still leaves rings folded, from the first build; the better of the two stands
    (1000 sites of radius 1e-5 at (3e4, 1e4), phase 0.2: 4 invalid rings -> none folded).
    ``tested`` marks every cell a merge or contraction can have moved past its site.
    """
    run = _Rounds(state, out, cells, rebuild)
    _rounds(run)
    if run.best is not None and run.best[0] != (0, 0) and run.first is not None:
        # the joined classes were named from their middle members (the first try:
        # 1000 sites of radius 1e-3 at (3e4, 1e4) 22,000 -> 50 ulps off the exact cells);
        # where rings still fold, the same rounds from the first build with each joined
        # class named near its best-conditioned member, and the better of the two stands
        # (1000 sites of radius 1e-3 at (5e5, 4e6), phase 0.15: one ring folded -> none)
        then = run.best
        run.best = run.first
        run.restore()
        run.middle = False
        run.refitted = False
        run.contracted = False
        run.risk = run.risk0.copy()
        _rounds(run)
        if then[0] <= run.best[0]:
            run.best = then
    return (run.cells if run.best is None else run.best[2]), run.tested


def _rounds(run):
    """:func:`unfold_cells`' rounds, then :func:`_refine` from the best and the first build."""
    for _ in range(FOLD_MAX_ROUNDS):
        if not run.risk.any():
            break
        run.measure()
        if not run.folded().shape[0] or not run.step(False):
            break
    else:
        run.measure()  # the last round's cells
    if run.best is not None and run.best[0] != (0, 0):
        run.refitted = True
        run.restore()
        _refine(run)
        if run.best[0] != (0, 0) and run.first is not run.best:
            # the rounds' joins can leave a class spread over thousands of ulps that no
            # fresh name fixes (1000 sites of radius 1e-5 at (-5e4, 2e4), phase 0.15): the
            # same moves from the first build, and the better of the two stands
            then = run.best
            run.best = run.first
            run.restore()
            _refine(run)
            if then[0] <= run.best[0]:
                run.best = then


def _refine(run):
    """From the best round: moves kept while they score better (:func:`unfold_cells`).

    The classes at the rings' bad turns named afresh; the classes the rings that are not
    simple ask to join, joined (each named, then named afresh where its cells fit best,
    every other class keeping its vertex: :func:`.centers.contract` with ``only``); every
    join asked, alike. After a move that scores no worse the moves start again; after one
    that scores worse the best round is restored and the next move tried.
    """
    moves = ((True, False), (False, True), (False, False))
    tried = 0
    for _ in range(FOLD_MAX_ROUNDS):
        if tried == len(moves) or not run.folded().shape[0]:
            break
        refit, tangled = moves[tried]
        sites = run.tangled() if tangled else run.folded()
        if sites.shape[0] and run.step(refit, sites) and run.measure():
            tried = 0
            continue
        run.restore()
        tried += 1


class _Rounds:
    """The state of :func:`unfold_cells`'s rounds.

    Centres and classes (changed in place), the rings, the last test of each ring (``bad``),
    and the best round seen with what restores it.
    """

    def __init__(self, state, out, cells, rebuild):
        self.state = state
        self.cx, self.cy, self.err, self.cls, self.risk = state[7:12]
        self.terr, self.reach = state[13:15]
        self.out, self.cells, self.rebuild = out, cells, rebuild
        # only cells with a vertex of a short edge (for its ends' rounding bounds and naming
        # moves) or of an undecided one can fold (most inputs, exact grids too: none); once
        # a fold is contracted, every cell is checked, and then each round builds and checks
        # again only the cells whose vertices it changed
        self.tested = self.risk.copy()
        self.risk0 = self.risk.copy()
        self.middle = True  # joined classes named from their middle members (first try)
        self.bad = np.zeros(self.risk.shape[0], dtype=np.bool_)
        self.checked_all = False
        self.contracted = False
        self.refitted = False  # from the best round on, a join names only its own classes
        self.best = None  # (score, out, cells, (cx, cy, cls, bad, terr, reach))
        self.first = None  # the first build's, as ``best``

    def measure(self):
        """Test the rings built since the last test; whether the round is the best so far."""
        order, risk = self.state[5], self.risk
        self.bad[risk] = folded_rings(self.cells[0], self.cells[1], order, risk)[risk]
        if not self.checked_all and self.bad.any():
            # a ring folds: test every cell of the first build once. A cell outside ``risk``
            # (no short edge) folds too where its wedge is narrower than its vertices'
            # rounding (1000 sites of radius 1e-5 at (3e4, 1e4): 41 folded rings seen, 65
            # folded); untested, the best round's score missed them and they were returned
            risk = np.ones(risk.shape[0], dtype=np.bool_)
            self.bad[:] = folded_rings(self.cells[0], self.cells[1], order, risk)
            self.checked_all = True
        score = _score(self.cells, self.bad, order)
        if self.best is not None and score > self.best[0]:
            return False
        keep = (self.cx.copy(), self.cy.copy(), self.cls.copy(), self.bad.copy())
        self.best = (score, self.out, self.cells, (*keep, self.terr, self.reach))
        if self.first is None:
            self.first = self.best
        return True

    def restore(self):
        """Back to the best round (its centres, classes, rings and tests)."""
        _, self.out, self.cells, keep = self.best
        for now, then in zip((self.cx, self.cy, self.cls, self.bad), keep[:4], strict=True):
            now[:] = then
        self.terr, self.reach = keep[4], keep[5]

    def folded(self):
        """The sites whose rings the last test found folded."""
        return np.flatnonzero(self.bad).astype(np.int64)

    def tangled(self):
        """The sites whose rings the last test found not simple."""
        order = self.state[5]
        return np.flatnonzero(_tangled(self.cells[0], self.cells[1], order, self.bad))

    def step(self, refit, folded=None):
        """Join the classes the folded rings ask for, and build the changed cells again.

        ``refit``: name the classes at the rings' bad turns afresh instead. False where
        nothing changed.
        """
        xs, ys, tri, he, box, order, kmap = self.state[:7]
        cx, cy, err, cls = self.cx, self.cy, self.err, self.cls
        coords, lengths, _ = self.cells
        folded = self.folded() if folded is None else folded
        if refit:
            pa = _stalled(folded, tri, he, self.out, cx, cy, cls, coords, lengths, order)
            pb = pa
        else:
            args = (xs, ys, tri, he, self.out, cx, cy, err, cls, coords, lengths, order)
            pa, pb = fold_pairs(folded, *args)
        before = (cx.view(np.int64).copy(), cy.view(np.int64).copy(), cls.copy(), self.reach)
        only = self.refitted
        if not pa.shape[0] or not contract_by(
            xs, ys, tri, he, cls, cx, cy, kmap, box, err, pa, pb, only, np.bool_(self.middle)
        ):
            return False
        # only cells at a triangle whose vertex (bits) or class changed can change: building
        # every cell again made a float circle's rounds quadratic (1e6: 19 rounds of 3 s)
        self.terr = class_err(cls, err)
        self.reach = side_reaches(xs, ys, tri, cls, cx, cy, self.terr, box)
        moved = (cx.view(np.int64) != before[0]) | (cy.view(np.int64) != before[1])
        moved |= (cls != before[2]) | (self.reach != before[3])
        redo = np.zeros(xs.shape[0], dtype=np.bool_)
        redo[tri.reshape(-1, 3)[moved].ravel()] = True
        # every cell is checked once after the first contraction (a cell outside ``risk``
        # can fold then), and from then on the cells built again (the others kept their bits)
        self.risk = redo if self.checked_all else np.ones(xs.shape[0], dtype=np.bool_)
        self.tested |= self.risk if self.contracted else True
        self.checked_all = True
        self.contracted = True
        args = (xs, ys, tri, he, cx, cy, self.terr, self.reach, cls, box, order, kmap)
        self.out, self.cells = self.rebuild(*args, self.cells, redo)
        return True
