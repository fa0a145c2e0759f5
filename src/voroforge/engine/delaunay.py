"""Public Delaunay triangulation: :func:`delaunay` and the :class:`Triangulation` result."""

from __future__ import annotations

from functools import cached_property

import numpy as np

from ..kernels.centers import triangle_centers
from ..kernels.delaunay import triangulate
from .csr import csr_from_pairs
from .inputs import as_points, as_query, duplicate_map, from_working, working_frame
from .threads import serial_below


class Triangulation:
    """Delaunay triangulation in the Delaunator layout.

    Attributes
    ----------
    points : (n, 2) float64
        The input points, in input order (a read-only copy).
    triangles : (t, 3) int32
        Point indices of each triangle, counter-clockwise.
    halfedges : (3 t,) int32
        Halfedge ``e`` is the edge of triangle ``e // 3`` from corner ``e % 3`` to corner
        ``(e + 1) % 3``; ``halfedges[e]`` is the opposite halfedge, or -1 on the hull.
    hull : (h,) int32
        Point indices of the convex hull, counter-clockwise. For collinear input (no
        triangles) all distinct points in order along their line.
    duplicate_of : (n,) int64
        -1, or the index of the earlier identical point; duplicates are not triangulated.

    Examples
    --------
    Walk the three neighbours of triangle 0:

    >>> import voroforge as vf
    >>> tri = vf.delaunay([[0, 0], [1, 0], [0, 1], [1, 1]])
    >>> e = 0
    >>> [int(tri.halfedges[3 * 0 + k]) // 3 for k in range(3)]  # -1 // 3 == -1 on the hull
    [-1, 1, -1]
    """

    def __init__(self, points, triangles, halfedges, hull, duplicate_of):
        self.points = points
        self.triangles = triangles
        self.halfedges = halfedges
        self.hull = hull
        self.duplicate_of = duplicate_of
        for arr in (points, triangles, halfedges, hull, duplicate_of):
            arr.setflags(write=False)

    def __repr__(self) -> str:
        return (
            f"Triangulation(points={len(self.points)}, triangles={len(self.triangles)}, "
            f"hull={len(self.hull)})"
        )

    @property
    def collinear(self) -> bool:
        """True when there is no triangle (fewer than 3 distinct points, or all collinear)."""
        return len(self.triangles) == 0

    @cached_property
    def neighbors(self) -> tuple[np.ndarray, np.ndarray]:
        """CSR ``(indptr, indices)`` of Delaunay neighbours of each point.

        Neighbours of point ``i`` are ``indices[indptr[i]:indptr[i + 1]]`` (sorted). For
        collinear input consecutive points along the line are neighbours.
        """
        n = len(self.points)
        if self.collinear:
            return csr_from_pairs(n, self.hull[:-1], self.hull[1:])
        flat = self.triangles.ravel()
        nxt = self.triangles[:, [1, 2, 0]].ravel()
        return csr_from_pairs(n, flat, nxt)

    @cached_property
    def edges(self) -> np.ndarray:
        """(m, 2) int32 unique Delaunay edges ``i < j``."""
        indptr, indices = self.neighbors
        src = np.repeat(np.arange(len(self.points), dtype=np.int32), np.diff(indptr))
        keep = src < indices
        return np.stack((src[keep], indices[keep]), axis=1)

    @cached_property
    def circumcenters(self) -> np.ndarray:
        """(t, 2) float64 circumcentres of the triangles: the Voronoi vertices, bit for bit.

        Each is the vertex named by its triangle's sites (``kernels/vertex``); triangles with
        one circumcircle (exactly cocircular sites) share the vertex of its canonical name,
        as in :func:`voroforge.voronoi`'s cells. A triangle whose centre overflows gets
        ``inf``. (Centres that the cells merge only because they lie within rounding of
        each other stay each triangle's own here.)
        """
        work, k = working_frame(self.points)
        work = np.array(work, dtype=np.float64, order="C")  # writable, as in the build
        # the kernels see the array types the Voronoi build passes them (contiguous
        # coordinates, writable triangles), so they are not compiled a second time
        tri = np.array(self.triangles.ravel(), dtype=np.int32)
        he = np.array(self.halfedges, dtype=np.int32)
        xs = np.ascontiguousarray(work[:, 0])
        ys = np.ascontiguousarray(work[:, 1])
        cx, cy = triangle_centers(xs, ys, tri, he)
        return from_working(np.stack((cx, cy), axis=1), k)

    @cached_property
    def _tree(self):
        from scipy.spatial import cKDTree

        owners = np.flatnonzero(self.duplicate_of < 0)
        return cKDTree(self.points[owners]), owners

    def find(self, xy) -> np.ndarray | int:
        """Index of the nearest input point to each query point.

        Parameters
        ----------
        xy : (2,) or (m, 2) array_like
            Query point(s).

        Returns
        -------
        int or (m,) int64
            Nearest point index (the first occurrence for duplicated points; ties between
            distinct points at equal distance go to either).
        """
        q, single = as_query(xy)
        if len(self.points) == 0:
            raise ValueError("cannot find the nearest point of an empty triangulation")
        tree, owners = self._tree
        _, idx = tree.query(q)
        out = owners[idx]
        return int(out[0]) if single else out


def _collinear_hull(points: np.ndarray, unique: np.ndarray) -> np.ndarray:
    """Distinct collinear points in order along their line."""
    p = points[unique]
    order = np.lexsort((p[:, 1], p[:, 0]))
    return unique[order].astype(np.int32)


def delaunay(points) -> Triangulation:
    """Delaunay triangulation of 2D points with exact predicates.

    Parameters
    ----------
    points : (n, 2) array_like
        Point coordinates; any finite values. Exact duplicates are allowed (only the first
        occurrence is triangulated). The input is never modified.

    Returns
    -------
    Triangulation
        Triangles, halfedges and hull in the Delaunator layout, in input indices.

    Raises
    ------
    ValueError
        If ``points`` is not an ``(n, 2)`` array of finite numbers.

    Examples
    --------
    >>> import numpy as np, voroforge as vf
    >>> tri = vf.delaunay(np.random.default_rng(0).random((100, 2)))
    >>> tri.triangles.shape[1], int(tri.find([0.5, 0.5])) in range(100)
    (3, True)
    """
    pts = as_points(points)
    work, k = working_frame(pts)
    if work is not pts:
        pts = from_working(work, k)  # equal to the input unless it spans > 1e57 in magnitude
    dup, unique = duplicate_map(work)
    all_unique = len(unique) == len(work)
    sub = work if all_unique else work[unique]
    with serial_below(len(sub)):
        tri, he, hull, ok = triangulate(
            np.ascontiguousarray(sub[:, 0]), np.ascontiguousarray(sub[:, 1])
        )
    if ok:
        triangles = tri.reshape(-1, 3)
        if not all_unique:
            ids = unique.astype(np.int32)
            triangles = ids[triangles]
            hull = ids[hull]
    else:
        triangles = np.zeros((0, 3), dtype=np.int32)
        he = np.zeros(0, dtype=np.int32)
        hull = _collinear_hull(work, unique)
    return Triangulation(pts, triangles, he, hull, dup)
