"""The result of a planar diagram: :class:`Diagram` (cells, areas, edges) and :class:`Edges`.

Cells are GeoArrow multipolygon buffers ``(coords, ring, poly, geom)``; cell ``i`` belongs to
site ``i``. The engine's modules build diagrams and read them through the small internal API
at the end of this module (:func:`buffers`, :func:`frame_exponent`, :func:`domain_of`), never
through a diagram's private attributes.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from functools import cached_property
from typing import NamedTuple

import numpy as np
import shapely

from ..config import AREA_FRAME_EXP, EDGE_LENGTH_RTOL
from ..kernels.moments import area_centroid
from .csr import csr_from_pairs
from .domain import Domain
from .edgeowners import reown, split_at_junctions
from .threads import serial_below


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


class LazyEdges:
    """:class:`Edges` computed on first use (once, read-only), then kept.

    The engine builds a diagram's cells eagerly and its shared edges only when something
    reads them (:attr:`Diagram.edges`, :attr:`Diagram.neighbors`): many callers (a design's
    cell operations, an editor's redraw) never do.

    Parameters
    ----------
    make : callable
        Called with no arguments, once; returns the :class:`Edges`. Dropped after the call
        (with whatever it holds).
    """

    def __init__(self, make: Callable[[], Edges]):
        self._make = make
        self._value: Edges | None = None
        self._lock = threading.Lock()

    def resolve(self) -> Edges:
        """The edges, computed now if not yet (their arrays read-only)."""
        if self._value is None:
            with self._lock:
                if self._value is None:
                    value = self._make()
                    for arr in value:
                        arr.setflags(write=False)
                    self._value, self._make = value, None
        return self._value

    @property
    def coords(self) -> np.ndarray:
        """(m, 2, 2) float64 end points (see :class:`Edges`)."""
        return self.resolve().coords

    @property
    def pairs(self) -> np.ndarray:
        """(m, 2) int64 cell pairs (see :class:`Edges`)."""
        return self.resolve().pairs

    def __getstate__(self):  # pickled as the edges themselves
        return {"_value": self.resolve()}

    def __setstate__(self, state):
        self._value, self._make = state["_value"], None
        self._lock = threading.Lock()


class Diagram:
    """A Voronoi diagram clipped to a domain; cell ``i`` belongs to site ``i``.

    Cells are stored as GeoArrow multipolygon buffers (a clipped cell can gain holes or split
    into parts); :attr:`cells` gives shapely geometries and :meth:`to_geoarrow` the buffers.

    Attributes
    ----------
    sites : (n, 2) float64
        The input sites, in input order (read-only copy), as the engine used them: a
        coordinate below about ``2**-188`` of the largest magnitude of the sites and the
        domain's box (scaled into the working frame, ``inputs.working_frame``) is rounded to
        a multiple of ``2**-240`` of it, the resolution of the exact predicates.
    duplicate_of : (n,) int64
        -1, or the index of the earlier identical site that owns the cell (this one is
        empty). Sites made identical by the rounding above count as identical: sites 1e-100
        apart in a domain 1e300 wide are one site.
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
    unresolved : (m,) int64
        Distinct sites inside the domain's box whose cell float64 cannot represent: a site
        a few ulps from others whose cell is a strip narrower than the coordinates'
        spacing. Its cell is empty, or, where the strip is most of a bigger cell (the hull
        site of a cluster a few ulps wide far from the origin), a ring that lies beside the
        site by an ulp, kept so the cells tile the domain. On a torus (unwrapped cells),
        also the sites whose cell has a vertex that cannot be an exact shift of its image
        (a box an odd number of ulps across a power of two); the cell is kept. Usually
        empty; such a site is not a duplicate (``duplicate_of == -1``).
    """

    periodic = False
    wrapped = False

    def __init__(
        self,
        sites,
        duplicate_of,
        domain: Domain,
        buffers,
        edges,
        algorithm,
        k=0,
        unresolved=None,
        reach=None,
    ):
        self.sites = sites
        self._reach = reach  # see convex_reach
        self._k = k  # the working frame's scale exponent (areas are computed there)
        self.duplicate_of = duplicate_of
        self._domain = domain
        self._buffers = buffers
        self._edges = edges  # Edges, or LazyEdges until read (see the edges property)
        self.algorithm = algorithm
        self.unresolved = np.zeros(0, np.int64) if unresolved is None else unresolved
        for arr in (sites, duplicate_of, self.unresolved, *buffers):
            arr.setflags(write=False)
        if not isinstance(edges, LazyEdges):
            for arr in edges:
                arr.setflags(write=False)

    def __len__(self) -> int:
        return len(self.sites)

    def __repr__(self) -> str:
        return (
            f"Diagram(sites={len(self.sites)}, edges={len(self.edges.pairs)}, "
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
        big = float(np.abs(coords).max(initial=0.0))
        if big > 0.0 and np.isfinite(big):
            # cubes of the scaled coordinates stay finite: the working frame may put the
            # domain near 2**900 (sites 1e-154 apart in a box 10 wide: areas were inf)
            k = min(k, AREA_FRAME_EXP - int(np.frexp(big)[1]))
        with serial_below(len(self.sites)):
            if not k:
                areas, centroids = area_centroid(coords, ring, poly, geom)
            else:
                # at extreme scales squared coordinates leave the double range: work scaled
                # (read-only like the buffers, so the kernel is compiled once for both)
                scaled = np.ldexp(coords, k)
                scaled.setflags(write=False)
                areas, centroids = area_centroid(scaled, ring, poly, geom)
                with np.errstate(over="ignore"):  # an area past 1.8e308 is inf
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
        """Unique shared edges (each once) with the pair of cells they separate.

        Computed on first use (most callers of the engine read only the cells), then kept.
        """
        edges = self._edges
        if isinstance(edges, LazyEdges) or not getattr(self, "_owned", False):
            if isinstance(edges, LazyEdges):
                edges = edges.resolve()
            mended = reown(edges, self._buffers, len(self.sites))
            if len(self.unresolved) and not self.periodic:
                # beside a lost site an edge can run past a T-junction (engine.edgeowners);
                # a torus edge may be drawn at another image of its cells' sides: left alone
                x0, y0, x1, y1 = self.bounds
                tol = EDGE_LENGTH_RTOL * max(x1 - x0, y1 - y0)
                mended = split_at_junctions(mended, self._buffers, tol)
            if mended is not edges:
                for arr in mended:
                    arr.setflags(write=False)
                edges = Edges(*mended)
            self._edges = edges
            self._owned = True  # (a pair naming an empty cell mended: engine.edgeowners)
        return edges

    @cached_property
    def neighbors(self) -> tuple[np.ndarray, np.ndarray]:
        """CSR ``(indptr, indices)`` of cells sharing an edge of positive length."""
        pairs = self.edges.pairs
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


# --- internal API: how the engine's modules read a diagram they did not build ----------------


def buffers(d: Diagram) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The cells' GeoArrow buffers ``(coords, ring, poly, geom)`` (read-only, not copied).

    Parameters
    ----------
    d : Diagram

    Returns
    -------
    coords : (k, 2) float64
    ring, poly, geom : (·,) int64
        Ring, polygon and cell offsets, as in :meth:`Diagram.to_geoarrow`.
    """
    return d._buffers


def convex_reach(d: Diagram) -> np.ndarray | None:
    """Each cell's farthest vertex from its site before the polygon clip, or ``None``.

    On a polygon domain a cell is its convex ring (the cell of the domain's box) intersected
    with the polygon, and a crossing inside the box (a hole's edge, a gap between parts) is
    computed from the ring's own vertices, which may lie far beyond the clipped cell: a
    site within twice this distance can change the clipped cell's bits, none beyond it
    (``scale``'s certificate). Kept by ``vf.voronoi`` on polygon domains (``None`` else).
    """
    return getattr(d, "_reach", None)


def frame_exponent(d: Diagram) -> int:
    """The working frame's exponent ``k`` of ``d``: its moments are computed at ``2**k``.

    Parameters
    ----------
    d : Diagram

    Returns
    -------
    int
        0 for ordinary coordinates (see :func:`voroforge.engine.inputs.working_frame`).
    """
    return d._k


def domain_of(d: Diagram) -> Domain:
    """The validated :class:`~voroforge.engine.domain.Domain` the cells of ``d`` are clipped to.

    Parameters
    ----------
    d : Diagram

    Returns
    -------
    Domain
    """
    return d._domain
