"""Each site's Delaunay candidates: the sites of the Delaunay polytopes at it.

A 3D Voronoi cell is the container cut by the bisectors of the sites that share a face
with it, and each of its vertices is named from every site on the vertex's empty sphere
(:mod:`kernels.vertex3d`). Both kinds of site are vertices of the Delaunay polytopes at
the cell's site: the polytope dual to a vertex is the set of sites on its empty sphere,
and a triangulation that refines the Delaunay subdivision (``vf.delaunay3d``'s symbolic
perturbation) splits it into tetrahedra with that one circumsphere, joined across faces
whose opposite vertex lies exactly on it (:func:`polytopes`). :func:`candidate_lists`
gathers, per site, the sites of its polytopes, nearest first.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT
from .predicates3d import insphere


@njit(**NJIT)
def _root(parent, t):
    while parent[t] != t:
        parent[t] = parent[parent[t]]  # path halving
        t = parent[t]
    return t


@njit(**NJIT)
def polytopes(P, T, N):
    """``(m,)`` the polytope of each tetrahedron of ``T (m, 4)`` (neighbours ``N``, -1 none).

    Two tetrahedra sharing a face are one polytope when the vertex of one across the face
    is exactly on the other's circumsphere (exact ``insphere`` 0). Labels are the smallest
    tetrahedron of each polytope.
    """
    m = T.shape[0]
    parent = np.arange(m)
    P5 = np.zeros((5, 3))
    for t in range(m):
        for f in range(4):
            u = N[t, f]
            if u <= t:  # each shared face once; -1: a hull face
                continue
            o = -1
            for q in range(4):
                x = T[u, q]
                if x != T[t, 0] and x != T[t, 1] and x != T[t, 2] and x != T[t, 3]:
                    o = x
            if o < 0:
                continue
            for q in range(4):
                for c in range(3):
                    P5[q, c] = P[T[t, q], c]
            for c in range(3):
                P5[4, c] = P[o, c]
            if insphere(P5) == 0.0:
                a = _root(parent, t)
                b = _root(parent, u)
                parent[max(a, b)] = min(a, b)
    for t in range(m):
        parent[t] = _root(parent, t)
    return parent


@njit(**NJIT)
def _lists(P, pstart, psite, spoly, sstart, most, out, ostart):
    """Fill (``out`` given) or count (``out`` empty) each site's candidates, nearest first.

    ``pstart, psite``: the sites of each polytope (CSR); ``sstart, spoly``: the polytopes
    of each site. A site with a polytope of more than ``most`` sites, or with none, gets
    no list (-1 in the counts).
    """
    ns = P.shape[0]
    cnt = np.zeros(ns, np.int64)
    mark = np.full(ns, -1, np.int64)
    d2 = np.zeros(ns)
    fill = out.shape[0] > 0
    for i in range(ns):
        if sstart[i] == sstart[i + 1]:
            cnt[i] = -1
            continue
        big = False
        for k in range(sstart[i], sstart[i + 1]):
            big |= pstart[spoly[k] + 1] - pstart[spoly[k]] > most
        if big:
            cnt[i] = -1
            continue
        c = 0
        o = ostart[i] if fill else 0
        for k in range(sstart[i], sstart[i + 1]):
            p = spoly[k]
            for q in range(pstart[p], pstart[p + 1]):
                j = psite[q]
                if j == i or mark[j] == i:
                    continue
                mark[j] = i
                if fill:
                    out[o + c] = j
                c += 1
        cnt[i] = c
        if fill and c > 0:  # nearest first (ties by number): insertion sort, lists are short
            for a in range(c):
                j = out[o + a]
                dx = P[j, 0] - P[i, 0]
                dy = P[j, 1] - P[i, 1]
                dz = P[j, 2] - P[i, 2]
                d2[a] = dx * dx + dy * dy + dz * dz
            for a in range(1, c):
                j = out[o + a]
                da = d2[a]
                b = a - 1
                while b >= 0 and (d2[b] > da or (d2[b] == da and out[o + b] > j)):
                    out[o + b + 1] = out[o + b]
                    d2[b + 1] = d2[b]
                    b -= 1
                out[o + b + 1] = j
                d2[b + 1] = da
    return cnt


def candidate_lists(P: np.ndarray, T: np.ndarray, N: np.ndarray, most: int):
    """Each site's candidates from a Delaunay triangulation ``T (m, 4)`` of ``P`` (``N``).

    Returns ``(start (ns + 1,), sites, listed (ns,) bool)``: site ``i``'s list is
    ``sites[start[i]:start[i + 1]]`` (nearest first); ``listed[i]`` is False (and the list
    empty) for a site in no tetrahedron or in a polytope of more than ``most`` sites.
    """
    ns = len(P)
    T = np.ascontiguousarray(T, np.int64)
    label = polytopes(P, T, np.ascontiguousarray(N, np.int64))
    # (polytope, site) pairs, once each
    key = np.unique(np.repeat(label, 4) * ns + T.ravel())
    poly, site = key // ns, key % ns
    bounds = np.flatnonzero(np.r_[True, poly[1:] != poly[:-1]])
    pid = np.cumsum(np.r_[False, poly[1:] != poly[:-1]])  # polytopes renumbered 0..k-1
    pstart = np.r_[bounds, len(poly)].astype(np.int64)
    bysite = np.argsort(site, kind="stable")
    sstart = np.zeros(ns + 1, np.int64)
    np.cumsum(np.bincount(site, minlength=ns), out=sstart[1:])
    spoly = pid[bysite].astype(np.int64)
    site = site.astype(np.int64)
    none = np.zeros(0, np.int64)
    cnt = _lists(P, pstart, site, spoly, sstart, most, none, none)
    listed = cnt >= 0
    start = np.zeros(ns + 1, np.int64)
    np.cumsum(np.maximum(cnt, 0), out=start[1:])
    out = np.zeros(max(int(start[-1]), 1), np.int64)
    _lists(P, pstart, site, spoly, sstart, most, out, start)
    return start, out[: start[-1]], listed
