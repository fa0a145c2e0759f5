"""Slow, obvious references for the solid tests: brute-force 3D Voronoi cells and volumes."""

from __future__ import annotations

import numpy as np
from scipy.spatial import ConvexHull, Delaunay, HalfspaceIntersection


def box_cells(points, box):
    """Each site's Voronoi cell in ``box`` as the intersection of all bisector half-spaces.

    Returns a list of ``trimesh.Trimesh`` (convex, closed), one per site.
    """
    import trimesh

    p = np.asarray(points, dtype=np.float64)
    lo, hi = np.asarray(box[:3], float), np.asarray(box[3:], float)
    walls = np.array(
        [[-1, 0, 0, lo[0]], [0, -1, 0, lo[1]], [0, 0, -1, lo[2]],
         [1, 0, 0, -hi[0]], [0, 1, 0, -hi[1]], [0, 0, 1, -hi[2]]],
        dtype=np.float64,
    )  # fmt: skip
    out = []
    for i, s in enumerate(p):
        o = np.delete(p, i, axis=0)
        n = o - s
        # |x - s|^2 <= |x - o|^2  <=>  n . x - (|o|^2 - |s|^2) / 2 <= 0
        off = -(np.einsum("ij,ij->i", o, o) - s @ s) / 2.0
        hs = np.vstack([np.column_stack([n, off]), walls])
        v = HalfspaceIntersection(hs, s).intersections
        h = ConvexHull(v)
        m = trimesh.Trimesh(v, h.simplices, process=True)
        m.fix_normals()
        out.append(m)
    return out


def hull_volume(points) -> float:
    """Volume of the convex hull of ``points`` as a sum of Delaunay tetrahedra (no hull facets)."""
    pts = np.asarray(points, dtype=np.float64)
    t = Delaunay(pts).simplices
    a, b, c, d = (pts[t[:, i]] for i in range(4))
    return float(np.abs(np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a)).sum() / 6.0)
