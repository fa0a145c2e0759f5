"""Exact ties of 3D power cells: a face that lies on two sites' planes (issue 12).

Weights can make the planes of two sites ``k`` and ``j`` with cell ``i``'s site coincide
(sites on one ray from ``i``; sites .25, .5, .75 on a line with weights 0, -1/16, 0: both
planes of the middle site are x = .5). The nearer site's power cell is then empty (zero
volume, no face of positive area) and the face belongs to the farther one. The cut
(:func:`.cellcut3d._cut_batch`) labels a face with the plane that cut it and only records
a plane that merely touches the cell, so the label depended on the cut order and the
relation came out one-sided (checker20 F2). :func:`retie` runs on each touching plane
and gives the face the farther site, whatever the order: ``neighbors`` stay symmetric and
each face is listed once with both cells. Unweighted planes never coincide (two sites on
one ray have bisectors at different distances): no Voronoi cell changes.
"""

from __future__ import annotations

from numba import njit

from ..config import NJIT
from ..config3d import TIES_RAY_RTOL

NJIT_INLINE = {**NJIT, "inline": "always"}
NJIT_NO_NRT = {**NJIT, "_nrt": False}


@njit(**NJIT_INLINE)
def _farther(i, k, j, P):
    """Whether site ``j`` lies beyond ``k`` on the ray from ``i`` (their planes coincide).

    Coinciding planes ``L_k = 0`` and ``L_j = c L_k`` (``L``: power of ``i`` less power of
    the other) have ``c = |p_j - p_i| / |p_k - p_i|``: past the face the farther site is
    nearer in power, so its cell is across the face and the nearer one's is empty. Decided
    on one coordinate (exact float comparisons); False unless the sites are on one ray.
    """
    a = 0
    big = 0.0
    dot = 0.0
    nk = 0.0
    nj = 0.0
    for q in range(3):
        dk = P[k, q] - P[i, q]
        dj = P[j, q] - P[i, q]
        dot += dk * dj
        nk += dk * dk
        nj += dj * dj
        if abs(dk) > big:
            big = abs(dk)
            a = q
    if not dot > 0.0 or dot * dot < nk * nj * (1.0 - TIES_RAY_RTOL):
        return False
    if P[j, a] == P[k, a]:
        return j < k  # (coincident sites are merged before: an order-free rule anyway)
    return (P[j, a] > P[k, a]) == (P[k, a] > P[i, a])


@njit(**NJIT_NO_NRT)
def retie(i, j, nv, nf, S, C, G, P):
    """Label a face lying on ``j``'s touching plane with the farther of its two sites.

    Weights can make two sites' planes with ``i`` coincide (the nearer one's power cell is
    then empty): whichever came first labelled the face, and the label must not depend on
    the cut order, so the face takes :func:`_farther`'s site (the non-empty cell across).
    A face lies on the plane when its vertices (three or more) are on it exactly
    (``S == 0``: decided by :func:`_resolve`). Walls keep their label.
    """
    nz = 0
    for v in range(nv):
        nz += S[v] == 0.0
    if nz < 3:
        return
    if G[0].shape[0] == 0:
        F = C[1]
        R = C[2]
        for f in range(nf):
            k = F[f, 0]
            if k < 0 or k == j or F[f, 2] < 3:
                continue
            on = True
            for t in range(F[f, 1], F[f, 1] + F[f, 2]):
                on &= S[R[t]] == 0.0
            if on:
                if _farther(i, k, j, P):
                    F[f, 0] = j
                return  # (one face at most lies on a plane)
        return
    DEG, ED, BK, LB = G[0], G[1], G[2], G[3]
    for v in range(nv):
        if S[v] != 0.0:
            continue
        for e in range(DEG[v]):
            k = LB[v, e]
            if k < 0 or k == j:
                continue
            for relabel in range(2):  # walk the face: test it, then relabel it
                u = v
                x = e
                n = 0
                on = True
                while True:
                    if relabel:
                        LB[u, x] = j
                    on &= S[u] == 0.0
                    n += 1
                    w = ED[u, x]
                    x = BK[u, x] - 1
                    u = w
                    x = x if x >= 0 else DEG[u] - 1
                    if u == v or n > nv:
                        break
                if not on or n < 3:
                    break
                if relabel == 0 and not _farther(i, k, j, P):
                    return
            if on and n >= 3:
                return
