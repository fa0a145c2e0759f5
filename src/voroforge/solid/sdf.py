"""Signed-distance kernels on voxel blocks: capsules (struts) and triangle meshes.

Capsules make lattices; meshes make containers (signed, by ray parity) and shells
(unsigned).

A block is ``(nx, ny, nz)`` samples at ``origin + h * (i, j, k)``. Values are float32,
negative inside, clamped to ``+-band`` away from the surface (the marching cubes in
:mod:`.implicit` only needs the sign far from it).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .. import config

__all__ = ["capsules_block", "mesh_distance", "mesh_sdf_block"]


@njit(**config.NJIT)
def _capsules(grid, origin, h, a, b, ra, rb, k_smooth, band):
    nx, ny, nz = grid.shape
    for s in range(a.shape[0]):
        rmax = max(ra[s], rb[s]) + band
        lo = np.empty(3, np.int64)  # noqa: TID251 (both filled below)
        hi = np.empty(3, np.int64)  # noqa: TID251
        dims = (nx, ny, nz)
        for c in range(3):
            mn = min(a[s, c], b[s, c]) - rmax
            mx = max(a[s, c], b[s, c]) + rmax
            lo[c] = max(int(np.floor((mn - origin[c]) / h)), 0)
            hi[c] = min(int(np.ceil((mx - origin[c]) / h)), dims[c] - 1)
        abx = b[s, 0] - a[s, 0]
        aby = b[s, 1] - a[s, 1]
        abz = b[s, 2] - a[s, 2]
        ll = abx * abx + aby * aby + abz * abz
        if ll <= 0.0:
            ll = 1e-300
        for i in range(lo[0], hi[0] + 1):
            x = origin[0] + h * i - a[s, 0]
            for j in range(lo[1], hi[1] + 1):
                y = origin[1] + h * j - a[s, 1]
                for kk in range(lo[2], hi[2] + 1):
                    z = origin[2] + h * kk - a[s, 2]
                    t = (x * abx + y * aby + z * abz) / ll
                    t = min(max(t, 0.0), 1.0)
                    dx = x - t * abx
                    dy = y - t * aby
                    dz = z - t * abz
                    d = np.sqrt(dx * dx + dy * dy + dz * dz) - (ra[s] + t * (rb[s] - ra[s]))
                    g = grid[i, j, kk]
                    if k_smooth > 0.0:
                        m = max(k_smooth - abs(d - g), 0.0) / k_smooth
                        v = min(d, g) - m * m * k_smooth * 0.25
                    else:
                        v = min(d, g)
                    grid[i, j, kk] = v


def capsules_block(shape, origin, h, a, b, ra, rb, *, smooth=0.0, band=None):
    """Union (``smooth > 0``: smooth minimum) of round-cone struts ``a -> b`` on a block."""
    band = 3.0 * h if band is None else band
    grid = np.full(shape, band, dtype=np.float32)
    if len(a):
        _capsules(
            grid,
            np.asarray(origin, np.float64),
            float(h),
            np.ascontiguousarray(a, np.float64),
            np.ascontiguousarray(b, np.float64),
            np.ascontiguousarray(ra, np.float64),
            np.ascontiguousarray(rb, np.float64),
            float(smooth),
            float(band),
        )
    return grid


@njit(**config.NJIT)
def _pt_tri(px, py, pz, tri):
    """Distance from a point to a triangle (3, 3) (Ericson's closest-point regions)."""
    ax, ay, az = tri[0, 0], tri[0, 1], tri[0, 2]
    abx, aby, abz = tri[1, 0] - ax, tri[1, 1] - ay, tri[1, 2] - az
    acx, acy, acz = tri[2, 0] - ax, tri[2, 1] - ay, tri[2, 2] - az
    apx, apy, apz = px - ax, py - ay, pz - az
    d1 = abx * apx + aby * apy + abz * apz
    d2 = acx * apx + acy * apy + acz * apz
    if d1 <= 0 and d2 <= 0:
        return np.sqrt(apx * apx + apy * apy + apz * apz)
    bpx, bpy, bpz = px - tri[1, 0], py - tri[1, 1], pz - tri[1, 2]
    d3 = abx * bpx + aby * bpy + abz * bpz
    d4 = acx * bpx + acy * bpy + acz * bpz
    if d3 >= 0 and d4 <= d3:
        return np.sqrt(bpx * bpx + bpy * bpy + bpz * bpz)
    vc = d1 * d4 - d3 * d2
    if vc <= 0 and d1 >= 0 and d3 <= 0:
        v = d1 / (d1 - d3)
        qx, qy, qz = apx - v * abx, apy - v * aby, apz - v * abz
        return np.sqrt(qx * qx + qy * qy + qz * qz)
    cpx, cpy, cpz = px - tri[2, 0], py - tri[2, 1], pz - tri[2, 2]
    d5 = abx * cpx + aby * cpy + abz * cpz
    d6 = acx * cpx + acy * cpy + acz * cpz
    if d6 >= 0 and d5 <= d6:
        return np.sqrt(cpx * cpx + cpy * cpy + cpz * cpz)
    vb = d5 * d2 - d1 * d6
    if vb <= 0 and d2 >= 0 and d6 <= 0:
        w = d2 / (d2 - d6)
        qx, qy, qz = apx - w * acx, apy - w * acy, apz - w * acz
        return np.sqrt(qx * qx + qy * qy + qz * qz)
    va = d3 * d6 - d5 * d4
    if va <= 0 and (d4 - d3) >= 0 and (d5 - d6) >= 0:
        w = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        qx = bpx - w * (tri[2, 0] - tri[1, 0])
        qy = bpy - w * (tri[2, 1] - tri[1, 1])
        qz = bpz - w * (tri[2, 2] - tri[1, 2])
        return np.sqrt(qx * qx + qy * qy + qz * qz)
    den = 1.0 / (va + vb + vc)
    v = vb * den
    w = vc * den
    qx = apx - v * abx - w * acx
    qy = apy - v * aby - w * acy
    qz = apz - v * abz - w * acz
    return np.sqrt(qx * qx + qy * qy + qz * qz)


@njit(**config.NJIT)
def _unsigned(grid, origin, h, tris, band):
    nx, ny, nz = grid.shape
    dims = (nx, ny, nz)
    lo = np.empty(3, np.int64)  # noqa: TID251 (both filled below)
    hi = np.empty(3, np.int64)  # noqa: TID251
    for t in range(tris.shape[0]):
        tri = tris[t]
        for c in range(3):
            mn = min(tri[0, c], min(tri[1, c], tri[2, c])) - band
            mx = max(tri[0, c], max(tri[1, c], tri[2, c])) + band
            lo[c] = max(int(np.floor((mn - origin[c]) / h)), 0)
            hi[c] = min(int(np.ceil((mx - origin[c]) / h)), dims[c] - 1)
        # the unit normal: the distance to the triangle's plane bounds the distance to the
        # triangle from below, so a sample already nearer another triangle is skipped
        # (a face's coplanar fan: its sample pays one full test, not one per triangle)
        ux, uy, uz = tri[1, 0] - tri[0, 0], tri[1, 1] - tri[0, 1], tri[1, 2] - tri[0, 2]
        vx, vy, vz = tri[2, 0] - tri[0, 0], tri[2, 1] - tri[0, 1], tri[2, 2] - tri[0, 2]
        nx_, ny_, nz_ = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
        nn = np.sqrt(nx_ * nx_ + ny_ * ny_ + nz_ * nz_)
        if nn > 0.0:
            nx_, ny_, nz_ = nx_ / nn, ny_ / nn, nz_ / nn
        for i in range(lo[0], hi[0] + 1):
            px = origin[0] + h * i
            for j in range(lo[1], hi[1] + 1):
                py = origin[1] + h * j
                for k in range(lo[2], hi[2] + 1):
                    pz = origin[2] + h * k
                    if nn > 0.0:
                        dp = abs(
                            nx_ * (px - tri[0, 0]) + ny_ * (py - tri[0, 1]) + nz_ * (pz - tri[0, 2])
                        )
                        if dp >= grid[i, j, k]:
                            continue
                    d = _pt_tri(px, py, pz, tri)
                    if d < grid[i, j, k]:
                        grid[i, j, k] = d


@njit(**config.NJIT)
def _parity(inside, origin, h, tris):
    """Flip ``inside`` above every crossing of a +z ray through each column (x_i, y_j)."""
    nx, ny, nz = inside.shape
    for t in range(tris.shape[0]):
        x0, y0, z0 = tris[t, 0, 0], tris[t, 0, 1], tris[t, 0, 2]
        x1, y1, z1 = tris[t, 1, 0], tris[t, 1, 1], tris[t, 1, 2]
        x2, y2, z2 = tris[t, 2, 0], tris[t, 2, 1], tris[t, 2, 2]
        area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
        if area == 0.0:
            continue
        i0 = max(int(np.ceil((min(x0, min(x1, x2)) - origin[0]) / h)), 0)
        i1 = min(int(np.floor((max(x0, max(x1, x2)) - origin[0]) / h)), nx - 1)
        j0 = max(int(np.ceil((min(y0, min(y1, y2)) - origin[1]) / h)), 0)
        j1 = min(int(np.floor((max(y0, max(y1, y2)) - origin[1]) / h)), ny - 1)
        for i in range(i0, i1 + 1):
            px = origin[0] + h * i
            for j in range(j0, j1 + 1):
                py = origin[1] + h * j
                w0 = (x1 - px) * (y2 - py) - (x2 - px) * (y1 - py)
                w1 = (x2 - px) * (y0 - py) - (x0 - px) * (y2 - py)
                w2 = (x0 - px) * (y1 - py) - (x1 - px) * (y0 - py)
                # half-open rule (ties go to one side consistently): count once per column
                if area > 0:
                    ok = w0 > 0 or (w0 == 0 and (y2 > y1 or (y2 == y1 and x2 < x1)))
                    ok = ok and (w1 > 0 or (w1 == 0 and (y0 > y2 or (y0 == y2 and x0 < x2))))
                    ok = ok and (w2 > 0 or (w2 == 0 and (y1 > y0 or (y1 == y0 and x1 < x0))))
                else:
                    ok = w0 < 0 or (w0 == 0 and (y2 < y1 or (y2 == y1 and x2 > x1)))
                    ok = ok and (w1 < 0 or (w1 == 0 and (y0 < y2 or (y0 == y2 and x0 > x2))))
                    ok = ok and (w2 < 0 or (w2 == 0 and (y1 < y0 or (y1 == y0 and x1 > x0))))
                if not ok:
                    continue
                z = (w0 * z0 + w1 * z1 + w2 * z2) / area
                k0 = max(int(np.floor((z - origin[2]) / h)) + 1, 0)
                for k in range(k0, nz):
                    inside[i, j, k] = not inside[i, j, k]


def _tris(mesh) -> np.ndarray:
    return np.ascontiguousarray(mesh.vertices[mesh.faces], dtype=np.float64)


def mesh_sdf_block(mesh, shape, origin, h, *, band=None, signed=True, tris=None):
    """Signed distance to a closed mesh on a block (negative inside), clamped to ``band``.

    ``signed=False`` gives the unsigned distance (open surfaces: shells).
    """
    band = 3.0 * h if band is None else float(band)
    tris = _tris(mesh) if tris is None else tris
    grid = np.full(shape, band, dtype=np.float64)
    o = np.asarray(origin, np.float64)
    _unsigned(grid, o, float(h), tris, band)
    grid = np.minimum(grid, band)
    if signed:
        inside = np.zeros(shape, dtype=np.bool_)
        # columns start below the mesh: parity counts every crossing under the sample
        _parity(inside, o, float(h), tris)
        grid[inside] *= -1.0
    return grid.astype(np.float32)


def mesh_distance(mesh, xyz) -> np.ndarray:
    """Unsigned distance from points ``(m, 3)`` to a mesh surface (exact, chunked)."""
    from scipy.spatial import cKDTree

    xyz = np.asarray(xyz, dtype=np.float64)
    tris = _tris(mesh)
    cent = tris.mean(axis=1)
    rad = np.linalg.norm(tris - cent[:, None], axis=2).max(axis=1)
    tree = cKDTree(cent)
    d0, _ = tree.query(xyz)  # an upper bound plus the triangle radius
    out = np.full(len(xyz), np.inf)
    rmax = float(rad.max())
    for s in range(len(xyz)):
        cand = tree.query_ball_point(xyz[s], d0[s] + 2 * rmax)
        out[s] = min(_pt_tri(xyz[s, 0], xyz[s, 1], xyz[s, 2], tris[c]) for c in cand)
    return out
