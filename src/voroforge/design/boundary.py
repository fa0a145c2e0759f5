"""Boundaries (the part to be cut): primitives, validation and readers for GeoJSON, SVG, DXF.

Every function returns a valid shapely ``Polygon`` or ``MultiPolygon`` in millimetres (or
the file's drawing units, see :func:`from_svg`). Curves (SVG Béziers and arcs, DXF bulges,
circles and ellipses) are flattened to polylines whose distance from the true curve is at
most ``tolerance``. Closed curves are combined by the even-odd rule: a curve inside another
one is a hole, a curve inside a hole is an island again.
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import shapely

__all__ = [
    "circle",
    "curves_from_svg",
    "from_dxf",
    "from_geojson",
    "from_svg",
    "load",
    "polygon",
    "polygonal_part",
    "rectangle",
    "svg_in_mm",
    "union",
]

_DEFAULT_TOL = 0.01  # mm: well below laser and CNC resolution


# ----------------------------------------------------------------------------- validation


def _finite(value, name: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return v


def _positive(value, name: str) -> float:
    v = _finite(value, name)
    if v <= 0:
        raise ValueError(f"{name} must be > 0, got {value!r}")
    return v


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
    w = _positive(width, "width")
    h = _positive(height, "height")
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
    r = _positive(radius, "radius")
    cx, cy = _xy(center, "center")
    if int(segments) != segments or segments < 3:
        raise ValueError(f"segments must be an integer >= 3, got {segments!r}")
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
    out = shapely.union_all(np.asarray(geoms, dtype=object))
    return as_polygonal(polygonal_part(out), "union")


def polygonal_part(geom):
    """The polygonal part of a GEOS result (drops stray lines/points of collections)."""
    if isinstance(geom, shapely.Polygon | shapely.MultiPolygon):
        return geom
    parts = [g for g in getattr(geom, "geoms", []) if isinstance(g, shapely.Polygon)]
    parts += [
        p
        for g in getattr(geom, "geoms", [])
        if isinstance(g, shapely.MultiPolygon)
        for p in g.geoms
    ]
    if not parts:
        return shapely.Polygon()
    return parts[0] if len(parts) == 1 else shapely.MultiPolygon(parts)


def even_odd(rings) -> shapely.Polygon | shapely.MultiPolygon:
    """Combine closed rings by the even-odd rule (nested ring = hole, and so on).

    Parameters
    ----------
    rings : sequence of (k, 2) float64
        Closed curves (closing vertex optional). Self-intersecting rings are repaired
        with ``shapely.make_valid`` (both lobes kept).

    Returns
    -------
    shapely.Polygon or shapely.MultiPolygon
        Possibly empty when no ring encloses area.
    """
    result = shapely.Polygon()
    for ring in rings:
        arr = np.asarray(ring, dtype=np.float64)
        if len(arr) >= 2 and (arr[0] == arr[-1]).all():
            arr = arr[:-1]
        if len(arr) < 3:
            continue
        poly = shapely.Polygon(arr)
        if not poly.is_valid:
            poly = polygonal_part(shapely.make_valid(poly))
        if poly.is_empty or poly.area <= 0:
            continue
        result = shapely.symmetric_difference(result, poly)
    result = polygonal_part(result)
    return shapely.orient_polygons(result) if not result.is_empty else result


# ----------------------------------------------------------------------------- curve flattening


def _arc_points(cx, cy, rx, ry, phi, t0, dt, tol) -> np.ndarray:
    """Points of an elliptical arc (centre, radii, x-rotation phi, start angle, sweep).

    Excludes the start point, includes the end point. The chord error is <= ``tol``.
    """
    r = max(rx, ry)
    if r <= tol:
        n = 1
    else:
        step = 2.0 * math.acos(max(-1.0, 1.0 - tol / r))
        n = max(1, math.ceil(abs(dt) / step))
    t = t0 + dt * np.arange(1, n + 1) / n
    c, s = math.cos(phi), math.sin(phi)
    x = rx * np.cos(t)
    y = ry * np.sin(t)
    return np.column_stack((cx + c * x - s * y, cy + s * x + c * y))


def _bezier_points(ctrl: np.ndarray, tol: float) -> np.ndarray:
    """Flatten a quadratic (3 control points) or cubic (4) Bézier; start point excluded.

    The number of uniform parameter steps comes from the bound on the second derivative
    (deviation <= M / (8 n^2)), so the polyline is within ``tol`` of the curve.
    """
    if len(ctrl) == 3:
        m = 2.0 * np.linalg.norm(ctrl[0] - 2 * ctrl[1] + ctrl[2])
    else:
        m = 6.0 * max(
            np.linalg.norm(ctrl[0] - 2 * ctrl[1] + ctrl[2]),
            np.linalg.norm(ctrl[1] - 2 * ctrl[2] + ctrl[3]),
        )
    n = max(1, math.ceil(math.sqrt(m / (8.0 * tol))))
    t = (np.arange(1, n + 1) / n)[:, None]
    u = 1.0 - t
    if len(ctrl) == 3:
        return u * u * ctrl[0] + 2 * u * t * ctrl[1] + t * t * ctrl[2]
    return u**3 * ctrl[0] + 3 * u * u * t * ctrl[1] + 3 * u * t * t * ctrl[2] + t**3 * ctrl[3]


def _svg_arc(p0, rx, ry, angle_deg, large, sweep, p1, tol) -> np.ndarray:
    """SVG endpoint-parameterised arc to points (SVG 1.1 implementation notes F.6.5)."""
    x1, y1 = p0
    x2, y2 = p1
    rx, ry = abs(rx), abs(ry)
    if (x1 == x2 and y1 == y2) or rx == 0 or ry == 0:
        return np.array([[x2, y2]], dtype=np.float64)
    phi = math.radians(angle_deg % 360.0)
    c, s = math.cos(phi), math.sin(phi)
    dx, dy = (x1 - x2) / 2.0, (y1 - y2) / 2.0
    xp = c * dx + s * dy
    yp = -s * dx + c * dy
    lam = (xp / rx) ** 2 + (yp / ry) ** 2
    if lam > 1.0:  # radii too small: scale them up until the arc just fits
        rx *= math.sqrt(lam)
        ry *= math.sqrt(lam)
    num = rx * rx * ry * ry - rx * rx * yp * yp - ry * ry * xp * xp
    den = rx * rx * yp * yp + ry * ry * xp * xp
    coef = math.sqrt(max(0.0, num / den))
    if large == sweep:
        coef = -coef
    cxp = coef * rx * yp / ry
    cyp = -coef * ry * xp / rx
    cx = c * cxp - s * cyp + (x1 + x2) / 2.0
    cy = s * cxp + c * cyp + (y1 + y2) / 2.0
    ux, uy = (xp - cxp) / rx, (yp - cyp) / ry
    vx, vy = (-xp - cxp) / rx, (-yp - cyp) / ry
    t0 = math.atan2(uy, ux)
    dt = math.atan2(ux * vy - uy * vx, ux * vx + uy * vy)
    if not sweep and dt > 0:
        dt -= 2.0 * math.pi
    elif sweep and dt < 0:
        dt += 2.0 * math.pi
    pts = _arc_points(cx, cy, rx, ry, phi, t0, dt, tol)
    pts[-1] = (x2, y2)  # land exactly on the end point
    return pts


# ----------------------------------------------------------------------------- SVG

_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_COMMANDS = "MmLlHhVvCcSsQqTtAaZz"
_ARGS = {"M": 2, "L": 2, "H": 1, "V": 1, "C": 6, "S": 4, "Q": 4, "T": 2, "A": 7, "Z": 0}


class _Scanner:
    """Tokenizer for SVG path data: commands, numbers and single-character arc flags."""

    def __init__(self, text: str):
        self.text = text
        self.pos = 0

    def _skip(self):
        text = self.text
        while self.pos < len(text) and (text[self.pos].isspace() or text[self.pos] == ","):
            self.pos += 1

    def command(self) -> str | None:
        self._skip()
        if self.pos < len(self.text) and self.text[self.pos] in _COMMANDS:
            self.pos += 1
            return self.text[self.pos - 1]
        return None

    def at_number(self) -> bool:
        self._skip()
        return self.pos < len(self.text) and self.text[self.pos] in "+-.0123456789"

    def done(self) -> bool:
        self._skip()
        return self.pos >= len(self.text)

    def number(self) -> float:
        self._skip()
        m = _NUMBER.match(self.text, self.pos)
        if not m:
            raise ValueError(f"expected a number at character {self.pos}")
        self.pos = m.end()
        return float(m.group())

    def flag(self) -> int:
        self._skip()
        ch = self.text[self.pos : self.pos + 1]
        if ch not in ("0", "1"):
            raise ValueError(f"expected an arc flag 0 or 1 at character {self.pos}")
        self.pos += 1
        return int(ch)


def path_rings(d: str, *, tolerance: float = _DEFAULT_TOL) -> list[np.ndarray]:
    """Flatten SVG path data into closed rings (one per subpath, as a fill would close it).

    Parameters
    ----------
    d : str
        The ``d`` attribute: commands M/m L/l H/h V/v C/c S/s Q/q T/t A/a Z/z.
    tolerance : float
        Largest distance between a curve and its polyline.

    Returns
    -------
    list of (k, 2) float64
        The subpaths (in path coordinates); subpaths with fewer than 3 points are dropped.

    Raises
    ------
    ValueError
        Malformed path data (position of the problem in the message).
    """
    return [pts for pts, _ in _subpaths(d, tolerance) if len(pts) >= 3]


def path_lines(d: str, *, tolerance: float = _DEFAULT_TOL) -> list[np.ndarray]:
    """Flatten SVG path data into polylines, one per subpath (for curve attractors).

    Subpaths closed with ``Z`` end with their first point repeated; open ones stay open.

    Returns
    -------
    list of (k >= 2, 2) float64
    """
    out = []
    for pts, closed in _subpaths(d, tolerance):
        if closed and not (pts[0] == pts[-1]).all():
            pts = np.vstack((pts, pts[:1]))
        if len(pts) >= 2:
            out.append(pts)
    return out


def _subpaths(d: str, tolerance) -> list[tuple[np.ndarray, bool]]:
    """Parse path data into ``(points, closed)`` per subpath."""
    tol = _positive(tolerance, "tolerance")
    sc = _Scanner(d)
    rings: list[tuple[np.ndarray, bool]] = []
    current: list[np.ndarray] = []
    pos = np.zeros(2)
    start = np.zeros(2)
    last_ctrl = None  # reflected control point for S/s and T/t
    last_cmd = ""
    cmd = sc.command()
    if cmd is None and not sc.done():
        raise ValueError("path data must start with a command (M or m)")

    def flush(closed=False):
        if current:
            rings.append((np.vstack(current), closed))
            current.clear()

    while cmd is not None:
        upper = cmd.upper()
        rel = cmd.islower()
        if upper == "Z":
            flush(closed=True)
            pos = start.copy()
            last_ctrl, last_cmd = None, "Z"
            cmd = sc.command()
            if cmd is None and not sc.done():
                raise ValueError(f"unexpected text after Z at character {sc.pos}")
            continue
        first = True
        while first or sc.at_number():
            base = pos if rel else np.zeros(2)
            if upper == "M":
                p = np.array([sc.number(), sc.number()]) + base
                if first:
                    flush()
                    start = p.copy()
                    current.append(p[None])
                else:  # implicit lineto
                    current.append(p[None])
                pos = p
                last_ctrl = None
            elif upper in ("L", "H", "V"):
                if upper == "L":
                    p = np.array([sc.number(), sc.number()]) + base
                elif upper == "H":
                    p = np.array([sc.number() + (pos[0] if rel else 0.0), pos[1]])
                else:
                    p = np.array([pos[0], sc.number() + (pos[1] if rel else 0.0)])
                if not current:
                    current.append(pos[None])
                current.append(p[None])
                pos = p
                last_ctrl = None
            elif upper in ("C", "S"):
                if upper == "C":
                    c1 = np.array([sc.number(), sc.number()]) + base
                else:
                    c1 = 2 * pos - last_ctrl if last_cmd in "CS" and last_ctrl is not None else pos
                c2 = np.array([sc.number(), sc.number()]) + base
                p = np.array([sc.number(), sc.number()]) + base
                if not current:
                    current.append(pos[None])
                current.append(_bezier_points(np.array([pos, c1, c2, p]), tol))
                pos, last_ctrl = p, c2
            elif upper in ("Q", "T"):
                if upper == "Q":
                    c1 = np.array([sc.number(), sc.number()]) + base
                else:
                    c1 = 2 * pos - last_ctrl if last_cmd in "QT" and last_ctrl is not None else pos
                p = np.array([sc.number(), sc.number()]) + base
                if not current:
                    current.append(pos[None])
                current.append(_bezier_points(np.array([pos, c1, p]), tol))
                pos, last_ctrl = p, c1
            else:  # A
                rx, ry, ang = sc.number(), sc.number(), sc.number()
                large, sweep = sc.flag(), sc.flag()
                p = np.array([sc.number(), sc.number()]) + base
                if not current:
                    current.append(pos[None])
                current.append(_svg_arc(pos, rx, ry, ang, large, sweep, p, tol))
                pos = p
                last_ctrl = None
            last_cmd = "L" if upper == "M" else upper
            first = False
        cmd = sc.command()
        if cmd is None and not sc.done():
            raise ValueError(f"unexpected character {sc.text[sc.pos]!r} at {sc.pos}")
    flush()
    return rings


_TRANSFORM = re.compile(r"(matrix|translate|scale|rotate|skewX|skewY)\s*\(([^)]*)\)")


def _transform(text: str | None) -> np.ndarray:
    """Parse an SVG ``transform`` attribute into a 3×3 affine matrix."""
    m = np.eye(3)
    if not text:
        return m
    for name, args in _TRANSFORM.findall(text):
        v = [float(a) for a in _NUMBER.findall(args)]
        t = np.eye(3)
        if name == "matrix" and len(v) == 6:
            t[:2] = [[v[0], v[2], v[4]], [v[1], v[3], v[5]]]
        elif name == "translate" and v:
            t[0, 2], t[1, 2] = v[0], v[1] if len(v) > 1 else 0.0
        elif name == "scale" and v:
            t[0, 0], t[1, 1] = v[0], v[1] if len(v) > 1 else v[0]
        elif name == "rotate" and v:
            a = math.radians(v[0])
            r = np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0], [0, 0, 1]])
            if len(v) == 3:
                tr, back = np.eye(3), np.eye(3)
                tr[:2, 2] = v[1], v[2]
                back[:2, 2] = -v[1], -v[2]
                r = tr @ r @ back
            t = r
        elif name == "skewX" and v:
            t[0, 1] = math.tan(math.radians(v[0]))
        elif name == "skewY" and v:
            t[1, 0] = math.tan(math.radians(v[0]))
        else:
            raise ValueError(f"malformed transform {name}({args})")
        m = m @ t
    return m


_LENGTH = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([a-z%]*)\s*$")
_MM_PER_UNIT = {
    "mm": 1.0,
    "cm": 10.0,
    "in": 25.4,
    "pt": 25.4 / 72,
    "pc": 25.4 / 6,
    "px": 25.4 / 96,
    "q": 0.25,
}
_SKIP = {"defs", "clipPath", "mask", "pattern", "symbol", "marker", "metadata", "style"}


def _attr_float(el, name: str, default: float = 0.0) -> float:
    text = el.get(name)
    if text is None:
        return default
    m = _LENGTH.match(text)
    if not m:
        raise ValueError(f"<{_tag(el)}> attribute {name}={text!r} is not a number")
    return float(m.group(1))


def _tag(el) -> str:
    return el.tag.rsplit("}", 1)[-1] if isinstance(el.tag, str) else ""


def _element_rings(el, tol: float) -> list[np.ndarray]:
    tag = _tag(el)
    if tag == "path":
        return path_rings(el.get("d", ""), tolerance=tol)
    if tag == "polygon":
        v = [float(a) for a in _NUMBER.findall(el.get("points", ""))]
        return [np.array(v[: len(v) // 2 * 2]).reshape(-1, 2)] if len(v) >= 6 else []
    if tag == "rect":
        x, y = _attr_float(el, "x"), _attr_float(el, "y")
        w, h = _attr_float(el, "width"), _attr_float(el, "height")
        if w <= 0 or h <= 0:
            return []
        rx = el.get("rx")
        ry = el.get("ry")
        rx = _attr_float(el, "rx") if rx is not None else (_attr_float(el, "ry") if ry else 0.0)
        ry = _attr_float(el, "ry") if ry is not None else rx
        rx, ry = min(rx, w / 2), min(ry, h / 2)
        if rx <= 0 or ry <= 0:
            return [np.array([[x, y], [x + w, y], [x + w, y + h], [x, y + h]])]
        corners = [
            (x + w - rx, y + ry, -np.pi / 2),
            (x + w - rx, y + h - ry, 0.0),
            (x + rx, y + h - ry, np.pi / 2),
            (x + rx, y + ry, np.pi),
        ]
        pts = [_arc_points(cx, cy, rx, ry, 0.0, t0, np.pi / 2, tol) for cx, cy, t0 in corners]
        return [np.vstack(pts)]
    if tag in ("circle", "ellipse"):
        cx, cy = _attr_float(el, "cx"), _attr_float(el, "cy")
        if tag == "circle":
            rx = ry = _attr_float(el, "r")
        else:
            rx, ry = _attr_float(el, "rx"), _attr_float(el, "ry")
        if rx <= 0 or ry <= 0:
            return []
        return [_arc_points(cx, cy, rx, ry, 0.0, 0.0, 2 * np.pi, tol)]
    return []


def _element_lines(el, tol: float) -> list[np.ndarray]:
    """Outlines of an element as polylines (closed shapes repeat their first point)."""
    tag = _tag(el)
    if tag == "path":
        return path_lines(el.get("d", ""), tolerance=tol)
    if tag == "line":
        a = [_attr_float(el, k) for k in ("x1", "y1", "x2", "y2")]
        return [np.array(a).reshape(2, 2)]
    if tag == "polyline":
        v = [float(a) for a in _NUMBER.findall(el.get("points", ""))]
        return [np.array(v[: len(v) // 2 * 2]).reshape(-1, 2)] if len(v) >= 4 else []
    return [np.vstack((r, r[:1])) for r in _element_rings(el, tol)]


def _read_svg(p: Path, tol: float, flip_y: bool, reader) -> list[np.ndarray]:
    """Every element's point lists (from ``reader(el, tol)``) in output coordinates."""
    try:
        root = ET.parse(p).getroot()
    except ET.ParseError as exc:
        raise ValueError(f"{p}: not a valid SVG/XML file ({exc})") from None
    scale, box = _document_scale(root)
    found_all: list[np.ndarray] = []

    def walk(el, matrix):
        tag = _tag(el)
        if tag in _SKIP:
            return
        m = matrix @ _transform(el.get("transform"))
        try:
            found = reader(el, tol / max(scale * _matrix_scale(m), 1e-300))
        except ValueError as exc:
            raise ValueError(f"{p}: <{tag} id={el.get('id')!r}>: {exc}") from None
        for r in found:
            found_all.append(r @ m[:2, :2].T + m[:2, 2])
        for child in el:
            walk(child, m)

    walk(root, np.eye(3))
    out = [r * scale for r in found_all]
    if flip_y and out:
        top = (box[1] + box[3]) * scale if box is not None else max(r[:, 1].max() for r in out)
        out = [np.column_stack((r[:, 0], top - r[:, 1])) for r in out]
    return out


def _document_scale(root) -> tuple[float, np.ndarray]:
    """Scale from user units to mm (1 when width has no physical unit) and the viewBox."""
    vb = root.get("viewBox")
    box = None
    if vb:
        v = [float(a) for a in _NUMBER.findall(vb)]
        if len(v) == 4 and v[2] > 0 and v[3] > 0:
            box = np.array(v)
    width = root.get("width")
    m = _LENGTH.match(width) if width else None
    if m and m.group(2) in _MM_PER_UNIT:
        mm = float(m.group(1)) * _MM_PER_UNIT[m.group(2)]
        return (mm / box[2] if box is not None else _MM_PER_UNIT[m.group(2)]), box
    return 1.0, box


def svg_in_mm(path) -> bool:
    """True when the SVG's root ``width`` has a physical unit, so :func:`from_svg` reads mm.

    Parameters
    ----------
    path : str or Path
        The SVG file.

    Returns
    -------
    bool
    """
    import xml.etree.ElementTree as ET

    m = _LENGTH.match(ET.parse(_existing(path)).getroot().get("width") or "")
    return bool(m and m.group(2) in _MM_PER_UNIT)


def from_svg(path, *, tolerance: float = _DEFAULT_TOL, flip_y: bool = True):
    """Read the filled shapes of an SVG file as one boundary (even-odd nesting).

    Reads ``<path>`` (all commands, absolute and relative, curves and arcs flattened),
    ``<polygon>``, ``<rect>`` (rounded corners too), ``<circle>`` and ``<ellipse>``;
    ``transform`` attributes on elements and their ``<g>`` parents are applied. Each
    subpath is a closed ring, and all rings of the file are combined by the even-odd rule,
    so a shape drawn inside another is a hole. Ignored: ``<defs>``/``<clipPath>``/
    ``<mask>``/``<symbol>`` content, ``<use>``, ``<polyline>``/``<line>`` (not closed), text,
    CSS styles (fill rules and strokes: everything counts as a filled outline).

    Parameters
    ----------
    path : str or Path
        The SVG file.
    tolerance : float
        Largest distance between a curve and its polyline, in output units.
    flip_y : bool
        SVG's y axis points down. True (default): the result has y up with the bottom of the
        ``viewBox`` (or the drawing's lowest point, without a viewBox) at y = 0, so it looks
        the same as in a drawing program and ``voroforge.io.write_svg`` writes it back upright.

    Returns
    -------
    shapely.Polygon or shapely.MultiPolygon
        In millimetres when the root ``width`` has a physical unit (``"600mm"``, ``"8in"``,
        ``"96px"`` at 96 px per inch) and a ``viewBox``; otherwise 1 user unit = 1 mm.

    Raises
    ------
    ValueError
        Missing or unreadable file, malformed path data, or no closed shape with area.
    """
    p = _existing(path)
    tol = _positive(tolerance, "tolerance")
    rings = _read_svg(p, tol, flip_y, _element_rings)
    if not rings:
        raise ValueError(f"{p}: no closed shapes (path, polygon, rect, circle, ellipse)")
    out = even_odd(rings)
    if out.is_empty:
        raise ValueError(f"{p}: the shapes enclose no area")
    return as_polygonal(out, str(p))


def curves_from_svg(path, *, tolerance: float = _DEFAULT_TOL, flip_y: bool = True):
    """Read every outline of an SVG file as lines (for :class:`CurveAttractor`, say).

    Open and closed ``<path>`` subpaths, ``<line>``, ``<polyline>``, ``<polygon>``,
    ``<rect>``, ``<circle>`` and ``<ellipse>``, with transforms, units and the y flip of
    :func:`from_svg`.

    Parameters
    ----------
    path : str or Path
        The SVG file.
    tolerance : float
        Largest distance between a curve and its polyline, in output units.
    flip_y : bool
        As in :func:`from_svg`.

    Returns
    -------
    shapely.MultiLineString
    """
    p = _existing(path)
    tol = _positive(tolerance, "tolerance")
    lines = [ln for ln in _read_svg(p, tol, flip_y, _element_lines) if len(ln) >= 2]
    if not lines:
        raise ValueError(f"{p}: no curves (path, line, polyline, polygon, rect, circle, ellipse)")
    return shapely.MultiLineString(lines)


def _matrix_scale(m: np.ndarray) -> float:
    """Largest stretch of an affine matrix (so the flattening tolerance survives it)."""
    return float(np.linalg.svd(m[:2, :2], compute_uv=False).max())


# ----------------------------------------------------------------------------- DXF


def _bulge_polyline(points: np.ndarray, bulges: np.ndarray, closed: bool, tol: float):
    """Vertices of a polyline whose segments carry DXF bulges (tan of a quarter of the arc)."""
    n = len(points)
    out = [points[:1]]
    last = n if closed else n - 1
    for i in range(last):
        a = points[i]
        b = points[(i + 1) % n]
        bulge = bulges[i]
        if bulge == 0.0 or (a == b).all():
            out.append(b[None])
            continue
        theta = 4.0 * math.atan(bulge)  # signed included angle, > 0 counter-clockwise
        chord = b - a
        length = math.hypot(*chord)
        radius = length / (2.0 * abs(math.sin(theta / 2.0)))
        mid = (a + b) / 2.0
        left = np.array([-chord[1], chord[0]]) / length
        # centre left of the chord for counter-clockwise arcs under a half turn; cos < 0
        # past a half turn moves it to the other side, as it must
        centre = mid + left * math.copysign(1.0, bulge) * radius * math.cos(theta / 2.0)
        t0 = math.atan2(a[1] - centre[1], a[0] - centre[0])
        pts = _arc_points(centre[0], centre[1], radius, radius, 0.0, t0, theta, tol)
        pts[-1] = b
        out.append(pts)
    pts = np.vstack(out)
    if closed and len(pts) > 1 and (pts[-1] == pts[0]).all():
        pts = pts[:-1]
    return pts


def _ocs_to_wcs(entity, pts: np.ndarray) -> np.ndarray:
    """Map OCS points of a planar entity to WCS x, y (mirrored when extrusion is -z)."""
    ext = entity.dxf.get("extrusion", (0.0, 0.0, 1.0))
    if tuple(ext) == (0.0, 0.0, 1.0):
        return pts
    ocs = entity.ocs()
    wcs = np.array([tuple(v)[:2] for v in ocs.points_to_wcs([(x, y, 0.0) for x, y in pts])])
    return wcs


#: $INSUNITS codes -> millimetres per drawing unit
_DXF_MM = {1: 25.4, 2: 304.8, 4: 1.0, 5: 10.0, 6: 1000.0, 9: 0.0254, 10: 914.4, 13: 1e-3, 14: 100.0}


def from_dxf(
    path,
    *,
    tolerance: float = _DEFAULT_TOL,
    layers=None,
    loose: bool = True,
    to_mm: bool = False,
):
    """Read closed outlines from a DXF file as one boundary (even-odd nesting).

    Reads the modelspace: closed ``LWPOLYLINE`` and 2D ``POLYLINE`` (bulges flattened as true
    arcs), ``CIRCLE``, full ``ELLIPSE`` and closed ``SPLINE`` (flattened by ezdxf). With
    ``loose=True`` the ``LINE`` and ``ARC`` entities and open polylines are joined into
    closed faces as well (``shapely.polygonize``), as many drawings are made of loose
    segments. Blocks (``INSERT``) and hatches are ignored.

    Parameters
    ----------
    path : str or Path
        The DXF file.
    tolerance : float
        Largest distance between a curve and its polyline, in output units.
    layers : sequence of str, optional
        Read only these layers (default: all).
    loose : bool
        Also assemble loose lines/arcs/open polylines into faces.
    to_mm : bool
        Scale to millimetres by the header's ``$INSUNITS`` (inches, feet, cm, m, ...;
        unitless drawings stay as they are). Off by default: many programs (ezdxf's own
        ``new()`` among them) write "metres" for drawings made in millimetres.

    Returns
    -------
    shapely.Polygon or shapely.MultiPolygon

    Raises
    ------
    ValueError
        Missing or unreadable file, or no closed outline.
    """
    import ezdxf

    p = _existing(path)
    tol = _positive(tolerance, "tolerance")
    try:
        doc = ezdxf.readfile(p)
    except (OSError, ezdxf.DXFError) as exc:
        raise ValueError(f"{p}: not a readable DXF file ({exc})") from None
    factor = _DXF_MM.get(int(doc.header.get("$INSUNITS", 0)), 1.0) if to_mm else 1.0
    tol = tol / factor  # flatten in drawing units
    wanted = None if layers is None else {str(name) for name in layers}
    rings: list[np.ndarray] = []
    lines: list[np.ndarray] = []
    for e in doc.modelspace():
        if wanted is not None and e.dxf.get("layer", "0") not in wanted:
            continue
        kind = e.dxftype()
        if kind == "LWPOLYLINE":
            data = np.array(e.get_points("xyb"), dtype=np.float64).reshape(-1, 3)
            closed = bool(e.closed) or (len(data) > 2 and (data[0, :2] == data[-1, :2]).all())
            if len(data) < 2:
                continue
            pts = _bulge_polyline(data[:, :2], data[:, 2], closed, tol)
            (rings if closed else lines).append(_ocs_to_wcs(e, pts))
        elif kind == "POLYLINE":
            if not (e.is_2d_polyline or e.is_3d_polyline):
                continue
            verts = list(e.vertices)
            if len(verts) < 2:
                continue
            xy = np.array([tuple(v.dxf.location)[:2] for v in verts], dtype=np.float64)
            bulge = np.array([v.dxf.get("bulge", 0.0) for v in verts], dtype=np.float64)
            closed = bool(e.is_closed) or (len(xy) > 2 and (xy[0] == xy[-1]).all())
            pts = _bulge_polyline(xy, bulge, closed, tol)
            if e.is_2d_polyline:
                pts = _ocs_to_wcs(e, pts)
            (rings if closed else lines).append(pts)
        elif kind == "CIRCLE":
            c = tuple(e.dxf.center)
            pts = _arc_points(c[0], c[1], e.dxf.radius, e.dxf.radius, 0.0, 0.0, 2 * np.pi, tol)
            rings.append(_ocs_to_wcs(e, pts))
        elif kind == "ELLIPSE":
            pts = np.array([tuple(v)[:2] for v in e.flattening(tol)], dtype=np.float64)
            span = (e.dxf.end_param - e.dxf.start_param) % (2 * np.pi)
            full = min(span, 2 * np.pi - span) < 1e-9
            (rings if full else lines).append(pts)
        elif kind == "SPLINE":
            pts = np.array([tuple(v)[:2] for v in e.flattening(tol)], dtype=np.float64)
            closed = bool(e.closed) or (len(pts) > 2 and np.allclose(pts[0], pts[-1]))
            (rings if closed else lines).append(pts)
        elif loose and kind == "LINE":
            lines.append(np.array([tuple(e.dxf.start)[:2], tuple(e.dxf.end)[:2]]))
        elif loose and kind == "ARC":
            c = tuple(e.dxf.center)
            a0 = math.radians(e.dxf.start_angle)
            sweep = math.radians((e.dxf.end_angle - e.dxf.start_angle) % 360.0) or 2 * np.pi
            start = np.array(
                [[c[0] + e.dxf.radius * math.cos(a0), c[1] + e.dxf.radius * math.sin(a0)]]
            )
            arc = _arc_points(c[0], c[1], e.dxf.radius, e.dxf.radius, 0.0, a0, sweep, tol)
            lines.append(_ocs_to_wcs(e, np.vstack((start, arc))))
    if loose and lines:
        noded = shapely.node(shapely.MultiLineString([ln for ln in lines if len(ln) >= 2]))
        faces = shapely.get_parts(shapely.polygonize(shapely.get_parts(noded)))
        rings.extend(np.asarray(f.exterior.coords) for f in faces)
    if not rings:
        raise ValueError(f"{p}: no closed outlines (closed LWPOLYLINE/POLYLINE, CIRCLE, ...)")
    out = even_odd([r * factor for r in rings] if factor != 1.0 else rings)
    if out.is_empty:
        raise ValueError(f"{p}: the outlines enclose no area")
    return as_polygonal(out, str(p))


# ----------------------------------------------------------------------------- GeoJSON, dispatch


def _existing(path) -> Path:
    p = Path(path)
    if not p.is_file():
        raise ValueError(f"{p}: no such file")
    return p


def from_geojson(path):
    """Read the polygons of a GeoJSON file (features united, holes kept).

    Parameters
    ----------
    path : str or Path
        A ``.geojson`` / ``.json`` file with Polygon or MultiPolygon geometries.

    Returns
    -------
    shapely.Polygon or shapely.MultiPolygon
    """
    from ..io.readers import read_boundary

    p = _existing(path)
    return as_polygonal(read_boundary(p), str(p))


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
    readers = {".geojson": from_geojson, ".json": from_geojson, ".svg": from_svg, ".dxf": from_dxf}
    if suffix not in readers:
        raise ValueError(
            f"{path}: unsupported boundary file type {suffix or '(none)'!r}; "
            "use .geojson, .json, .svg or .dxf"
        )
    if readers[suffix] is from_geojson and options:
        raise ValueError(f"{path}: GeoJSON boundaries take no options ({', '.join(options)})")
    return readers[suffix](path, **options)
