"""Points inside a closed triangle mesh: ray parity along +x with exact, perturbed crossings.

A ray from ``p`` along +x crosses triangle ``t`` when ``p``'s (y, z) lies in ``t``'s (y, z)
projection and the plane of ``t`` is ahead of ``p``. The projection test uses the exact
:func:`kernels.predicates.orient2d` with ``p`` perturbed by ``(eps, eps**2)`` in (y, z)
(simulation of simplicity), so a ray through a shared edge or vertex counts exactly one
of the triangles there: the parity is right for every point off the surface. Triangles
are bucketed by their (y, z) bounding boxes so each query tests only its bucket.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..config import NJIT, NJIT_PARALLEL
from .predicates import orient2d
from .predicates3d import orient3d


@njit(**NJIT)
def perturbed_side(ay, az, by, bz, py, pz):
    """Sign of the orientation of ``(a, b, p)`` with ``p`` perturbed: never 0 for a != b."""
    o = orient2d(ay, az, by, bz, py, pz)
    if o > 0.0:
        return 1
    if o < 0.0:
        return -1
    # o(p + (e, e^2)) = o(p) - (bz - az) e + (by - ay) e^2
    if bz != az:
        return 1 if bz < az else -1
    if by != ay:
        return 1 if by > ay else -1
    return 0


@njit(**{**NJIT, "inline": "always"})
def ray_hit(V, F, t, py, pz):
    """Where the line along x through ``(py, pz)`` meets triangle ``t``: ``(nx, x)``.

    ``nx`` is the x component of the triangle's normal (its orientation decides the sign of
    a crossing), ``x`` the plane's x at ``(py, pz)``; ``nx == 0.0`` where the line misses
    the triangle (not strictly inside its yz projection under :func:`perturbed_side`, or
    the plane parallel to x).
    """
    i0 = F[t, 0]
    i1 = F[t, 1]
    i2 = F[t, 2]
    # strictly outside the projection's box: so is the perturbed point (the same answer as
    # the orientations below, without them; most triangles of a bucket miss the point)
    y0 = V[i0, 1]
    y1 = V[i1, 1]
    y2 = V[i2, 1]
    if py < min(y0, min(y1, y2)) or py > max(y0, max(y1, y2)):
        return 0.0, 0.0
    z0 = V[i0, 2]
    z1 = V[i1, 2]
    z2 = V[i2, 2]
    if pz < min(z0, min(z1, z2)) or pz > max(z0, max(z1, z2)):
        return 0.0, 0.0
    s0 = perturbed_side(V[i0, 1], V[i0, 2], V[i1, 1], V[i1, 2], py, pz)
    s1 = perturbed_side(V[i1, 1], V[i1, 2], V[i2, 1], V[i2, 2], py, pz)
    s2 = perturbed_side(V[i2, 1], V[i2, 2], V[i0, 1], V[i0, 2], py, pz)
    if s0 == 0 or s1 == 0 or s2 == 0 or not (s0 == s1 and s1 == s2):
        return 0.0, 0.0
    ux = V[i1, 0] - V[i0, 0]
    uy = V[i1, 1] - V[i0, 1]
    uz = V[i1, 2] - V[i0, 2]
    wx = V[i2, 0] - V[i0, 0]
    wy = V[i2, 1] - V[i0, 1]
    wz = V[i2, 2] - V[i0, 2]
    nx = uy * wz - uz * wy
    if nx == 0.0:
        return 0.0, 0.0
    ny = uz * wx - ux * wz
    nz = ux * wy - uy * wx
    return nx, V[i0, 0] - (ny * (py - V[i0, 1]) + nz * (pz - V[i0, 2])) / nx


@njit(**NJIT)
def yz_grid(V, F, nb):
    """Bucket triangles by their (y, z) boxes on an ``nb x nb`` grid: ``(g, start, items)``."""
    lo_y = V[:, 1].min()
    lo_z = V[:, 2].min()
    hy = (V[:, 1].max() - lo_y) / nb * (1 + 1e-9) + 1e-300
    hz = (V[:, 2].max() - lo_z) / nb * (1 + 1e-9) + 1e-300
    m = F.shape[0]
    count = np.zeros(nb * nb + 1, np.int64)
    for t in range(m):
        y0 = min(V[F[t, 0], 1], min(V[F[t, 1], 1], V[F[t, 2], 1]))
        y1 = max(V[F[t, 0], 1], max(V[F[t, 1], 1], V[F[t, 2], 1]))
        z0 = min(V[F[t, 0], 2], min(V[F[t, 1], 2], V[F[t, 2], 2]))
        z1 = max(V[F[t, 0], 2], max(V[F[t, 1], 2], V[F[t, 2], 2]))
        for a in range(int((y0 - lo_y) / hy), min(nb - 1, int((y1 - lo_y) / hy)) + 1):
            for b in range(int((z0 - lo_z) / hz), min(nb - 1, int((z1 - lo_z) / hz)) + 1):
                count[a * nb + b + 1] += 1
    for k in range(nb * nb):
        count[k + 1] += count[k]
    items = np.zeros(count[nb * nb], np.int64)
    fill = count[:-1].copy()
    for t in range(m):
        y0 = min(V[F[t, 0], 1], min(V[F[t, 1], 1], V[F[t, 2], 1]))
        y1 = max(V[F[t, 0], 1], max(V[F[t, 1], 1], V[F[t, 2], 1]))
        z0 = min(V[F[t, 0], 2], min(V[F[t, 1], 2], V[F[t, 2], 2]))
        z1 = max(V[F[t, 0], 2], max(V[F[t, 1], 2], V[F[t, 2], 2]))
        for a in range(int((y0 - lo_y) / hy), min(nb - 1, int((y1 - lo_y) / hy)) + 1):
            for b in range(int((z0 - lo_z) / hz), min(nb - 1, int((z1 - lo_z) / hz)) + 1):
                items[fill[a * nb + b]] = t
                fill[a * nb + b] += 1
    g = np.array([lo_y, lo_z, hy, hz, nb])
    return g, count, items


@njit(**NJIT_PARALLEL)
def inside_mesh(Q, V, F, g, start, items):
    """``(m,) bool``: which query points ``Q (m, 3)`` lie inside the closed mesh ``(V, F)``.

    Parallel over the points (callers run it under ``engine.threads.serial_below``).
    """
    nb = int(g[4])
    out = np.zeros(Q.shape[0], np.bool_)
    for q in prange(Q.shape[0]):
        px = Q[q, 0]
        py = Q[q, 1]
        pz = Q[q, 2]
        a = int((py - g[0]) / g[2])
        b = int((pz - g[1]) / g[3])
        if not (0 <= a < nb and 0 <= b < nb):
            continue
        k = a * nb + b
        par = 0
        for s in range(start[k], start[k + 1]):
            t = items[s]
            nx, xh = ray_hit(V, F, t, py, pz)
            if nx != 0.0 and xh > px:
                par ^= 1
        out[q] = par == 1
    return out


@njit(**NJIT)
def on_triangle(V, F, t, px, py, pz):
    """Whether ``p`` lies on the closed triangle ``t`` of ``(V, F)``, decided exactly.

    On its plane (:func:`kernels.predicates3d.orient3d` zero) and, in a coordinate plane
    where the triangle's projection has area, on no edge's outer side (exact
    :func:`kernels.predicates.orient2d`): the projection is one to one on the plane.
    """
    a = F[t, 0]
    b = F[t, 1]
    c = F[t, 2]
    for k in range(3):  # the bounding box first (cheap, and most triangles are far)
        lo = min(V[a, k], min(V[b, k], V[c, k]))
        hi = max(V[a, k], max(V[b, k], V[c, k]))
        q = px if k == 0 else (py if k == 1 else pz)
        if q < lo or q > hi:
            return False
    if (
        orient3d(
            V[a, 0],
            V[a, 1],
            V[a, 2],
            V[b, 0],
            V[b, 1],
            V[b, 2],
            V[c, 0],
            V[c, 1],
            V[c, 2],
            px,
            py,
            pz,
        )
        != 0.0
    ):
        return False
    p = (px, py, pz)
    for drop in range(3):
        i = 1 if drop == 0 else 0
        j = 1 if drop == 2 else 2
        s = orient2d(V[a, i], V[a, j], V[b, i], V[b, j], V[c, i], V[c, j])
        if s == 0.0:
            continue
        s0 = orient2d(V[a, i], V[a, j], V[b, i], V[b, j], p[i], p[j])
        s1 = orient2d(V[b, i], V[b, j], V[c, i], V[c, j], p[i], p[j])
        s2 = orient2d(V[c, i], V[c, j], V[a, i], V[a, j], p[i], p[j])
        if s > 0.0:
            return s0 >= 0.0 and s1 >= 0.0 and s2 >= 0.0
        return s0 <= 0.0 and s1 <= 0.0 and s2 <= 0.0
    return False  # a needle or a point triangle: no plane (validation refuses them)


@njit(**NJIT_PARALLEL)
def on_mesh(Q, V, F, lo, h, dims, start, items):
    """``(m,) bool``: which points ``Q (m, 3)`` lie exactly on a triangle of ``(V, F)``.

    The triangles of each point's bucket of :func:`kernels.meshclip3d.tri_grid` (``lo``,
    ``h``, ``dims``, ``start``, ``items``; the same clamped floor of ``(x - lo) / h``
    places a triangle's box and a point in it, so a triangle through the point is in its
    bucket). Parallel over the points.
    """
    out = np.zeros(Q.shape[0], np.bool_)
    nz = dims[2]
    ny = dims[1]
    for q in prange(Q.shape[0]):
        px = Q[q, 0]
        py = Q[q, 1]
        pz = Q[q, 2]
        b = 0
        for c in range(3):
            x = Q[q, c] - lo[c]
            if not x >= 0.0 or x > dims[c] * h * 2.0:
                b = -1
                break
            k = min(dims[c] - 1, max(0, int(x / h)))
            b = b * (nz if c == 2 else ny if c == 1 else 1) + k
        if b < 0:
            continue
        for s in range(start[b], start[b + 1]):
            if on_triangle(V, F, items[s], px, py, pz):
                out[q] = True
                break
    return out
