"""3D cells for the solids: relaxed (3D Lloyd) and recursively subdivided Voronoi cells."""

from __future__ import annotations

import numpy as np

__all__ = ["relax", "subdivide"]


def relax(points, container, *, iterations: int = 10):
    """3D Lloyd: move each site to its cell's centroid, ``iterations`` times.

    Parameters
    ----------
    points : (n, 3) array_like
    container : box tuple, ``vf.Convex`` or closed mesh (as :func:`voroforge.voronoi3d`)
    iterations : int

    Returns
    -------
    (n, 3) float64
        The relaxed sites (empty cells keep their site).
    """
    from ..engine.voronoi3d import voronoi3d

    p = np.array(points, dtype=np.float64)
    if iterations < 0:
        raise ValueError(f"iterations must be >= 0, got {iterations!r}")
    for _ in range(int(iterations)):
        c = np.asarray(voronoi3d(p, container).centroids)
        ok = np.isfinite(c).all(axis=1)
        p[ok] = c[ok]
    return p


def _inside(a, b, x):
    return (x @ a.T <= b[None, :] + 1e-12).all(axis=1)


def subdivide(cells, counts, *, levels: int = 1, field=None, seed: int = 0):
    """Recursive 3D Voronoi: each cell split again by Voronoi cells of seeds inside it.

    Parameters
    ----------
    cells : Diagram3D or list of convex Trimesh
        The cells to subdivide.
    counts : int or (lo, hi)
        Seeds per cell; with ``field`` the pair of counts at field 0 and 1 (a cell with
        ``round(count) < 2`` stays whole).
    levels : int
        How many times to recurse (each level subdivides the previous level's cells).
    field : callable, optional
        A 0..1 3D field sampled at each cell's centroid.
    seed : int
        Random seed of the seeds (uniform in each cell).

    Returns
    -------
    list of trimesh.Trimesh
        The leaf cells (convex, closed), usable by ``lattice`` and ``foam``.
    """
    from ..engine.containers import Convex
    from ..engine.voronoi3d import voronoi3d
    from .graph import cell_meshes

    rng = np.random.default_rng(seed)
    cur = cell_meshes(cells)
    for _ in range(int(levels)):
        cen = np.array([c.center_mass for c in cur])
        if field is None:
            k = np.full(len(cur), float(counts if np.ndim(counts) == 0 else counts[0]))
        else:
            lo, hi = (counts, counts) if np.ndim(counts) == 0 else counts
            k = lo + (hi - lo) * np.clip(np.asarray(field(cen), dtype=np.float64), 0, 1)
        nxt = []
        for c, kk in zip(cur, np.rint(k).astype(int), strict=True):
            if kk < 2:
                nxt.append(c)
                continue
            a = np.asarray(c.face_normals)
            b = np.einsum("ij,ij->i", a, c.triangles_center)
            lo_, hi_ = c.bounds
            seeds = np.zeros((0, 3))
            for _try in range(50):
                x = rng.uniform(lo_, hi_, size=(4 * kk, 3))
                seeds = np.vstack([seeds, x[_inside(a, b, x)]])
                if len(seeds) >= kk:
                    break
            seeds = seeds[:kk]
            if len(seeds) < 2:
                nxt.append(c)
                continue
            d = voronoi3d(seeds, Convex(points=np.asarray(c.vertices)))
            nxt.extend(m for m, v in zip(d.to_trimesh(), d.volumes, strict=True) if v > 0)
        cur = nxt
    return cur
