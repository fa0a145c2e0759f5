"""3D cells for the solids: relaxed (3D Lloyd) and recursively subdivided Voronoi cells."""

from __future__ import annotations

import numpy as np

from ..config import SUBDIVIDE_SLIVER as SLIVER

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


def _hull_mesh(vertices):
    """The convex hull of ``vertices`` as a closed, outward Trimesh of those same floats.

    A leaf's rings hold its vertices as the Voronoi engine rounded them: far from the origin
    (1e5 .. 1e9) a ring can turn the wrong way by an ulp, and the fan triangles of a ring
    with three nearly collinear vertices have normals rounding chose, which trimesh's
    ``is_convex`` (adjacent normals within 1e-5 of the mesh's size) rejects. The hull of the
    same points (Qhull, about their mean) is convex on those floats. A hull triangle lower
    than ``SLIVER`` of the hull's size (or 64 ulps of its coordinates) has a vertex that
    close to the segment of the other two (near-coincident or collinear points; Qhull's
    triangulation keeps some): that vertex is left out and the hull taken again, so a
    vertex is dropped only where the hull moves by less than that; no vertex is moved or
    made. Triangles are oriented by walking Qhull's neighbours from the facet whose plane
    is surest. Returns ``None`` when Qhull finds no 3D hull.
    """
    import trimesh
    from scipy.spatial import ConvexHull, QhullError

    v = np.asarray(vertices, dtype=np.float64)
    keep = np.arange(len(v))
    q = v - v.mean(axis=0)
    eps = max(SLIVER * float(np.ptp(q, axis=0).max(initial=0.0)), 64.0 * _ulp(v))
    for _ in range(len(v)):
        if len(keep) < 4:
            return None
        try:
            h = ConvexHull(q[keep])
        except QhullError:
            return None
        tri = keep[np.array(h.simplices, dtype=np.int64)]
        e = np.stack([q[tri[:, 2]] - q[tri[:, 1]], q[tri[:, 0]] - q[tri[:, 2]]])
        e = np.concatenate([e, (q[tri[:, 1]] - q[tri[:, 0]])[None]])
        lens = np.linalg.norm(e, axis=2)  # (3, t): the edge opposite each corner
        cr = np.cross(e[2], -e[1])
        area2 = np.linalg.norm(cr, axis=1)
        height = area2 / np.maximum(lens.max(axis=0), 1e-300)
        # a triangle's own plane must hold the hull: Qhull's triangles of a merged facet
        # (coplanar to its precision) can be nearly collinear, their planes tilted
        nrm = cr / np.maximum(area2, 1e-300)[:, None]
        sd = ((q[keep][None] - q[tri[:, 0]][:, None]) * nrm[:, None]).sum(axis=2)
        both = np.minimum(sd.max(axis=1), -sd.min(axis=1))  # points on both sides
        low = (height < eps) | (both > eps)
        if not low.any():
            break
        # the corner opposite the longest edge of the lowest bad triangle lies near that edge
        t = int(np.flatnonzero(low)[np.argmin(height[low])])
        if height[t] > 1e3 * eps:
            break  # not a sliver: a hull a user's point set makes
        drop = tri[t, int(np.argmax(lens[:, t]))]
        keep = keep[keep != drop]
    else:
        return None
    nb = np.asarray(h.neighbors, dtype=np.int64)
    k0 = int(np.argmax(np.abs(np.einsum("ij,ij->i", cr, h.equations[:, :3]))))
    if np.dot(cr[k0], h.equations[k0, :3]) < 0:
        tri[k0] = tri[k0, ::-1]
    done = np.zeros(len(tri), dtype=bool)
    done[k0] = True
    stack = [k0]
    while stack:
        f = stack.pop()
        a = tri[f]
        directed = {(int(a[i]), int(a[(i + 1) % 3])) for i in range(3)}
        for g in nb[f]:
            if done[g]:
                continue
            b = tri[g]
            if any((int(b[i]), int(b[(i + 1) % 3])) in directed for i in range(3)):
                tri[g] = b[::-1]  # a shared edge must run the other way in the neighbour
            done[g] = True
            stack.append(int(g))
    used, inv = np.unique(tri, return_inverse=True)
    return trimesh.Trimesh(v[used], inv.reshape(-1, 3), process=False)


def _ulp(v) -> float:
    return float(np.spacing(np.abs(v).max(initial=0.0)))


def _from_planes(v, seeds, i):
    """Cell ``i`` of ``seeds`` in the hull of ``v`` from its half-spaces (Qhull), as a mesh.

    The hull's facets and the bisectors towards the other seeds, intersected about their
    Chebyshev centre (an LP) in a frame at the hull's mean; ``None`` if the cell is empty.
    """
    from scipy.optimize import linprog
    from scipy.spatial import ConvexHull, HalfspaceIntersection, QhullError

    o = v.mean(axis=0)
    t = seeds - o
    nb = np.delete(t, i, axis=0) - t[i]
    mid = 0.5 * (np.delete(t, i, axis=0) + t[i])
    rows = np.vstack(
        [ConvexHull(v - o).equations, np.column_stack([nb, -np.einsum("ij,ij->i", nb, mid)])]
    )
    norm = np.linalg.norm(rows[:, :3], axis=1)
    res = linprog(
        np.array([0.0, 0.0, 0.0, -1.0]),
        A_ub=np.column_stack([rows[:, :3], norm]),
        b_ub=-rows[:, 3],
        bounds=[(None, None)] * 3 + [(0, None)],
    )
    if res.status != 0 or res.x[3] <= 0:
        return None
    try:
        pts = HalfspaceIntersection(rows, res.x[:3]).intersections
    except QhullError:
        return None
    return _hull_mesh(pts + o)


def _split(v, seeds):
    """The Voronoi cells of ``seeds`` in the hull of ``v``, as convex meshes (no empty ones).

    Each cell is the hull of its vertices (:func:`_hull_mesh`) where that hull's volume is
    the cell's (to 1e-7, or rounding of the offset times the area): one in 431 leaves two
    levels down a 10-wide box at 1000 had rings through two vertices of other cells
    (folded: the cell's volume right, its mesh not convex; 12cff29's engine), and such a
    cell is built again from its half-spaces (:func:`_from_planes`). Far out the float cut
    of a hull's walls can fail ("degenerate half-spaces": one of 72 relaxed cells of a
    10-wide box at 1e6); then the hull is split about its lowest corner (differences exact
    within a binade) and the leaves moved back.
    """
    from ..engine.containers import Convex
    from ..engine.voronoi3d import voronoi3d

    o = np.zeros(3)
    try:
        try:
            d = voronoi3d(seeds, Convex(points=v))
        except ValueError:
            o = v.min(axis=0)
            d = voronoi3d(seeds - o, Convex(points=v - o))
        vols = np.asarray(d.volumes)
    except ValueError:
        d, vols = None, np.zeros(len(seeds))
    from scipy.spatial import ConvexHull

    whole = ConvexHull(v - v.mean(axis=0))
    tol = max(1e-9 * whole.volume, 8.0 * _ulp(v) * whole.area)
    trust = d is not None and abs(vols.sum() - whole.volume) <= tol
    out = []
    for i in range(len(seeds)):
        h = None
        if trust and vols[i] > 0:
            h = _hull_mesh(np.asarray(d.cell(i).vertices) + o)
            if h is not None:
                c = np.asarray(h.vertices).mean(axis=0)
                hv = h.copy().apply_translation(-c).volume
                if abs(hv - vols[i]) > max(1e-7 * vols[i], 8.0 * _ulp(v) * h.area):
                    h = None
        if h is None and (not trust or vols[i] > 0):
            h = _from_planes(v, seeds, i)
        if h is not None:
            out.append(h)
    return out


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
        The leaf cells, usable by ``lattice`` and ``foam``: each the convex hull of its
        Voronoi cell's vertices (the same floats), so trimesh's ``is_convex`` and
        ``is_watertight`` hold at any offset (leaves at 1e5 .. 1e9 had rings an ulp from
        convex with sliver triangles; their volumes sum to the parents' to rounding).
    """
    from .graph import convex_cell_meshes

    rng = np.random.default_rng(seed)
    # seeds and leaves are taken from each cell's hull
    cur = convex_cell_meshes(cells, "subdivide", "its leaves would fill the hull")
    hulled = set()
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
            leaves = _split(np.asarray(c.vertices, dtype=np.float64), seeds)
            hulled.update(id(m) for m in leaves)
            nxt.extend(leaves)
        cur = nxt
    out = []
    for c in cur:  # cells never split are hulled here; a leaf's hull is itself
        h = c if id(c) in hulled else _hull_mesh(c.vertices)
        out.append(c if h is None else h)
    return out
