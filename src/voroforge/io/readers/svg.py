"""SVG in: path data (lines, Béziers, arcs), shapes, transforms and units, flattened.

:func:`read_svg` reads a drawing's filled shapes as one polygon (even-odd nesting, y up,
millimetres when the document says so); :func:`read_svg_curves` reads every outline as
lines. Curves are flattened to polylines within ``tolerance`` of the true curve.
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import shapely

from ...config import CURVE_TOLERANCE, SVG_MIN_SCALE
from .curves import arc_points, bezier_points
from .files import existing_file, positive_number
from .rings import even_odd

__all__ = [
    "path_lines",
    "path_rings",
    "read_svg",
    "read_svg_curves",
    "svg_arc",
    "svg_in_mm",
    "svg_page",
]


def svg_arc(p0, rx, ry, angle_deg, large, sweep, p1, tol) -> np.ndarray:
    """SVG endpoint-parameterised arc to points (SVG 1.1 implementation notes F.6.5).

    Parameters
    ----------
    p0, p1 : (2,) float
        Start and end point.
    rx, ry : float
        Radii (scaled up when too small for the end points, as SVG says).
    angle_deg : float
        Rotation of the x radius in degrees.
    large, sweep : {0, 1}
        SVG's large-arc and sweep flags.
    tol : float
        Largest chord error.

    Returns
    -------
    (k, 2) float64
        Start point excluded; the last point is exactly ``p1``.
    """
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
        lam = 1.0
    if not large and lam * max(rx, ry) <= tol:  # the small arc within tol of its chord
        return np.array([[x2, y2]], dtype=np.float64)
    if lam == 0.0:  # radii past 1e154 times the chord (rx * rx overflowed here)
        raise ValueError(
            f"the large arc of radii ({rx:g}, {ry:g}) through two points "
            f"{math.hypot(x2 - x1, y2 - y1):g} apart reaches past any drawing"
        )
    # the centre's offset (F.6.5.2) divided through by rx^2 ry^2: no overflow
    coef = math.sqrt(max(0.0, (1.0 - lam) / lam))
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
    pts = arc_points(cx, cy, rx, ry, phi, t0, dt, tol)
    pts[-1] = (x2, y2)  # land exactly on the end point
    return pts


_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_COMMANDS = "MmLlHhVvCcSsQqTtAaZz"


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


def path_rings(d: str, *, tolerance: float = CURVE_TOLERANCE) -> list[np.ndarray]:
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


def path_lines(d: str, *, tolerance: float = CURVE_TOLERANCE) -> list[np.ndarray]:
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
    tol = positive_number(tolerance, "tolerance")
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
                current.append(bezier_points(np.array([pos, c1, c2, p]), tol))
                pos, last_ctrl = p, c2
            elif upper in ("Q", "T"):
                if upper == "Q":
                    c1 = np.array([sc.number(), sc.number()]) + base
                else:
                    c1 = 2 * pos - last_ctrl if last_cmd in "QT" and last_ctrl is not None else pos
                p = np.array([sc.number(), sc.number()]) + base
                if not current:
                    current.append(pos[None])
                current.append(bezier_points(np.array([pos, c1, p]), tol))
                pos, last_ctrl = p, c1
            else:  # A
                rx, ry, ang = sc.number(), sc.number(), sc.number()
                large, sweep = sc.flag(), sc.flag()
                p = np.array([sc.number(), sc.number()]) + base
                if not current:
                    current.append(pos[None])
                current.append(svg_arc(pos, rx, ry, ang, large, sweep, p, tol))
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


def _element_rings(el, tol: float, close_tolerance: float | None = None) -> list[np.ndarray]:
    tag = _tag(el)
    if tag == "path":
        if close_tolerance is None:  # every subpath closed, as a fill would close it
            return path_rings(el.get("d", ""), tolerance=tol)
        out = []
        for k, (pts, closed) in enumerate(_subpaths(el.get("d", ""), tol)):
            gap = float(np.hypot(*(pts[-1] - pts[0])))
            if not closed and gap > close_tolerance:
                raise ValueError(
                    f"subpath {k + 1} is open: its ends are {gap:.6g} user units apart "
                    f"(close it with Z, or allow gaps up to that with a closing tolerance; "
                    f"now {close_tolerance:g})"
                )
            if len(pts) >= 3:
                out.append(pts)
        return out
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
        pts = [arc_points(cx, cy, rx, ry, 0.0, t0, np.pi / 2, tol) for cx, cy, t0 in corners]
        return [np.vstack(pts)]
    if tag in ("circle", "ellipse"):
        cx, cy = _attr_float(el, "cx"), _attr_float(el, "cy")
        if tag == "circle":
            rx = ry = _attr_float(el, "r")
        else:
            rx, ry = _attr_float(el, "rx"), _attr_float(el, "ry")
        if rx <= 0 or ry <= 0:
            return []
        return [arc_points(cx, cy, rx, ry, 0.0, 0.0, 2 * np.pi, tol)]
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

    # depth first, in document order, without recursion (groups nest as deep as a file says)
    stack = [(root, np.eye(3))]
    while stack:
        el, matrix = stack.pop()
        tag = _tag(el)
        if tag in _SKIP:
            continue
        m = matrix @ _transform(el.get("transform"))
        try:
            found = reader(el, tol / max(scale * _matrix_scale(m), SVG_MIN_SCALE))
        except ValueError as exc:
            raise ValueError(f"{p}: <{tag} id={el.get('id')!r}>: {exc}") from None
        for r in found:
            found_all.append(r @ m[:2, :2].T + m[:2, 2])
        stack.extend((child, m) for child in reversed(el))
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


def svg_page(path) -> tuple[float, float, float, float]:
    """The page (``viewBox``) of an SVG file in the coordinates :func:`read_svg` returns.

    With ``flip_y=True`` the page's bottom is y = 0, so the page is
    ``(vx, 0, vx + vw, vh)`` scaled to mm when the root width has a physical unit. Writing
    an SVG with these bounds (``write_layers(..., bounds=page)``) gives a file that lies
    exactly over the source drawing.

    Raises
    ------
    ValueError
        When the file has no usable ``viewBox``.
    """
    p = existing_file(path)
    try:
        root = ET.parse(p).getroot()
    except ET.ParseError as exc:
        raise ValueError(f"{p}: not a valid SVG/XML file ({exc})") from None
    scale, box = _document_scale(root)
    if box is None:
        raise ValueError(f"{p}: no viewBox, so there is no page to keep")
    vx, _, vw, vh = (float(v) for v in box)
    return vx * scale, 0.0, (vx + vw) * scale, vh * scale


def svg_in_mm(path) -> bool:
    """True when the SVG's root ``width`` has a physical unit, so :func:`read_svg` reads mm.

    Parameters
    ----------
    path : str or Path
        The SVG file.

    Returns
    -------
    bool
    """
    m = _LENGTH.match(ET.parse(existing_file(path)).getroot().get("width") or "")
    return bool(m and m.group(2) in _MM_PER_UNIT)


def read_svg(
    path,
    *,
    tolerance: float = CURVE_TOLERANCE,
    flip_y: bool = True,
    close_tolerance: float | None = 0.0,
):
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
    close_tolerance : float or None
        A ``<path>`` subpath not closed with ``Z`` is an error naming the file and the element
        unless its ends are at most this far apart (user units; 0: only ends that meet), as
        an open DXF outline is. ``None`` closes every subpath as a fill would.

    Returns
    -------
    shapely.Polygon or shapely.MultiPolygon
        In millimetres when the root ``width`` has a physical unit (``"600mm"``, ``"8in"``,
        ``"96px"`` at 96 px per inch) and a ``viewBox``; otherwise 1 user unit = 1 mm.

    Raises
    ------
    ValueError
        Missing or unreadable file, malformed path data, an open outline, or no closed shape
        with area.
    """
    from functools import partial

    p = existing_file(path)
    tol = positive_number(tolerance, "tolerance")
    if close_tolerance is not None and not float(close_tolerance) >= 0:
        raise ValueError(f"close_tolerance must be >= 0 or None; got {close_tolerance!r}")
    reader = partial(_element_rings, close_tolerance=close_tolerance)
    rings = _read_svg(p, tol, flip_y, reader)
    if not rings:
        raise ValueError(f"{p}: no closed shapes (path, polygon, rect, circle, ellipse)")
    out = even_odd(rings)
    if out.is_empty:
        raise ValueError(f"{p}: the shapes enclose no area")
    return out


def read_svg_curves(path, *, tolerance: float = CURVE_TOLERANCE, flip_y: bool = True):
    """Read every outline of an SVG file as lines (for a curve attractor, say).

    Open and closed ``<path>`` subpaths, ``<line>``, ``<polyline>``, ``<polygon>``,
    ``<rect>``, ``<circle>`` and ``<ellipse>``, with transforms, units and the y flip of
    :func:`read_svg`.

    Parameters
    ----------
    path : str or Path
        The SVG file.
    tolerance : float
        Largest distance between a curve and its polyline, in output units.
    flip_y : bool
        As in :func:`read_svg`.

    Returns
    -------
    shapely.MultiLineString
    """
    p = existing_file(path)
    tol = positive_number(tolerance, "tolerance")
    lines = [ln for ln in _read_svg(p, tol, flip_y, _element_lines) if len(ln) >= 2]
    if not lines:
        raise ValueError(f"{p}: no curves (path, line, polyline, polygon, rect, circle, ellipse)")
    return shapely.MultiLineString(lines)


def _matrix_scale(m: np.ndarray) -> float:
    """Largest stretch of an affine matrix (so the flattening tolerance survives it)."""
    return float(np.linalg.svd(m[:2, :2], compute_uv=False).max())
