"""A 3D cell's vertices within the float filter's band of a cutting plane, decided exactly.

Split from :mod:`kernels.cellcut3d` (whose :func:`.cellcut3d._cut_batch` calls
:func:`resolve`): a vertex whose float value is within ``tol`` of a candidate's plane is
decided on its owners, the planes of its faces (:func:`_graph_side`, :func:`_ring_side`,
:func:`kernels.predicates3d.bisector_side`), or first in floats and double-double about its
exact offset, solved once a cell and kept in :func:`offset_cache` (:func:`_cached_vertex`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT
from .expansion import two_diff
from .predicates3d import (
    bisector_side,
    frame_lift,
    frame_offset,
    frame_side,
    offset_side,
    vertex_offset,
)

#: small hot helpers are inlined (see kernels.cellcut3d); the per-cell functions allocate
#: nothing and are compiled without reference counting
NJIT_INLINE = {**NJIT, "inline": "always"}
NJIT_NO_NRT = {**NJIT, "_nrt": False}


@njit(**NJIT_INLINE)
def owner_key(lab, ns):
    """The owner key of a face label: a site, or ``ns + w`` for wall ``w`` (label ``-1 - w``)."""
    return lab if lab >= 0 else ns + (-1 - lab)


@njit(**NJIT_NO_NRT)
def _graph_side(i, v, j, DEG, LB, ns, P, W, WP, X):
    """Exact side of graph vertex ``v`` of cell ``i`` against key ``j`` (see ``bisector_side``).

    The vertex is where the planes of its faces meet: the first independent triple of its
    face labels defines it. Returns 2 when none is independent.
    """
    d = DEG[v]
    for a in range(d):
        for b in range(a + 1, d):
            for c in range(b + 1, d):
                r = bisector_side(
                    i,
                    owner_key(LB[v, a], ns),
                    owner_key(LB[v, b], ns),
                    owner_key(LB[v, c], ns),
                    j,
                    P,
                    W,
                    WP,
                    ns,
                    X[0],
                    X[1],
                )
                if r != 2:
                    return r
    return 2


@njit(**NJIT)
def offset_cache(vcap):
    """The cache of :func:`_cached_vertex` for cells of up to ``vcap`` vertices: ``(XK, XF)``.

    ``XK[0, 0]`` counts the cells begun (:func:`one_cell`), ``XK[0, 1]`` is that count once
    the cell's frame ``o = XF[vcap, :3]`` is set; ``XK[1 + v] = (count, k0, k1, k2)`` says
    for which cell and owner triple ``XF[v]`` holds graph vertex ``v``'s point ``x``:
    ``(c, x - c, x - o, error of x - o)``, ``c`` a float point near it (NaN: the triple
    is not independent). An entry of another cell or triple is stale.
    """
    return np.zeros((vcap + 1, 4), np.int64), np.zeros((vcap + 1, 12))


@njit(**NJIT_NO_NRT)
def _cached_vertex(i, v, V, DEG, LB, ns, P, W, WP, X):
    """Whether graph vertex ``v``'s exact offsets are in the cache (solved now if stale).

    A vertex whose float value is within the filter's band of a plane is mostly one whose
    coordinates, relative to the site, are too coarse for that plane, not one on it: a
    vertex near the centre of sites on a sphere has every bisector within an ulp, and the
    exact test of every candidate against it made such cells cost quadratic time. Its
    point relative to ``c`` (its float position) is solved once from its first three
    owners (:func:`kernels.predicates3d.vertex_offset`), and relative to the cell's frame
    ``o`` (the first such ``c``), so that each plane is then decided in floats or
    double-double with a proven bound (:func:`_resolve`). The first triple is the one
    :func:`_graph_side` tries first, so a decision on it is its decision. False when the
    triple is not independent (then :func:`_graph_side` decides, as before).
    """
    XK = X[3]
    XF = X[4]
    vcap = XF.shape[0] - 1
    if DEG[v] < 3 or v >= vcap:
        return False
    k0 = owner_key(LB[v, 0], ns)
    k1 = owner_key(LB[v, 1], ns)
    k2 = owner_key(LB[v, 2], ns)
    gen = XK[0, 0]
    if not (
        XK[v + 1, 0] == gen and XK[v + 1, 1] == k0 and XK[v + 1, 2] == k1 and XK[v + 1, 3] == k2
    ):
        cx = P[i, 0] + V[v, 0]
        cy = P[i, 1] + V[v, 1]
        cz = P[i, 2] + V[v, 2]
        XF[v, 0] = cx
        XF[v, 1] = cy
        XF[v, 2] = cz
        if not vertex_offset(i, k0, k1, k2, P, W, WP, ns, X[1], cx, cy, cz, XF[v, 3:6]):
            XF[v, 3] = np.nan
        elif XK[0, 1] != gen:  # the cell's frame: at its first solved vertex
            XK[0, 1] = gen
            XF[vcap, 0] = cx
            XF[vcap, 1] = cy
            XF[vcap, 2] = cz
        if XF[v, 3] == XF[v, 3]:
            frame_offset(
                cx,
                cy,
                cz,
                XF[v, 3],
                XF[v, 4],
                XF[v, 5],
                XF[vcap, 0],
                XF[vcap, 1],
                XF[vcap, 2],
                XF[v, 6:12],
            )
        XK[v + 1, 0] = gen
        XK[v + 1, 1] = k0
        XK[v + 1, 2] = k1
        XK[v + 1, 3] = k2
    return XF[v, 3] == XF[v, 3]


@njit(**NJIT_NO_NRT)
def _ring_side(i, v, j, C, nf, ns, P, W, WP, X):
    """:func:`_graph_side` for a cell held as face rings (the fallback): its faces at ``v``."""
    F = C[1]
    R = C[2]
    labs = C[5][:, 3]  # work's last column: free until the cut
    m = 0
    for f in range(nf):
        for k in range(F[f, 2]):
            if R[F[f, 1] + k] == v:
                if m < labs.shape[0]:
                    labs[m] = owner_key(F[f, 0], ns)
                    m += 1
                break
    for a in range(m):
        for b in range(a + 1, m):
            for c in range(b + 1, m):
                r = bisector_side(i, labs[a], labs[b], labs[c], j, P, W, WP, ns, X[0], X[1])
                if r != 2:
                    return r
    return 2


#: the value given to a vertex within the filter's band that is exactly off the plane and
#: whose float value has the wrong sign: the cut then treats it as just off (no new vertex
#: is moved by more than the float error)
_TINY = 1e-300


@njit(**NJIT_NO_NRT)
def resolve(nv, tol, S, i, j, C, nf, G, P, W, WP, X, VL, nvl):
    """Decide the values within ``tol`` of 0 exactly, on the vertices' owners.

    The owners are the planes of the vertex's faces (:func:`_graph_side`,
    :func:`_ring_side`): 0 when the vertex is on ``j``'s plane (in a graph it is flagged: it
    may have more owners than faces), else the float value if its sign is right, or a tiny
    value of the right sign. Returns the new largest value. With ``nvl >= 0`` only the
    vertices ``VL[:nvl, 1]`` are looked at (:mod:`kernels.climb3d`: every vertex within
    the band is among them; each decision is exact, so their order does not matter).
    """
    smax = -np.inf
    graph = G[0].shape[0] > 0
    ns = P.shape[0]
    XF = X[4]
    vcap = XF.shape[0] - 1
    lifted = False  # j's plane in the cell's frame (frame_lift), once a vertex needs it
    K = kerr = rh0 = rh1 = rh2 = rl0 = rl1 = rl2 = 0.0
    for q in range(nv if nvl < 0 else nvl):
        v = q if nvl < 0 else VL[q, 1]
        s = S[v]
        if abs(s) <= tol:
            if graph:
                side = 2
                if _cached_vertex(i, v, C[0], G[0], G[3], ns, P, W, WP, X):
                    if not lifted:
                        lifted = True
                        K, kerr = frame_lift(i, j, XF[vcap, 0], XF[vcap, 1], XF[vcap, 2], P, W)
                        rh0, rl0 = two_diff(P[j, 0], P[i, 0])
                        rh1, rl1 = two_diff(P[j, 1], P[i, 1])
                        rh2, rl2 = two_diff(P[j, 2], P[i, 2])
                    side = frame_side(XF[v, 6:12], rh0, rh1, rh2, rl0, rl1, rl2, K, kerr)
                    if side == 0:
                        e = XF[v]
                        side = offset_side(i, j, e[0], e[1], e[2], e[3], e[4], e[5], P, W)
                        if side == 0:
                            side = 2
                if side == 2:
                    side = _graph_side(i, v, j, G[0], G[3], ns, P, W, WP, X)
            else:
                side = _ring_side(i, v, j, C, nf, ns, P, W, WP, X)
            if side == 0 or side == 2:
                s = 0.0
                if graph:
                    G[6][v] = True
            elif s == 0.0 or (s > 0.0) != (side > 0):
                s = side * _TINY
            S[v] = s
        if s > smax:
            smax = s
    return smax
