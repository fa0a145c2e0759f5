"""A container template cut by one half-space in floating point (a hull's template from a box).

Split from :mod:`kernels.cells3d` (which re-exports it): the same cut as a cell's,
:func:`.polyhedron.cut` on :func:`.polyhedron.plane_values` within ``VORONOI3D_CUT_RTOL``.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT, VORONOI3D_CUT_RTOL
from .polyhedron import CUT_NONE, cut, plane_values

__all__ = ["container_cut"]


@njit(**NJIT)
def container_cut(TV, TF, TR, nx, ny, nz, h, label, caps):
    """Cut a container template by the half-space ``n . x <= h`` (absolute frame).

    Returns ``(status, V, F, R)`` trimmed; used to build a hull's template from a box (the
    half-spaces of ``Convex(halfspaces=)`` go to the exact :mod:`engine.polytope3d`).
    """
    V = np.zeros((caps, 3))
    F = np.zeros((caps, 3), np.int64)
    R = np.zeros(4 * caps, np.int64)
    R2 = np.zeros(4 * caps, np.int64)
    S = np.zeros(caps)
    work = np.zeros((4 * caps, 4), np.int64)
    nv = TV.shape[0]
    nf = TF.shape[0]
    V[:nv] = TV
    F[:nf] = TF
    R[: TR.shape[0]] = TR
    scale = 0.0
    for v in range(nv):
        scale = max(scale, abs(TV[v, 0]) + abs(TV[v, 1]) + abs(TV[v, 2]))
    nn = np.sqrt(nx * nx + ny * ny + nz * nz)
    tol = VORONOI3D_CUT_RTOL * (nn * scale + abs(h))
    plane_values(V, nv, nx, ny, nz, h, tol, S)
    st, nv, nf = cut(V, nv, F, nf, R, R2, S, work, label)
    if st == CUT_NONE:
        return st, TV.copy(), TF.copy(), TR.copy()
    nr = 0
    for f in range(nf):
        nr += F[f, 2]
    # faces may not be packed from 0 in R after cut; repack
    R3 = np.zeros(nr, np.int64)
    t = 0
    F3 = F[:nf].copy()
    for f in range(nf):
        for q in range(F[f, 2]):
            R3[t + q] = R[F[f, 1] + q]
        F3[f, 1] = t
        t += F[f, 2]
    return st, V[:nv].copy(), F3, R3
