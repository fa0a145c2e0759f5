"""Public Voronoi diagram: :func:`voronoi` (the result is :class:`~voroforge.Diagram`)."""

from __future__ import annotations

from .diagram import Diagram
from .domain import make_domain
from .inputs import as_points
from .periodic import periodic_voronoi
from .planar import build, check_algorithm


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
    check_algorithm(algorithm)
    if periodic:
        return periodic_voronoi(points, boundary, algorithm=algorithm, wrap=wrap)
    if wrap:
        raise ValueError("wrap=True applies to periodic diagrams only; pass periodic=True")
    pts = as_points(points)
    return build(pts, make_domain(boundary, pts), algorithm)
