"""Boundaries (the part to be cut): shape primitives and validation; files via the readers.

Every function returns a valid shapely ``Polygon`` or ``MultiPolygon`` in millimetres (or
the file's drawing units, see :func:`from_svg`). The file readers live in
:mod:`voroforge.io.readers` (SVG paths, Béziers, arcs and transforms; DXF bulges, circles
and ellipses; GeoJSON): curves are flattened to polylines whose distance from the true curve
is at most ``tolerance``, and closed curves are combined by the even-odd rule (a curve
inside another one is a hole, a curve inside a hole is an island again). The functions here
check what they read with :func:`as_polygonal`.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import shapely

from ..config import BOUNDARY_MAX_SEGMENTS, CURVE_TOLERANCE
from ..io.readers import BOUNDARY_SUFFIXES, read_boundary, read_dxf, read_svg, read_svg_curves
from ..io.readers.files import existing_file, positive_number
from ..io.readers.geojson import read_geojson_polygons
from ..io.readers.rings import even_odd, polygonal_part
from ..io.readers.svg import path_lines, path_rings, svg_in_mm

__all__ = [
    "MM_PER_UNIT",
    "as_polygonal",
    "circle",
    "curves_from_svg",
    "even_odd",
    "from_dxf",
    "from_geojson",
    "from_svg",
    "load",
    "load_in_units",
    "path_lines",
    "path_rings",
    "polygon",
    "polygonal_part",
    "rectangle",
    "svg_in_mm",
    "svg_in_units",
    "union",
]


# ----------------------------------------------------------------------------- validation


def _xy(value, name: str) -> tuple[float, float]:
    arr = np.asarray(value, dtype=np.float64)
    if arr.shape != (2,) or not np.isfinite(arr).all():
        raise ValueError(f"{name} must be two finite numbers (x, y), got {value!r}")
    return float(arr[0]), float(arr[1])


def as_polygonal(geom, name: str = "boundary"):
    """Check that ``geom`` is a valid, non-empty Polygon or MultiPolygon and return it.

    Parameters
    ----------
    geom : shapely geometry
        The candidate boundary.
    name : str
        How error messages call it.

    Returns
    -------
    shapely.Polygon or shapely.MultiPolygon
        ``geom`` itself, unchanged.

    Raises
    ------
    ValueError
        If it is not polygonal, empty, has zero area or is invalid (with GEOS's reason).
    """
    if not isinstance(geom, shapely.Polygon | shapely.MultiPolygon):
        kind = type(geom).__name__
        raise ValueError(f"{name} must be a shapely Polygon or MultiPolygon, got {kind}")
    if geom.is_empty:
        raise ValueError(f"{name} is empty")
    if not geom.is_valid:
        raise ValueError(f"{name} is invalid: {shapely.is_valid_reason(geom)}")
    if not geom.area > 0:
        raise ValueError(f"{name} has zero area")
    return geom


def _ring(coords, name: str) -> np.ndarray:
    arr = np.asarray(coords, dtype=np.float64)
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"{name} must be an (n, 2) array of vertices, got shape {arr.shape}")
    if not np.isfinite(arr).all():
        raise ValueError(f"{name} has NaN or infinite coordinates")
    if len(arr) >= 2 and (arr[0] == arr[-1]).all():
        arr = arr[:-1]
    if len(arr) < 3:
        raise ValueError(f"{name} needs at least 3 distinct vertices, got {len(arr)}")
    return arr


# ----------------------------------------------------------------------------- primitives


def rectangle(width, height, *, origin=(0.0, 0.0)) -> shapely.Polygon:
    """Axis-aligned rectangle ``width`` × ``height`` with its lower-left corner at ``origin``.

    Parameters
    ----------
    width, height : float
        Side lengths (> 0).
    origin : (2,) float
        Lower-left corner.

    Returns
    -------
    shapely.Polygon

    Examples
    --------
    >>> rectangle(600, 400).bounds
    (0.0, 0.0, 600.0, 400.0)
    """
    w = positive_number(width, "width")
    h = positive_number(height, "height")
    x, y = _xy(origin, "origin")
    return shapely.box(x, y, x + w, y + h)


def circle(radius, *, center=(0.0, 0.0), segments: int = 256) -> shapely.Polygon:
    """Regular ``segments``-gon inscribed in the circle of ``radius`` around ``center``.

    Parameters
    ----------
    radius : float
        Circle radius (> 0).
    center : (2,) float
        Centre.
    segments : int
        Number of vertices (>= 3). The chord error is ``radius * (1 - cos(pi / segments))``.

    Returns
    -------
    shapely.Polygon
    """
    r = positive_number(radius, "radius")
    cx, cy = _xy(center, "center")
    if int(segments) != segments or not 3 <= segments <= BOUNDARY_MAX_SEGMENTS:
        raise ValueError(
            f"segments must be an integer in 3..{BOUNDARY_MAX_SEGMENTS}, got {segments!r}"
        )
    t = np.linspace(0.0, 2.0 * np.pi, int(segments), endpoint=False)
    return shapely.Polygon(np.column_stack((cx + r * np.cos(t), cy + r * np.sin(t))))


def polygon(shell, holes=()) -> shapely.Polygon:
    """Polygon from an outer ring and optional hole rings, validated.

    Parameters
    ----------
    shell : (n, 2) array_like
        Outer ring (closed or not; any orientation).
    holes : sequence of (k, 2) array_like
        Hole rings.

    Returns
    -------
    shapely.Polygon
        Oriented counter-clockwise outside, clockwise holes.

    Raises
    ------
    ValueError
        Too few vertices, non-finite coordinates, or an invalid polygon (self-intersection,
        hole outside the shell, ...) with GEOS's reason.
    """
    outer = _ring(shell, "shell")
    inner = [_ring(h, f"hole {i}") for i, h in enumerate(holes)]
    poly = shapely.Polygon(outer, inner)
    as_polygonal(poly, "polygon")
    return shapely.orient_polygons(poly)


def union(*geoms):
    """Union of polygons (overlapping or not) into one Polygon or MultiPolygon.

    Parameters
    ----------
    *geoms : shapely Polygon or MultiPolygon
        At least one.

    Returns
    -------
    shapely.Polygon or shapely.MultiPolygon
    """
    if not geoms:
        raise ValueError("union needs at least one polygon")
    for i, g in enumerate(geoms):
        as_polygonal(g, f"geometry {i}")
    out = union_all_checked(np.asarray(geoms, dtype=object))
    return as_polygonal(polygonal_part(out), "union")


def union_all_checked(geoms):
    """``shapely.union_all`` of polygons, checked: no polygon is left out.

    GEOS's cascaded union can drop whole polygons whose edges lie a rounding apart from
    their neighbours' (25 cells inset by 1e-16: two of them missing, the union 22.54 of
    25.0, and valid). A polygon whose interior point the union does not cover is united
    again, pairwise with the result, until every one is covered.
    """
    parts = shapely.get_parts(np.asarray(geoms, dtype=object).ravel())
    parts = parts[~shapely.is_empty(parts)]
    out = shapely.union_all(parts)
    if len(parts) < 2:
        return out
    probe = shapely.point_on_surface(parts)
    px, py = shapely.get_x(probe), shapely.get_y(probe)
    for _ in range(4):
        shapely.prepare(out)
        lost = np.flatnonzero(~shapely.intersects_xy(out, px, py))
        if not len(lost):
            return out
        for k in lost:
            out = shapely.union(out, parts[k])
    return out


# ----------------------------------------------------------------------------- files


def from_svg(path, *, tolerance: float = CURVE_TOLERANCE, flip_y: bool = True):
    """Read the filled shapes of an SVG file as one valid boundary (even-odd nesting).

    :func:`voroforge.io.readers.read_svg` parses the file (paths with every command,
    polygons, rects, circles, ellipses, transforms, units, y flipped up; its parameters and
    its millimetre rule); this checks the result with :func:`as_polygonal`.
    """
    return as_polygonal(read_svg(path, tolerance=tolerance, flip_y=flip_y), str(Path(path)))


def curves_from_svg(path, *, tolerance: float = CURVE_TOLERANCE, flip_y: bool = True):
    """Read every outline of an SVG file as lines (for :class:`CurveAttractor`, say).

    :func:`voroforge.io.readers.read_svg_curves`: open and closed outlines, with the
    transforms, units and y flip of :func:`from_svg`.

    Returns
    -------
    shapely.MultiLineString
    """
    return read_svg_curves(path, tolerance=tolerance, flip_y=flip_y)


def from_dxf(
    path,
    *,
    tolerance: float = CURVE_TOLERANCE,
    layers=None,
    loose: bool = True,
    to_mm: bool = False,
):
    """Read closed outlines from a DXF file as one valid boundary (even-odd nesting).

    :func:`voroforge.io.readers.read_dxf` parses the file (closed polylines with bulges as
    true arcs, circles, ellipses, splines; loose lines and arcs joined into faces unless
    ``loose=False``; ``layers`` and ``to_mm`` as there); this checks the result with
    :func:`as_polygonal`.
    """
    geom = read_dxf(path, tolerance=tolerance, layers=layers, loose=loose, to_mm=to_mm)
    return as_polygonal(geom, str(Path(path)))


def from_geojson(path):
    """Read the polygons of a GeoJSON file (features united, holes kept), checked.

    :func:`voroforge.io.readers.read_geojson_polygons` reads a ``.geojson`` / ``.json`` file
    with Polygon or MultiPolygon geometries; this checks the result with :func:`as_polygonal`.
    """
    return as_polygonal(read_geojson_polygons(path), str(Path(path)))


def load(path, **options):
    """Read a boundary from a file, choosing the reader by suffix.

    Parameters
    ----------
    path : str or Path
        ``.geojson``/``.json``, ``.svg`` or ``.dxf``.
    **options
        Passed to the reader (``tolerance=...`` for SVG and DXF).

    Returns
    -------
    shapely.Polygon or shapely.MultiPolygon
    """
    suffix = Path(path).suffix.lower()
    if suffix not in BOUNDARY_SUFFIXES:
        raise ValueError(
            f"{path}: unsupported boundary file type {suffix or '(none)'!r}; "
            "use .geojson, .json, .svg or .dxf"
        )
    p = existing_file(path)
    return as_polygonal(read_boundary(p, **options), str(p))


#: Millimetres per design unit
MM_PER_UNIT = {"mm": 1.0, "cm": 10.0, "m": 1000.0, "in": 25.4}


def load_in_units(path: Path, units: str, close_tolerance: float = 0.0):
    """A boundary file in the design's units.

    An SVG whose width has a physical unit (``width="24in"``) is read in mm, so it is scaled
    to the design's units (a 24 in panel in an inch design was 609.6 in wide). Unitless
    SVGs, DXF (coordinates as drawn) and GeoJSON are taken as they are.
    """
    svg = path.suffix.lower() == ".svg"
    geom = load(path, close_tolerance=close_tolerance) if svg else load(path)
    return svg_in_units(geom, path, units) if svg else geom


def svg_in_units(geom, path: Path, units: str):
    """Geometry read from an SVG (in mm when its width has a unit) in the design's units."""
    from shapely import affinity

    if units == "mm" or not svg_in_mm(path):
        return geom
    factor = 1.0 / MM_PER_UNIT[units]
    return affinity.scale(geom, factor, factor, origin=(0.0, 0.0))
