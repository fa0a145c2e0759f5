"""GeoJSON in: the points and the polygons of a file, with errors that name the file."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import shapely
from shapely.geometry import shape

from .files import existing_file

__all__ = [
    "geojson_crs",
    "geometries",
    "load_json",
    "read_geojson_point_table",
    "read_geojson_points",
    "read_geojson_polygons",
]


def load_json(path: Path):
    """Parse a JSON file (UTF-8, BOM allowed).

    Parameters
    ----------
    path : Path
        An existing file.

    Returns
    -------
    object
        The parsed document.

    Raises
    ------
    ValueError
        Invalid JSON (with its line) or not a text file.
    """
    try:
        return json.loads(path.read_text(encoding="utf-8-sig"))
    except json.JSONDecodeError as exc:
        raise ValueError(f"{path}: line {exc.lineno}: invalid JSON ({exc.msg})") from None
    except UnicodeDecodeError as exc:
        raise ValueError(f"{path}: not a text file ({exc.reason})") from None
    except RecursionError:  # json recurses once a level of [..] / {..}
        raise ValueError(f"{path}: invalid JSON (arrays or objects nested too deeply)") from None


def geometries(obj) -> list[dict]:
    """All geometry objects of a GeoJSON object (collections and features flattened).

    Parameters
    ----------
    obj : object
        A parsed GeoJSON document or any part of one.

    Returns
    -------
    list of dict
        Geometry objects (each with ``type`` and ``coordinates``), in document order.
    """
    if not isinstance(obj, dict):
        return []
    kind = obj.get("type")
    if kind == "FeatureCollection":
        return [g for f in obj.get("features") or [] for g in geometries(f)]
    if kind == "Feature":
        return geometries(obj.get("geometry"))
    if kind == "GeometryCollection":
        return [g for part in obj.get("geometries") or [] for g in geometries(part)]
    return [obj] if isinstance(kind, str) and "coordinates" in obj else []


def _found(geoms: list[dict]) -> str:
    kinds = sorted({g["type"] for g in geoms})
    return f" (found {', '.join(kinds)})" if kinds else ""


def _not_a_number(coords) -> tuple[bool, object]:
    """``(True, leaf)``: the first leaf of nested coordinates that is not a JSON number.

    ``(False, None)`` when every leaf is a number. Strings (``"0.5"``) and booleans would
    pass numpy's and shapely's conversions silently.
    """
    stack = [coords]
    while stack:
        c = stack.pop()
        if isinstance(c, (list, tuple)):
            stack.extend(reversed(c))
        elif isinstance(c, bool) or not isinstance(c, (int, float)):
            return True, c
    return False, None


def _point_features(obj, props=None):
    """``(coordinates, properties)`` of every point, features' properties carried along."""
    if not isinstance(obj, dict):
        return
    kind = obj.get("type")
    if kind == "FeatureCollection":
        for f in obj.get("features") or []:
            yield from _point_features(f)
    elif kind == "Feature":
        yield from _point_features(obj.get("geometry"), obj.get("properties") or {})
    elif kind == "GeometryCollection":
        for part in obj.get("geometries") or []:
            yield from _point_features(part, props)
    elif kind == "Point":
        yield obj.get("coordinates"), props or {}
    elif kind == "MultiPoint":
        for c in obj.get("coordinates") or []:
            yield c, props or {}


def _pointless_feature(doc) -> str | None:
    """Why a feature of a points file gives no point (None when each gives one or more).

    Each feature is one row or more (a MultiPoint's points); one with a null or empty
    geometry or no point in it would silently renumber every later row.
    """
    if not isinstance(doc, dict) or doc.get("type") != "FeatureCollection":
        return None
    features = doc.get("features")
    if not isinstance(features, list):
        return None
    for i, f in enumerate(features):
        if next(_point_features(f), None) is not None:
            continue
        geom = f.get("geometry") if isinstance(f, dict) else None
        name = f"feature {i}" + (
            f" (id {f['id']!r})" if isinstance(f, dict) and f.get("id") is not None else ""
        )
        if not isinstance(geom, dict):
            what = "has no geometry (null)"
        elif geom.get("type") in ("Point", "MultiPoint"):
            what = f"has an empty {geom.get('type')}"
        elif geom.get("type") == "GeometryCollection":
            what = "has no point in its GeometryCollection"
        else:
            what = f"is a {geom.get('type')}, not a Point or MultiPoint"
        return (
            f"{name} {what}: each feature is a row and cell i is row i, so it cannot be "
            "skipped; give it a point or remove the feature"
        )
    return None


def read_geojson_point_table(path) -> tuple[np.ndarray, dict]:
    """The points of a GeoJSON file and their features' properties, in file order.

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    points : (n, 2) float64
    attributes : dict of name -> list
        One column per property name met (in first-seen order); ``None`` where a feature
        lacks it. Every point of a MultiPoint gets its feature's properties.

    Raises
    ------
    ValueError
        No points in the file, coordinates that are not ``[x, y]`` numbers, or a feature
        without a point (null or empty geometry, a LineString among points, ...): skipping
        it would renumber the rows after it.
    """
    path = existing_file(path)
    doc = load_json(path)
    rows = list(_point_features(doc))
    if not rows:
        raise ValueError(f"{path}: no Point or MultiPoint geometries{_found(geometries(doc))}")
    pointless = _pointless_feature(doc)
    if pointless:
        raise ValueError(f"{path}: {pointless}")
    for k, (c, _) in enumerate(rows):
        found, bad = _not_a_number(c)
        if not found and not (isinstance(c, (list, tuple)) and len(c) >= 2):
            found, bad = True, c  # not a position: [x, y] or [x, y, z]
        if found or any(isinstance(v, (list, tuple)) for v in c):
            raise ValueError(
                f"{path}: point {k}'s coordinates are not [x, y] numbers (found {bad!r})"
            )
    try:
        arr = np.array([c[:2] for c, _ in rows], dtype=np.float64)
    except (TypeError, ValueError, IndexError):
        raise ValueError(f"{path}: point coordinates are not [x, y] numbers") from None
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"{path}: point coordinates are not [x, y] numbers")
    names: dict = {}
    for _, props in rows:
        for k in props:
            names.setdefault(str(k), None)
    attrs = {k: [props.get(k) for _, props in rows] for k in names}
    return arr, attrs


def read_geojson_points(path) -> np.ndarray:
    """The Point and MultiPoint coordinates of a GeoJSON file, in file order.

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    (n, 2) float64

    Raises
    ------
    ValueError
        No points in the file, or coordinates that are not ``[x, y]`` numbers.
    """
    return read_geojson_point_table(path)[0]


def geojson_crs(path):
    """The legacy ``"crs"`` member of a GeoJSON file (QGIS, GDAL), or None.

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    dict or None
    """
    doc = load_json(existing_file(path))
    crs = doc.get("crs") if isinstance(doc, dict) else None
    return crs if isinstance(crs, dict) else None


def read_geojson_polygons(path):
    """The polygons of a GeoJSON file as one domain (features united, holes kept).

    Several features, and the overlapping or edge-sharing parts of one MultiPolygon, are
    united; a part or polygon that is invalid by itself (a self-intersecting ring) is not
    repaired and fails the domain's checks with GEOS's reason.

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    shapely.Polygon or shapely.MultiPolygon

    Raises
    ------
    ValueError
        No polygons, malformed coordinates, or an invalid polygon among several.
    """
    path = existing_file(path)
    geoms = geometries(load_json(path))
    polygons = [g for g in geoms if g["type"] in ("Polygon", "MultiPolygon")]
    if not polygons:
        raise ValueError(f"{path}: no Polygon or MultiPolygon geometries{_found(geoms)}")
    for k, g in enumerate(polygons):
        found, bad = _not_a_number(g.get("coordinates"))
        if found:
            raise ValueError(f"{path}: polygon {k}'s coordinates are not numbers (found {bad!r})")
    try:
        shapes = [shape(g) for g in polygons]
    except (TypeError, ValueError, IndexError, KeyError, shapely.errors.ShapelyError) as exc:
        raise ValueError(f"{path}: malformed polygon coordinates ({exc})") from None
    shapes = [_united(s) for s in shapes]
    if len(shapes) == 1:
        return shapes[0]
    invalid = [i for i, s in enumerate(shapes) if not s.is_valid]
    if invalid:
        reason = shapely.is_valid_reason(shapes[invalid[0]])
        raise ValueError(f"{path}: polygon {invalid[0]} is invalid ({reason})")
    return shapely.union_all(shapes)


def _united(geom):
    """A MultiPolygon whose valid parts overlap or share edges, united; else ``geom``."""
    if geom.geom_type != "MultiPolygon":
        return geom
    try:  # GEOS squares coordinates: past ~1e150 it may raise; the domain's checks then decide
        if geom.is_valid:
            return geom
        parts = shapely.get_parts(geom)
        if not shapely.is_valid(parts).all():
            return geom
        return shapely.union_all(parts)
    except shapely.errors.GEOSException:
        return geom
