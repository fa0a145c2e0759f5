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

__all__ = ["KINDS", "Report", "Violation", "check", "inscribed_circles", "kerf", "split_frame"]

#: Violation kinds, in the order a report lists them.
KINDS = ("web", "opening", "corner", "island")

_UNITS = {
    "web": "web width between cuts",
    "opening": "opening size (inscribed circle diameter)",
    "corner": "material left in an inside corner by the tool",
    "island": "loose part (area)",
}


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
        What was measured (web width, inscribed diameter, depth of uncut material, area).
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

    def describe(self) -> str:
        """One line: kind, where, value and limit."""
        x, y = self.location
        return f"{self.kind} at ({x:.3f}, {y:.3f}): {self.value:.3f} (limit {self.limit:g})"


@dataclass(frozen=True)
class Report:
    """The result of :func:`check`.

    Attributes
    ----------
    violations : list of Violation
        Sorted by kind (:data:`KINDS` order), then by value, worst first.
    limits : dict
        The limits checked (``None`` for a check that was not asked for).
    frame : shapely geometry
        The frame checked (boundary minus openings), for drawing.
    openings : (n,) object array of shapely Polygon
        The openings checked.
    """

    violations: list[Violation]
    limits: dict = field(default_factory=dict)
    frame: object = None
    openings: object = None

    @property
    def ok(self) -> bool:
        """True when nothing breaks a limit."""
        return not self.violations

    def counts(self) -> dict[str, int]:
        """Number of violations per kind (every kind listed)."""
        return {k: sum(1 for v in self.violations if v.kind == k) for k in KINDS}

    def table(self, *, max_rows: int = 50) -> str:
        """The violations as a plain-text table (at most ``max_rows`` rows, then a count).

        Returns
        -------
        str
            A header, one row per violation and a summary line.
        """
        lines = []
        checked = ", ".join(f"{k}={v:g}" for k, v in self.limits.items() if v is not None)
        if self.ok:
            return f"fabrication check: no violations ({checked or 'nothing checked'})"
        head = f"{'kind':<8} {'x':>12} {'y':>12} {'value':>10} {'limit':>8}  what"
        lines.append(head)
        lines.append("-" * len(head))
        for v in self.violations[:max_rows]:
            x, y = v.location
            lines.append(
                f"{v.kind:<8} {x:>12.3f} {y:>12.3f} {v.value:>10.3f} {v.limit:>8g}  "
                f"{_UNITS[v.kind]}"
            )
        if len(self.violations) > max_rows:
            lines.append(f"... and {len(self.violations) - max_rows} more")
        summary = ", ".join(f"{n} {k}" for k, n in self.counts().items() if n)
        lines.append(f"{len(self.violations)} violations: {summary} ({checked})")
        return "\n".join(lines)

    def markers(self, radius: float | None = None) -> np.ndarray:
        """Circles around each violation, for drawing (object array of Polygon)."""
        if radius is None:
            radius = _marker_radius(self.frame, self.openings)
        pts = shapely.points([v.location for v in self.violations]) if self.violations else []
        return np.asarray(shapely.buffer(pts, radius, quad_segs=8), dtype=object).reshape(-1)

    def write_png(self, path, *, size: int = 1024) -> Path:
        """Draw the frame in grey and a red ring around every violation; write a PNG.

        Returns
        -------
        Path
            The file written.
        """
        from ..io.png import write_png

        rings = [
            m.exterior.buffer(_marker_radius(self.frame, self.openings) * 0.25)
            for m in self.markers()
        ]
        geoms = [self.frame, *rings]
        colours = [(200, 200, 200)] + [(220, 30, 30)] * len(rings)
        return write_png(geoms, path, size=size, colors=colours, edge_width=0.5)

    def write_svg(self, path) -> Path:
        """Write the frame (layer ``CUT``) and violation circles (layer ``MARK``) as mm SVG.

        Returns
        -------
        Path
            The file written.
        """
        from ..io.svg import write_layers

        layers = {"CUT": [self.frame], "MARK": [m.exterior for m in self.markers()]}
        return write_layers(path, layers, colours={"MARK": "#ff8000"})


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


def check(
    frame=None,
    *,
    openings=None,
    boundary=None,
    min_web: float | None = None,
    min_opening: float | None = None,
    min_inside_radius: float | None = None,
    corner_tolerance: float = config.FAB_CORNER_TOLERANCE,
    tolerance: float = config.FAB_LIMIT_ATOL,
    islands: bool = True,
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
      deeper than ``corner_tolerance``, at the deepest point; the value is that depth (for
      an opening the tool cannot enter at all: the largest radius that fits, at its centre).
    - **island**: frame parts that touch no outline of the boundary (they fall out when cut),
      at a point inside them; the value is their area.

    Parameters
    ----------
    frame : shapely Polygon or MultiPolygon, optional
        The panel as cut.
    openings : sequence of shapely Polygon, optional
        The holes cut into the boundary (used with ``boundary``).
    boundary : shapely Polygon or MultiPolygon, optional
        The panel's outline (holes allowed).
    min_web, min_opening, min_inside_radius : float, optional
        Limits in drawing units (mm).
    corner_tolerance : float
        Uncut material thinner than this is ignored (chord-vs-arc noise of fillets).
    tolerance : float
        Webs and openings within this of their limit pass (a web inset to exactly
        ``min_web`` is not a violation because of rounding).
    islands : bool
        Look for loose parts.

    Returns
    -------
    Report
        The violations, worst first within each kind.

    Raises
    ------
    ValueError
        Without geometry, with both ``frame`` and ``openings``, or for a negative limit.
    """
    min_web = _check_limit("min_web", min_web)
    min_opening = _check_limit("min_opening", min_opening)
    min_inside_radius = _check_limit("min_inside_radius", min_inside_radius)
    corner_tolerance = _check_limit("corner_tolerance", corner_tolerance) or 0.0
    tolerance = _check_limit("tolerance", tolerance) or 0.0
    if frame is not None and openings is not None:
        raise ValueError("give either frame or openings (with boundary), not both")
    if frame is not None:
        frame_geom = shapely.union_all(_as_polygons(frame, "frame"))
        outline, holes = split_frame(frame_geom)
        if boundary is not None:
            outline = shapely.union_all(_as_polygons(boundary, "boundary"))
    elif openings is not None:
        if boundary is None:
            raise ValueError("openings need a boundary to check against")
        holes = _as_polygons(openings, "openings")
        outline = shapely.union_all(_as_polygons(boundary, "boundary"))
        frame_geom = outline.difference(shapely.union_all(holes)) if len(holes) else outline
    else:
        raise ValueError("check needs a frame, or openings and a boundary")

    found: list[Violation] = []
    if min_web is not None and min_web > 0:
        found += _webs(holes, outline, min_web, tolerance)
    if min_opening is not None and min_opening > 0:
        found += _openings(holes, min_opening, tolerance)
    if min_inside_radius is not None and min_inside_radius > 0:
        found += _corners(holes, outline, min_inside_radius, corner_tolerance)
    if islands:
        found += _islands(frame_geom, outline)
    order = {k: i for i, k in enumerate(KINDS)}
    worst_first = {"web": 1, "opening": 1, "corner": -1, "island": -1}
    found.sort(key=lambda v: (order[v.kind], worst_first[v.kind] * v.value, v.location))
    limits = {
        "min_web": min_web,
        "min_opening": min_opening,
        "min_inside_radius": min_inside_radius,
    }
    return Report(found, limits, frame_geom, holes)


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
    if tolerance is None:
        xmin, ymin, xmax, ymax = shapely.bounds(polys).T
        tolerance = np.maximum(
            np.minimum(xmax - xmin, ymax - ymin) * config.INSCRIBED_RTOL, config.INSCRIBED_FLOOR
        )
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


def _deepest(pieces: np.ndarray, reach) -> list[tuple[float, tuple[float, float], int]]:
    """For each leftover piece: depth (largest distance of its vertices from ``reach``)."""
    out = []
    for k, piece in enumerate(pieces):
        xy = shapely.get_coordinates(piece)
        if not len(xy):
            continue
        d = shapely.distance(shapely.points(xy), reach)
        j = int(np.argmax(d))
        out.append((float(d[j]), (float(xy[j, 0]), float(xy[j, 1])), k))
    return out


def _corners(holes: np.ndarray, outline, radius: float, tolerance: float) -> list[Violation]:
    out = []
    quad = 16
    if len(holes):
        reach = shapely.buffer(
            shapely.buffer(holes, -radius, quad_segs=quad), radius, quad_segs=quad
        )
        left = shapely.difference(holes, reach)
        area_floor = (tolerance * config.FAB_CORNER_AREA_RTOL) ** 2
        for i in np.flatnonzero(shapely.area(left) > area_floor).tolist():
            if reach[i].is_empty:  # the tool does not fit at all: value = largest radius that does
                centres, radii = inscribed_circles([holes[i]])
                x, y = centres[0]
                out.append(Violation("corner", (float(x), float(y)), float(radii[0]), radius, (i,)))
                continue
            for depth, xy, _ in _deepest(shapely.get_parts(left[i]), reach[i]):
                if depth > tolerance:
                    out.append(Violation("corner", xy, depth, radius, (i,)))
    if not outline.is_empty:
        # The outline is cut from outside: the tool cannot enter concave notches of the part.
        closed = outline.buffer(radius, quad_segs=quad).buffer(-radius, quad_segs=quad)
        extra = shapely.get_parts(closed.difference(outline))
        for depth, xy, _ in _deepest(extra, outline.boundary):
            if depth > tolerance:
                out.append(Violation("corner", xy, depth, radius, (-1,)))
    return out


def _islands(frame, outline) -> list[Violation]:
    if frame is None or frame.is_empty or outline.is_empty:
        return []
    rim = outline.boundary
    out = []
    tol = config.ISLAND_TOUCH_RTOL * max(1.0, float(np.abs(shapely.bounds(outline)).max()))
    for part in shapely.get_parts(frame):
        if part.is_empty or part.geom_type != "Polygon":
            continue
        if shapely.distance(part.exterior, rim) > tol:
            p = part.point_on_surface()
            out.append(Violation("island", (p.x, p.y), float(part.area), 0.0))
    return out


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
