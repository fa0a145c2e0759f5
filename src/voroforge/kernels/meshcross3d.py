"""Whether a closed triangle mesh crosses itself: the first pair of triangles that cross.

A mesh whose edges are each shared by two faces, consistently oriented, may still be no
solid: two shells that overlap (two boxes as one mesh) or a shell through itself pass the
edge checks, and the cut then counts the overlap twice. :func:`first_crossing` finds two
triangles that cross properly: an edge of one passes through the other's interior, every
sign certain (a float filter on :func:`predicates3d.orient3d`'s determinant). Triangles
that share an edge are not compared; triangles that only touch (a vertex on a face,
coplanar contact) do not count: they give no overlap of volume. Candidates come from a
bucket grid of the triangles' boxes (:func:`meshclip3d.tri_grid`), each pair tested once
(in the first bucket both boxes meet).
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..config import MESH_CROSS_FILTER, NJIT, NJIT_PARALLEL
from .inside3d import ray_hit
from .meshclip3d import tri_grid


@njit(**NJIT)
def _o3(V, a, b, c, d):
    """:func:`predicates3d.orient3d` of the vertices ``a, b, c, d`` where certain, else 0."""
    adx = V[a, 0] - V[d, 0]
    ady = V[a, 1] - V[d, 1]
    adz = V[a, 2] - V[d, 2]
    bdx = V[b, 0] - V[d, 0]
    bdy = V[b, 1] - V[d, 1]
    bdz = V[b, 2] - V[d, 2]
    cdx = V[c, 0] - V[d, 0]
    cdy = V[c, 1] - V[d, 1]
    cdz = V[c, 2] - V[d, 2]
    det = adx * (bdy * cdz - bdz * cdy) + bdx * (cdy * adz - cdz * ady)
    det += cdx * (ady * bdz - adz * bdy)
    perm = abs(adx) * (abs(bdy * cdz) + abs(bdz * cdy))
    perm += abs(bdx) * (abs(cdy * adz) + abs(cdz * ady))
    perm += abs(cdx) * (abs(ady * bdz) + abs(adz * bdy))
    return det if abs(det) > MESH_CROSS_FILTER * perm else 0.0


@njit(**NJIT)
def _edge_through(V, p, q, a, b, c):
    """Whether segment ``p q`` passes through the interior of triangle ``a b c`` (strictly)."""
    if p == a or p == b or p == c or q == a or q == b or q == c:
        return False  # an end in the triangle's plane: not strictly across it
    sp = _o3(V, a, b, c, p)
    sq = _o3(V, a, b, c, q)
    if not ((sp > 0.0 and sq < 0.0) or (sp < 0.0 and sq > 0.0)):
        return False
    s1 = _o3(V, p, q, a, b)
    s2 = _o3(V, p, q, b, c)
    s3 = _o3(V, p, q, c, a)
    return (s1 > 0.0 and s2 > 0.0 and s3 > 0.0) or (s1 < 0.0 and s2 < 0.0 and s3 < 0.0)


@njit(**NJIT)
def _one_side(V, F, t, u):
    """Whether ``t``'s corners not shared with ``u`` lie strictly on one side of ``u``'s plane.

    Certainly (a float filter): then ``t`` meets ``u`` at most in shared corners.
    """
    a = F[u, 0]
    e1x = V[F[u, 1], 0] - V[a, 0]
    e1y = V[F[u, 1], 1] - V[a, 1]
    e1z = V[F[u, 1], 2] - V[a, 2]
    e2x = V[F[u, 2], 0] - V[a, 0]
    e2y = V[F[u, 2], 1] - V[a, 1]
    e2z = V[F[u, 2], 2] - V[a, 2]
    nx = e1y * e2z - e1z * e2y
    ny = e1z * e2x - e1x * e2z
    nz = e1x * e2y - e1y * e2x
    nn = abs(nx) + abs(ny) + abs(nz)
    pos = 0
    neg = 0
    for k in range(3):
        v = F[t, k]
        if v == F[u, 0] or v == F[u, 1] or v == F[u, 2]:
            continue
        dx = V[v, 0] - V[a, 0]
        dy = V[v, 1] - V[a, 1]
        dz = V[v, 2] - V[a, 2]
        d = nx * dx + ny * dy + nz * dz
        # far above the rounding of d (a few ulps of nn times the largest difference)
        err = 1e-12 * nn * (abs(dx) + abs(dy) + abs(dz) + abs(e1x) + abs(e1y) + abs(e1z))
        if d > err:
            pos += 1
        elif d < -err:
            neg += 1
        else:
            return False
    return pos == 0 or neg == 0


@njit(**NJIT)
def _cross(V, F, t, u):
    if _one_side(V, F, t, u) or _one_side(V, F, u, t):
        return False
    for k in range(3):
        if _edge_through(V, F[t, k], F[t, (k + 1) % 3], F[u, 0], F[u, 1], F[u, 2]):
            return True
        if _edge_through(V, F[u, k], F[u, (k + 1) % 3], F[t, 0], F[t, 1], F[t, 2]):
            return True
    return False


@njit(**NJIT)
def first_crossing(V, F):
    """``(t, u)``: two triangles of ``F`` (rows into ``V``) that cross, ``t < u``; ``(-1, -1)``.

    Triangles bucketed by their boxes (:func:`meshclip3d.tri_grid`, buckets about a
    triangle's size, at most ~8 per triangle); boxes, grid and tests in one kernel (numpy's
    reductions over the short axes took as long as the tests: 20k triangles, 10 ms).
    """
    m = F.shape[0]
    T = np.zeros((m, 3, 3))
    box = np.zeros((m, 6))  # each triangle's box, and its bucket range
    ext = np.zeros(m)
    lo = np.full(3, np.inf)
    hi = np.full(3, -np.inf)
    for t in range(m):
        for c in range(3):
            for q in range(3):
                T[t, q, c] = V[F[t, q], c]
            x0 = min(T[t, 0, c], min(T[t, 1, c], T[t, 2, c]))
            x1 = max(T[t, 0, c], max(T[t, 1, c], T[t, 2, c]))
            box[t, c] = x0
            box[t, 3 + c] = x1
            ext[t] = max(ext[t], x1 - x0)
            lo[c] = min(lo[c], x0)
            hi[c] = max(hi[c], x1)
    vol = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2])
    h = max(np.median(ext), (vol / (8.0 * m)) ** (1 / 3))
    if not (h > 0.0 and np.isfinite(h)):
        h = max(hi[0] - lo[0], max(hi[1] - lo[1], max(hi[2] - lo[2], 1.0)))
    dims = np.ones(3, np.int64)
    while True:  # a flat or needle mesh: coarser buckets, at most ~8 per triangle
        nb = 1
        for c in range(3):
            dims[c] = max(1, min(1 << 20, int(np.ceil((hi[c] - lo[c]) / h))))
            nb *= dims[c]
        if nb <= 8 * m + 64:
            break
        h *= 2.0
    start, items = tri_grid(T, lo, h, dims)
    ny, nz = dims[1], dims[2]
    cell = np.zeros((m, 6), np.int64)
    for t in range(m):
        for c in range(3):
            cell[t, c] = min(dims[c] - 1, max(0, int((box[t, c] - lo[c]) / h)))
            cell[t, 3 + c] = min(dims[c] - 1, max(0, int((box[t, 3 + c] - lo[c]) / h)))
    for t in range(m):
        for i in range(cell[t, 0], cell[t, 3] + 1):
            for j in range(cell[t, 1], cell[t, 4] + 1):
                for k in range(cell[t, 2], cell[t, 5] + 1):
                    bk = (i * ny + j) * nz + k
                    for s in range(start[bk], start[bk + 1]):
                        u = items[s]
                        if u <= t:
                            continue
                        # the pair once: in the first bucket both boxes cover
                        if i != max(cell[t, 0], cell[u, 0]) or j != max(cell[t, 1], cell[u, 1]):
                            continue
                        if k != max(cell[t, 2], cell[u, 2]):
                            continue
                        if (
                            box[t, 3] < box[u, 0]
                            or box[u, 3] < box[t, 0]
                            or box[t, 4] < box[u, 1]
                            or box[u, 4] < box[t, 1]
                            or box[t, 5] < box[u, 2]
                            or box[u, 5] < box[t, 2]
                        ):
                            continue
                        shared = 0
                        for p in range(3):
                            for q in range(3):
                                if F[t, p] == F[u, q]:
                                    shared += 1
                        if shared >= 2:
                            continue
                        if _cross(V, F, t, u):
                            return t, u
    return -1, -1


@njit(**NJIT_PARALLEL)
def others_winding(V, F, shell, g, start, items, out):
    """Per face: the winding of the other shells at its centroid, and one shell that adds to it.

    ``out (m, 2)``: ``(w, s)``: ``w`` signed crossings of the ray from the centroid along +x
    with faces of other shells (+1 where the face's normal has x > 0, as
    :func:`inside3d.inside_mesh` counts parity), ``s`` the shell of the first such face (-1
    if none); ``w = -(1 << 40)`` where the centroid lies on another shell's face (within
    ``1e-12`` of the coordinates' size: ambiguous, skipped).
    """
    nb = int(g[4])
    for f in prange(F.shape[0]):
        px = (V[F[f, 0], 0] + V[F[f, 1], 0] + V[F[f, 2], 0]) / 3.0
        py = (V[F[f, 0], 1] + V[F[f, 1], 1] + V[F[f, 2], 1]) / 3.0
        pz = (V[F[f, 0], 2] + V[F[f, 1], 2] + V[F[f, 2], 2]) / 3.0
        out[f, 0] = 0
        out[f, 1] = -1
        a = int((py - g[0]) / g[2])
        b = int((pz - g[1]) / g[3])
        if not (0 <= a < nb and 0 <= b < nb):
            continue
        k = a * nb + b
        w = 0
        first = -1
        for s in range(start[k], start[k + 1]):
            t = items[s]
            if shell[t] == shell[f]:
                continue
            nx, xh = ray_hit(V, F, t, py, pz)
            if nx == 0.0:
                continue
            i0 = F[t, 0]
            size = abs(px) + abs(py) + abs(pz) + abs(V[i0, 0]) + abs(V[i0, 1]) + abs(V[i0, 2])
            if abs(xh - px) <= 1e-12 * size:
                w = -(1 << 40)
                break
            if xh > px:
                w += 1 if nx > 0.0 else -1
                if first < 0:
                    first = shell[t]
        out[f, 0] = w
        out[f, 1] = first
