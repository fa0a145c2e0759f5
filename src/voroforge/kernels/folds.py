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
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..config import (
    FOLD_REACH_ERRS,
    FOLD_REACH_RTOL,
    FOLD_SPAN_ERRS,
    FOLD_STALL_DOUBLINGS,
    FOLD_STALL_SPACING,
    NJIT,
    NJIT_PARALLEL,
)
from .centers import short_edge
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
    ox, oy = voronoi_vertex(tri[3 * t], tri[3 * t + 1], tri[3 * t + 2], xs, ys)
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
    """
    args = (sites, xs, ys, tri, he, out, cx, cy, err, cls, coords, lengths, order)
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
        pa = _stalled(sites, tri, he, out, cx, cy, coords, lengths, order)
        pb = pa
    return pa, pb


@njit(**NJIT)
def _stalled(sites, tri, he, out, cx, cy, coords, lengths, order):
    """Every triangle of the rings' fans at a bad turn or its two neighbours (by bits).

    All triangles holding a vertex's bits, so every class there, whatever triangle the
    builder's numbering puts first (two classes may share a name).
    """
    most = 0
    for s in range(sites.shape[0]):
        i = sites[s]
        most = max(most, lengths[order[i] + 1] - lengths[order[i]])
    fan = np.zeros(tri.shape[0] // 3 + 1, dtype=np.int64)
    got = np.zeros(3 * most * sites.shape[0] + 1, dtype=np.int64)
    ng = 0
    for s in range(sites.shape[0]):
        i = sites[s]
        b = lengths[order[i]]
        m = lengths[order[i] + 1] - b - 1
        if m < 3:
            continue
        nf = _fan(i, tri, he, out, fan)
        for k in range(m):
            kp = k - 1 if k > 0 else m - 1
            kn = k + 1 if k + 1 < m else 0
            if not _bad_turn(coords, b + kp, b + k, b + kn):
                continue
            for j in (kp, k, kn):
                for d in range(nf):  # every class at the vertex (two may share its bits)
                    t = fan[d]
                    if cx[t] == coords[b + j, 0] and cy[t] == coords[b + j, 1]:
                        if ng == got.shape[0]:
                            got = np.concatenate((got, got))
                        got[ng] = t
                        ng += 1
    return got[:ng]


@njit(**NJIT)
def _pairs_within(
    sites, xs, ys, tri, he, out, cx, cy, err, cls, coords, lengths, order, rtol, near
):
    """:func:`fold_pairs` with the reach ``rtol`` of a vertex's distance from its site.

    ``near``: also keep every join's ends within ``FOLD_STALL_SPACING`` of the site's
    distance to its nearest neighbour of their exact centres (what the join and the earlier
    ones move them), so that no stalled contraction carries a vertex across the sites.
    """
    total = 0
    most = 0
    for s in range(sites.shape[0]):
        i = sites[s]
        size = lengths[order[i] + 1] - lengths[order[i]]
        total += size
        most = max(most, size)
    pa = np.zeros(total, dtype=np.int64)
    pb = np.zeros(total, dtype=np.int64)
    fan = np.zeros(tri.shape[0] // 3 + 1, dtype=np.int64)
    tk = np.zeros(most, dtype=np.int64)
    mv = np.zeros(most)
    used = np.zeros(most, dtype=np.uint8)
    np_ = 0
    for s in range(sites.shape[0]):
        i = sites[s]
        b = lengths[order[i]]
        m = lengths[order[i] + 1] - b - 1
        if m < 3:
            continue
        nf = _fan(i, tri, he, out, fan)
        lim = np.inf
        if near:
            sp = np.inf
            for d in range(nf):
                for j in range(3):
                    v = tri[3 * fan[d] + j]
                    if v != i:
                        sp = min(sp, abs(xs[v] - xs[i]) + abs(ys[v] - ys[i]))
            lim = FOLD_STALL_SPACING * sp
        h = 0
        for k in range(m):
            tk[k] = -1
            used[k] = 0
            mv[k] = 8.0 * _U * (abs(coords[b + k, 0]) + abs(coords[b + k, 1]))  # a crossing
            for d in range(nf):
                t = fan[(h + d) % nf]
                if cx[t] == coords[b + k, 0] and cy[t] == coords[b + k, 1]:
                    tk[k] = t
                    h = (h + d) % nf
                    # the most any member of its class in the fan moved (they follow it)
                    mv[k] = _moved(t, xs, ys, tri, err, cx, cy)
                    for d2 in range(1, nf):
                        u = fan[(h + d2) % nf]
                        if cls[u] != cls[t]:
                            break
                        mv[k] = max(mv[k], _moved(u, xs, ys, tri, err, cx, cy))
                    break
        for k in range(m):
            kp = k - 1 if k > 0 else m - 1
            kn = k + 1 if k + 1 < m else 0
            t = tk[k]
            u = tk[kn]
            if t >= 0 and u >= 0 and cls[t] != cls[u] and used[k] == 0:
                if cx[t] == cx[u] and cy[t] == cy[u]:
                    used[k] = 1  # two classes with one name: one vertex already
                    pa[np_] = t
                    pb[np_] = u
                    np_ += 1
            if not _bad_turn(coords, b + kp, b + k, b + kn):
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
                    t = tk[j]
                    u = tk[jn]
                    if t < 0 or u < 0 or cls[t] == cls[u]:
                        break
                    if not _one_vertex(i, xs, ys, tri, err, cx, cy, t, u, rtol):
                        break
                    if near and not _within(xs, ys, tri, err, cx, cy, t, u, lim):
                        break
                    if used[e] == 0:
                        used[e] = 1
                        pa[np_] = t
                        pb[np_] = u
                        np_ += 1
                    j = jn
                    if j == k:
                        break
            if np_ == before:
                e = _straight_fold(xs[i], ys[i], cls, coords, b, tk, mv, kp, k, kn, rtol)
                en = e + 1 if e + 1 < m else 0
                if near and e >= 0 and not _within(xs, ys, tri, err, cx, cy, tk[e], tk[en], lim):
                    e = -1
                if e >= 0 and used[e] == 0:
                    used[e] = 1
                    pa[np_] = tk[e]
                    pb[np_] = tk[en]
                    np_ += 1
    return pa[:np_], pb[:np_]


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
