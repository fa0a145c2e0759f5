"""The convex cut on a cell held as a vertex graph (voro++'s layout): cost of the cut part only.

:mod:`kernels.polyhedron` rebuilds every face ring on each cut; the cell builder cuts a
cell ~15 times, mostly near its end when each plane takes off one corner, so it keeps the
cell here instead and cuts it in time proportional to what the plane removes. The rule is
the same (signed values ``S`` per vertex, those within the caller's tolerance snapped to 0;
``s <= 0`` kept unmoved, a crossing edge gets one vertex interpolated from the endpoint
nearer the plane, the new face labelled by the caller) and so are the results; the face
rings are read off at the end (:func:`to_rings`).

Layout, for vertices ``0:nv`` (coordinates ``V (cap, 3)``, kept by the caller):

``DEG (cap,)``
    the vertex's degree;
``ED (cap, D)``
    its neighbours, counter-clockwise seen from outside the cell;
``BK (cap, D)``
    back pointers: ``ED[ED[v, k], BK[v, k]] == v``;
``LB (cap, D)``
    the label of the face whose outward (counter-clockwise) ring has the edge
    ``v -> ED[v, k]``.

Walking a face: after the edge ``v -> u`` (``u = ED[v, k]``, ``j = BK[v, k]``) comes
``u -> ED[u, j - 1]`` (indices modulo the degree).

Anything the cut cannot do simply (a degree above ``D``, a cap that is not one simple ring,
as rounding on nearly degenerate input can make) is reported as ``GCUT_BROKEN``; the cell
builder then builds that cell again with :func:`kernels.polyhedron.cut`.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT

GCUT_NONE = 0
GCUT_DONE = 1
GCUT_EMPTY = 2
GCUT_BROKEN = 3  # also: out of room; the caller falls back to the face-ring cut

#: allocates nothing: compiled without reference counting (see kernels.cellcut3d)
_NO_NRT = {**NJIT, "_nrt": False}


@njit(**{**NJIT, "inline": "always"})
def remap_rings(nf, F, R, remap):
    """Face rings ``F``/``R`` renumbered by ``remap`` and packed again, in place.

    A vertex repeated next to itself (two merged into one) is kept once, and a face left
    with fewer than three vertices is dropped. Returns the faces and ring entries kept.
    """
    nr = 0
    nf2 = 0
    for f in range(nf):
        st = F[f, 1]
        ln = F[f, 2]
        b = nr
        for k in range(ln):
            x = remap[R[st + k]]
            if nr > b and R[nr - 1] == x:
                continue
            R[nr] = x
            nr += 1
        while nr - b > 1 and R[nr - 1] == R[b]:
            nr -= 1
        if nr - b >= 3:
            F[nf2, 0] = F[f, 0]
            F[nf2, 1] = b
            F[nf2, 2] = nr - b
            nf2 += 1
        else:
            nr = b
    return nf2, nr


@njit(**NJIT)
def from_rings(nv, F, nf, R, DEG, ED, BK, LB):
    """Build the graph of polyhedron ``(nv, F, nf, R)`` (outward rings). Returns ok."""
    D = ED.shape[1]
    for v in range(nv):
        DEG[v] = 0
    # out-edges per vertex in any order, with the predecessor of v in that face
    for f in range(nf):
        st = F[f, 1]
        ln = F[f, 2]
        for k in range(ln):
            v = R[st + k]
            d = DEG[v]
            if d >= D:
                return False
            ED[v, d] = R[st + (k + 1) % ln]
            LB[v, d] = F[f, 0]
            BK[v, d] = R[st + (k - 1 + ln) % ln]  # the predecessor, for the order below
            DEG[v] = d + 1
    # counter-clockwise order: the out-edge v -> a of face f (predecessor p) comes right
    # before the out-edge v -> p
    tmp_e = np.zeros(D, np.int64)
    tmp_l = np.zeros(D, np.int64)
    for v in range(nv):
        d = DEG[v]
        if d < 3:
            return False
        k = 0
        for q in range(d):
            tmp_e[q] = ED[v, k]
            tmp_l[q] = LB[v, k]
            p = BK[v, k]
            nxt = -1
            for r in range(d):
                if ED[v, r] == p:
                    nxt = r
                    break
            if nxt < 0:
                return False
            k = nxt
        if k != 0:
            return False
        for q in range(d):
            ED[v, q] = tmp_e[q]
            LB[v, q] = tmp_l[q]
    for v in range(nv):
        for k in range(DEG[v]):
            u = ED[v, k]
            b = -1
            for r in range(DEG[u]):
                if ED[u, r] == v:
                    b = r
                    break
            if b < 0:
                return False
            BK[v, k] = b
    return True


@njit(**{**NJIT, "inline": "always"})
def _next(k, d):
    """``(k + 1) % d`` for ``0 <= k < d``, without a division (the cut's hot walks)."""
    k += 1
    return k if k < d else 0


@njit(**{**NJIT, "inline": "always"})
def _prev(k, d):
    """``(k - 1) % d`` for ``0 <= k < d``, without a division."""
    return k - 1 if k > 0 else d - 1


@njit(**{**NJIT, "inline": "always"})
def _move(V, DEG, ED, BK, LB, FL, a, b):
    """Move vertex ``a`` to slot ``b`` (free), repointing its neighbours."""
    V[b, 0] = V[a, 0]
    V[b, 1] = V[a, 1]
    V[b, 2] = V[a, 2]
    FL[b] = FL[a]
    d = DEG[a]
    DEG[b] = d
    for k in range(d):
        u = ED[a, k]
        ED[b, k] = u
        BK[b, k] = BK[a, k]
        LB[b, k] = LB[a, k]
        ED[u, BK[a, k]] = b


@njit(**{**NJIT, "inline": "always"})
def _only_edge(DEG, ED, v, u):
    """The index of ``u`` among ``v``'s neighbours; -1 if absent or there twice."""
    a = -1
    for r in range(DEG[v]):
        if ED[v, r] == u:
            if a >= 0:
                return -1
            a = r
    return a


@njit(**{**NJIT, "inline": "always"})
def cut(V, nv, DEG, ED, BK, LB, FL, S, CP, label):
    """Cut the cell by the plane whose values are ``S[:nv]``; keep ``s <= 0``.

    ``FL (cap,)`` flags vertices that may lie on planes other than their faces' (the
    caller's mark); a new vertex on an edge is flagged when both ends are (the edge may lie
    in such a plane). ``CP (cap, 3) int64`` is scratch (the cap's ring; the removed
    vertices). Returns
    ``(status, nv, r2)``, ``r2`` (done) the largest ``|v|^2`` of the vertices left.

    :func:`cut_open` then :func:`cut_close`: a caller that moves the cap's points (the cell
    builder's exact re-solve, :func:`kernels.vertex3d.resettle`) does so between them.
    """
    st, nv, w, nlist = cut_open(V, nv, DEG, ED, BK, LB, FL, S, CP, label)
    if st != GCUT_DONE:
        return st, nv, 0.0
    return cut_close(V, nv, DEG, ED, BK, LB, FL, S, CP, nlist)


@njit(**{**NJIT, "inline": "always"})
def cut_open(V, nv, DEG, ED, BK, LB, FL, S, CP, label):
    """The cut of :func:`cut` up to the removed vertices' slots: the cap built and wired.

    Returns ``(status, nv, w, nlist)``. Done: ``CP[:w, 2]`` are the cap's points in order
    (the new vertices, numbered from the ``nv`` given, and the vertices found on the
    plane), ``nv`` counts the new vertices, the removed ones are still in their slots and
    ``nlist`` is for :func:`cut_close`; or, where every cap point is new and there are at
    least as many as removed vertices (the usual cut), the new vertices already at the
    numbers :func:`cut_close` would move them to (:func:`_place_cap`), ``nv`` the count
    left and ``nlist`` -2. Else ``nv`` is :func:`cut`'s.
    """
    nup, down, listed = list_above(nv, S, CP)
    if nup == 0:
        return GCUT_NONE, nv, 0, -1
    if not down:
        return GCUT_EMPTY, 0, 0, -1
    return cut_listed(V, nv, DEG, ED, BK, LB, FL, S, CP, label, nup, listed)


@njit(**{**NJIT, "inline": "always"})
def list_above(nv, S, CP):
    """:func:`cut_open`'s first pass: the vertices above the plane and whether one is below.

    Returns ``(nup, down, listed)``; listed: they are in ``CP``'s column 2 from its last row
    up, ascending (:func:`cut_listed`).
    """
    ncap = CP.shape[0]
    # the vertices above (removed), in order, listed branch-free from CP's last row up in
    # column 2 (q-th at row ncap - 1 - q; the cap's trace fills rows from 0), and whether
    # one is below
    nup = 0
    down = False
    listed = nv < ncap
    if listed:
        for v in range(nv):
            s = S[v]
            CP[ncap - 1 - nup, 2] = v
            nup += s > 0.0
            down |= s < 0.0
    else:
        for v in range(nv):
            nup += S[v] > 0.0
            down |= S[v] < 0.0
    return nup, down, listed


@njit(**{**NJIT, "inline": "always"})
def cut_listed(V, nv, DEG, ED, BK, LB, FL, S, CP, label, nup, listed):
    """:func:`cut_open` once the ``nup`` removed vertices are known (at least one kept).

    ``listed``: they are in ``CP``'s column 2 from its last row up, ascending (else found by
    a scan of ``S``). Only the values of the removed vertices and of their neighbours are
    read (:mod:`kernels.climb3d` evaluates no others).
    """
    vcap = V.shape[0]
    D = ED.shape[1]
    ncap = CP.shape[0]
    # the boundary edges v -> u (v removed, u kept): one to start from, and their count
    e0v = -1
    e0k = -1
    nbound = 0
    for q in range(nup if listed else nv):
        v = CP[ncap - 1 - q, 2] if listed else q
        if not S[v] > 0.0:
            continue
        for k in range(DEG[v]):
            if S[ED[v, k]] <= 0.0:
                if e0v < 0:
                    e0v = v
                    e0k = k
                nbound += 1
    # the trace writes at most nbound + 1 rows: the list must lie past them
    listed = listed and nup + nbound < ncap
    # trace the cap: CP[m] = (boundary vertex v, its index k, point, -)
    m = 0
    v = e0v
    k = e0k
    nb = 0
    while True:
        if m >= ncap:
            return GCUT_BROKEN, nv, 0, -1
        CP[m, 0] = v
        CP[m, 1] = k
        m += 1
        # walk the face of v -> ED[v, k] backwards through removed vertices to its entry
        # edge a -> b (a kept); the next boundary edge is b -> a
        k1 = _next(k, DEG[v])
        a = ED[v, k1]
        b = v
        j = BK[v, k1]  # index of b in a's list
        steps = 0
        while S[a] > 0.0:
            # previous vertex before a in this face: ED[a, j + 1]
            jj = _next(j, DEG[a])
            na = ED[a, jj]
            j = BK[a, jj]
            b = a
            a = na
            steps += 1
            if steps > nv:
                return GCUT_BROKEN, nv, 0, -1
        v = b
        k = BK[a, j]  # ED[b, k] == a
        nb += 1
        if v == e0v and k == e0k:
            break
        if nb > nbound:
            return GCUT_BROKEN, nv, 0, -1
    if m != nbound:  # the cap is not one ring
        return GCUT_BROKEN, nv, 0, -1
    # cap points: a new vertex on each edge to a vertex below, the vertex itself if on
    nv0 = nv
    for q in range(m):
        v = CP[q, 0]
        k = CP[q, 1]
        u = ED[v, k]
        if S[u] == 0.0:
            CP[q, 2] = u
        else:
            if nv >= vcap:
                return GCUT_BROKEN, nv, 0, -1
            x = nv
            nv += 1
            sv = S[v]
            su = S[u]
            a = u
            b = v
            sa = su
            sb = sv
            if abs(sa) > abs(sb):  # from the endpoint nearer the plane
                a = v
                b = u
                sa = sv
                sb = su
            t = sa / (sa - sb)
            V[x, 0] = V[a, 0] + t * (V[b, 0] - V[a, 0])
            V[x, 1] = V[a, 1] + t * (V[b, 1] - V[a, 1])
            V[x, 2] = V[a, 2] + t * (V[b, 2] - V[a, 2])
            S[x] = 0.0
            FL[x] = FL[u] and FL[v]
            CP[q, 2] = x
    # collapse repeats of an on-plane vertex (consecutive, cyclically)
    w = 0
    for q in range(m):
        if w > 0 and CP[w - 1, 2] == CP[q, 2]:
            continue
        if w != q:
            CP[w, 0] = CP[q, 0]
            CP[w, 1] = CP[q, 1]
            CP[w, 2] = CP[q, 2]
        w += 1
    while w > 1 and CP[w - 1, 2] == CP[0, 2]:
        w -= 1
    if w < 3:
        return GCUT_BROKEN, nv0, 0, -1
    # an on-plane vertex must appear once
    for q in range(w):
        c = CP[q, 2]
        if c < nv0:
            for r in range(q + 1, w):
                if CP[r, 2] == c:
                    return GCUT_BROKEN, nv0, 0, -1
    if listed and nv - nv0 == w and nup <= w and D < 256:
        return _place_cap(V, nv0, nv, DEG, ED, BK, LB, FL, S, CP, label, w, nup)
    # rewire. Per point q (prev p = q - 1, next n = q + 1) its list gets ... A, next, prev, B
    # where the removed run lay; new vertices get [prev, u, next].
    for q in range(w):
        c = CP[q, 2]
        cprev = CP[_prev(q, w), 2]
        cnext = CP[_next(q, w), 2]
        if c >= nv0:
            v = CP[q, 0]
            k = CP[q, 1]
            u = ED[v, k]
            j = BK[v, k]
            DEG[c] = 3
            ED[c, 0] = cprev
            ED[c, 1] = u
            ED[c, 2] = cnext
            LB[c, 0] = LB[u, j]
            LB[c, 1] = LB[v, k]
            LB[c, 2] = label
            ED[u, j] = c
            BK[u, j] = 1
            BK[c, 1] = j
        else:
            u = c
            d = DEG[u]
            # the removed run in u's list: find a kept neighbour, then the run after it
            s0 = -1
            for r in range(d):
                if S[ED[u, r]] <= 0.0 and S[ED[u, (r + 1) % d]] > 0.0:
                    if s0 >= 0:
                        return GCUT_BROKEN, nv0, 0, -1  # two runs
                    s0 = r
            if s0 < 0:
                return GCUT_BROKEN, nv0, 0, -1
            # run is s0 + 1 .. s0 + t
            t = 0
            while S[ED[u, (s0 + 1 + t) % d]] > 0.0:
                t += 1
            A = ED[u, s0]
            B = ED[u, (s0 + t + 1) % d]
            lab_t = LB[u, (s0 + t) % d]  # face of u -> r_t: continues as u -> prev
            # the new list, built in the free row nv: the kept entries from B round to A,
            # then next and prev (each left out where it is A or B already)
            nk = 0
            kept = d - t
            if kept + 2 > D:
                return GCUT_BROKEN, nv0, 0, -1
            if nv >= vcap:
                return GCUT_BROKEN, nv0, 0, -1
            tmp = nv
            for r in range(kept):
                src = (s0 + t + 1 + r) % d  # B first, A last
                ED[tmp, nk] = ED[u, src]
                LB[tmp, nk] = LB[u, src]
                BK[tmp, nk] = BK[u, src]
                nk += 1
            # now after A (last written) come next then prev
            if cnext == A:
                LB[tmp, nk - 1] = label
            else:
                ED[tmp, nk] = cnext
                LB[tmp, nk] = label
                nk += 1
            if cprev != B:
                ED[tmp, nk] = cprev
                LB[tmp, nk] = lab_t
                nk += 1
            if nk < 3:
                return GCUT_BROKEN, nv0, 0, -1
            for r in range(nk):
                ED[u, r] = ED[tmp, r]
                LB[u, r] = LB[tmp, r]
                BK[u, r] = BK[tmp, r]
            DEG[u] = nk
            for r in range(kept):  # kept neighbours point back at their new index
                BK[ED[u, r], BK[u, r]] = r
    # back pointers along the cap (and duplicate-edge check; two new points in a row have
    # [prev, u, next] lists of distinct entries (w >= 3): cn is c's entry 2, c is cn's 0)
    for q in range(w):
        c = CP[q, 2]
        cn = CP[_next(q, w), 2]
        if c >= nv0 and cn >= nv0:
            BK[c, 2] = 0
            BK[cn, 0] = 2
            continue
        a = _only_edge(DEG, ED, c, cn)
        b = _only_edge(DEG, ED, cn, c)
        if a < 0 or b < 0:
            return GCUT_BROKEN, nv0, 0, -1
        BK[c, a] = b
        BK[cn, b] = a
    return GCUT_DONE, nv, w, nup if listed else -1


@njit(**{**NJIT, "inline": "always"})
def _place_cap(V, nv0, nv, DEG, ED, BK, LB, FL, S, CP, label, w, nup):
    """:func:`cut_open`'s rewiring where every cap point is new and they fill every hole.

    :func:`cut_close` would move new vertex ``nv - 1 - q`` into the ``q``-th removed slot
    (ascending) and repoint its neighbours; here each new vertex is wired at that final
    number at once (the same arrays, bit for bit, without the moves). Returns
    :func:`cut_open`'s tuple with ``nv`` the count left and ``nlist`` -2 (nothing to fill).
    """
    ncap = CP.shape[0]
    nnew = nv - nv0
    # what the rewiring reads of the removed vertices, before their slots are reused:
    # (u << 8 | j, LB[v, k]) for the edge v -> u of cap point q (D < 256)
    for q in range(w):
        v = CP[q, 0]
        k = CP[q, 1]
        CP[q, 0] = (np.int64(ED[v, k]) << 8) | BK[v, k]
        CP[q, 1] = LB[v, k]
    # final numbers: new vertex nv0 + c goes to the (nnew - 1 - c)-th hole, if there is one
    for q in range(w):
        x = CP[q, 2]
        r = nnew - 1 - (x - nv0)
        if r < nup:
            f = CP[ncap - 1 - r, 2]
            V[f, 0] = V[x, 0]
            V[f, 1] = V[x, 1]
            V[f, 2] = V[x, 2]
            FL[f] = FL[x]
            S[f] = 0.0
            CP[q, 2] = f
    for q in range(w):
        c = CP[q, 2]
        u = CP[q, 0] >> 8
        j = CP[q, 0] & 255
        DEG[c] = 3
        ED[c, 0] = CP[_prev(q, w), 2]
        ED[c, 1] = u
        ED[c, 2] = CP[_next(q, w), 2]
        LB[c, 0] = LB[u, j]
        LB[c, 1] = CP[q, 1]
        LB[c, 2] = label
        ED[u, j] = c
        BK[u, j] = 1
        BK[c, 1] = j
        BK[c, 2] = 0
        BK[CP[_next(q, w), 2], 0] = 2
    return GCUT_DONE, nv - nup, w, -2


@njit(**{**NJIT, "inline": "always"})
def cut_close(V, nv, DEG, ED, BK, LB, FL, S, CP, nlist, radius=True):
    """:func:`cut`'s end after :func:`cut_open`: the removed vertices' slots filled from the top.

    ``nlist`` is :func:`cut_open`'s (the removed vertices listed in ``CP``'s column 2 from
    its last row up, or -1: found by a scan of ``S``, or -2: none left to fill). Returns
    ``(GCUT_DONE, nv, r2)``; ``r2`` is 0 unless ``radius`` (the cell builder finds it when
    it needs it: ``cellcut3d._cut_batch``).
    """
    ncap = CP.shape[0]
    if nlist == -2:  # (_place_cap: nothing to fill)
        r2 = 0.0
        for v in range(nv if radius else 0):
            r2 = max(r2, V[v, 0] * V[v, 0] + V[v, 1] * V[v, 1] + V[v, 2] * V[v, 2])
        return GCUT_DONE, nv, r2
    listed = nlist >= 0
    nup = nlist
    # drop the removed vertices (listed: in order; else found by a scan of S, in order):
    # fill each hole from the top (listed: the removed ones there skipped by the list, so
    # that the values of vertices not listed are not read)
    top = nv
    q = 0
    qt = nup - 1  # (listed: the highest removed vertex at or below top)
    v = 0
    while True:
        if listed:
            if q == nup:
                break
            v = CP[ncap - 1 - q, 2]
            q += 1
        else:
            while v < top and not S[v] > 0.0:
                v += 1
        if v >= top:
            break
        top -= 1
        if listed:
            while top > v:
                while qt >= 0 and CP[ncap - 1 - qt, 2] > top:
                    qt -= 1
                if qt < 0 or CP[ncap - 1 - qt, 2] != top:
                    break
                top -= 1
        else:
            while top > v and S[top] > 0.0:
                top -= 1
        if top > v:
            _move(V, DEG, ED, BK, LB, FL, top, v)
            S[v] = S[top]
        v += 1
    # the largest squared distance of a vertex left from the origin (the site)
    r2 = 0.0
    for v in range(top if radius else 0):
        r2 = max(r2, V[v, 0] * V[v, 0] + V[v, 1] * V[v, 1] + V[v, 2] * V[v, 2])
    return GCUT_DONE, top, r2


@njit(**_NO_NRT)
def to_rings(nv, DEG, ED, BK, LB, F, R, seen):
    """Face rings ``(F, R)`` of the graph (layout of :mod:`kernels.polyhedron`).

    ``seen (cap, D) bool`` is scratch. Returns ``nf``, or -1 when ``F`` or ``R`` is too small.
    """
    fcap = F.shape[0]
    rcap = R.shape[0]
    for v in range(nv):
        for k in range(DEG[v]):
            seen[v, k] = False
    nf = 0
    nr = 0
    for v0 in range(nv):
        for k0 in range(DEG[v0]):
            if seen[v0, k0]:
                continue
            if nf >= fcap:
                return -1
            F[nf, 0] = LB[v0, k0]
            F[nf, 1] = nr
            v = v0
            k = k0
            while True:
                if nr >= rcap:
                    return -1
                seen[v, k] = True
                R[nr] = v
                nr += 1
                u = ED[v, k]
                j = BK[v, k]
                k = _prev(j, DEG[u])
                v = u
                if v == v0 and k == k0:
                    break
                if seen[v, k]:
                    return -1
            F[nf, 2] = nr - F[nf, 1]
            nf += 1
    return nf
