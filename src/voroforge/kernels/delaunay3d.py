"""3D Delaunay tetrahedralisation: incremental (Bowyer-Watson) with exact predicates.

Every decision is an exact sign: :func:`.predicates3d.orient3d` and
:func:`.predicates3d.insphere` (filtered, then exact expansions). Ties (five points on one
sphere, four on a hull plane and its circle) are broken by a symbolic perturbation of the
lifting: point ``i`` is lifted to ``|p_i|^2 + eps_i`` with ``eps_i`` infinitesimal and larger
for larger ``i``. The perturbed diagram is a unique triangulation of the points (no flat
tetrahedron anywhere), a function of the points and their order only (not of the insertion
order), and a Delaunay triangulation of the unperturbed points: no point lies strictly inside
any tetrahedron's circumsphere. On a cubic grid every cube is cut into tetrahedra the same
way wherever it occurs in the input order.

Tetrahedra are stored positively oriented (``orient3d(a, b, c, d) > 0`` in
:func:`.predicates3d.orient3d`'s convention), with the infinite vertex ``-1`` standing for the
outside: a hull facet ``abc`` has the infinite tetrahedron ``(a, b, c, -1)`` beyond it.
``nb[t, i]`` is the tetrahedron across the face opposite vertex ``i``.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT
from .predicates3d import insphere, orient3d

INF = -1


# inlined: called with literal rows (``_o3(Q, 0, 1, 2, 4)``), a dispatcher compiled one
# specialisation per literal tuple (6 in all)
@njit(**{**NJIT, "inline": "always"})
def _o3(P, a, b, c, d):
    """``orient3d`` of rows ``a, b, c, d`` of ``P``."""
    return orient3d(
        P[a, 0], P[a, 1], P[a, 2], P[b, 0], P[b, 1], P[b, 2],
        P[c, 0], P[c, 1], P[c, 2], P[d, 0], P[d, 1], P[d, 2],
    )  # fmt: skip


@njit(**NJIT)
def insphere_sos(Q, rank):
    """Sign of the perturbed insphere of the rows of ``Q (5, 3)``: +1 inside, -1 outside.

    ``Q[4]`` is the query; the sign is relative to ``orient3d(Q[0..3])`` as in
    :func:`.predicates3d.insphere`. A tie is broken by the lifting's perturbation: the
    determinant's coefficient of ``eps_i`` is the cofactor of row ``i``'s lift, ``(-1)**(i+1)``
    times ``orient3d`` of the other four rows in order; the row of largest ``rank`` whose
    cofactor is nonzero decides.
    """
    s = insphere(Q)
    if s > 0.0:
        return 1
    if s < 0.0:
        return -1
    order = np.argsort(-rank)
    for j in range(5):
        i = order[j]
        if i == 0:
            c = -_o3(Q, 1, 2, 3, 4)
        elif i == 1:
            c = _o3(Q, 0, 2, 3, 4)
        elif i == 2:
            c = -_o3(Q, 0, 1, 3, 4)
        elif i == 3:
            c = _o3(Q, 0, 1, 2, 4)
        else:
            c = -_o3(Q, 0, 1, 2, 3)
        if c > 0.0:
            return 1
        if c < 0.0:
            return -1
    return 0


@njit(**NJIT)
def _off_plane(P, a, b, c):
    """A float point off the plane through ``a, b, c``, and whether there is one.

    ``a`` moved along an axis on which the plane's normal is nonzero, chosen by the exact
    orientation (a nearly collinear triangle's float normal can be all zeros); False when
    ``a, b, c`` are collinear.
    """
    Q = np.empty((4, 3))  # noqa: TID251 (filled before use)
    Q[0] = P[a]
    Q[1] = P[b]
    Q[2] = P[c]
    for k in range(3):
        Q[3] = P[a]
        Q[3, k] = Q[3, k] + max(1.0, abs(Q[3, k]))
        if _o3(Q, 0, 1, 2, 3) != 0.0:
            return Q[3].copy(), True
    return Q[3].copy(), False  # a, b, c collinear


@njit(**NJIT)
def conflict(P, T, t, p):
    """Whether point ``p`` is in conflict with tetrahedron ``t``.

    Its perturbed circumsphere holds ``p``; for an infinite one: ``p`` lies beyond its hull
    facet, or on the facet's plane inside its perturbed circumcircle.
    """
    Q = np.empty((5, 3))  # noqa: TID251 (filled before use)
    rank = np.empty(5)  # noqa: TID251 (filled before use)
    k = -1
    for i in range(4):
        v = T[t, i]
        if v == INF:
            k = i
        else:
            Q[i] = P[v]
            rank[i] = v
    Q[4] = P[p]
    rank[4] = p
    if k < 0:
        return insphere_sos(Q, rank) > 0
    # the facet's side: the tetrahedron with p in the infinite vertex's place
    Q[k] = P[p]
    o = _o3(Q, 0, 1, 2, 3)
    if o != 0.0:
        return o > 0.0
    # coplanar: p inside the facet's circle, i.e. inside the sphere through the facet and
    # any point off its plane (that sphere meets the plane in the circle)
    f = np.empty(3, np.int64)  # noqa: TID251 (filled before use)
    j = 0
    for i in range(4):
        if i != k:
            f[j] = T[t, i]
            j += 1
    Q[k] = _off_plane(P, f[0], f[1], f[2])[0]
    rank[k] = -1.0
    od = _o3(Q, 0, 1, 2, 3)
    s = insphere_sos(Q, rank)
    return (s > 0) == (od > 0.0) and s != 0


@njit(**NJIT)
def _grow(T, nb, alive, need):
    m = T.shape[0]
    if need <= m:
        return T, nb, alive
    m2 = max(need, 2 * m)
    T2 = np.full((m2, 4), INF, np.int64)
    nb2 = np.full((m2, 4), -1, np.int64)
    a2 = np.zeros(m2, np.bool_)
    T2[:m] = T
    nb2[:m] = nb
    a2[:m] = alive
    return T2, nb2, a2


@njit(**NJIT)
def _first_tet(P, order):
    """Positions in ``order`` of four points spanning 3D, or -1s (all coplanar)."""
    n = len(order)
    out = np.full(4, -1, np.int64)
    if n < 4:
        return out
    a = order[0]
    ib = -1
    for i in range(1, n):
        q = order[i]
        if P[q, 0] != P[a, 0] or P[q, 1] != P[a, 1] or P[q, 2] != P[a, 2]:
            ib = i
            break
    if ib < 0:
        return out
    b = order[ib]
    ic = -1
    for i in range(ib + 1, n):
        q = order[i]
        if not _collinear(P, a, b, q):
            ic = i
            break
    if ic < 0:
        return out
    c = order[ic]
    for i in range(ic + 1, n):
        q = order[i]
        if _o3(P, a, b, c, q) != 0.0:
            out[0] = 0
            out[1] = ib
            out[2] = ic
            out[3] = i
            return out
    return out


@njit(**NJIT)
def _collinear(P, a, b, q):
    # collinear iff no point off a along an axis is off the plane through a, b, q
    return not _off_plane(P, a, b, q)[1]


#: the face opposite vertex i, ordered so that (face, vertex i) is positively oriented
FACE = np.array([[1, 3, 2], [0, 2, 3], [0, 3, 1], [0, 1, 2]], np.int64)


@njit(**NJIT)
def triangulate(P, order):
    """Delaunay tetrahedra of the distinct points ``P`` inserted in ``order``.

    Returns ``(T, nb, ok)``: the live tetrahedra (finite and infinite) and their neighbours,
    ``ok`` False when the points span no volume (fewer than 4, or all coplanar).
    """
    n = len(order)
    T = np.full((max(16, 8 * n), 4), INF, np.int64)
    nb = np.full(T.shape, -1, np.int64)
    alive = np.zeros(T.shape[0], np.bool_)
    first = _first_tet(P, order)
    if first[0] < 0:
        return T[:0], nb[:0], False
    a, b, c, d = order[first[0]], order[first[1]], order[first[2]], order[first[3]]
    if _o3(P, a, b, c, d) < 0.0:
        b, c = c, b
    T[0, 0] = a
    T[0, 1] = b
    T[0, 2] = c
    T[0, 3] = d
    # an infinite tetrahedron on each face: the face (oriented to look outward) and -1, so
    # that -1 stands where a point beyond the face would make it positive
    for i in range(4):
        T[1 + i, 0] = T[0, FACE[i, 0]]
        T[1 + i, 1] = T[0, FACE[i, 2]]
        T[1 + i, 2] = T[0, FACE[i, 1]]
        T[1 + i, 3] = INF
    m = 5
    _link_small(T, nb, m)
    alive[:m] = True
    used = np.zeros(n, np.bool_)
    for f in range(4):
        used[first[f]] = True
    # (np.int64: a literal 0 compiled _locate, conflict and _doubled once more for it, while
    # type inference had not yet unified it with the later values)
    last = np.int64(0)
    stack = np.empty(64, np.int64)  # noqa: TID251 (filled before use)
    cav = np.empty(64, np.int64)  # noqa: TID251 (filled before use)
    incav = np.zeros(T.shape[0], np.bool_)
    # boundary faces of the cavity: (outside tet, its slot facing in, a, b, c)
    bnd = np.empty((64, 5), np.int64)  # noqa: TID251 (filled before use)
    for r in range(n):
        if used[r]:
            continue
        p = order[r]
        t = _locate(P, T, nb, alive, last, p)
        if t < 0:
            raise RuntimeError("delaunay3d: no tetrahedron in conflict with a point")
        # the cavity: tetrahedra in conflict, connected to t
        if T.shape[0] > len(incav):
            incav = np.zeros(T.shape[0], np.bool_)
        ncav = np.int64(0)
        stack[0] = t
        nst = 1
        incav[t] = True
        nb_count = 0
        while nst > 0:
            nst -= 1
            u = stack[nst]
            if ncav >= len(cav):
                cav = _doubled(cav, ncav)
            cav[ncav] = u
            ncav += 1
            for i in range(4):
                w = nb[u, i]
                if incav[w]:
                    continue
                if conflict(P, T, w, p):
                    incav[w] = True
                    if nst >= len(stack):
                        stack = _doubled(stack, nst)
                    stack[nst] = w
                    nst += 1
                else:
                    if nb_count >= len(bnd):
                        b2 = np.empty((2 * len(bnd), 5), np.int64)  # noqa: TID251 (filled before use)
                        b2[:nb_count] = bnd[:nb_count]
                        bnd = b2
                    # the face of u opposite vertex i, oriented as in u
                    bnd[nb_count, 0] = w
                    bnd[nb_count, 1] = u
                    bnd[nb_count, 2] = T[u, FACE[i, 0]]
                    bnd[nb_count, 3] = T[u, FACE[i, 1]]
                    bnd[nb_count, 4] = T[u, FACE[i, 2]]
                    nb_count += 1
        # new tetrahedra: each boundary face with p; reuse the cavity's slots first
        need = m + max(0, nb_count - ncav)
        if need > T.shape[0]:
            T, nb, alive = _grow(T, nb, alive, need)
            incav2 = np.zeros(T.shape[0], np.bool_)
            incav2[: len(incav)] = incav
            incav = incav2
        slots = np.empty(nb_count, np.int64)  # noqa: TID251 (filled before use)
        for j in range(nb_count):
            if j < ncav:
                slots[j] = cav[j]
            else:
                slots[j] = m
                m += 1
        for j in range(ncav):
            incav[cav[j]] = False
        for j in range(nb_count, ncav):
            alive[cav[j]] = False
        # edges of the new tetrahedra's faces through p, to pair them: (lo, hi, tet, slot)
        ekey = np.empty((3 * nb_count, 4), np.int64)  # noqa: TID251 (filled before use)
        for j in range(nb_count):
            s = slots[j]
            w, u = bnd[j, 0], bnd[j, 1]
            fa, fb, fc = bnd[j, 2], bnd[j, 3], bnd[j, 4]
            # face (fa, fb, fc) is oriented as seen from u's opposite vertex: the tetrahedron
            # (fa, fb, fc, x) is positive for x on u's side; p takes slot 3
            T[s, 0] = fa
            T[s, 1] = fb
            T[s, 2] = fc
            T[s, 3] = p
            alive[s] = True
            nb[s, 3] = w
            for i in range(4):
                if nb[w, i] == u and _same_face(T, w, i, fa, fb, fc):
                    nb[w, i] = s
                    break
            for i in range(3):
                x = T[s, (i + 1) % 3]
                y = T[s, (i + 2) % 3]
                lo = min(x, y)
                hi = max(x, y)
                ekey[3 * j + i, 0] = lo
                ekey[3 * j + i, 1] = hi
                ekey[3 * j + i, 2] = s
                ekey[3 * j + i, 3] = i
        key = ekey[:, 0] * (len(P) + 2) + ekey[:, 1]
        srt = np.argsort(key)
        for q in range(0, len(srt), 2):
            e1 = srt[q]
            e2 = srt[q + 1]
            nb[ekey[e1, 2], ekey[e1, 3]] = ekey[e2, 2]
            nb[ekey[e2, 2], ekey[e2, 3]] = ekey[e1, 2]
        last = slots[0]
        for j in range(nb_count):
            if T[slots[j], 0] != INF and T[slots[j], 1] != INF and T[slots[j], 2] != INF:
                last = slots[j]
                break
    keep = np.flatnonzero(alive[:m])
    remap = np.full(m, -1, np.int64)
    remap[keep] = np.arange(len(keep))
    nbk = nb[keep]
    for i in range(len(keep)):
        for j in range(4):
            nbk[i, j] = remap[nbk[i, j]]
    return T[keep], nbk, True


@njit(**NJIT)
def _doubled(a, n):
    """``a`` (1D) in an array twice as long, its first ``n`` entries kept."""
    out = np.empty(2 * len(a), a.dtype)  # noqa: TID251 (filled before use)
    out[:n] = a[:n]
    return out


@njit(**NJIT)
def _link_small(T, nb, m):
    """Neighbours of the first ``m`` tetrahedra by matching their faces (a few only)."""
    for t in range(m):
        for i in range(4):
            for u in range(m):
                if u != t:
                    a, b, c = T[t, FACE[i, 0]], T[t, FACE[i, 1]], T[t, FACE[i, 2]]
                    for j in range(4):
                        if _same_face(T, u, j, a, b, c):
                            nb[t, i] = u


@njit(**NJIT)
def _same_face(T, w, i, a, b, c):
    for k in range(3):
        v = T[w, FACE[i, k]]
        if v != a and v != b and v != c:
            return False
    return True


@njit(**NJIT)
def _locate(P, T, nb, alive, start, p):
    """A tetrahedron in conflict with ``p``.

    A visibility walk from ``start`` (faces tried in a varying order so degenerate loops
    end), then a scan of every live one if the walk ran long.
    """
    t = start
    steps = 0
    limit = 64 + 4 * int(np.sqrt(T.shape[0]))
    rot = 0
    while steps < limit:
        steps += 1
        if T[t, 0] == INF or T[t, 1] == INF or T[t, 2] == INF or T[t, 3] == INF:
            if conflict(P, T, t, p):
                return t
            # step inward through the hull facet
            for i in range(4):
                if T[t, i] == INF:
                    t = nb[t, i]
                    break
            continue
        moved = False
        rot = (rot + 1) & 3
        for ii in range(4):
            i = (ii + rot) & 3
            a = T[t, FACE[i, 0]]
            b = T[t, FACE[i, 1]]
            c = T[t, FACE[i, 2]]
            # p beyond face i: the tetrahedron with p for vertex i is negative
            if _o3(P, a, b, c, p) < 0.0:
                t = nb[t, i]
                moved = True
                break
        if not moved:
            return t
    for t in range(T.shape[0]):
        if alive[t] and conflict(P, T, t, p):
            return t
    return -1
