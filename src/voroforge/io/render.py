"""A tiny render context shared by the writers, plus their common helpers.

Every writer draws geometry the same way: :func:`trace` walks the rings of a shapely
(Multi)Polygon and calls ``move_to`` / ``line_to`` / ``close_path`` on a context. The context
decides what the calls become: :class:`PathContext` builds an SVG path string and
:class:`RingContext` collects closed rings of points (for raster drawing, DXF polylines or a
canvas). A new output format only needs a new context.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import shapely

from ..config import DRAW_MAX_COORD

__all__ = [
    "PathContext",
    "RingContext",
    "as_boundary",
    "as_geometries",
    "data_bounds",
    "digits_for",
    "format_number",
    "palette",
    "trace",
]


def format_number(value: float, digits: int) -> str:
    """Format ``value`` with at most ``digits`` decimals, without trailing zeros or ``-0``."""
    text = f"{value:.{digits}f}"
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


class PathContext:
    """Render context that produces an SVG path ``d`` string.

    Parameters
    ----------
    digits : int
        Decimals written per coordinate.

    Examples
    --------
    >>> ctx = PathContext(digits=1)
    >>> ctx.move_to(0, 0); ctx.line_to(1, 0); ctx.line_to(0, 1.25); ctx.close_path()
    >>> str(ctx)
    'M0,0L1,0L0,1.2Z'
    """

    def __init__(self, digits: int = 6):
        self.digits = digits
        self._parts: list[str] = []

    def _xy(self, x: float, y: float) -> str:
        return f"{format_number(x, self.digits)},{format_number(y, self.digits)}"

    def move_to(self, x: float, y: float) -> None:
        """Start a new sub-path at ``(x, y)``."""
        self._parts.append("M" + self._xy(x, y))

    def line_to(self, x: float, y: float) -> None:
        """Draw a straight segment to ``(x, y)``."""
        self._parts.append("L" + self._xy(x, y))

    def close_path(self) -> None:
        """Close the current sub-path."""
        self._parts.append("Z")

    def __str__(self) -> str:
        return "".join(self._parts)


class RingContext:
    """Render context that collects closed rings as lists of ``(x, y)`` tuples.

    Examples
    --------
    >>> ctx = RingContext()
    >>> ctx.move_to(0, 0); ctx.line_to(1, 0); ctx.line_to(0, 1); ctx.close_path()
    >>> ctx.rings
    [[(0, 0), (1, 0), (0, 1)]]
    """

    def __init__(self):
        self.rings: list[list[tuple[float, float]]] = []

    def move_to(self, x: float, y: float) -> None:
        """Start a new ring at ``(x, y)``."""
        self.rings.append([(x, y)])

    def line_to(self, x: float, y: float) -> None:
        """Add ``(x, y)`` to the current ring."""
        self.rings[-1].append((x, y))

    def close_path(self) -> None:
        """Close the current ring (rings are always closed; nothing to record)."""


Transform = Callable[[np.ndarray], np.ndarray]


def _polygons(geom) -> list:
    """Return the polygon parts of a polygonal geometry (empty list for empty or non-polygonal)."""
    if geom is None or geom.is_empty:
        return []
    kind = geom.geom_type
    if kind == "Polygon":
        return [geom]
    if kind in ("MultiPolygon", "GeometryCollection"):
        return [p for part in geom.geoms for p in _polygons(part)]
    return []


def trace(ctx, geom, transform: Transform | None = None) -> int:
    """Draw every ring of a polygonal geometry on ``ctx``; return the number of rings.

    Parameters
    ----------
    ctx : object with ``move_to``, ``line_to`` and ``close_path``
        The render context.
    geom : shapely Polygon, MultiPolygon or GeometryCollection
        Non-polygonal parts and empty geometries draw nothing.
    transform : callable, optional
        Maps a ``(k, 2)`` array of coordinates to drawing coordinates.

    Returns
    -------
    int
        Rings drawn. Each ring is one ``move_to``, some ``line_to`` and one ``close_path``;
        holes are drawn as further rings (fill them with the even-odd rule).
    """
    count = 0
    for poly in _polygons(geom):
        for ring in (poly.exterior, *poly.interiors):
            xy = np.asarray(ring.coords)[:-1, :2]
            if len(xy) < 3:
                continue
            if transform is not None:
                xy = transform(xy)
            ctx.move_to(float(xy[0, 0]), float(xy[0, 1]))
            for x, y in xy[1:].tolist():
                ctx.line_to(x, y)
            ctx.close_path()
            count += 1
    return count


def as_geometries(geoms) -> np.ndarray:
    """Return ``geoms`` as a 1-D object array of shapely geometries (``None`` becomes empty).

    Raises
    ------
    ValueError
        If an element is not a shapely geometry.
    """
    if isinstance(geoms, shapely.Geometry):
        geoms = [geoms]
    out = np.array(list(geoms) if not isinstance(geoms, np.ndarray) else geoms, dtype=object)
    out = out.reshape(-1)
    for i, g in enumerate(out):
        if g is None:
            out[i] = shapely.Polygon()
        elif not isinstance(g, shapely.Geometry):
            raise ValueError(f"geometry {i} is a {type(g).__name__}, not a shapely geometry")
    return out


def as_boundary(boundary):
    """Return ``boundary`` as a shapely geometry or ``None``.

    ``(xmin, ymin, xmax, ymax)`` becomes a box; shapely geometries pass through.
    """
    if boundary is None or isinstance(boundary, shapely.Geometry):
        return boundary
    values = np.asarray(boundary, dtype=np.float64).reshape(-1)
    if values.shape != (4,):
        raise ValueError(
            f"boundary must be (xmin, ymin, xmax, ymax) or a shapely geometry; got {boundary!r}"
        )
    return shapely.box(*values.tolist())


def data_bounds(geoms: np.ndarray, sites=None, boundary=None) -> tuple[float, float, float, float]:
    """Bounds ``(xmin, ymin, xmax, ymax)`` of everything drawn, never of zero width or height."""
    parts = [g for g in geoms if not g.is_empty]
    if boundary is not None and not boundary.is_empty:
        parts.append(boundary)
    boxes = [shapely.total_bounds(np.array(parts, dtype=object))] if parts else []
    if sites is not None and len(sites):
        pts = np.asarray(sites, dtype=np.float64).reshape(-1, 2)
        boxes.append(np.concatenate((pts.min(axis=0), pts.max(axis=0))))
    if not boxes:
        return 0.0, 0.0, 1.0, 1.0
    b = np.array(boxes)
    xmin, ymin = b[:, 0].min(), b[:, 1].min()
    xmax, ymax = b[:, 2].max(), b[:, 3].max()
    with np.errstate(over="ignore"):
        span = max(xmax - xmin, ymax - ymin)
    far = max(abs(xmin), abs(ymin), abs(xmax), abs(ymax))
    if not (math.isfinite(span) and max(span, far) <= DRAW_MAX_COORD):
        # past DRAW_MAX_COORD the page's size, margins and pixel scale overflow float64
        raise ValueError(
            f"the drawing spans ({xmin:.6g}, {ymin:.6g}) to ({xmax:.6g}, {ymax:.6g}): its width"
            f" overflows float64 once drawn (coordinates and width up to {DRAW_MAX_COORD:g}),"
            " so no drawing or raster can hold it (write .geojson, .csv or .parquet, or scale"
            " the input)"
        )
    pad = span * 0.5 if span > 0 else max(1.0, abs(xmin), abs(ymin)) * 0.5
    if xmax - xmin <= 0:
        xmin, xmax = xmin - pad, xmax + pad
    if ymax - ymin <= 0:
        ymin, ymax = ymin - pad, ymax + pad
    return float(xmin), float(ymin), float(xmax), float(ymax)


def digits_for(span: float) -> int:
    """Decimals that keep about 1e-7 of ``span`` (coordinates stay exact enough to cut)."""
    if span <= 0 or not math.isfinite(span):
        return 6
    return int(min(12, max(0, 7 - math.floor(math.log10(span)))))


def palette(n: int, seed: int = 0) -> np.ndarray:
    """Return ``n`` distinct, light, pleasant colours as an ``(n, 3) uint8`` array.

    Hues step by the golden ratio from a seeded start, so consecutive colours differ
    strongly; saturation and value vary a little. The same ``(n, seed)`` gives the same
    colours.
    """
    rng = np.random.default_rng(seed)
    start = rng.random()
    hue = (start + 0.6180339887498949 * np.arange(n)) % 1.0
    sat = rng.uniform(0.22, 0.42, n)
    val = rng.uniform(0.88, 0.98, n)
    # HSV -> RGB, vectorised.
    h6 = hue * 6.0
    sector = np.floor(h6).astype(np.int64) % 6
    f = h6 - np.floor(h6)
    p = val * (1.0 - sat)
    q = val * (1.0 - sat * f)
    t = val * (1.0 - sat * (1.0 - f))
    table = np.stack(
        [
            np.stack([val, t, p], axis=-1),
            np.stack([q, val, p], axis=-1),
            np.stack([p, val, t], axis=-1),
            np.stack([p, q, val], axis=-1),
            np.stack([t, p, val], axis=-1),
            np.stack([val, p, q], axis=-1),
        ]
    )
    rgb = table[sector, np.arange(n)] if n else np.zeros((0, 3))
    return np.round(rgb * 255.0).astype(np.uint8)
