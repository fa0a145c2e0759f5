"""File readers: point sets and domains, chosen by suffix, with errors that name the file.

One dispatcher per kind of input: :func:`read_points` (``.csv``/``.txt``/``.xy``, ``.npy``,
``.geojson``/``.json``) and :func:`read_boundary` (a bounding-box string, or a GeoJSON,
SVG or DXF file). The format modules (:mod:`.points`, :mod:`.geojson`, :mod:`.svg`,
:mod:`.dxf`) hold the parsers; :mod:`voroforge.design.boundary` validates what they read.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import shapely

from .dxf import read_dxf
from .files import existing_file, parse_number
from .geojson import (
    geojson_crs,
    read_geojson_point_table,
    read_geojson_points,
    read_geojson_polygons,
)
from .points import read_npy_points, read_text_point_table, read_text_points
from .svg import read_svg, read_svg_curves

__all__ = [
    "BOUNDARY_SUFFIXES",
    "POINT_SUFFIXES",
    "boundary_crs",
    "read_boundary",
    "read_dxf",
    "read_point_table",
    "read_points",
    "read_svg",
    "read_svg_curves",
]

#: Point file suffixes and the reader of each.
_POINT_READERS = {
    ".csv": read_text_points,
    ".txt": read_text_points,
    ".xy": read_text_points,
    ".npy": read_npy_points,
    ".geojson": read_geojson_points,
    ".json": read_geojson_points,
}
POINT_SUFFIXES = tuple(_POINT_READERS)

#: Boundary file suffixes and the reader of each (any other existing file is read as GeoJSON).
_BOUNDARY_READERS = {
    ".geojson": read_geojson_polygons,
    ".json": read_geojson_polygons,
    ".svg": read_svg,
    ".dxf": read_dxf,
}
BOUNDARY_SUFFIXES = tuple(_BOUNDARY_READERS)

#: Point readers that also return attribute columns.
_TABLE_READERS = {
    ".csv": read_text_point_table,
    ".txt": read_text_point_table,
    ".xy": read_text_point_table,
    ".geojson": read_geojson_point_table,
    ".json": read_geojson_point_table,
}


def read_points(path) -> np.ndarray:
    """Read 2-D points from a file.

    Supported: ``.csv`` / ``.txt`` / ``.xy`` (two numeric columns, or columns named ``x`` and
    ``y`` anywhere in a header row; commas, semicolons, tabs or spaces; ``#`` comments),
    ``.npy`` (an ``(n, 2)`` array) and ``.geojson`` / ``.json`` (Point and MultiPoint
    features or geometries).

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    (n, 2) float64
        The points, in file order.

    Raises
    ------
    ValueError
        Naming the file and the problem: missing file, unknown suffix, no points, missing
        columns, or a non-numeric value (with its line number).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> f = pathlib.Path(tempfile.mkdtemp()) / "pts.csv"
    >>> _ = f.write_text(chr(10).join(["id,x,y", "a,0,1", "b,2.5,3"]))
    >>> read_points(f).tolist()
    [[0.0, 1.0], [2.5, 3.0]]
    """
    path = existing_file(path)
    suffix = path.suffix.lower()
    reader = _POINT_READERS.get(suffix)
    if reader is None:
        raise ValueError(
            f"{path}: unsupported point file type {suffix or '(none)'!r}; "
            f"use one of {', '.join(POINT_SUFFIXES)}"
        )
    points = reader(path)
    if len(points) == 0:
        raise ValueError(f"{path}: no points")
    return np.ascontiguousarray(points, dtype=np.float64)


def read_point_table(path) -> tuple[np.ndarray, dict]:
    """Read points and their attributes: the other CSV columns, or GeoJSON properties.

    Parameters
    ----------
    path : str or Path
        As for :func:`read_points`.

    Returns
    -------
    points : (n, 2) float64
        As :func:`read_points` returns them, in file order (row ``i`` is site ``i``).
    attributes : dict of name -> list
        One column of length ``n`` per attribute (``.npy`` files have none).

    Raises
    ------
    ValueError
        As for :func:`read_points`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> f = pathlib.Path(tempfile.mkdtemp()) / "trees.csv"
    >>> _ = f.write_text(chr(10).join(["x,y,species,height", "0,1,oak,12.5", "2.5,3,elm,8"]))
    >>> pts, attrs = read_point_table(f)
    >>> attrs
    {'species': ['oak', 'elm'], 'height': [12.5, 8.0]}
    """
    suffix = Path(path).suffix.lower()
    reader = _TABLE_READERS.get(suffix)
    if reader is None:
        return read_points(path), {}
    points, attrs = reader(existing_file(path))
    if len(points) == 0:
        raise ValueError(f"{path}: no points")
    return np.ascontiguousarray(points, dtype=np.float64), attrs


def boundary_crs(spec):
    """The CRS a boundary file declares (a GeoJSON ``"crs"`` member), or None.

    Parameters
    ----------
    spec : str, Path or anything :func:`read_boundary` takes

    Returns
    -------
    dict or None
        The member as written, ready for ``write_geojson(..., crs=...)``.
    """
    if spec is None or isinstance(spec, shapely.Geometry | tuple | list):
        return None
    path = Path(str(spec))
    if not path.is_file() or path.suffix.lower() in (".svg", ".dxf"):
        return None
    return geojson_crs(path)


def _parse_bbox(text: str) -> tuple[float, float, float, float] | None:
    parts = [p.strip() for p in text.split(",")]
    if len(parts) != 4:
        return None
    values = [parse_number(p) for p in parts]
    if any(v is None for v in values):
        return None
    xmin, ymin, xmax, ymax = values
    if not all(math.isfinite(v) for v in values) or not (xmin < xmax and ymin < ymax):
        raise ValueError(f"boundary {text!r}: need finite numbers with xmin < xmax and ymin < ymax")
    return xmin, ymin, xmax, ymax


def read_boundary(spec, **options):
    """Read a domain: ``"xmin,ymin,xmax,ymax"``, or a GeoJSON, SVG or DXF file.

    Parameters
    ----------
    spec : str, Path, tuple or shapely geometry
        A bounding-box string; a path to a GeoJSON file whose polygonal features are united
        into one domain (holes kept), to an SVG file (filled shapes, :func:`read_svg`) or to
        a DXF file (closed outlines, :func:`read_dxf`); or an already parsed
        tuple/geometry (passed through). Files of any other suffix are read as GeoJSON.
    **options
        Passed to the SVG and DXF readers (``tolerance=...``, ``flip_y=...``, ``layers=...``).

    Returns
    -------
    tuple of 4 floats or shapely Polygon/MultiPolygon
        Ready for ``vf.voronoi(points, boundary)``.

    Raises
    ------
    ValueError
        If the string is neither a file nor four numbers, or the file has no polygons.

    Examples
    --------
    >>> read_boundary("0, 0, 100, 50")
    (0.0, 0.0, 100.0, 50.0)
    """
    if spec is None or isinstance(spec, shapely.Geometry | tuple | list):
        return tuple(spec) if isinstance(spec, list) else spec
    text = str(spec)
    path = Path(text)
    if not path.exists():
        bbox = _parse_bbox(text)
        if bbox is not None:
            return bbox
        raise ValueError(f"boundary {text!r}: no such file, and not xmin,ymin,xmax,ymax")
    path = existing_file(path)
    reader = _BOUNDARY_READERS.get(path.suffix.lower(), read_geojson_polygons)
    if reader is read_geojson_polygons:
        if options:
            raise ValueError(f"{path}: GeoJSON boundaries take no options ({', '.join(options)})")
        return reader(path)
    return reader(path, **options)
