"""GeoJSON output: a FeatureCollection with one Feature per cell, in cell order."""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from pathlib import Path

import numpy as np
import shapely
from shapely.geometry import mapping

from .render import as_geometries

__all__ = ["feature_collection", "write_geojson"]


def _plain(value):
    """Convert numpy scalars/arrays and tuples to JSON-ready Python values (NaN -> None)."""
    if isinstance(value, np.ndarray):
        return [_plain(v) for v in value.tolist()]
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, list | tuple):
        return [_plain(v) for v in value]
    if isinstance(value, Mapping):
        return {str(k): _plain(v) for k, v in value.items()}
    return value


def _per_feature(properties, n: int) -> list[dict]:
    """Turn ``properties`` (columns mapping or list of dicts) into one dict per feature."""
    if properties is None:
        return [{} for _ in range(n)]
    if isinstance(properties, Mapping):
        rows: list[dict] = [{} for _ in range(n)]
        for key, column in properties.items():
            values = list(column)
            if len(values) != n:
                raise ValueError(f"property {key!r} has {len(values)} values for {n} geometries")
            for row, v in zip(rows, values, strict=True):
                row[str(key)] = v
        return rows
    rows = [dict(r) for r in properties]
    if len(rows) != n:
        raise ValueError(f"properties has {len(rows)} rows for {n} geometries")
    return rows


def feature_collection(geoms, *, sites=None, properties=None) -> dict:
    """Build a GeoJSON FeatureCollection; see :func:`write_geojson` for the parameters.

    Returns
    -------
    dict
        JSON-ready ``{"type": "FeatureCollection", "features": [...]}``.
    """
    # RFC 7946 3.1.6: exterior rings counter-clockwise, holes clockwise (the design's
    # buffered cells and openings come out of GEOS clockwise); rings already so are untouched
    cells = shapely.orient_polygons(as_geometries(geoms), exterior_cw=False)
    n = len(cells)
    pts = None
    if sites is not None:
        pts = np.asarray(sites, dtype=np.float64).reshape(-1, 2)
        if len(pts) != n:
            raise ValueError(f"sites has {len(pts)} points for {n} geometries")
    areas = shapely.area(cells) if n else np.zeros(0)
    extra = _per_feature(properties, n)
    features = []
    for i, geom in enumerate(cells):
        props = {"index": i}
        if pts is not None:
            props["site"] = pts[i].tolist()
        props["area"] = float(areas[i])
        props.update(extra[i])
        geometry = None if geom.is_empty else _plain(mapping(geom))
        features.append({"type": "Feature", "properties": _plain(props), "geometry": geometry})
    return {"type": "FeatureCollection", "features": features}


def write_geojson(geoms, path, *, sites=None, properties=None, crs=None) -> Path:
    """Write polygons (for example ``diagram.cells``) as a GeoJSON FeatureCollection.

    Feature ``i`` is geometry ``i`` with properties ``{"index": i, "site": [x, y],
    "area": a}`` (``site`` only when ``sites`` is given) plus any extra ``properties``.
    Empty cells are kept, with a ``null`` geometry, so feature order always matches cell
    order. Coordinates are plain floats, unrounded.

    Parameters
    ----------
    geoms : sequence of shapely geometries
        One feature each.
    path : str or Path
        Output file (``.geojson`` or ``.json``).
    sites : (n, 2) array_like, optional
        Site of each cell.
    properties : mapping of name to sequence, or sequence of dicts, optional
        Extra properties: columns of length ``n`` or one dict per feature.
    crs : dict, optional
        A legacy GeoJSON ``"crs"`` member (``{"type": "name", "properties": {"name":
        "urn:ogc:def:crs:EPSG::32633"}}``) for coordinates that are not WGS 84 lon/lat, as
        QGIS and GDAL read and write it; copied as given.

    Returns
    -------
    Path
        The file written.

    Examples
    --------
    >>> import shapely, tempfile, pathlib, json
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "cells.geojson"
    >>> _ = write_geojson([shapely.box(0, 0, 2, 1)], out, sites=[[1, 0.5]])
    >>> json.loads(out.read_text())["features"][0]["properties"]
    {'index': 0, 'site': [1.0, 0.5], 'area': 2.0}
    """
    collection = feature_collection(geoms, sites=sites, properties=properties)
    lines = [json.dumps(f, allow_nan=False, separators=(",", ":")) for f in collection["features"]]
    body = ",\n".join(lines)
    head = '{"type":"FeatureCollection",'
    if crs is not None:
        head += '"crs":' + json.dumps(crs, allow_nan=False, separators=(",", ":")) + ","
    text = head + '"features":[\n' + body + ("\n" if body else "") + "]}\n"
    from .atomic import write_atomically

    return write_atomically(path, lambda tmp: Path(tmp).write_text(text, encoding="utf-8"))
