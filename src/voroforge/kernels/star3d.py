"""One 3D cell read off its Delaunay star, for cells with long candidate lists.

A cell cut plane by plane costs its number of vertices per plane: the centre site of n
points on a sphere has n faces, so its cut was quadratic (40,000 points: 66 s of 70). Its
Voronoi region is dual to its Delaunay star: one vertex per Delaunay polytope at the site
(the circumcentre of the polytope's sites), one face per Delaunay edge at it, whose ring is
the polytopes around the edge in turn. Each vertex is named from its polytope's sites by
the vertex rule (:func:`.vertex3d.name_vertex`: sorted owners, first independent
quadruple, solved from the name), so it has the bits every other cell computes for it.

The region is the cell only where the container does not cut it: the site interior (no
hull face in its star) and every vertex inside every wall by more than the filter's band
(``VORONOI3D_CUT_RTOL``). Otherwise :func:`star_cell` declines and the cell is cut as
before.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT, STAR3D_WALL_BANDS, VORONOI3D_CUT_RTOL
from .graph3d import remap_rings
from .merge3d import keep_vertex
from .predicates3d import wall_lift
from .vertex3d import name_key, name_vertex, place

#: no allocation here (the caller passes the scratch): no reference counting
_NO_NRT = {**NJIT, "_nrt": False}
#: star_cell's results besides ``OK`` (the kernels.cellcut3d codes): not a cell this way
DECLINE = -1


@njit(**_NO_NRT)
def _parity(a, b, c, d):
    """Whether ``(a, b, c, d)``, a permutation of 0..3, is even."""
    inv = (a > b) + (a > c) + (a > d) + (b > c) + (b > d) + (c > d)
    return inv % 2 == 0


@njit(**_NO_NRT)
def star_cell(i, P, W, WP, ST, F, R, NM, buf, mark, caps):
    """Cell ``i`` from its star: ``(status, nv, nf, nr)``, status 0 (OK), 2 or ``DECLINE``.

    ``ST = (tstart, tlist, T, N, tpid, pstart, psite, _)``: the tetrahedra at each site
    (CSR), the triangulation (right-handed ``T``, neighbours ``N`` opposite each vertex, -1
    on the hull), each tetrahedron's polytope and each polytope's sites (increasing).
    Writes the named vertices into ``NM``'s ``vnames, vabs, vrel`` (as
    :func:`.cells3d._name_cell`) and the faces into ``F (label, start, length)`` and ``R``
    (outward rings). ``mark = (pstamp, ploc, sstamp)`` are scratch stamped with ``i + 1``
    (per polytope: whether seen and its vertex; per site: its edge done). Status 2
    (OVERFLOW) with ``(nv, nf, nr)`` bounds when ``caps`` (vertices, faces, ring entries)
    are too small.
    """
    tstart, tlist, T, N, tpid, pstart, psite = ST[0], ST[1], ST[2], ST[3], ST[4], ST[5], ST[6]
    vnames, vabs, vrel, rows, y, name, x = NM[0], NM[1], NM[2], NM[4], NM[5], NM[6], NM[7]
    pstamp, ploc, sstamp = mark
    ns = P.shape[0]
    t0 = tstart[i]
    t1 = tstart[i + 1]
    nt = t1 - t0
    if nt == 0:
        return DECLINE, 0, 0, 0
    # vertices <= tetrahedra, faces <= edges (<= 3 a tetrahedron), ring entries <= 2 a
    # tetrahedron per face through it
    if nt > caps[0] or 3 * nt > caps[1] or 6 * nt > caps[2]:
        return 2, nt, 3 * nt, 6 * nt
    stamp = i + 1
    nv = 0
    for q in range(t0, t1):
        t = tlist[q]
        for f in range(4):
            if T[t, f] != i and N[t, f] < 0:
                return DECLINE, 0, 0, 0  # a hull face at the site: its region is open
        p = tpid[t]
        if pstamp[p] == stamp:
            continue
        pstamp[p] = stamp
        ploc[p] = nv
        keys = psite[pstart[p] : pstart[p + 1]]
        u = keys.shape[0]
        r = name_vertex(keys, u, P, W, WP, ns, rows, y, name, buf)
        if r == 0:
            return DECLINE, 0, 0, 0
        a = name[0]
        place(name, P, W, WP, ns, y, x, buf)
        for c in range(4):
            vnames[nv, c] = name[c]
        vnames[nv, 4] = (name_key(u, name) << 8) | min(u, 255)
        for c in range(3):
            vabs[nv, c] = x[c] + 0.0  # one zero: equal values, equal bits (merge_star)
            if x[c] == P[a, c] + y[c]:
                vrel[nv, c] = (P[a, c] - P[i, c]) + y[c]
            else:
                vrel[nv, c] = x[c] - P[i, c]
        nv += 1
    # every vertex inside every wall by more than the cut's band: the container is not met
    px = P[i, 0]
    py = P[i, 1]
    pz = P[i, 2]
    rmax = 0.0
    for v in range(nv):
        rmax = max(rmax, np.sqrt(vrel[v, 0] ** 2 + vrel[v, 1] ** 2 + vrel[v, 2] ** 2))
    for w in range(WP.shape[0]):
        h = wall_lift(WP, w, px, py, pz)
        nn = np.sqrt(WP[w, 0] ** 2 + WP[w, 1] ** 2 + WP[w, 2] ** 2)
        tol = STAR3D_WALL_BANDS * VORONOI3D_CUT_RTOL * (nn * rmax + abs(h))
        for v in range(nv):
            s = WP[w, 0] * vrel[v, 0] + WP[w, 1] * vrel[v, 1] + WP[w, 2] * vrel[v, 2] - h
            if not s < -tol:
                return DECLINE, 0, 0, 0
    # faces: one per site sharing an edge with i, its ring the polytopes around the edge
    nf = 0
    nr = 0
    for q in range(t0, t1):
        t = tlist[q]
        for pj in range(4):
            j = T[t, pj]
            if j == i or sstamp[j] == stamp:
                continue
            sstamp[j] = stamp
            b0 = nr
            cur = t
            steps = 0
            while True:
                a = -1  # the positions of the other two: (i, j, k, l) right-handed
                b = -1
                ci = 0
                cj = 0
                for c in range(4):
                    if T[cur, c] == i:
                        ci = c
                    elif T[cur, c] == j:
                        cj = c
                    elif a < 0:
                        a = c
                    else:
                        b = c
                if not _parity(ci, cj, a, b):
                    a, b = b, a
                vloc = ploc[tpid[cur]]
                if nr == b0 or R[nr - 1] != vloc:
                    R[nr] = vloc
                    nr += 1
                cur = N[cur, a]  # across the face (i, j, l): on around the edge
                steps += 1
                if cur < 0 or steps > nt:
                    return DECLINE, 0, 0, 0
                if cur == t:
                    break
            while nr - b0 > 1 and R[nr - 1] == R[b0]:
                nr -= 1
            if nr - b0 >= 3:
                F[nf, 0] = j
                F[nf, 1] = b0
                F[nf, 2] = nr - b0
                nf += 1
            else:
                nr = b0
    return 0, nv, nf, nr


@njit(**_NO_NRT)
def merge_star(nv, F, nf, R, vnames, vabs, vrel, remap, vbits, table):
    """:func:`.merge3d.merge_named` for a star's vertices, in linear time.

    Two polytopes never share a name (the name's four sites lie on one empty sphere), so
    only vertices with equal coordinates and join keys merge (distinct exact vertices that
    round to the same doubles and whose names' keys collide), found through a hash table
    on their bits (``vbits``: ``vabs``'s int64 view; ``table``: scratch of at least
    ``2 nv`` slots). The merge of all pairs cost ``nv^2`` (80,000 vertices: 5 s). Returns
    ``(nv, nf, nr)``; as there, vertices keep the order of their first occurrence and
    rings drop repeats and faces of fewer than three vertices.
    """
    size = 1
    while size < 2 * nv:
        size *= 2
    size = min(size, table.shape[0])
    mask = size - 1
    for h in range(size):
        table[h] = -1
    m = 0
    for v in range(nv):
        key = vnames[v, 4] >> 8
        hv = np.uint64(key)
        for q in range(3):
            hv = (hv ^ np.uint64(vbits[v, q])) * np.uint64(0x9E3779B97F4A7C15)
            hv ^= hv >> np.uint64(29)
        h = np.int64(hv & np.uint64(mask))
        same = -1
        while table[h] >= 0:
            u = table[h]  # a kept vertex (its new number is remap[u]... u is new)
            if (
                vabs[u, 0] == vabs[v, 0]
                and vabs[u, 1] == vabs[v, 1]
                and vabs[u, 2] == vabs[v, 2]
                and vnames[u, 4] >> 8 == key
            ):
                same = u
                break
            h = (h + 1) & mask
        if same >= 0:
            remap[v] = same
            continue
        remap[v] = m
        keep_vertex(m, v, vnames, vabs, vrel)
        table[h] = m
        m += 1
    nf2, nr = remap_rings(nf, F, R, remap)
    return m, nf2, nr
