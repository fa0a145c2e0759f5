"""Public Voronoi diagram: :func:`voronoi` and the :class:`Diagram` result."""

from __future__ import annotations

from functools import cached_property
from typing import NamedTuple

import numpy as np
import shapely

from ..kernels.cells import cells_from_neighbors, cells_from_triangulation
from ..kernels.delaunay import triangulate_sorted
from ..kernels.fortune import fortune_delaunay
from ..kernels.halfplane import halfplane_cells
from ..kernels.rings import area_centroid, close_rings
from ._assemble import clip_to_polygon, domain_edges, domain_grid, geom_offsets_for
from ._csr import csr_from_pairs
from ._inputs import as_points, duplicate_map, from_working, working_frame
from ._threads import serial_below
from .domain import Domain, make_domain

ALGORITHMS = ("delaunay", "fortune", "halfplane")


class Edges(NamedTuple):
    """Unique shared Voronoi edges: each edge between two cells appears once.

    Attributes
    ----------
    coords : (m, 2, 2) float64
        End points of each edge.
    pairs : (m, 2) int64
        The two cells ``(i, j)``, ``i < j``, that the edge separates.
    """

    coords: np.ndarray
    pairs: np.ndarray


class Diagram:
    """A Voronoi diagram clipped to a domain; cell ``i`` belongs to site ``i``.

    Cells are stored as GeoArrow multipolygon buffers (a clipped cell can gain holes or split
    into parts); :attr:`cells` gives shapely geometries and :meth:`to_geoarrow` the buffers.

    Attributes
    ----------
    sites : (n, 2) float64
        The input sites, in input order (read-only copy).
    duplicate_of : (n,) int64
        -1, or the index of the earlier identical site that owns the cell (this one is empty).
    boundary : shapely.Polygon or shapely.MultiPolygon
        The domain the cells are clipped to.
    bounds : tuple of 4 floats
        The domain's ``(xmin, ymin, xmax, ymax)``.
    algorithm : str
        The construction method used.
    periodic : bool
        True for a diagram on the torus (``voronoi(..., periodic=True)``).
    wrapped : bool
        True when periodic cells were cut into the box (``wrap=True``).
    """

    periodic = False
    wrapped = False

    def __init__(self, sites, duplicate_of, domain: Domain, buffers, edges, algorithm, k=0):
        self.sites = sites
        self._k = k  # the working frame's scale exponent (areas are computed there)
        self.duplicate_of = duplicate_of
        self._domain = domain
        self._buffers = buffers
        self._edges = edges
        self.algorithm = algorithm
        for arr in (sites, duplicate_of, *buffers, *edges):
            arr.setflags(write=False)

    def __len__(self) -> int:
        return len(self.sites)

    def __repr__(self) -> str:
        return (
            f"Diagram(sites={len(self.sites)}, edges={len(self._edges.pairs)}, "
            f"bounds={self.bounds}, algorithm={self.algorithm!r})"
        )

    @property
    def boundary(self):
        """The clipping domain as a shapely geometry."""
        return self._domain.geometry

    @property
    def bounds(self) -> tuple[float, float, float, float]:
        """``(xmin, ymin, xmax, ymax)`` of the domain."""
        return self._domain.bounds

    def to_geoarrow(self):
        """Raw GeoArrow multipolygon buffers of the cells.

        Returns
        -------
        coords : (k, 2) float64
            All ring coordinates (rings closed: last == first).
        offsets : tuple of 3 (·,) int64
            ``(ring_offsets, polygon_offsets, geom_offsets)`` as in ``shapely.to_ragged_array``:
            ring ``r`` is ``coords[ring_offsets[r]:ring_offsets[r+1]]``, polygon ``p`` has rings
            ``polygon_offsets[p]:polygon_offsets[p+1]`` (the first is the exterior), cell ``i``
            has polygons ``geom_offsets[i]:geom_offsets[i+1]``.
        """
        coords, ring, poly, geom = self._buffers
        return coords, (ring, poly, geom)

    @cached_property
    def cells(self) -> np.ndarray:
        """(n,) object array of shapely geometries: Polygon, or MultiPolygon for split cells."""
        coords, ring, poly, geom = self._buffers
        parts = np.diff(geom)
        if (parts <= 1).all():
            # every cell is one polygon (or empty): build Polygons directly
            n = len(geom) - 1
            poly_of_cell = np.zeros(n + 1, dtype=np.int64)
            np.cumsum(parts, out=poly_of_cell[1:])
            ring_of_cell = poly[poly_of_cell]
            return shapely.from_ragged_array(
                shapely.GeometryType.POLYGON, coords, (ring, ring_of_cell)
            )
        # one Polygon per part, then the few split cells gathered into MultiPolygons
        polys = shapely.from_ragged_array(shapely.GeometryType.POLYGON, coords, (ring, poly))
        out = np.full(len(parts), shapely.Polygon(), dtype=object)
        single = np.flatnonzero(parts == 1)
        out[single] = polys[geom[single]]
        multi = np.flatnonzero(parts > 1)
        members = np.concatenate([np.arange(geom[i], geom[i + 1]) for i in multi])
        owner = np.repeat(np.arange(len(multi)), parts[multi])
        out[multi] = shapely.multipolygons(polys[members], indices=owner)
        return out

    @cached_property
    def _area_centroid(self):
        coords, ring, poly, geom = self._buffers
        k = self._k
        with serial_below(len(self.sites)):
            if not k:
                areas, centroids = area_centroid(coords, ring, poly, geom)
            else:
                # at extreme scales squared coordinates leave the double range: work scaled
                areas, centroids = area_centroid(np.ldexp(coords, k), ring, poly, geom)
                areas, centroids = np.ldexp(areas, -2 * k), np.ldexp(centroids, -k)
        # cached and shared by every caller: read-only, like the other results
        areas.setflags(write=False)
        centroids.setflags(write=False)
        return areas, centroids

    @property
    def areas(self) -> np.ndarray:
        """(n,) float64 cell areas."""
        return self._area_centroid[0]

    @property
    def centroids(self) -> np.ndarray:
        """(n, 2) float64 cell centroids (NaN for empty cells)."""
        return self._area_centroid[1]

    @property
    def edges(self) -> Edges:
        """Unique shared edges (each once) with the pair of cells they separate."""
        return self._edges

    @cached_property
    def neighbors(self) -> tuple[np.ndarray, np.ndarray]:
        """CSR ``(indptr, indices)`` of cells sharing an edge of positive length."""
        pairs = self._edges.pairs
        return csr_from_pairs(len(self.sites), pairs[:, 0], pairs[:, 1])

    @cached_property
    def vertices(self) -> np.ndarray:
        """(v, 2) float64 distinct vertices of all cells."""
        coords = self._buffers[0]
        return np.unique(coords, axis=0) if len(coords) else np.zeros((0, 2))

    def locate(self, xy):
        """Index of the site whose cell contains each query point (its nearest site).

        Parameters
        ----------
        xy : (2,) or (m, 2) array_like
            Query points (anywhere; on a periodic diagram taken modulo the box).

        Returns
        -------
        int or (m,) int64
            Site index; duplicates map to the owning (first) site, ties between
            equidistant sites go to the lowest index. See :func:`voroforge.locate`.
        """
        from .interpolate import locate_in_diagram

        return locate_in_diagram(self, xy)

    def describe(self):
        """Structure report: counts, Euler's formula, unbounded and non-convex cells.

        Returns
        -------
        voroforge.engine.describe.Description
            See :func:`voroforge.engine.describe.describe`.
        """
        from .describe import describe

        return describe(self)


def _collinear_neighbors(xs, ys):
    order = np.lexsort((ys, xs))
    a = order[:-1]
    b = order[1:]
    return csr_from_pairs(len(xs), a, b)


def _closed_cells(xs, ys, box, algorithm, kmap):
    """Kernel dispatch: closed convex rings of distinct sites clipped to ``box``.

    Returns ``(coords, lengths, owner)`` with distinct site ``k``'s ring at
    ``coords[lengths[k]:lengths[k + 1]]`` and owners mapped through ``kmap``.
    """
    if algorithm in ("delaunay", "fortune"):
        if algorithm == "fortune":
            # the sweep's Delaunay dual, through the same cell builder as the default
            order, sx, sy, tri, he, ok = fortune_delaunay(xs, ys)
        else:
            order, sx, sy, tri, he, _, ok = triangulate_sorted(xs, ys)
        if ok:
            return cells_from_triangulation(sx, sy, tri, he, box, order, kmap[order])
        indptr, indices = _collinear_neighbors(xs, ys)
        coords, offsets, owner = cells_from_neighbors(xs, ys, indptr, indices.astype(np.int64), box)
        ident = np.arange(len(xs))
        return close_rings(coords, offsets, owner, ident, kmap)
    if algorithm == "halfplane":
        # every cell on its own: the box cut by bisectors, finished with exact predicates
        return halfplane_cells(xs, ys, box, kmap)
    raise ValueError(f"unknown algorithm {algorithm!r}; choose one of {', '.join(ALGORITHMS)}")


def voronoi(
    points,
    boundary=None,
    *,
    algorithm: str = "delaunay",
    periodic: bool = False,
    wrap: bool = False,
) -> Diagram:
    """Voronoi diagram of 2D sites, every cell clipped to a domain.

    Parameters
    ----------
    points : (n, 2) array_like
        Sites. Any finite coordinates; duplicates allowed (the first occurrence owns the cell,
        later copies get an empty cell and ``duplicate_of``). Never modified.
    boundary : None, (xmin, ymin, xmax, ymax) or shapely Polygon/MultiPolygon, optional
        The domain. None: the sites' bounding box padded by 10% on each side. Polygons may be
        concave, have holes and several parts. Sites may lie outside the domain: their cell is
        the part of the domain nearest to them (possibly empty).
    algorithm : {"delaunay", "fortune", "halfplane"}
        Construction method; all methods give the same cells. "delaunay": sweep-hull
        Delaunay triangulation, cells from its circumcentres. "fortune": Fortune's sweep line
        (its Delaunay dual goes through the same cell builder). "halfplane": each cell on its
        own as the box cut by nearby bisectors (voro++-style, in parallel).
    periodic : bool
        Diagram on the torus made by gluing opposite edges of ``boundary``, which must then
        be a box ``(xmin, ymin, xmax, ymax)``; sites are taken modulo the box (``sites``
        holds the wrapped values). Cells tile the torus and their areas sum to the box area.
        Cell ``i`` is the unwrapped convex polygon around site ``i`` and may reach past the
        box edges. ``edges`` lists each torus edge once, placed where it bounds the cell of
        the lower index (of the two cells it separates) in that cell's unwrapped position;
        a cell that borders its own image (one or two sites) has edges ``(i, i)`` and lists
        itself among its ``neighbors``.
    wrap : bool
        With ``periodic=True``: cut every cell into the box instead (a cell that crosses an
        edge becomes a MultiPolygon of its pieces, all inside the box; pieces of a cell that
        borders its own image are united) and report ``edges`` cut into the box too (an
        edge crossing the box edge appears as its two pieces).

    Returns
    -------
    Diagram
        Cells in input order with areas, centroids, neighbours and unique edges.

    Raises
    ------
    ValueError
        Malformed points (shape, NaN/inf), an invalid or empty boundary, an unknown algorithm.

    Examples
    --------
    >>> import numpy as np, voroforge as vf
    >>> pts = np.random.default_rng(1).random((50, 2))
    >>> d = vf.voronoi(pts, (0, 0, 1, 1))
    >>> round(float(d.areas.sum()), 12)
    1.0
    """
    if algorithm not in ALGORITHMS:
        raise ValueError(f"unknown algorithm {algorithm!r}; choose one of {', '.join(ALGORITHMS)}")
    if periodic:
        from .periodic import periodic_voronoi

        return periodic_voronoi(points, boundary, algorithm=algorithm, wrap=wrap)
    if wrap:
        raise ValueError("wrap=True applies to periodic diagrams only; pass periodic=True")
    pts = as_points(points)
    dom = make_domain(boundary, pts)
    n = len(pts)
    work, k = working_frame(pts, np.array(dom.bounds, dtype=np.float64))
    if work is not pts:
        pts = from_working(work, k)  # equal to the input unless it spans > 1e57 in magnitude
    wdom = dom.scaled(k)  # everything below runs in the working frame
    dup, unique = duplicate_map(work)
    sub = work if len(unique) == n else work[unique]
    xs = np.ascontiguousarray(sub[:, 0])
    ys = np.ascontiguousarray(sub[:, 1])
    box = np.array(wdom.bounds, dtype=np.float64)
    with serial_below(n):
        closed, lengths, own = _closed_cells(xs, ys, box, algorithm, unique)
        nonempty = lengths[1:] > lengths[:-1]
        ring_offsets = np.concatenate(([0], lengths[1:][nonempty]))
        ring_cell = unique[nonempty]
        grid = None if wdom.is_rect else domain_grid(wdom, len(ring_cell))
        edge_coords, edge_pairs = domain_edges(wdom, grid, closed, ring_offsets, ring_cell, own)
        if wdom.is_rect:
            polys = np.arange(len(ring_cell) + 1, dtype=np.int64)
            buffers = (closed, ring_offsets, polys, geom_offsets_for(n, ring_cell))
        else:
            buffers = clip_to_polygon(wdom, grid, closed, ring_offsets, ring_cell, n)
    if k:
        buffers = (np.ldexp(buffers[0], -k), *buffers[1:])
        edge_coords = np.ldexp(edge_coords, -k)
    edges = Edges(edge_coords, edge_pairs)
    return Diagram(pts, dup, dom, buffers, edges, algorithm, k)
