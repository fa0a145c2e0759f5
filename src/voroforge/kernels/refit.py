"""A stalled fold test's last resort: classes named afresh where their cells fit best.

A float circle of small radius far from the origin (issue 15: 600 sites of radius 1e-6 at
``(1e5, 3e4)``) has its exact Voronoi vertices within its centres' ulps of each other and
every cell a chain that turns by less than an ulp. The fold test's contractions
(:func:`.folds.fold_pairs`, :func:`.centers.contract`) grow classes of up to hundreds of
triangles whose members' exact centres span hundreds of ulps; the class's usual name, near
its best-conditioned member (every bound ~1 ulp there: an arbitrary one), can lie across
its cells' other edges, and the test stalls with rings still folded. When it stalls,
:func:`fit_classes` names each class at a bad turn of a folded ring at the centre of one of
its triples that leaves its sites' rings the fewest bad turns.

A class whose members' own centres spread over more than ``CLASS_SPREAD_ULPS`` (a fold
round's joins) is named near its middle member's centre (:func:`middle_member`), not near its
best-conditioned one, which may lie at its edge (:func:`.centers._name_classes`).

Every choice is a function of the classes (sets of sites), their vertices and the rings,
never of the triangles' numbering: the sweep and the default triangulate four exactly
cocircular sites with different diagonals, so the candidates are the class's triangles and,
across each exactly cocircular edge inside it, the other diagonal's two; ties go to the
lower vertex by coordinates.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import CLASS_SPREAD_ULPS, FOLD_FIT_MAX_MEMBERS, NJIT
from .clip import ring_corner
from .predicates import incircle, orient2d
from .vertex import voronoi_vertex

_U = 2.0**-53


@njit(**NJIT)
def chain_bad_turns(px, py, m, closed):
    """How many turns of the chain ``p[:m]`` go right or reverse (exact on the floats).

    ``closed``: the chain wraps around (every vertex is a corner), else only its inner
    vertices are. Corners at a non-finite vertex are not counted.
    """
    bad = 0
    for k in range(0 if closed else 1, m if closed else m - 1):
        k0, k2, ex, ey, fx, fy = ring_corner(px, py, m, k)
        if not (np.isfinite(ex) and np.isfinite(ey) and np.isfinite(fx) and np.isfinite(fy)):
            continue
        o = orient2d(px[k0], py[k0], px[k], py[k], px[k2], py[k2])
        rev = (ex != 0.0 and fx != 0.0 and (ex < 0.0) != (fx < 0.0)) or (
            ey != 0.0 and fy != 0.0 and (ey < 0.0) != (fy < 0.0)
        )
        if o < 0.0 or (o == 0.0 and rev):
            bad += 1
    return bad


@njit(**NJIT)
def fan_ring(s, t0, tri, he, parent, c, px, py, cx0, cy0, bx, by):
    """Site ``s``'s ring of triangle centres, walked from triangle ``t0``: ``(m, closed)``.

    Triangles of class ``c`` (``parent``) are at ``(px, py)``, the others at ``cx0, cy0``;
    a repeated vertex is written once, into ``bx[:m]``, ``by[:m]`` (scratch for the site's
    degree); an open fan (a hull site's) from its first halfedge.
    """
    e0 = 3 * t0 + (0 if tri[3 * t0] == s else (1 if tri[3 * t0 + 1] == s else 2))
    e, closed = e0, False
    while he[e] != -1 and not closed:  # back to the first halfedge of an open fan
        e = he[e] - 2 if he[e] % 3 == 2 else he[e] + 1
        closed = e == e0
    start = e
    m = 0
    while True:
        t = e // 3
        x, y = (px, py) if parent[t] == c else (cx0[t], cy0[t])
        if m == 0 or not (bx[m - 1] == x and by[m - 1] == y):
            bx[m] = x
            by[m] = y
            m += 1
        e = he[e - e % 3 + (e + 2) % 3]
        if e == -1 or e == start:
            break
    if closed and m > 1 and bx[0] == bx[m - 1] and by[0] == by[m - 1]:
        m -= 1
    return m, closed


@njit(**NJIT)
def fan_bad_turns(s, t0, tri, he, parent, c, px, py, cx0, cy0, bx, by):
    """Bad turns of site ``s``'s ring of triangle centres (:func:`fan_ring`).

    An open fan (a hull site's) counts only at its inner vertices (:func:`chain_bad_turns`).
    """
    m, closed = fan_ring(s, t0, tri, he, parent, c, px, py, cx0, cy0, bx, by)
    return chain_bad_turns(bx, by, m, closed)


@njit(**NJIT)
def _candidates(xs, ys, tri, he, parent, c, mem, cand):
    """The triples :func:`fit_classes` tries for class ``c`` (members ``mem``) into ``cand``.

    Each member's sites, and across an edge inside the class whose four sites are exactly
    cocircular the other diagonal's two triangles. Returns how many entries (3 per triple).
    """
    nc = 0
    for t in mem:
        cand[nc] = tri[3 * t]
        cand[nc + 1] = tri[3 * t + 1]
        cand[nc + 2] = tri[3 * t + 2]
        nc += 3
        for j in range(3):
            e = 3 * t + j
            f = he[e]
            if f < 0 or parent[f // 3] != c:
                continue
            a = tri[e]
            b = tri[e - e % 3 + (e + 1) % 3]
            q = tri[e - e % 3 + (e + 2) % 3]
            d = tri[f - f % 3 + (f + 2) % 3]
            if incircle(xs[a], ys[a], xs[b], ys[b], xs[q], ys[q], xs[d], ys[d]) == 0.0:
                cand[nc], cand[nc + 1], cand[nc + 2] = a, q, d
                cand[nc + 3], cand[nc + 4], cand[nc + 5] = b, q, d
                nc += 6
    return nc


@njit(**NJIT)
def fit_classes(xs, ys, tri, he, parent, cx, cy, fresh, changed):
    """Name each class with ``fresh`` at its root where its sites' rings turn best.

    A class of two to ``FOLD_FIT_MAX_MEMBERS`` triangles is scored by the bad turns of its sites'
    rings of centres (:func:`fan_bad_turns`, every other class at its vertex as it was, so
    no choice depends on another's). Unless its vertex leaves none, each candidate triple's
    centre (:func:`_candidates`, ``vertex.voronoi_vertex``: the same bits in any order) is
    scored alike, and the class takes the one with the fewest, ties to the lower by
    coordinates; a class none improves keeps its vertex. ``parent`` is compressed (each
    triangle's root); ``changed`` marks the triangles given a new vertex. Returns how many
    classes were renamed.
    """
    cx0, cy0 = cx.copy(), cy.copy()
    bx, by = np.zeros(parent.shape[0] + 2), np.zeros(parent.shape[0] + 2)
    stamp = np.full(xs.shape[0], -1, dtype=np.int64)
    cand = np.zeros(21 * FOLD_FIT_MAX_MEMBERS, dtype=np.int64)
    tf = np.flatnonzero(fresh[parent])  # the classes' members, grouped by class
    tf = tf[np.argsort(parent[tf], kind="mergesort")]
    renamed = 0
    j = 0
    while j < tf.shape[0]:
        i, c = j, parent[tf[j]]
        while j < tf.shape[0] and parent[tf[j]] == c:
            j += 1
        mem = tf[i:j]
        if mem.shape[0] < 2 or mem.shape[0] > FOLD_FIT_MAX_MEMBERS:
            continue  # (the cost is candidates times the class's sites' degrees)
        sites = np.zeros(3 * mem.shape[0], np.int64)
        where = np.zeros(3 * mem.shape[0], np.int64)
        k = 0
        for t in mem:
            for v in tri[3 * t : 3 * t + 3]:
                if stamp[v] != c:
                    stamp[v] = c
                    sites[k] = v
                    where[k] = t
                    k += 1
        best = 0
        for q in range(k):
            best += fan_bad_turns(
                sites[q], where[q], tri, he, parent, c, cx0[c], cy0[c], cx0, cy0, bx, by
            )
        if best == 0:
            continue
        found = False
        wx, wy = cx0[c], cy0[c]
        nc = _candidates(xs, ys, tri, he, parent, c, mem, cand)
        for g in range(0, nc, 3):
            vx, vy = voronoi_vertex(cand[g], cand[g + 1], cand[g + 2], xs, ys)
            if not (np.isfinite(vx) and np.isfinite(vy)) or (vx == cx0[c] and vy == cy0[c]):
                continue
            b = 0
            for q in range(k):
                if b > best:
                    break
                b += fan_bad_turns(sites[q], where[q], tri, he, parent, c, vx, vy, cx0, cy0, bx, by)
            if b < best or (b == best and found and (vx < wx or (vx == wx and vy < wy))):
                best = b
                found = True
                wx, wy = vx, vy
        if found:
            renamed += 1
            for t in mem:
                if not (cx[t] == wx and cy[t] == wy) or wx == 0.0 or wy == 0.0:
                    changed[t] = 1  # (as centres._set_vertex: a zero's sign is not seen)
                cx[t] = wx
                cy[t] = wy
    return renamed


@njit(**NJIT)
def rank_key(t, tri, rank):
    """Triangle ``t``'s site ranks, sorted: a key that no builder's numbering changes."""
    a = rank[tri[3 * t]]
    b = rank[tri[3 * t + 1]]
    c = rank[tri[3 * t + 2]]
    if a > b:
        a, b = b, a
    if b > c:
        b, c = c, b
    if a > b:
        a, b = b, a
    return a, b, c


@njit(**NJIT)
def middle_member(xs, ys, tri, mem, rank):
    """The member of a widely spread class whose own centre is nearest the class's middle.

    Returns ``(t, x, y)``: member ``t`` and its own centre (:func:`.vertex.voronoi_vertex`,
    the same bits in any order), nearest (L1) the coordinate-wise median of the members'
    own centres, ties to the lower rank key (:func:`rank_key`: no builder's numbering);
    ``t = -1`` where those centres spread over at most ``CLASS_SPREAD_ULPS`` unit
    roundoffs of their magnitude (exactly cocircular classes, centres equal to rounding:
    the best-conditioned member names them, as before) or one is not finite.

    The fold rounds (:func:`.centers.contract`) join classes whose members' exact centres span
    thousands of ulps (a float circle far out: its exact vertices near the centre scatter
    over ~ulp * n**2 / 20). Named near the best-conditioned member, wherever it lies in the
    class, a join put the vertex at the class's edge, so the next rings folded and the
    next rounds joined more: 1000 sites of radius 1e-3 at (3e4, 1e4), phase 0.65, ended
    with one class of 997 of 998 triangles named 22,000 ulps from the circle's centre
    (every cell a triangle with that apex). Named from the middle, the rounds stop at a
    class of 167 and the cells are within 50 ulps of the exact ones.
    """
    m = mem.shape[0]
    ox = np.zeros(m)
    oy = np.zeros(m)
    for j in range(m):
        t = mem[j]
        # int64 site numbers (the triangles are int32): the vertex kernels' one signature
        a, b, c = np.int64(tri[3 * t]), np.int64(tri[3 * t + 1]), np.int64(tri[3 * t + 2])
        ox[j], oy[j] = voronoi_vertex(a, b, c, xs, ys)
    if not (np.isfinite(ox).all() and np.isfinite(oy).all()):
        return -1, 0.0, 0.0
    spread = (ox.max() - ox.min()) + (oy.max() - oy.min())
    if not spread > CLASS_SPREAD_ULPS * _U * (abs(ox[0]) + abs(oy[0])):
        return -1, 0.0, 0.0
    mx = np.median(ox)
    my = np.median(oy)
    pick = 0
    dp = abs(ox[0] - mx) + abs(oy[0] - my)
    for j in range(1, m):
        dj = abs(ox[j] - mx) + abs(oy[j] - my)
        if dj < dp or (dj == dp and rank_key(mem[j], tri, rank) < rank_key(mem[pick], tri, rank)):
            pick = j
            dp = dj
    return mem[pick], ox[pick], oy[pick]
