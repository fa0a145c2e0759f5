"""Writers and readers: SVG, PNG, GeoJSON and DXF out; points and domains in.

All writers take a sequence of shapely polygons (``diagram.cells``), so they work on any
polygon set, Delaunay triangles included (:func:`triangle_polygons`). :func:`write` picks
the writer from the file suffix. The readers live in :mod:`.readers` (CSV/TXT, NPY and
GeoJSON points; GeoJSON, SVG and DXF domains), each dispatching on the suffix; the DXF and
SVG layer writers share the arc fitting of :mod:`.arcs`.

Examples
--------
>>> import voroforge as vf
>>> d = vf.voronoi(np.random.default_rng(0).random((50, 2)), (0, 0, 1, 1))  # doctest: +SKIP
>>> vf.io.write(d.cells, "cells.svg", sites=d.sites, boundary=d.boundary)  # doctest: +SKIP
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import shapely

from .dxf import write_dxf  # ezdxf itself is imported on first use
from .geojson import feature_collection, write_geojson
from .gif import write_gif
from .png import render_image, write_png
from .readers import read_boundary, read_points
from .svg import svg_string, write_layers, write_svg

__all__ = [
    "FORMATS",
    "dxf_units",
    "feature_collection",
    "read_boundary",
    "read_points",
    "render_image",
    "svg_string",
    "triangle_polygons",
    "write",
    "write_geojson",
    "write_png",
    "write_svg",
    "write_dxf",
    "write_gif",
    "write_layers",
]

#: Output suffixes understood by :func:`write`, and the format each one means.
FORMATS = {
    ".svg": "svg",
    ".png": "png",
    ".geojson": "geojson",
    ".json": "geojson",
    ".dxf": "dxf",
}


def dxf_units(units: str | None) -> str:
    """The DXF ``$INSUNITS`` name of an SVG ``units`` (``None``, px and pt: ``"unitless"``).

    SVG sizes come in screen and print units that DXF has no name for; those drawings are
    written without units, as a DXF without ``units`` is. Other names pass unchanged (the
    DXF writer refuses those it does not know).
    """
    return "unitless" if units in (None, "px", "pt") else units


def output_format(path) -> str:
    """Return the format (``"svg"``, ``"png"``, ``"geojson"``, ``"dxf"``) of ``path``'s suffix.

    Raises
    ------
    ValueError
        For a suffix no writer knows.
    """
    suffix = Path(path).suffix.lower()
    try:
        return FORMATS[suffix]
    except KeyError:
        raise ValueError(
            f"{path}: unsupported output type {suffix or '(none)'!r}; "
            f"use one of {', '.join(FORMATS)}"
        ) from None


def write(
    geoms,
    path,
    *,
    sites=None,
    boundary=None,
    properties=None,
    size: int = 1024,
    units: str | None = None,
) -> Path:
    """Write polygons to ``path`` in the format its suffix names (see :data:`FORMATS`).

    Parameters
    ----------
    geoms : sequence of shapely Polygon or MultiPolygon
        What to write, for example ``diagram.cells``.
    path : str or Path
        Output file; ``.svg``, ``.png``, ``.geojson``, ``.json`` or ``.dxf`` (the cells'
        edges on layer CELLS, each shared edge once, joined into runs: :func:`write_dxf`'s
        ``dedupe`` and ``merge``; the boundary on BOUNDARY, sites as POINTs on SITES).
    sites : (n, 2) array_like, optional
        Sites to draw (SVG, PNG) or to record per feature (GeoJSON).
    boundary : shapely geometry or (xmin, ymin, xmax, ymax), optional
        Outline to draw (SVG, PNG; GeoJSON ignores it).
    properties : mapping of name to sequence, optional
        Extra GeoJSON properties (other formats ignore them).
    size : int
        PNG size in pixels (longer side).
    units : str, optional
        SVG and DXF units, for example ``"mm"`` (a DXF without units, or in px or pt, which
        DXF cannot name, is ``unitless``: :func:`dxf_units`).

    Returns
    -------
    Path
        The file written.
    """
    kind = output_format(path)
    if kind == "svg":
        return write_svg(geoms, path, sites=sites, boundary=boundary, units=units)
    if kind == "png":
        return write_png(geoms, path, sites=sites, boundary=boundary, size=size)
    if kind == "dxf":
        layers = {}
        if boundary is not None:
            if isinstance(boundary, tuple | list):
                boundary = shapely.box(*boundary)
            layers["BOUNDARY"] = [boundary]
        if sites is not None:
            layers["SITES"] = [shapely.multipoints(np.asarray(sites, dtype=np.float64))]
        return write_dxf(geoms, path, layer="CELLS", layers=layers, units=dxf_units(units))
    return write_geojson(geoms, path, sites=sites, properties=properties)


def triangle_polygons(points, triangles) -> np.ndarray:
    """Triangles as shapely polygons, ready for the writers.

    Parameters
    ----------
    points : (n, 2) float64
        Vertex coordinates (``tri.points``).
    triangles : (t, 3) int
        Vertex indices (``tri.triangles``).

    Returns
    -------
    (t,) object array of shapely Polygon
    """
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    tris = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    if len(tris) == 0:
        return np.zeros(0, dtype=object)
    return shapely.polygons(pts[tris])
