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


def winding_numbers(vertices, faces, points, chunk: int = 256) -> np.ndarray:
    """Generalised winding number of a closed triangle mesh at each point (solid angles).

    Van Oosterom and Strackee's formula per triangle, summed over all of them: 1 inside,
    0 outside, 2 where two parts of a self-intersecting mesh overlap. Slow (points x faces).
    """
    v = np.asarray(vertices, dtype=np.float64)
    t = v[np.asarray(faces)]
    p = np.asarray(points, dtype=np.float64)
    out = np.zeros(len(p))
    for s in range(0, len(p), chunk):
        q = p[s : s + chunk, None, None, :]
        a, b, c = (t[None, :, i, :] - q[:, :, 0] for i in range(3))
        la, lb, lc = (np.linalg.norm(x, axis=2) for x in (a, b, c))
        det = np.einsum("pfk,pfk->pf", a, np.cross(b, c))
        den = (
            la * lb * lc
            + np.einsum("pfk,pfk->pf", a, b) * lc
            + np.einsum("pfk,pfk->pf", b, c) * la
            + np.einsum("pfk,pfk->pf", c, a) * lb
        )
        out[s : s + chunk] = 2.0 * np.arctan2(det, den).sum(axis=1) / (4.0 * np.pi)
    return out


def segment_distance(points, a, b) -> np.ndarray:
    """Distance from each point to the nearest of the segments ``a[i] -> b[i]`` (brute force)."""
    p = np.asarray(points, dtype=np.float64)[:, None, :]
    ab = (b - a)[None]
    t = np.clip(np.einsum("psk,psk->ps", p - a[None], ab) / np.einsum("psk,psk->ps", ab, ab), 0, 1)
    return np.linalg.norm(p - a[None] - t[..., None] * ab, axis=2).min(axis=1)
