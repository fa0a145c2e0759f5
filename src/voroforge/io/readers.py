"""Readers for point sets and domains, with errors that name the file and the problem."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import shapely
from shapely.geometry import shape

__all__ = ["read_boundary", "read_points"]

_X_NAMES = ("x", "lon", "lng", "longitude", "easting")
_Y_NAMES = ("y", "lat", "latitude", "northing")
_POINT_SUFFIXES = (".csv", ".txt", ".xy", ".npy", ".geojson", ".json")


def _existing(path) -> Path:
    path = Path(path)
    if not path.exists():
        raise ValueError(f"{path}: no such file")
    if path.is_dir():
        raise ValueError(f"{path}: is a directory, not a file")
    return path


def _number(token: str) -> float | None:
    try:
        return float(token)
    except ValueError:
        return None


def _split(line: str, delimiter: str | None) -> list[str]:
    parts = line.split(delimiter) if delimiter else line.split()
    return [p.strip().strip("\"'").strip() for p in parts]


def _read_text(path: Path) -> np.ndarray:
    """Points from delimited text: commas, semicolons, tabs or spaces; optional header."""
    try:
        text = path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError as exc:
        raise ValueError(f"{path}: not a text file ({exc.reason})") from None
    rows = [
        (number, line.strip())
        for number, line in enumerate(text.splitlines(), start=1)
        if line.strip() and not line.lstrip().startswith("#")
    ]
    if not rows:
        raise ValueError(f"{path}: no points (the file is empty)")
    first = rows[0][1]
    delimiter = next((d for d in (",", ";", "\t") if d in first), None)

    columns = (0, 1)
    head = _split(first, delimiter)
    if any(_number(t) is None for t in head):  # a header row
        names = [t.lower() for t in head]
        xi = next((names.index(n) for n in _X_NAMES if n in names), None)
        yi = next((names.index(n) for n in _Y_NAMES if n in names), None)
        if xi is None or yi is None:
            if len(names) == 2:
                xi, yi = 0, 1
            else:
                raise ValueError(
                    f"{path}: line {rows[0][0]}: header {head} has no columns named x and y"
                )
        columns = (xi, yi)
        rows = rows[1:]
        if not rows:
            raise ValueError(f"{path}: no points (only a header row)")

    need = max(columns) + 1
    out = np.zeros((len(rows), 2), dtype=np.float64)
    for k, (number, line) in enumerate(rows):
        tokens = _split(line, delimiter)
        if len(tokens) < need:
            raise ValueError(
                f"{path}: line {number}: expected at least {need} columns, got {len(tokens)}"
            )
        for j, c in enumerate(columns):
            value = _number(tokens[c])
            if value is None:
                raise ValueError(f"{path}: line {number}: {tokens[c]!r} is not a number")
            if not math.isfinite(value):
                raise ValueError(f"{path}: line {number}: {tokens[c]!r} is not a finite number")
            out[k, j] = value
    return out


def _read_npy(path: Path) -> np.ndarray:
    try:
        arr = np.load(path, allow_pickle=False)
    except (ValueError, OSError) as exc:
        raise ValueError(f"{path}: not a readable .npy array ({exc})") from None
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"{path}: expected an (n, 2) array, got shape {arr.shape}")
    try:
        arr = arr.astype(np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"{path}: array of dtype {arr.dtype} is not numeric") from None
    if not np.isfinite(arr).all():
        row = int(np.flatnonzero(~np.isfinite(arr).all(axis=1))[0])
        raise ValueError(f"{path}: row {row} is not finite: {arr[row].tolist()}")
    return arr


def _load_json(path: Path):
    try:
        return json.loads(path.read_text(encoding="utf-8-sig"))
    except json.JSONDecodeError as exc:
        raise ValueError(f"{path}: line {exc.lineno}: invalid JSON ({exc.msg})") from None
    except UnicodeDecodeError as exc:
        raise ValueError(f"{path}: not a text file ({exc.reason})") from None


def _geometries(obj) -> list[dict]:
    """All geometry objects of a GeoJSON object (collections and features flattened)."""
    if not isinstance(obj, dict):
        return []
    kind = obj.get("type")
    if kind == "FeatureCollection":
        return [g for f in obj.get("features") or [] for g in _geometries(f)]
    if kind == "Feature":
        return _geometries(obj.get("geometry"))
    if kind == "GeometryCollection":
        return [g for part in obj.get("geometries") or [] for g in _geometries(part)]
    return [obj] if isinstance(kind, str) and "coordinates" in obj else []


def _read_geojson_points(path: Path) -> np.ndarray:
    geoms = _geometries(_load_json(path))
    coords: list = []
    for g in geoms:
        if g["type"] == "Point":
            coords.append(g["coordinates"])
        elif g["type"] == "MultiPoint":
            coords.extend(g["coordinates"])
    if not coords:
        found = sorted({g["type"] for g in geoms})
        what = f" (found {', '.join(found)})" if found else ""
        raise ValueError(f"{path}: no Point or MultiPoint geometries{what}")
    try:
        arr = np.array([c[:2] for c in coords], dtype=np.float64)
    except (TypeError, ValueError, IndexError):
        raise ValueError(f"{path}: point coordinates are not [x, y] numbers") from None
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"{path}: point coordinates are not [x, y] numbers")
    return arr


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
    path = _existing(path)
    suffix = path.suffix.lower()
    if suffix in (".csv", ".txt", ".xy"):
        points = _read_text(path)
    elif suffix == ".npy":
        points = _read_npy(path)
    elif suffix in (".geojson", ".json"):
        points = _read_geojson_points(path)
    else:
        raise ValueError(
            f"{path}: unsupported point file type {suffix or '(none)'!r}; "
            f"use one of {', '.join(_POINT_SUFFIXES)}"
        )
    if len(points) == 0:
        raise ValueError(f"{path}: no points")
    return np.ascontiguousarray(points, dtype=np.float64)


def _parse_bbox(text: str) -> tuple[float, float, float, float] | None:
    parts = [p.strip() for p in text.split(",")]
    if len(parts) != 4:
        return None
    values = [_number(p) for p in parts]
    if any(v is None for v in values):
        return None
    xmin, ymin, xmax, ymax = values
    if not all(math.isfinite(v) for v in values) or not (xmin < xmax and ymin < ymax):
        raise ValueError(f"boundary {text!r}: need finite numbers with xmin < xmax and ymin < ymax")
    return xmin, ymin, xmax, ymax


def read_boundary(spec):
    """Read a domain: ``"xmin,ymin,xmax,ymax"`` or a GeoJSON file of polygons.

    Parameters
    ----------
    spec : str, Path, tuple or shapely geometry
        A bounding-box string, a path to a GeoJSON file whose polygonal features are united
        into one domain (holes kept), or an already parsed tuple/geometry (passed through).

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
    path = _existing(path)
    geoms = _geometries(_load_json(path))
    polygons = [g for g in geoms if g["type"] in ("Polygon", "MultiPolygon")]
    if not polygons:
        found = sorted({g["type"] for g in geoms})
        what = f" (found {', '.join(found)})" if found else ""
        raise ValueError(f"{path}: no Polygon or MultiPolygon geometries{what}")
    try:
        shapes = [shape(g) for g in polygons]
    except (TypeError, ValueError, IndexError, KeyError, shapely.errors.ShapelyError) as exc:
        raise ValueError(f"{path}: malformed polygon coordinates ({exc})") from None
    if len(shapes) == 1:
        return shapes[0]
    invalid = [i for i, s in enumerate(shapes) if not s.is_valid]
    if invalid:
        reason = shapely.is_valid_reason(shapes[invalid[0]])
        raise ValueError(f"{path}: polygon {invalid[0]} is invalid ({reason})")
    return shapely.union_all(shapes)
