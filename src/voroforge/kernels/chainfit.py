"""Chained classes named where every cell at them keeps its site (issue 15).

A class of three or more triangles (``kernels/centers``: a chain of fold joins, whose
members' exact centres lie many rounding bounds apart) is named near one member
(:func:`.centers._name_classes_by`). Far from the origin a float circle's exact vertices
lie a few ulps apart, and that name can lie across the other edges of a thin wedge at
the class: site 243 of 257 on a circle of radius 1e-7 at (5e5, 4e6), phase 0.35, sits
in a class of six whose own centres span 190 units of x's ulp; named at one end, its ring
of centres passed on the wrong side of the site and the site was flagged.
:func:`fit_chains` scores each such class's name by its sites' rings of centres (every
other class at its vertex as named): the turns that go right or reverse, and the edges
that leave the ring's own site on their right; where the name scores above zero, each
member's own centre is tried, and the class takes the one with the lowest score (ties to
the nearer to the name, then the lower by coordinates), keeping its name unless one is
strictly better. Every choice is a function of the classes' sets of triangles and their
centres, never of the triangles' numbering.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import FOLD_FIT_MAX_MEMBERS, NJIT
from .predicates import orient2d
from .refit import chain_bad_turns, fan_ring
from .vertex import voronoi_vertex


@njit(**NJIT)
def fan_score(s, t0, tri, he, parent, c, px, py, cx0, cy0, xs, ys, bx, by):
    """Bad turns of site ``s``'s ring of centres and its edges that leave ``s`` outside.

    As :func:`.refit.fan_bad_turns` (class ``c`` at ``(px, py)``, every other triangle at
    ``cx0, cy0``; walked counter-clockwise from triangle ``t0``), plus each edge between
    two finite centres whose exact ``orient2d`` with the site is not positive.
    """
    m, closed = fan_ring(s, t0, tri, he, parent, c, px, py, cx0, cy0, bx, by)
    bad = chain_bad_turns(bx, by, m, closed)
    for k in range(m if closed else m - 1):
        k2 = k + 1 if k + 1 < m else 0
        if k2 == k or not (np.isfinite(bx[k]) and np.isfinite(by[k])):
            continue
        if not (np.isfinite(bx[k2]) and np.isfinite(by[k2])):
            continue
        if orient2d(bx[k], by[k], bx[k2], by[k2], xs[s], ys[s]) <= 0.0:
            bad += 1
    return bad


@njit(**NJIT)
def _score(sites, where, k, tri, he, parent, c, vx, vy, cx0, cy0, xs, ys, bx, by, cap):
    """The class's score at ``(vx, vy)``: :func:`fan_score` summed, stopping past ``cap``."""
    b = 0
    for q in range(k):
        if b > cap:
            break
        b += fan_score(sites[q], where[q], tri, he, parent, c, vx, vy, cx0, cy0, xs, ys, bx, by)
    return b


@njit(**NJIT)
def fit_chains(xs, ys, tri, he, parent, cx, cy, pick, changed):
    """Rename each class whose root ``pick`` marks where its sites' rings score best.

    ``parent`` is compressed (each triangle's root); classes of three to
    ``FOLD_FIT_MAX_MEMBERS`` triangles are scored (:func:`fan_score`) at their vertex and,
    where that is not zero, at each member's own centre (``vertex.voronoi_vertex``: the
    same bits in any order). ``changed`` marks the triangles given a new vertex. Returns
    how many classes were renamed.
    """
    cx0, cy0 = cx.copy(), cy.copy()
    bx, by = np.zeros(parent.shape[0] + 2), np.zeros(parent.shape[0] + 2)
    stamp = np.full(xs.shape[0], -1, dtype=np.int64)
    tf = np.flatnonzero(pick[parent])  # the classes' members, grouped by class
    tf = tf[np.argsort(parent[tf], kind="mergesort")]
    renamed = 0
    j = 0
    while j < tf.shape[0]:
        i, c = j, parent[tf[j]]
        while j < tf.shape[0] and parent[tf[j]] == c:
            j += 1
        mem = tf[i:j]
        if mem.shape[0] < 3 or mem.shape[0] > FOLD_FIT_MAX_MEMBERS:
            continue
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
        nx, ny = cx0[c], cy0[c]
        args = (tri, he, parent, c)
        best = _score(sites, where, k, *args, nx, ny, cx0, cy0, xs, ys, bx, by, 1 << 30)
        if best == 0:
            continue
        found = False
        wx, wy, wd = nx, ny, 0.0
        for t in mem:
            a, b, q = np.int64(tri[3 * t]), np.int64(tri[3 * t + 1]), np.int64(tri[3 * t + 2])
            vx, vy = voronoi_vertex(a, b, q, xs, ys)
            if not (np.isfinite(vx) and np.isfinite(vy)) or (vx == nx and vy == ny):
                continue
            if found and vx == wx and vy == wy:
                continue
            s = _score(sites, where, k, *args, vx, vy, cx0, cy0, xs, ys, bx, by, best)
            d = abs(vx - nx) + abs(vy - ny)
            tie = s == best and found
            if s < best or (tie and (d < wd or (d == wd and (vx < wx or (vx == wx and vy < wy))))):
                best, found, wx, wy, wd = s, True, vx, vy, d
        if found:
            renamed += 1
            for t in mem:
                if not (cx[t] == wx and cy[t] == wy) or wx == 0.0 or wy == 0.0:
                    changed[t] = 1  # (as centres._set_vertex: a zero's sign is not seen)
                cx[t] = wx
                cy[t] = wy
    return renamed
