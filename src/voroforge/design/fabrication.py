"""Fabrication checks for cut panels: thin webs, small openings, sharp inside corners, islands.

A cut panel is a *frame*: the boundary minus the openings. :func:`check` measures what a
laser or CNC shop cares about and returns a :class:`Report` listing every violation with
its location, the measured value and the limit, as a text table and as a picture marking
the spots. :func:`kerf` offsets geometry so the cut edge, not the beam centre, lands on the
design line.

Examples
--------
>>> import shapely
>>> panel = shapely.box(0, 0, 100, 50)
>>> holes = [shapely.box(10, 10, 40, 40), shapely.box(41, 10, 70, 40)]
>>> report = check(openings=holes, boundary=panel, min_web=3.0)
>>> [(v.kind, round(v.value, 3)) for v in report.violations]
[('web', 1.0)]
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import shapely

from .. import config
from .boundary import MM_PER_UNIT, union_all_checked
from .fabcorners import corners as _corners
from .fabcorners import deepest as _deepest  # noqa: F401 (its tests import it from here)

__all__ = [
    "KINDS",
    "MARK_STYLES",
    "Report",
    "Violation",
    "check",
    "design_corner_tolerance",
    "inscribed_circles",
    "kerf",
    "pack_pieces",
    "sort_key",
    "split_frame",
]

#: Violation kinds (a report lists them by severity, worst first, whatever their kind).
KINDS = ("web", "opening", "corner", "island")

_UNITS = {
    "web": "web width (mm)",
    "opening": "opening: inscribed circle diameter (mm)",
    "corner": "inside corner radius vs the tool radius (mm)",
    "island": "loose part, falls out when cut (area, mm^2)",
}

#: How each kind is drawn on the overlays: marker shape and colour.
MARK_STYLES = {
    "web": ("circle", (220, 30, 30)),
    "opening": ("square", (30, 90, 220)),
    "corner": ("triangle", (235, 130, 0)),
    "island": ("diamond", (170, 0, 170)),
}

#: The limit each kind is checked against, by its :func:`check` keyword.
LIMIT_OF = {"web": "min_web", "opening": "min_opening", "corner": "min_inside_radius"}


@dataclass(frozen=True)
class Violation:
    """One spot that breaks a fabrication limit.

    Attributes
    ----------
    kind : {"web", "opening", "corner", "island"}
        What is wrong.
    location : (float, float)
        Where: the middle of the thinnest web, the centre of the small opening, the corner
        point the tool cannot reach, a point on the loose island.
    value : float
        What was measured, in the limit's quantity: web width, inscribed diameter, the inside
        corner's radius (the largest tool radius that still reaches the corner), island area.
    limit : float
        The limit it breaks (``min_web``, ``min_opening``, ``min_inside_radius``, 0).
    items : tuple of int
        Indices of the openings involved (-1 for the outer boundary); empty for islands.
    """

    kind: str
    location: tuple[float, float]
    value: float
    limit: float
    items: tuple[int, ...] = ()

    @property
    def severity(self) -> float:
        """How badly the limit is broken, 0..1: the shortfall over the limit; 1 for an island.

        A web of 0 (openings touching) and a corner no tool reaches are as bad as a loose
        island; a web 10% under its limit is 0.1.
        """
        if self.kind == "island" or not self.limit > 0:
            return 1.0
        return float(min(1.0, max(0.0, (self.limit - self.value) / self.limit)))

    def describe(self) -> str:
        """One line: kind, where, value and limit."""
        x, y = self.location
        return f"{self.kind} at ({x:.3f}, {y:.3f}): {self.value:.3f} (limit {self.limit:g})"


def sort_key(v: Violation):
    """The order of a report: worst first (:attr:`Violation.severity`), then kind, value, spot."""
    return (
        -v.severity,
        KINDS.index(v.kind),
        v.value if v.kind != "island" else -v.value,
        v.location,
    )


@dataclass(frozen=True)
class Report:
    """The result of :func:`check`.

    Attributes
    ----------
    violations : list of Violation
        Sorted by severity (:attr:`Violation.severity`), worst first, across kinds.
    limits : dict
        The limits checked (``None`` for a check that was not asked for).
    frame : shapely geometry
        The frame checked (boundary minus openings), for drawing.
    openings : (n,) object array of shapely Polygon
        The openings checked.
    keys : dict
        The name to print for each limit (a design file's key, ``fabrication.tool_radius``
        for ``min_inside_radius``); limits not named print as they are.
    """

    violations: list[Violation]
    limits: dict = field(default_factory=dict)
    frame: object = None
    openings: object = None
    keys: dict = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        """True when nothing breaks a limit."""
        return not self.violations

    def counts(self) -> dict[str, int]:
        """Number of violations per kind (every kind listed)."""
        return {k: sum(1 for v in self.violations if v.kind == k) for k in KINDS}

    def table(self, *, max_rows: int | None = 50) -> str:
        """The violations as a plain-text table, worst first.

        Parameters
        ----------
        max_rows : int or None
            At most this many rows, then a count of the rest; ``None`` lists every one.

        Returns
        -------
        str
            A header, one row per violation and a summary line naming the limits' keys.
        """
        lines = []
        name = {k: self.keys.get(k, k) for k in self.limits}
        checked = ", ".join(f"{name[k]}={v:g}" for k, v in self.limits.items() if v is not None)
        if self.ok:
            return f"fabrication check: no violations ({checked or 'nothing checked'})"
        head = f"{'kind':<8} {'x':>12} {'y':>12} {'value':>10} {'limit':>8}  what"
        lines.append(head)
        lines.append("-" * len(head))
        shown = self.violations if max_rows is None else self.violations[:max_rows]
        for v in shown:
            x, y = v.location
            lines.append(
                f"{v.kind:<8} {x:>12.3f} {y:>12.3f} {v.value:>10.3f} {v.limit:>8g}  "
                f"{_UNITS[v.kind]}"
            )
        if len(shown) < len(self.violations):
            lines.append(
                f"... and {len(self.violations) - len(shown)} more (--all lists every one)"
            )
        counts = self.counts()
        parts = []
        for k, n in counts.items():
            if n:
                limit = LIMIT_OF.get(k)
                parts.append(f"{n} {k} (< {name[limit]})" if limit in name else f"{n} {k}")
        lines.append(f"{len(self.violations)} violations: {', '.join(parts)} ({checked})")
        return "\n".join(lines)

    def legend(self) -> list[tuple[str, tuple[int, int, int], str]]:
        """``(shape, colour, text)`` per kind found, as the overlays draw them."""
        rows = []
        for k, n in self.counts().items():
            if n:
                shape, colour = MARK_STYLES[k]
                limit = LIMIT_OF.get(k)
                what = f"{k}: {n}" + (
                    f" < {self.keys.get(limit, limit)} {self.limits[limit]:g}"
                    if self.limits.get(limit) is not None
                    else ""
                )
                rows.append((shape, colour, what))
        return rows

    def markers(self, radius: float | None = None) -> np.ndarray:
        """Circles around each violation, for drawing (object array of Polygon)."""
        if radius is None:
            radius = _marker_radius(self.frame, self.openings)
        pts = shapely.points([v.location for v in self.violations]) if self.violations else []
        return np.asarray(shapely.buffer(pts, radius, quad_segs=8), dtype=object).reshape(-1)

    def write_png(self, path, *, size: int = 1024) -> Path:
        """Draw the frame in grey and a marker per violation, one shape and colour per kind.

        Web: red circle, opening: blue square, corner: orange triangle, island: purple
        diamond, each with a dot on the spot, at a fixed size in pixels (a 0.1 mm web shows
        on a 2 m panel), and a legend with the counts. Worst violations are drawn last.

        Returns
        -------
        Path
            The file written.
        """
        from ..io.png import write_png

        marks = [(*v.location, *MARK_STYLES[v.kind]) for v in reversed(self.violations)]
        return write_png(
            [self.frame],
            path,
            size=size,
            colors=[(200, 200, 200)],
            edge_width=0.5,
            marks=marks,
            legend=self.legend(),
        )

    def write_svg(self, path) -> Path:
        """Write the frame (layer ``CUT``) and the violations as an mm SVG.

        One layer per kind found (``WEB``, ``OPENING``, ``CORNER``, ``ISLAND``), each marker
        a shape of its own (circle, square, triangle, diamond) around a cross on the spot,
        drawn with ``vector-effect="non-scaling-stroke"`` so the marks stay visible at any
        zoom; a ``LEGEND`` layer names the kinds and their counts.

        Returns
        -------
        Path
            The file written.
        """
        from ..io.svg import write_layers

        r = _marker_radius(self.frame, self.openings)
        layers: dict = {"CUT": [self.frame]}
        colours = {"CUT": "#8c8c8c"}  # an overlay: the panel in grey, visible at any zoom
        for kind in KINDS:
            found = [v for v in self.violations if v.kind == kind]
            if not found:
                continue
            shape, colour = MARK_STYLES[kind]
            layers[kind.upper()] = [_mark_geometry(v.location, shape, r) for v in found]
            colours[kind.upper()] = colour
        return write_layers(
            path,
            layers,
            colours=colours,
            order="file",
            merge=False,
            legend=[(text, colour) for _, colour, text in self.legend()],
            non_scaling=["CUT", *(k.upper() for k in KINDS)],
        )


def _mark_geometry(xy, shape: str, r: float):
    """A marker outline around ``xy`` plus a cross on the spot, as lines."""
    x, y = xy
    if shape == "circle":
        t = np.linspace(0.0, 2 * np.pi, 33)
        ring = np.column_stack((x + r * np.cos(t), y + r * np.sin(t)))
    else:
        unit = {
            "square": [(-0.8, -0.8), (0.8, -0.8), (0.8, 0.8), (-0.8, 0.8)],
            "triangle": [(0.0, 1.0), (0.95, -0.75), (-0.95, -0.75)],
            "diamond": [(0.0, 1.1), (1.0, 0.0), (0.0, -1.1), (-1.0, 0.0)],
        }[shape]
        ring = np.array([(x + u * r, y + v * r) for u, v in [*unit, unit[0]]])
    c = 0.3 * r
    cross = [[(x - c, y), (x + c, y)], [(x, y - c), (x, y + c)]]
    return shapely.MultiLineString([ring, *cross])


def _marker_radius(frame, openings) -> float:
    parts = [g for g in [frame, *(openings if openings is not None else [])] if g is not None]
    if not parts:
        return 1.0
    xmin, ymin, xmax, ymax = shapely.total_bounds(np.asarray(parts, dtype=object))
    return max(xmax - xmin, ymax - ymin, config.INSCRIBED_FLOOR) / 80.0


def _as_polygons(geoms, name: str) -> np.ndarray:
    if geoms is None:
        return np.zeros(0, dtype=object)
    if isinstance(geoms, shapely.Geometry):
        geoms = [geoms]
    out = []
    for i, g in enumerate(geoms):
        if g is None:
            continue
        if not isinstance(g, shapely.Geometry):
            raise ValueError(f"{name}[{i}] is a {type(g).__name__}, not a shapely geometry")
        out.extend(p for p in shapely.get_parts(g) if p.geom_type == "Polygon" and not p.is_empty)
    return np.asarray(out, dtype=object).reshape(-1)


def split_frame(frame) -> tuple[shapely.Geometry, np.ndarray]:
    """Boundary and openings of a frame: the union of exteriors, and the holes as polygons.

    Parameters
    ----------
    frame : shapely Polygon or MultiPolygon
        A cut panel (boundary minus openings).

    Returns
    -------
    boundary : shapely geometry
        The frame with its holes filled.
    openings : (n,) object array of Polygon
        One polygon per hole.
    """
    parts = _as_polygons(frame, "frame")
    shells = [shapely.Polygon(p.exterior) for p in parts]
    holes = [shapely.Polygon(r) for p in parts for r in p.interiors]
    boundary = shapely.union_all(shells) if shells else shapely.Polygon()
    # A part inside another part's hole is an island; its own exterior is not a hole.
    return boundary, np.asarray(holes, dtype=object).reshape(-1)


def _check_limit(name: str, value) -> float | None:
    if value is None:
        return None
    v = float(value)
    if not math.isfinite(v) or v < 0:
        raise ValueError(f"{name} must be a non-negative number; got {value!r}")
    return v


def design_corner_tolerance(design) -> float:
    """A design's ``fabrication.corner_tolerance``: as given, else 0.02 mm in its units.

    (:data:`~voroforge.config.FAB_CORNER_TOLERANCE_MM`; a default of 0.02 drawing units was
    20 mm in a design drawn in metres, and every uncut corner up to that deep passed.)
    """
    given = design.fabrication.corner_tolerance
    if given is not None:
        return given
    return config.FAB_CORNER_TOLERANCE_MM / MM_PER_UNIT[design.design.units]


def check(
    frame=None,
    *,
    openings=None,
    boundary=None,
    min_web: float | None = None,
    min_opening: float | None = None,
    min_inside_radius: float | None = None,
    corner_tolerance: float = config.FAB_CORNER_TOLERANCE,
    tolerance: float | None = None,
    islands: bool = True,
    keys: dict | None = None,
) -> Report:
    """Check a cut panel against fabrication limits.

    Give either the ``frame`` (boundary minus openings: its holes are the openings) or the
    ``openings`` and the ``boundary``. Checks that are not asked for (limit ``None``) are
    skipped; islands are always checked unless ``islands=False``.

    - **web**: every pair of openings closer than ``min_web``, and every opening closer than
      ``min_web`` to the boundary's outline, at the middle of the thinnest spot
      (``shapely.shortest_line``).
    - **opening**: every opening whose largest inscribed circle has a diameter below
      ``min_opening`` (largest inscribed circle, :func:`inscribed_circles`), at its centre.
    - **corner**: where a round tool of radius ``min_inside_radius`` cannot reach: the parts
      of each opening outside ``opening.buffer(-r).buffer(r)`` (and, for the outline cut
      from outside, the parts of ``boundary.buffer(r).buffer(-r)`` outside the boundary)
      deeper than ``corner_tolerance`` (from the tool's envelope, inside an opening and on
      the outline alike), at the corner. The value is the corner's inside radius, in the
      limit's quantity: the largest tool radius that reaches that corner to within
      ``corner_tolerance`` (by bisection): ``corner_tolerance / (1 / sin(a / 2) - 1)`` for a
      sharp corner of angle ``a`` (2.4 of it at 90 degrees), a fillet's radius plus that for
      a fillet; for an opening the tool cannot enter at all, the largest radius that fits,
      at its centre.
    - **island**: frame parts that touch no outline of the boundary (they fall out when cut),
      at a point inside them; the value is their area. A part thinner than
      ``corner_tolerance`` everywhere is not material (rounding where openings tile).

    Parameters
    ----------
    frame : shapely Polygon or MultiPolygon, optional
        The panel as cut. With ``openings`` and ``boundary`` too: the frame their islands
        and tongues are looked for in (default: boundary minus openings), for a caller that
        made it already and knows which openings tile their parent exactly.
    openings : sequence of shapely Polygon, optional
        The holes cut into the boundary (used with ``boundary``).
    boundary : shapely Polygon or MultiPolygon, optional
        The panel's outline (holes allowed).
    min_web, min_opening, min_inside_radius : float, optional
        Limits in drawing units (mm).
    corner_tolerance : float
        Uncut material thinner than this is ignored (chord-vs-arc noise of fillets).
    tolerance : float, optional
        Webs and openings within this of their limit pass (a web inset to exactly
        ``min_web`` is not a violation because of rounding). Default: 1e-6 of each limit
        plus 1e-14 of the panel's largest coordinate (``config.FAB_LIMIT_RTOL``,
        ``FAB_LIMIT_COORD_RTOL``), so any unit and scale is checked alike.
    islands : bool
        Look for loose parts.
    keys : dict, optional
        Names to print for the limits (``{"min_inside_radius": "fabrication.tool_radius"}``).

    Returns
    -------
    Report
        The violations, worst first (by :attr:`Violation.severity`, across kinds).

    Raises
    ------
    ValueError
        Without geometry, with both ``frame`` and ``openings``, or for a negative limit.
    """
    min_web = _check_limit("min_web", min_web)
    min_opening = _check_limit("min_opening", min_opening)
    min_inside_radius = _check_limit("min_inside_radius", min_inside_radius)
    corner_tolerance = _check_limit("corner_tolerance", corner_tolerance) or 0.0
    tolerance = _check_limit("tolerance", tolerance)
    if frame is not None and openings is not None and boundary is None:
        raise ValueError("give either frame or openings (with boundary), not both")
    if frame is not None and openings is None:
        frame_geom = shapely.union_all(_as_polygons(frame, "frame"))
        outline, holes = split_frame(frame_geom)
        if boundary is not None:
            outline = shapely.union_all(_as_polygons(boundary, "boundary"))
    elif openings is not None:
        if boundary is None:
            raise ValueError("openings need a boundary to check against")
        holes = _as_polygons(openings, "openings")
        outline = shapely.union_all(_as_polygons(boundary, "boundary"))
        if frame is not None:  # the caller's frame (compute's has no slivers of tilings)
            frame_geom = shapely.union_all(_as_polygons(frame, "frame"))
        elif len(holes):
            frame_geom = outline.difference(union_all_checked(holes))
        else:
            frame_geom = outline
    else:
        raise ValueError("check needs a frame, or openings and a boundary")

    found: list[Violation] = []
    if min_web is not None and min_web > 0:
        tol = _limit_tolerance(min_web, tolerance, outline)
        found += _webs(holes, outline, min_web, tol)
        found += _tongues(holes, outline, frame_geom, min_web, tol)
    if min_opening is not None and min_opening > 0:
        found += _openings(holes, min_opening, _limit_tolerance(min_opening, tolerance, outline))
    if min_inside_radius is not None and min_inside_radius > 0:
        found += _corners(holes, outline, min_inside_radius, corner_tolerance)
    if islands:
        found += _islands(frame_geom, outline, corner_tolerance)
    found.sort(key=sort_key)
    limits = {
        "min_web": min_web,
        "min_opening": min_opening,
        "min_inside_radius": min_inside_radius,
    }
    return Report(found, limits, frame_geom, holes, dict(keys or {}))


def _limit_tolerance(limit: float, tolerance: float | None, outline) -> float:
    """The slack of one limit: as given, else relative to the limit and the coordinates."""
    if tolerance is not None:
        return tolerance
    extent = np.abs(np.asarray(outline.bounds, dtype=np.float64)) if not outline.is_empty else 0
    return limit * config.FAB_LIMIT_RTOL + config.FAB_LIMIT_COORD_RTOL * float(np.max(extent))


def _webs(holes: np.ndarray, outline, min_web: float, tol: float) -> list[Violation]:
    out = []
    below = min_web - tol
    if len(holes) > 1:
        tree = shapely.STRtree(holes)
        left, right = tree.query(holes, predicate="dwithin", distance=min_web)
        keep = left < right
        left, right = left[keep], right[keep]
        if len(left):
            dist = shapely.distance(holes[left], holes[right])
            close = dist < below
            lines = shapely.shortest_line(holes[left[close]], holes[right[close]])
            mids = shapely.line_interpolate_point(lines, 0.5, normalized=True)
            for i, j, d, m in zip(
                left[close].tolist(), right[close].tolist(), dist[close].tolist(), mids, strict=True
            ):
                out.append(Violation("web", (m.x, m.y), d, min_web, (i, j)))
    if len(holes) and not outline.is_empty:
        rim = outline.boundary
        dist = shapely.distance(holes, rim)
        # An opening reaching over the outline leaves no web at all.
        outside = ~shapely.covered_by(holes, outline)
        dist = np.where(outside, 0.0, dist)
        for i in np.flatnonzero(dist < below).tolist():
            line = shapely.shortest_line(holes[i], rim)
            m = shapely.line_interpolate_point(line, 0.5, normalized=True)
            out.append(Violation("web", (m.x, m.y), float(dist[i]), min_web, (i, -1)))
    return out


def _tongues(holes, outline, frame, min_web: float, tol: float) -> list[Violation]:
    """Thin material inside one opening's own convex hull (a tongue between a U's arms).

    :func:`_webs` measures between two openings and from an opening to the outline; here the
    material in a non-convex opening's hull, away from every other cut, is opened
    morphologically with discs of diameter ``min_web - tol``: what no such disc covers, and
    reaches deeper than the disc's radius from what they do (a convex material corner of 60
    degrees or more does not), is a web narrower than the limit, its width the piece's
    inscribed diameter.
    """
    r = 0.5 * (min_web - tol)
    if not len(holes) or not r > 0:
        return []
    hulls = shapely.convex_hull(holes)
    concave = shapely.area(hulls) - shapely.area(holes) > 1e-9 * shapely.area(hulls)
    if not concave.any():
        return []
    tree = shapely.STRtree(holes)
    out = []
    for i in np.flatnonzero(concave).tolist():
        inside = shapely.intersection(hulls[i], frame)
        if not inside.area > 0:
            continue
        near = tree.query(hulls[i], predicate="dwithin", distance=min_web)
        cuts = [holes[j].buffer(min_web) for j in near.tolist() if j != i]
        cuts.append(outline.boundary.buffer(min_web))
        inside = inside.difference(shapely.union_all(cuts))
        if not inside.area > 0:
            continue
        around = shapely.intersection(frame, hulls[i].buffer(min_web))
        opened = around.buffer(-r).buffer(r)
        thin = shapely.get_parts(inside.difference(opened))
        thin = thin[shapely.area(thin) > 0]
        for piece in thin:
            probe = shapely.points(shapely.get_coordinates(shapely.segmentize(piece, r / 4)))
            if not opened.is_empty and not shapely.distance(probe, opened).max() > r * (1 + 1e-9):
                continue
            (centre,), (radius,) = inscribed_circles([piece])
            out.append(
                Violation("web", tuple(centre.tolist()), 2.0 * float(radius), min_web, (i, i))
            )
    return out


def inscribed_circles(polygons, *, tolerance=None) -> tuple[np.ndarray, np.ndarray]:
    """Centre and radius of the largest circle inside each polygon.

    Uses ``shapely.maximum_inscribed_circle`` (shapely >= 2.1), else polylabel with the
    distance to the outline.

    Parameters
    ----------
    polygons : (n,) object array of Polygon/MultiPolygon
        Non-empty polygons.
    tolerance : float or (n,) array_like, optional
        Precision of the search (default 1e-3 of each polygon's smaller box side).

    Returns
    -------
    centres : (n, 2) float64
    radii : (n,) float64
    """
    polys = np.asarray(polygons, dtype=object).reshape(-1)
    if not len(polys):
        return np.zeros((0, 2)), np.zeros(0)
    xmin, ymin, xmax, ymax = shapely.bounds(polys).T
    side = np.minimum(xmax - xmin, ymax - ymin)
    if tolerance is None:
        tolerance = np.maximum(side * config.INSCRIBED_RTOL, config.INSCRIBED_FLOOR)
    else:  # GEOS refines until the tolerance: 1e-300 of a 10 mm cell never finished
        tolerance = np.maximum(tolerance, side * config.INSCRIBED_MIN_RTOL)
    if hasattr(shapely, "maximum_inscribed_circle"):
        circles = shapely.maximum_inscribed_circle(polys, tolerance=tolerance)
        return shapely.get_coordinates(shapely.get_point(circles, 0)), shapely.length(circles)
    from shapely.ops import polylabel  # shapely 2.0

    tols = np.broadcast_to(np.asarray(tolerance, dtype=np.float64), (len(polys),))
    centres, radii = [], []
    for poly, t in zip(polys, tols, strict=True):
        part = max(shapely.get_parts(poly), key=lambda g: g.area)
        c = polylabel(part, tolerance=float(t))
        centres.append((c.x, c.y))
        radii.append(float(shapely.distance(c, part.boundary)))
    return np.asarray(centres, dtype=np.float64), np.asarray(radii, dtype=np.float64)


def _openings(holes: np.ndarray, min_opening: float, tol: float) -> list[Violation]:
    if not len(holes):
        return []
    centres, radii = inscribed_circles(holes)
    diameter = 2.0 * radii
    out = []
    for i in np.flatnonzero(diameter < min_opening - tol).tolist():
        x, y = centres[i]
        out.append(
            Violation("opening", (float(x), float(y)), float(diameter[i]), min_opening, (i,))
        )
    return out


def _islands(frame, outline, tolerance: float = 0.0) -> list[Violation]:
    if frame is None or frame.is_empty or outline.is_empty:
        return []
    rim = outline.boundary
    tol = config.ISLAND_TOUCH_RTOL * max(1.0, float(np.abs(shapely.bounds(outline)).max()))
    parts = shapely.get_parts(frame)
    parts = parts[(shapely.get_type_id(parts) == 3) & ~shapely.is_empty(parts)]
    loose = parts[shapely.distance(shapely.get_exterior_ring(parts), rim) > tol]
    if tolerance > 0 and len(loose):  # slivers (rounding where openings tile): no disc of
        # diameter ``tolerance`` fits in them anywhere
        loose = loose[~shapely.is_empty(shapely.buffer(loose, -0.5 * tolerance))]
    spots = shapely.point_on_surface(loose)
    return [
        Violation("island", (p.x, p.y), float(a), 0.0)
        for p, a in zip(spots, shapely.area(loose), strict=True)
    ]


def kerf(geoms, kerf: float, *, role: str = "part", join: str = "mitre", quad_segs: int = 8):
    """Offset geometry by half the kerf so the cut edge lands on the design line.

    A part (``role="part"``, the frame) grows by ``kerf / 2``: its outline moves outward and
    its holes shrink (the beam runs inside each hole). Openings given on their own
    (``role="hole"``) shrink by ``kerf / 2``. Outer corners get mitred tool paths by default
    (``join="mitre"``, limit 5): both a mitred and a round path still cut a sharp corner, but
    only mitred joins keep the vertices of a polygonal arc (rounded corners, circles, fillets
    of parts) on one circle, so the DXF writer can still write them as true arcs.

    Parameters
    ----------
    geoms : shapely geometry or sequence of them
        What to offset.
    kerf : float
        Width of the cut (the beam or tool diameter), >= 0.
    role : {"part", "hole"}
        Which side is material.
    join : {"mitre", "round"}
        Corner style of the offset at outer corners.
    quad_segs : int
        Segments per quarter circle of the round joins.

    Returns
    -------
    shapely geometry or (n,) object array
        Same shape as ``geoms``; the input is not changed.

    Raises
    ------
    ValueError
        For a negative kerf, an unknown role or an unknown join.
    """
    k = float(kerf)
    if not math.isfinite(k) or k < 0:
        raise ValueError(f"kerf must be a non-negative number; got {kerf!r}")
    if role not in ("part", "hole"):
        raise ValueError(f"role must be 'part' or 'hole'; got {role!r}")
    if join not in ("mitre", "round"):
        raise ValueError(f"join must be 'mitre' or 'round'; got {join!r}")
    if k == 0:
        return geoms
    d = k / 2.0 if role == "part" else -k / 2.0
    opts = {"quad_segs": quad_segs, "join_style": join, "mitre_limit": 5.0}
    if isinstance(geoms, shapely.Geometry):
        return shapely.buffer(geoms, d, **opts)
    arr = np.asarray(list(geoms), dtype=object).reshape(-1)
    return np.asarray(shapely.buffer(arr, d, **opts), dtype=object)


def pack_pieces(pieces, *, width: float, gap: float) -> np.ndarray:
    """Offsets that lay pieces out apart, in rows no wider than ``width`` (shelf packing).

    Pieces are taken tallest first; each row is filled left to right with ``gap`` between
    bounding boxes and between rows, rows stacked upwards from y = 0, x from 0.

    Parameters
    ----------
    pieces : (n,) sequence of shapely geometries
        Non-empty parts.
    width : float
        Sheet width (a piece wider than that gets a row of its own).
    gap : float
        Space between parts (at least the kerf, so neighbours do not share a cut).

    Returns
    -------
    (n, 2) float64
        Translation of each piece, in input order.
    """
    arr = np.asarray(pieces, dtype=object).reshape(-1)
    if not (math.isfinite(width) and width > 0 and math.isfinite(gap) and gap >= 0):
        raise ValueError(f"width must be > 0 and gap >= 0; got {width!r}, {gap!r}")
    out = np.zeros((len(arr), 2))
    if not len(arr):
        return out
    b = shapely.bounds(arr)
    w, h = b[:, 2] - b[:, 0], b[:, 3] - b[:, 1]
    x = y = row_h = 0.0
    for i in np.lexsort((np.arange(len(arr)), -h)).tolist():
        if x > 0 and x + w[i] > width:
            x, y, row_h = 0.0, y + row_h + gap, 0.0
        out[i] = (x - b[i, 0], y - b[i, 1])
        x += w[i] + gap
        row_h = max(row_h, h[i])
    return out
