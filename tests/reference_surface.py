"""Slow, obvious references for the surface Voronoi tests (plain Python and numpy)."""

from __future__ import annotations

import numpy as np


def clip_polygon(poly: list, keep) -> list:
    """Sutherland-Hodgman: the part of a 3D polygon where ``keep(x) <= 0`` (affine ``keep``)."""
    out = []
    m = len(poly)
    for k in range(m):
        a, b = poly[k], poly[(k + 1) % m]
        sa, sb = keep(a), keep(b)
        if sa <= 0:
            out.append(a)
        if (sa < 0 < sb) or (sb < 0 < sa):
            t = sa / (sa - sb)
            out.append(a + t * (b - a))
    return out


def polygon_area(poly: list) -> float:
    """Area of a planar 3D polygon (half the norm of its vector area)."""
    if len(poly) < 3:
        return 0.0
    p = np.asarray(poly)
    return 0.5 * float(np.linalg.norm(np.cross(p, np.roll(p, -1, axis=0)).sum(axis=0)))


def brute_rvd_areas(vertices, faces, sites) -> np.ndarray:
    """Restricted cell areas by its definition: every triangle cut by every bisector plane."""
    sites = np.asarray(sites, float)
    areas = np.zeros(len(sites))
    for f in faces:
        tri = [np.asarray(vertices[i], float) for i in f]
        for i, s in enumerate(sites):
            poly = tri
            for j, q in enumerate(sites):
                if j == i or not poly:
                    continue
                g, mid = q - s, 0.5 * (q + s)
                poly = clip_polygon(poly, lambda x, g=g, mid=mid: float(g @ (x - mid)))
            areas[i] += polygon_area(poly)
    return areas


def nearest_site(points, sites) -> np.ndarray:
    """Index of the nearest site of each point (brute force, first on ties)."""
    d = ((np.asarray(points)[:, None, :] - np.asarray(sites)[None, :, :]) ** 2).sum(axis=2)
    return d.argmin(axis=1)
