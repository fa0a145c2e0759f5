"""Each site's Delaunay candidates: the sites of the Delaunay polytopes at it.

A 3D Voronoi cell is the container cut by the bisectors of the sites that share a face
with it, and each of its vertices is named from every site on the vertex's empty sphere
(:mod:`kernels.vertex3d`). Both kinds of site are vertices of the Delaunay polytopes at
the cell's site: the polytope dual to a vertex is the set of sites on its empty sphere,
and a triangulation that refines the Delaunay subdivision (``vf.delaunay3d``'s symbolic
perturbation) splits it into tetrahedra with that one circumsphere, joined across faces
whose opposite vertex lies exactly on it (:func:`polytopes`). :func:`candidate_lists`
gathers, per site, the sites of its polytopes, nearest first.

A big polytope (integer points of one sphere: all n sites, one vertex at its centre) is
not listed whole: a site's faces there are bisectors of the polytope's edges at it and its
other vertices lie on the Voronoi edges dual to the polytope's 2-faces, so its list holds
the sites of the 2-faces at it (:func:`big_facets`: the polytope's boundary triangles
merged across coplanar edges). The centre itself is named once from all the polytope's
sites (``big``: :func:`.cells3d.build_cells` names a vertex whose name is four of them from
the whole polytope), so the cells agree on it without each testing every site.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT
from .predicates3d import insphere, orient3d


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
def _lists(P, pstart, psite, spoly, sstart, skip, out, ostart):
    """Fill (``out`` given) or count (``out`` empty) each site's candidates, nearest first.

    ``pstart, psite``: the sites of each polytope (CSR); ``sstart, spoly``: the polytopes
    of each site. A site marked in ``skip`` (two big polytopes), or with none, gets no
    list (-1 in the counts).
    """
    ns = P.shape[0]
    cnt = np.zeros(ns, np.int64)
    mark = np.full(ns, -1, np.int64)
    d2 = np.zeros(ns)
    fill = out.shape[0] > 0
    for i in range(ns):
        if sstart[i] == sstart[i + 1] or skip[i]:
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


@njit(**NJIT)
def big_facets(P, T, N, label, big):
    """The 2-faces of the big polytopes: ``(tri (k, 3), facet (k,))``.

    ``big (m,)``: whether tetrahedron ``t``'s polytope (``label[t]``) is big. Its boundary
    triangles (faces whose neighbour ``N`` is -1 or of another polytope) are joined into
    one facet across an edge where the two triangles are exactly coplanar (``orient3d``
    0: on a convex polytope's boundary, one 2-face). ``facet`` labels each triangle by
    the smallest triangle of its facet.
    """
    m = T.shape[0]
    k = 0
    for t in range(m):
        if big[t]:
            for f in range(4):
                u = N[t, f]
                k += u < 0 or label[u] != label[t]
    tri = np.zeros((k, 3), np.int64)
    poly = np.zeros(k, np.int64)
    k = 0
    for t in range(m):
        if not big[t]:
            continue
        for f in range(4):
            u = N[t, f]
            if u >= 0 and label[u] == label[t]:
                continue
            c = 0
            for q in range(4):
                if q != f:
                    tri[k, c] = T[t, q]
                    c += 1
            poly[k] = label[t]
            k += 1
    # edges (polytope, a < b) of the triangles, sorted: the two triangles at each edge
    ns = np.int64(P.shape[0])
    ekey = np.zeros(3 * k, np.int64)
    etri = np.zeros(3 * k, np.int64)
    for t in range(k):
        for e in range(3):
            a = tri[t, e]
            b = tri[t, (e + 1) % 3]
            ekey[3 * t + e] = min(a, b) * ns + max(a, b)
            etri[3 * t + e] = t
    parent = np.arange(k)
    ord_ = np.argsort(ekey, kind="mergesort")
    q = 0
    while q < 3 * k:
        r = q + 1
        while r < 3 * k and ekey[ord_[r]] == ekey[ord_[q]]:
            r += 1
        for x in range(q, r):
            for y in range(x + 1, r):
                s = etri[ord_[x]]
                t = etri[ord_[y]]
                if poly[s] != poly[t]:
                    continue
                o = -1  # the vertex of t off the shared edge
                for c in range(3):
                    v = tri[t, c]
                    if v != tri[s, 0] and v != tri[s, 1] and v != tri[s, 2]:
                        o = v
                if o < 0:
                    continue
                a = tri[s, 0]
                b = tri[s, 1]
                c = tri[s, 2]
                if (
                    orient3d(
                        P[a, 0],
                        P[a, 1],
                        P[a, 2],
                        P[b, 0],
                        P[b, 1],
                        P[b, 2],
                        P[c, 0],
                        P[c, 1],
                        P[c, 2],
                        P[o, 0],
                        P[o, 1],
                        P[o, 2],
                    )
                    == 0.0
                ):
                    ra = _root(parent, s)
                    rb = _root(parent, t)
                    parent[max(ra, rb)] = min(ra, rb)
        q = r
    for t in range(k):
        parent[t] = _root(parent, t)
    return tri, parent


def _pairs(group, site, ns):
    """Unique ``(group, site)`` pairs, sorted: ``(group, site)`` arrays."""
    key = np.unique(group.astype(np.int64) * ns + site.astype(np.int64))
    return key // ns, key % ns


def candidate_lists(P: np.ndarray, T: np.ndarray, N: np.ndarray, most: int):
    """Each site's candidates from a Delaunay triangulation ``T (m, 4)`` of ``P`` (``N``).

    Returns ``(start (ns + 1,), sites, listed (ns,) bool, big, polys)``: site ``i``'s list is
    ``sites[start[i]:start[i + 1]]`` (nearest first): the sites of its polytopes of at
    most ``most`` sites and of the 2-faces at it of its bigger polytopes. ``listed[i]`` is
    False (and the list empty) for a site in no tetrahedron or in two big polytopes.
    ``big = (bigof (ns,), bstart, bsite)``: the big polytope of each site (-1 none) and
    each big polytope's sites in increasing order (CSR). ``polys = (tpid (m,), pstart,
    psite)``: every tetrahedron's polytope and every polytope's sites, increasing (CSR).
    """
    ns = len(P)
    T = np.ascontiguousarray(T, np.int64)
    Nc = np.ascontiguousarray(N, np.int64)
    label = polytopes(P, T, Nc)
    # (polytope, site) pairs, once each
    poly, site = _pairs(np.repeat(label, 4), T.ravel(), ns)
    new = np.r_[True, poly[1:] != poly[:-1]]
    bounds = np.flatnonzero(new)
    size = np.diff(np.r_[bounds, len(poly)])
    bigpoly = poly[bounds][size > most]  # the big polytopes' labels
    polys = (
        np.searchsorted(poly[bounds], label).astype(np.int64),
        np.r_[bounds, len(poly)].astype(np.int64),
        site.astype(np.int64),
    )
    isbig = np.isin(poly, bigpoly)
    # groups: the small polytopes, then the 2-faces of the big ones
    gpoly, gsite = poly[~isbig], site[~isbig]
    bigof = np.full(ns, -1, np.int64)
    bstart = np.zeros(len(bigpoly) + 1, np.int64)
    bsite = site[isbig].astype(np.int64)  # by polytope, each in increasing order
    if len(bigpoly):
        np.cumsum(size[size > most], out=bstart[1:])
        bid = np.repeat(np.arange(len(bigpoly)), size[size > most])
        nbig = np.bincount(bsite, minlength=ns)
        bigof[bsite] = bid
        bigof[nbig > 1] = -1
        skip = nbig > 1  # a site in two big polytopes: no list (searched)
        tri, facet = big_facets(P, T, Nc, label, np.isin(label, bigpoly))
        fs, fsite = _pairs(np.repeat(facet, 3), tri.ravel(), ns)
        gpoly = np.r_[gpoly, fs + len(label)]  # (past every polytope label)
        gsite = np.r_[gsite, fsite]
    else:
        skip = np.zeros(ns, np.bool_)
    order = np.argsort(gpoly, kind="stable")
    gpoly, gsite = gpoly[order], gsite[order]
    new = np.r_[True, gpoly[1:] != gpoly[:-1]] if len(gpoly) else np.zeros(0, np.bool_)
    pstart = np.r_[np.flatnonzero(new), len(gpoly)].astype(np.int64)
    pid = np.cumsum(new) - 1  # groups renumbered 0..k-1
    bysite = np.argsort(gsite, kind="stable")
    sstart = np.zeros(ns + 1, np.int64)
    np.cumsum(np.bincount(gsite, minlength=ns), out=sstart[1:])
    spoly = pid[bysite].astype(np.int64)
    site = gsite.astype(np.int64)
    none = np.zeros(0, np.int64)
    cnt = _lists(P, pstart, site, spoly, sstart, skip, none, none)
    listed = cnt >= 0
    start = np.zeros(ns + 1, np.int64)
    np.cumsum(np.maximum(cnt, 0), out=start[1:])
    out = np.zeros(max(int(start[-1]), 1), np.int64)
    _lists(P, pstart, site, spoly, sstart, skip, out, start)
    return start, out[: start[-1]], listed, (bigof, bstart, bsite), polys
