"""Build a design file: boundary -> seeds -> relax -> Voronoi -> field -> cell ops -> files.

:func:`compute` turns a validated :class:`~voroforge.design.schema.Design` into geometry
(:class:`Result`); :func:`build` writes the files the design names (SVG/DXF layers, PNG
preview, GeoJSON, GIF sweep, fabrication report); :func:`check_design` runs the fabrication
check. Every random choice comes from the design's seed, and the writers are deterministic,
so the same file and seed give byte-identical outputs.

Examples
--------
>>> design = {
...     "boundary": {"shape": "rectangle", "width": 120, "height": 80},
...     "seeds": {"method": "poisson", "radius": 12},
...     "cells": {"web": 3, "fillet": 1.5},
... }
>>> import tempfile
>>> [p.name for p in build(design, tempfile.mkdtemp())]
['design.svg', 'design.png']
"""

from __future__ import annotations

import inspect
from collections.abc import Callable
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
import shapely

from .schema import Design, DesignError, Graded, Issue, key_lines, load

__all__ = [
    "STARTER",
    "DesignWarning",
    "Result",
    "build",
    "check_design",
    "compute",
    "products",
    "render_preview",
    "write_starter",
]

Stage = Callable[[str], None]


class DesignWarning(UserWarning):
    """A design that builds but probably not as meant (``voroforge build`` prints it)."""


@dataclass
class Result:
    """The geometry of a built design.

    Attributes
    ----------
    design : Design
        The validated design.
    boundary : shapely Polygon or MultiPolygon
        The panel outline.
    domain : shapely Polygon or MultiPolygon
        Where the cells live (the boundary shrunk by ``boundary.margin``).
    sites : (n, 2) float64
        The Voronoi sites after relaxation.
    raw : (m,) object array
        The cells before cell operations (all recursion levels' leaves).
    cells : (m,) object array
        The cells after inset, scale, smooth and fillet (empty where they vanished).
    mask : (m,) bool
        Which cells are openings.
    values : (m,) float64
        The attractor field at each cell (0 without attractors).
    level : (m,) int
        Recursion level of each cell (0 without recursion).
    openings : (k,) object array
        The non-empty openings, cut from the boundary.
    frame : shapely geometry
        The boundary minus the openings.
    extra : dict
        Recursion levels (``"levels"``) and cached derived data.
    """

    design: Design
    boundary: object
    domain: object
    sites: np.ndarray
    raw: np.ndarray
    cells: np.ndarray
    mask: np.ndarray
    values: np.ndarray
    level: np.ndarray
    openings: np.ndarray
    frame: object
    extra: dict = field(default_factory=dict)

    @property
    def edges(self):
        """The unique edges of the raw cells (each shared edge once), computed on first use."""
        if "edges" not in self.extra:
            from . import cellops

            self.extra["edges"] = cellops.edges_to_lines(cellops.explode(self.raw))
        return self.extra["edges"]


def _fail(key: str, message: str) -> DesignError:
    return DesignError([Issue(key, None, message)])


def _path(base: Path | None, name: str, key: str) -> Path:
    p = Path(name)
    if not p.is_absolute() and base is not None:
        p = base / p
    if not p.exists():
        raise _fail(key, f"file not found: {p}")
    return p


# --- boundary and seeds -----------------------------------------------------------------


def _file_boundary(path: Path, units: str):
    """A boundary file in the design's units.

    An SVG whose width has a physical unit (``width="24in"``) is read in mm, so it is scaled
    to the design's units (a 24 in panel in an inch design was 609.6 in wide). Unitless
    SVGs, DXF (coordinates as drawn) and GeoJSON are taken as they are.
    """
    from . import boundary as bd

    geom = bd.load(path)
    return _svg_in_units(geom, path, units) if path.suffix.lower() == ".svg" else geom


def _svg_in_units(geom, path: Path, units: str):
    """Geometry read from an SVG (in mm when its width has a unit) in the design's units."""
    import xml.etree.ElementTree as ET

    from shapely import affinity

    from . import boundary as bd

    if units == "mm":
        return geom
    m = bd._LENGTH.match(ET.parse(path).getroot().get("width") or "")
    if not (m and m.group(2) in bd._MM_PER_UNIT):
        return geom
    factor = 1.0 / _MM[units]
    return affinity.scale(geom, factor, factor, origin=(0.0, 0.0))


def _boundary(design: Design, base: Path | None):
    from . import boundary as bd

    spec = design.boundary
    if spec.shape == "rectangle":
        geom = bd.rectangle(spec.width, spec.height, origin=spec.origin)
    elif spec.shape == "circle":
        geom = bd.circle(spec.radius, center=spec.center, segments=spec.segments)
    elif spec.shape == "polygon":
        geom = bd.polygon(spec.points, spec.holes)
    elif spec.shape == "polygons":
        geom = bd.union(*(bd.polygon(p.points, p.holes) for p in spec.parts))
    else:
        geom = _file_boundary(_path(base, spec.file, "boundary.file"), design.design.units)
    if spec.corner_radius > 0:
        r = spec.corner_radius
        core = geom.buffer(-r, join_style="mitre")
        if core.is_empty:
            # r = half the width (a stadium, a disc): the core is a segment or a point, which
            # GEOS drops; 1e-4 r less keeps a sliver of it (and the outline inside the shape)
            r = r * (1 - 1e-4)
            core = geom.buffer(-r, join_style="mitre")
        geom = core.buffer(r, quad_segs=16)
        if geom.is_empty:
            raise _fail(
                "boundary.corner_radius", f"{spec.corner_radius} is too large for the boundary"
            )
    domain = geom
    if spec.margin > 0:
        domain = geom.buffer(-spec.margin, join_style="mitre")
        if domain.is_empty:
            raise _fail("boundary.margin", f"{spec.margin} leaves nothing of the boundary")
    return geom, domain


def _curve(a, base: Path | None, key: str, units: str = "mm"):
    """The polyline(s) of a curve attractor: points, SVG path data or a file."""
    from . import boundary as bd

    if a.points is not None:
        return np.asarray(a.points, dtype=np.float64)
    if a.path is not None:
        lines = bd.path_lines(a.path)
        if not lines:
            raise _fail(f"{key}.path", "the SVG path data draws nothing")
        return shapely.MultiLineString([np.asarray(x)[:, :2] for x in lines])
    path = _path(base, a.file, f"{key}.file")
    if path.suffix.lower() == ".svg":
        return _svg_in_units(bd.curves_from_svg(path), path, units)
    geom = shapely.union_all(shapely.get_parts(shapely.from_geojson(path.read_text("utf-8"))))
    lines = [g.boundary if g.geom_type.endswith("Polygon") else g for g in shapely.get_parts(geom)]
    merged = shapely.union_all([g for g in lines if "LineString" in g.geom_type])
    if merged.is_empty:
        raise _fail(f"{key}.file", "no lines or polygons in the file")
    return merged


def _field(design: Design, base: Path | None = None):
    """The combined attractor field, or ``None`` without attractors."""
    if not design.attractors:
        return None
    from . import attractors as at

    made = []
    for i, a in enumerate(design.attractors):
        options = {
            "radius": a.radius,
            "strength": a.strength,
            "falloff": a.falloff,
            "power": a.power,
        }
        if a.type == "point":
            made.append(at.PointAttractor(np.asarray(a.points, dtype=np.float64), **options))
        else:
            made.append(
                at.CurveAttractor(
                    _curve(a, base, f"attractors.{i}", design.design.units), **options
                )
            )
    combined = at.combine(made, mode=design.field.combine)
    if design.field.invert:
        return at.Field(lambda xy: 1.0 - np.asarray(combined(xy), dtype=np.float64))
    return combined


def _seeds(design: Design, domain, field_fn, base: Path | None) -> np.ndarray:
    from . import populate

    s = design.seeds
    seed = design.design.seed if s.seed is None else s.seed
    if s.method == "random":
        return populate.random(domain, s.count, seed=seed)
    if s.method == "grid":
        return populate.grid(domain, s.spacing, angle=s.angle, offset=s.offset)
    if s.method == "hexgrid":
        return populate.hexgrid(domain, s.spacing, angle=s.angle, offset=s.offset)
    if s.method == "jittered":
        return populate.jittered(
            domain, s.spacing, jitter=s.jitter, seed=seed, angle=s.angle, offset=s.offset
        )
    if s.method == "poisson":
        use = field_fn if s.use_field else None
        if s.use_field and field_fn is None:
            raise _fail("seeds.use_field", "needs at least one [[attractors]] table")
        return populate.poisson(domain, s.radius, seed=seed, field=use, radius_max=s.radius_max)
    if s.method == "density":
        if field_fn is None:
            raise _fail("seeds.method", "'density' needs at least one [[attractors]] table")
        return populate.by_density(domain, s.count, field_fn, seed=seed)
    with _section("seeds.file"):
        pts = populate.from_file(_path(base, s.file, "seeds.file"))
    inside = shapely.contains_xy(domain, pts[:, 0], pts[:, 1])
    return pts[inside]


def _site_properties(design: Design, domain, base: Path | None):
    """Points and properties of a GeoJSON seed file, for the seeds kept (or None)."""
    import json

    s = design.seeds
    if s.method != "file" or Path(s.file).suffix.lower() not in (".geojson", ".json"):
        return None
    data = json.loads(_path(base, s.file, "seeds.file").read_text(encoding="utf-8"))
    feats = data.get("features", []) if isinstance(data, dict) else []
    xy, props = [], []
    for f in feats:
        geom = f.get("geometry") or {}
        coords = geom.get("coordinates")
        points = (
            [coords]
            if geom.get("type") == "Point"
            else (coords if geom.get("type") == "MultiPoint" else [])
        )
        for c in points:
            xy.append(c[:2])
            props.append(dict(f.get("properties") or {}))
    if not xy:
        return None
    xy = np.asarray(xy, dtype=np.float64)
    inside = shapely.contains_xy(domain, xy[:, 0], xy[:, 1])
    return xy[inside], [p for p, keep in zip(props, inside.tolist(), strict=True) if keep]


def _relax(design: Design, points: np.ndarray, domain) -> np.ndarray:
    r = design.relax
    if r.iterations == 0 and r.tolerance is None:
        return points
    try:
        from .relax import relax
    except ImportError:  # the relax module is not there yet
        raise _fail("relax", "relaxation is not available in this version") from None
    iterations = r.iterations if r.iterations else 50
    return relax(points, domain, iterations=iterations, tol=r.tolerance)


# --- cells --------------------------------------------------------------------------------


def _voronoi(design: Design, points: np.ndarray, domain, field_fn=None) -> np.ndarray:
    import voroforge as vf

    algorithm = design.voronoi.algorithm
    radius = design.voronoi.power_radius
    if radius is not None:  # power (Laguerre) cells: a site of weight r^2 acts like a disc
        if not hasattr(vf, "power"):
            raise _fail("voronoi.power_radius", "power diagrams are not available in this version")
        values = np.zeros(len(points)) if field_fn is None else field_fn(points)
        r = _graded(
            radius,
            np.asarray(values, dtype=np.float64),
            "voronoi.power_radius",
            field_fn is not None,
        )
        weights = np.broadcast_to(np.asarray(r, dtype=np.float64) ** 2, (len(points),))
        return np.asarray(vf.power(points, weights, domain).cells, dtype=object)
    if not design.voronoi.periodic:
        return np.asarray(vf.voronoi(points, domain, algorithm=algorithm).cells, dtype=object)
    box = _tile(design, domain)
    if "periodic" in inspect.signature(vf.voronoi).parameters:
        d = vf.voronoi(points, box, algorithm=algorithm, periodic=True)
        return np.asarray(d.cells, dtype=object)
    # Without a periodic engine: the 3 x 3 copies of the sites, cells of the middle copy.
    xmin, ymin, xmax, ymax = box
    w, h = xmax - xmin, ymax - ymin
    shifts = [(dx, dy) for dy in (0.0, -h, h) for dx in (0.0, -w, w)]
    tiled = np.concatenate([points + s for s in shifts])
    d = vf.voronoi(tiled, (xmin - w, ymin - h, xmax + w, ymax + h), algorithm=algorithm)
    return np.asarray(d.cells, dtype=object)[: len(points)]


def _tile(design: Design, domain) -> tuple[float, float, float, float]:
    if (
        design.boundary.shape != "rectangle"
        or design.boundary.corner_radius
        or design.boundary.margin
    ):
        raise _fail("voronoi.periodic", "a periodic tile needs a plain rectangle boundary")
    return tuple(float(v) for v in domain.bounds)


def _wrap(cells: np.ndarray, box) -> tuple[np.ndarray, np.ndarray]:
    """Pieces of periodic cells inside the tile (every copy), and the cell each came from."""
    xmin, ymin, xmax, ymax = box
    w, h = xmax - xmin, ymax - ymin
    rect = shapely.box(*box)
    pieces, owner = [], []
    for dy in (0.0, -h, h):
        for dx in (0.0, -w, w):
            moved = shapely.transform(cells, lambda xy, dx=dx, dy=dy: xy + (dx, dy))
            cut = shapely.intersection(moved, rect)
            keep = ~shapely.is_empty(cut) & (shapely.area(cut) > 0)
            pieces.extend(cut[keep])
            owner.extend(np.flatnonzero(keep).tolist())
    return np.asarray(pieces, dtype=object), np.asarray(owner, dtype=np.int64)


def _values(cells: np.ndarray, field_fn) -> np.ndarray:
    if field_fn is None or not len(cells):
        return np.zeros(len(cells))
    live = ~shapely.is_empty(cells)
    pts = shapely.point_on_surface(cells[live])
    out = np.zeros(len(cells))
    out[live] = np.asarray(field_fn(shapely.get_coordinates(pts)), dtype=np.float64)
    return out


def _graded(value: Graded, values: np.ndarray, key: str, has_field: bool):
    if not value.graded:
        return float(value.value)
    if not has_field:
        raise _fail(key, "near/far values need at least one [[attractors]] table")
    return value.far + (value.near - value.far) * values


def _recurse(design: Design, domain, points, field_fn, seed):
    """Recursion levels -> (leaf cells, their openings, level per cell, the levels)."""
    rec = design.recursion
    from . import cellops
    from .recursive import subdivide

    count_spec = rec.count
    if count_spec.graded and field_fn is None:
        raise _fail("recursion.count", "near/far values need at least one [[attractors]] table")

    def count(region) -> int:
        if not count_spec.graded:
            return max(0, int(round(count_spec.value)))
        v = float(_values(np.asarray([region], dtype=object), field_fn)[0])
        return max(0, int(round(count_spec.far + (count_spec.near - count_spec.far) * v)))

    def select(level):
        live = ~shapely.is_empty(np.asarray(level.openings, dtype=object))
        if rec.probability >= 1.0:
            return live
        # A fresh, reproducible draw per level.
        draw = cellops.random(len(level), rec.probability, seed=seed * 1009 + level.depth)
        return np.asarray(draw, dtype=bool) & live

    webs = list(rec.web)
    if len(webs) not in (0, 1, rec.depth + 1):
        raise _fail("recursion.web", f"give one width or depth + 1 = {rec.depth + 1} widths")
    web = webs if len(webs) > 1 else (webs[0] if webs else 0.0)
    join = design.cells.join
    levels = subdivide(
        domain, points, depth=rec.depth, count=count, seed=seed, select=select, web=web, join=join
    )
    cells, holes, depth = [], [], []
    for i, lv in enumerate(levels):
        lv_cells = np.asarray(lv.cells, dtype=object)
        lv_open = np.asarray(lv.openings if lv.openings is not None else lv.cells, dtype=object)
        split = set()
        if i + 1 < len(levels):
            split = set(np.asarray(levels[i + 1].parent).tolist())
        keep = [j for j in range(len(lv_cells)) if j not in split]
        cells.extend(lv_cells[keep])
        holes.extend(lv_open[keep])
        depth.extend([lv.depth] * len(keep))
    return (
        np.asarray(cells, dtype=object),
        np.asarray(holes, dtype=object),
        np.asarray(depth, dtype=np.int64),
        levels,
    )


def _mask(design: Design, cells: np.ndarray, values: np.ndarray, seed: int) -> np.ndarray:
    from . import cellops

    o = design.openings
    n = len(cells)
    live = ~shapely.is_empty(cells) if n else np.zeros(0, dtype=bool)
    if o.select == "all":
        mask = np.ones(n, dtype=bool)
    elif o.select == "area":
        mask = cellops.by_area(cells, min=o.min_area, max=o.max_area)
    elif o.select == "random":
        mask = cellops.random(n, o.probability, seed=seed if o.seed is None else o.seed)
    elif o.select == "every_kth":
        mask = cellops.every_kth(n, o.k, start=o.start)
    elif o.select == "largest":
        mask = cellops.largest(cells, o.count)
    else:
        if not design.attractors:
            raise _fail("openings.select", "'field' needs at least one [[attractors]] table")
        mask = values >= o.threshold
    mask = np.asarray(mask, dtype=bool) & live
    return ~mask & live if o.invert else mask


def _operate(design: Design, cells: np.ndarray, values: np.ndarray, has_field: bool):
    from . import cellops

    c = design.cells
    out = cells
    amount = c.inset_amount()
    if amount is not None:
        key = "cells.web" if c.web is not None else "cells.inset"
        d = _graded(amount, values, key, has_field)
        if np.any(np.asarray(d) < 0):
            raise _fail(key, "must be >= 0 (use cells.scale > 1 to grow cells)")
        out = cellops.inset(out, d, join=c.join)
    if c.scale.graded or c.scale.value != 1.0:
        factor = _graded(c.scale, values, "cells.scale", has_field)
        if np.any(np.asarray(factor) < 0):
            raise _fail("cells.scale", "scale factors must be >= 0")
        out = cellops.scale(out, factor)
    if c.smooth:
        out = cellops.smooth(out, iterations=c.smooth)
    if c.fillet.graded or c.fillet.value:
        r = _graded(c.fillet, values, "cells.fillet", has_field)
        if np.any(np.asarray(r) < 0):
            raise _fail("cells.fillet", "fillet radii must be >= 0")
        out = cellops.fillet(out, r)
    out = np.asarray(out, dtype=object)
    if c.min_area > 0:
        out[shapely.area(out) < c.min_area] = shapely.Polygon()
    if c.min_size > 0:  # openings narrower than min_size (inscribed circle) stay solid
        live = np.flatnonzero(~shapely.is_empty(out))
        if len(live):
            from .fabrication import inscribed_circles

            _, radii = inscribed_circles(out[live], tolerance=c.min_size * 1e-3)
            thin = 2.0 * radii < c.min_size
            out[live[thin]] = shapely.Polygon()
    return np.asarray(out, dtype=object)


@contextmanager
def _located(source, overrides: dict | None):
    """Give build-time DesignErrors the design file's name and the lines of their keys."""
    try:
        yield
    except DesignError as exc:
        if not isinstance(source, str | Path) or exc.source is not None:
            raise
        try:
            lines = key_lines(Path(source).read_text(encoding="utf-8-sig"))
        except OSError:
            lines = {}
        touched = {str(k) for k in (overrides or {})}
        issues = []
        for it in exc.issues:
            path = tuple(int(p) if p.isdigit() else p for p in it.key.split(".") if p)
            line = None
            for n in range(len(path), 0, -1):
                if path[:n] in lines:
                    line = lines[path[:n]]
                    break
            if any(
                it.key == t or it.key.startswith(t + ".") or t.startswith(it.key + ".")
                for t in touched
            ):
                issues.append(Issue(it.key, None, it.message + " (from --set)"))
            else:
                issues.append(Issue(it.key, line, it.message))
        raise DesignError(issues, str(source)) from None


@contextmanager
def _section(key: str):
    """Turn a library ``ValueError`` raised while building ``key`` into a DesignError."""
    try:
        yield
    except DesignError:
        raise
    except ValueError as exc:
        raise _fail(key, str(exc)) from None


def compute(design: Design, base: Path | None = None, *, progress: Stage | None = None) -> Result:
    """Compute the geometry of a validated design.

    Parameters
    ----------
    design : Design
        From :func:`voroforge.design.schema.load`.
    base : Path, optional
        Folder that relative file names in the design are read from.
    progress : callable, optional
        Called with the name of each stage.

    Returns
    -------
    Result

    Raises
    ------
    DesignError
        For a design that validates but cannot be built (a missing file, a field-driven
        value without attractors, ...), naming the key.
    """
    stage = progress or (lambda name: None)
    seed = design.design.seed
    stage("boundary")
    with _section("boundary.file" if design.boundary.shape == "file" else "boundary"):
        boundary, domain = _boundary(design, base)
    with _section("attractors"):
        field_fn = _field(design, base)
    stage("seeds")
    with _section("seeds"):
        points = _seeds(design, domain, field_fn, base)
        points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    if len(points) < 1:
        raise _fail("seeds", "no seeds fall inside the boundary; need 1 or more")
    extra: dict = {}
    with _section("seeds.file"):
        given = _site_properties(design, domain, base)
    if given is not None and given[0].shape == points.shape and np.array_equal(given[0], points):
        extra["site_properties"] = given[1]
    with _section("relax"):
        points = _relax(design, points, domain)
    stage(f"{len(points)} Voronoi cells")
    if design.recursion.depth > 0:
        if design.voronoi.periodic:
            raise _fail("recursion.depth", "recursion and periodic tiles do not combine yet")
        if design.cells.inset_amount() is not None:
            raise _fail("cells.web", "with [recursion], give the webs as recursion.web")
        with _section("recursion"):
            raw, inset_cells, level, extra["levels"] = _recurse(
                design, domain, points, field_fn, seed
            )
    else:
        with _section("voronoi"):
            raw = _voronoi(design, points, domain, field_fn)
        inset_cells = raw
        level = np.zeros(len(raw), dtype=np.int64)
    values = _values(raw, field_fn)
    with _section("openings"):
        mask = _mask(design, raw, values, seed)
    stage("cell operations")
    with _section("cells"):
        cells = _operate(design, inset_cells, values, field_fn is not None)
    if design.voronoi.periodic:
        box = _tile(design, domain)
        # whole openings on the torus, for the fabrication check across the seams
        extra["tile"] = box
        extra["tile_openings"] = cells[mask & ~shapely.is_empty(cells)]
        cells, owner = _wrap(cells, box)
        raw_w, _ = _wrap(raw, box)
        raw, values, mask, level = raw_w, values[owner], mask[owner], level[owner]
    chosen = cells[mask & ~shapely.is_empty(cells)] if len(cells) else cells
    openings = np.asarray(chosen, dtype=object)
    frame = _frame(boundary, openings)
    return Result(
        design, boundary, domain, points, raw, cells, mask, values, level, openings, frame, extra
    )


def _frame(boundary, openings: np.ndarray):
    """Boundary minus openings; disjoint holes strictly inside become holes directly (fast)."""
    if not len(openings):
        return boundary
    simple = boundary.geom_type == "Polygon" and all(
        o.geom_type == "Polygon" and not o.interiors for o in openings
    )
    if simple:
        shapely.prepare(boundary)
        if shapely.contains_properly(boundary, openings).all():
            left, right = shapely.STRtree(openings).query(openings, predicate="intersects")
            if (left == right).all():
                rings = [*boundary.interiors, *(o.exterior for o in openings)]
                return shapely.Polygon(boundary.exterior, rings)
    return boundary.difference(shapely.union_all(openings))


# --- outputs ------------------------------------------------------------------------------


def products(result: Result, *, kerf: float = 0.0) -> dict[str, list]:
    """The geometry of every product name, optionally kerf-compensated (polygons only)."""
    from .fabrication import kerf as apply_kerf

    frame = result.frame
    openings = list(result.openings)
    cells = [c for c in result.cells if not c.is_empty]
    if kerf > 0:
        frame = apply_kerf(frame, kerf, role="part")
        openings = list(apply_kerf(openings, kerf, role="hole")) if openings else []
        cells = list(apply_kerf(cells, kerf, role="part")) if cells else []
    # The outline is the part's edge too: cut on a layer, it grows like the frame.
    outline = apply_kerf(result.boundary, kerf, role="part") if kerf > 0 else result.boundary
    return {
        "frame": [frame],
        "openings": openings,
        "cells": cells,
        "edges": [result.edges],
        "sites": [shapely.MultiPoint(result.sites)],
        "boundary": [outline],
    }


def _layers(result: Result, kerf: float) -> dict[str, list]:
    made = products(result, kerf=kerf)
    out = {}
    for name, what in result.design.output.layers.items():
        names = [what] if isinstance(what, str) else list(what)
        out[name.upper()] = [g for n in names for g in made[n]]
    return out


def render_preview(result: Result, *, size: int = 1200):
    """A PIL image of the design: openings in colour on the panel, or edges for line work."""
    from ..io.png import render_image
    from ..io.render import palette

    layers = result.design.output.layers
    first = next(iter(layers.values()), "frame")
    first = first if isinstance(first, str) else first[0]
    mode = result.design.output.png
    if mode == "layers" and first == "edges":
        xmin, ymin, xmax, ymax = result.boundary.bounds
        width = max(xmax - xmin, ymax - ymin) / 900.0
        lines = shapely.buffer(result.edges, width, quad_segs=2, cap_style="flat")
        return render_image(
            [lines], size=size, colors=[(25, 25, 35)], edge_width=0.0, boundary=result.boundary
        )
    if mode == "layers" and first in ("frame", "boundary"):
        return render_image([result.frame], size=size, colors=[(52, 58, 70)], edge_width=0.6)
    geoms = [result.frame, *result.openings]
    colours = [(236, 236, 240)] + [
        tuple(c) for c in palette(len(result.openings), result.design.design.seed).tolist()
    ]
    sites = result.sites if result.design.output.png_sites else None
    return render_image(geoms, size=size, colors=colours, edge_width=0.6, sites=sites)


def _source_crs(result: Result, base: Path | None):
    """The ``"crs"`` member of the boundary's or the seeds' GeoJSON file, or None.

    QGIS writes one for projected data; copying it keeps the output where the input was.
    """
    import json

    d = result.design
    files = [d.boundary.file if d.boundary.shape == "file" else None]
    files.append(d.seeds.file if d.seeds.method == "file" else None)
    for name in files:
        if not name or Path(name).suffix.lower() not in (".geojson", ".json"):
            continue
        try:
            data = json.loads(_path(base, name, "").read_text(encoding="utf-8"))
        except (OSError, ValueError, DesignError):
            continue
        if isinstance(data, dict) and isinstance(data.get("crs"), dict):
            return data["crs"]
    return None


def _geojson(result: Result, path: Path, base: Path | None = None) -> Path:
    from ..io.geojson import write_geojson

    crs = _source_crs(result, base)
    what = result.design.output.geojson
    if what == "cells":
        keep = ~shapely.is_empty(result.cells)
        geoms = result.cells[keep]
        props = {
            "cell": np.flatnonzero(keep),
            "field": result.values[keep],
            "opening": result.mask[keep],
            "level": result.level[keep],
        }
        sites = None
        one_to_one = len(result.cells) == len(result.sites) and not result.design.voronoi.periodic
        if one_to_one and result.design.recursion.depth == 0:
            sites = result.sites[keep]
            given = result.extra.get("site_properties")
            if given is not None:  # carry the seed file's properties (names, ids) over
                kept = [given[i] for i in np.flatnonzero(keep)]
                for name in sorted({k for p in kept for k in p}):
                    key = name if name not in (*props, "index", "area", "site") else f"site_{name}"
                    props[key] = [p.get(name) for p in kept]
        return write_geojson(geoms, path, sites=sites, properties=props, crs=crs)
    geoms = products(result)[what]
    if what == "edges":
        geoms = list(shapely.get_parts(result.edges))
    return write_geojson(geoms, path, crs=crs)


def build(
    source,
    out_dir=".",
    *,
    overrides: dict | None = None,
    preview: bool = False,
    progress: Stage | None = None,
) -> list[Path]:
    """Build a design file and write every output it names.

    Parameters
    ----------
    source : str, Path, dict or Design
        A TOML design file, its parsed mapping, or a validated design.
    out_dir : str or Path
        Output folder; created if missing.
    overrides : dict, optional
        ``{"seeds.count": 500, "cells.web": 2}`` (dotted keys, values or TOML strings).
    preview : bool
        Write only the PNG preview (at most 800 px).
    progress : callable, optional
        Called with the name of each stage.

    Returns
    -------
    list of Path
        The files written, in the order of ``output.formats``.

    Raises
    ------
    DesignError
        For a bad design file (each issue names key and line).
    """
    stage = progress or (lambda name: None)
    if isinstance(source, Design):
        design, base = source, None
        if overrides:
            design, base = load(design.model_dump(), overrides=overrides)
    else:
        design, base = load(source, overrides=overrides)
    with _located(source, overrides):
        result = compute(design, base, progress=stage)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    o = design.output
    stem = o.stem or design.design.name
    written: list[Path] = []
    if preview:
        stage("writing preview")
        path = out / f"{stem}.png"
        render_preview(result, size=min(o.png_size, 800)).save(path, optimize=False)
        return [path]
    if "svg" in o.formats and design.design.units not in ("mm", "cm", "in"):
        raise _fail("output.formats", f"svg needs units mm, cm or in; not {design.design.units!r}")
    kerf = o.kerf
    if "svg" in o.formats or "dxf" in o.formats:
        _warn_empty_layers(result)
    for fmt in o.formats:
        path = out / f"{stem}.{fmt}"
        stage(f"writing {path.name}")
        if fmt == "svg":
            from ..io.svg import write_layers

            written.append(
                write_layers(
                    path,
                    _layers(result, kerf),
                    units=design.design.units,
                    stroke_width=_stroke_width(design),
                    # kerf-compensated parts reach kerf / 2 past the outline: keep them on the page
                    bounds=tuple(
                        np.add(result.boundary.bounds, np.multiply([-1, -1, 1, 1], kerf / 2))
                    ),
                )
            )
        elif fmt == "dxf":
            from ..io.dxf import write_dxf

            written.append(
                write_dxf(
                    None,
                    path,
                    layers=_layers(result, kerf),
                    units=design.design.units,
                    arc_tolerance=o.arc_tolerance,
                )
            )
        elif fmt == "png":
            render_preview(result, size=o.png_size).save(path)
            written.append(path)
        elif fmt == "geojson":
            written.append(_geojson(result, path, base))
        elif fmt == "gif":
            with _located(source, overrides):
                written.append(_gif(design, base, path, stage))
    if design.fabrication.report:
        report = _report(result)
        text = out / f"{stem}-check.txt"
        text.write_text(report.table() + "\n", encoding="utf-8")
        written.append(text)
        written.append(report.write_png(out / f"{stem}-check.png", size=min(o.png_size, 1200)))
    return written


#: Millimetres per design unit.
_MM = {"mm": 1.0, "cm": 10.0, "m": 1000.0, "in": 25.4}


def _stroke_width(design: Design) -> float:
    """SVG stroke width in design units: as given, else a 0.01 mm laser hairline.

    Laser drivers take only hairlines (about 0.001 in or less) as vector cuts, so the default
    is 0.01 mm whatever the units (0.01 in would be engraved, not cut).
    """
    given = design.output.stroke_width
    return given if given is not None else 0.01 / _MM[design.design.units]


def _warn_empty_layers(result: Result) -> None:
    """Warn about SVG/DXF layers with nothing on them (a cut file that cuts nothing)."""
    import warnings

    made = products(result)
    for name, what in result.design.output.layers.items():
        names = [what] if isinstance(what, str) else list(what)
        if all(g.is_empty for n in names for g in made[n]):
            hint = ""
            if "frame" in names and len(result.openings):
                hint = (
                    ": the openings fill the whole boundary (set cells.web or cells.inset, "
                    "or draw the edges)"
                )
            warnings.warn(
                f"output.layers.{name}: the layer is empty ({', '.join(names)}){hint}",
                DesignWarning,
                stacklevel=3,
            )


def _gif(design: Design, base: Path | None, path: Path, stage: Stage) -> Path:
    from ..io.gif import write_gif

    gif = design.output.gif
    data = design.model_dump()
    frames = []
    values = gif.sweep()
    unique = {}
    for i, v in enumerate(values):
        if repr(v) not in unique:
            stage(f"gif frame {i + 1}/{len(values)}")
            try:
                d, _ = load(data, overrides={gif.key: v})
                unique[repr(v)] = render_preview(compute(d, base), size=gif.size)
            except DesignError as exc:
                raise DesignError(
                    [
                        Issue(
                            "output.gif.key",
                            None,
                            f"{gif.key} = {v!r}: {it.key}: "
                            + it.message.removesuffix(" (from --set)"),
                        )
                        for it in exc.issues
                    ]
                ) from None
        frames.append(unique[repr(v)])
    return write_gif(frames, path, fps=gif.fps)


def _report(result: Result):
    from .fabrication import Report, check

    f = result.design.fabrication
    limits = {
        "min_web": f.min_web,
        "min_opening": f.min_opening,
        "min_inside_radius": f.tool_radius,
        "corner_tolerance": f.corner_tolerance,
        "islands": f.islands,
    }
    if "tile" not in result.extra:
        return check(openings=result.openings, boundary=result.boundary, **limits)
    # A periodic tile is cut as copies side by side: openings cut by the tile's edge continue
    # in the next copy, so check the whole openings of 3 x 3 copies against each other (no
    # outline in reach) and report what lies in the middle copy.
    xmin, ymin, xmax, ymax = result.extra["tile"]
    w, h = xmax - xmin, ymax - ymin
    whole = result.extra["tile_openings"]
    copies = [
        shapely.transform(whole, lambda xy, dx=dx, dy=dy: xy + (dx, dy))
        for dy in (0.0, -h, h)
        for dx in (0.0, -w, w)
    ]
    holes = np.concatenate(copies) if len(whole) else whole
    far = shapely.box(xmin - 2 * w, ymin - 2 * h, xmax + 2 * w, ymax + 2 * h)
    tiled = check(openings=holes, boundary=far, **limits)
    n = max(len(whole), 1)
    kept = [
        replace(v, items=tuple(i % n if i >= 0 else i for i in v.items))
        for v in tiled.violations
        if xmin <= v.location[0] < xmax and ymin <= v.location[1] < ymax
    ]
    return Report(kept, tiled.limits, result.frame, result.openings)


def check_design(source, *, overrides: dict | None = None, progress: Stage | None = None):
    """Build a design's geometry and run the fabrication check with its ``[fabrication]`` limits.

    Returns
    -------
    voroforge.design.fabrication.Report
    """
    design, base = load(source, overrides=overrides)
    with _located(source, overrides):
        return _report(compute(design, base, progress=progress))


#: The commented starter design that ``voroforge new`` writes.
STARTER = """\
# A voroforge design file. Build it with:   voroforge build design.toml -o out
# Check it for fabrication with:            voroforge check design.toml
# Every key is documented in docs/design-files.md. Lengths are in [design] units (mm).

[design]
name = "my-panel"          # output files are my-panel.svg, my-panel.dxf, ...
units = "mm"
seed = 1                   # same seed -> same design, byte for byte

[boundary]
shape = "rectangle"        # rectangle | circle | polygon | file
width = 300
height = 200
corner_radius = 8          # round the panel's outer corners
margin = 10                # solid border between the outline and the pattern

[seeds]
method = "poisson"         # random | grid | hexgrid | jittered | poisson | density | file
radius = 22                # Poisson-disk: minimum distance between seeds
# radius_max = 45          # with use_field = true: spacing grows to this away from attractors
# use_field = true

[relax]
iterations = 0             # Lloyd relaxation steps (more = more even cells)

# Attractors make a field in [0, 1]: 1 at the attractor, 0 beyond its radius.
# Any number can then be a range: web = { near = 6, far = 2 }.
[[attractors]]
type = "point"             # point | curve (points = a polyline)
points = [[90, 70]]
radius = 180
falloff = "smoothstep"     # linear | smoothstep | gaussian | inverse_power

[cells]
web = { near = 6, far = 3 }  # width of material between openings
fillet = 2                 # round every corner of the openings
# scale = 1.0              # shrink/grow openings about their centroids
# smooth = 0               # Chaikin smoothing passes for organic outlines

[openings]
select = "all"             # all | area | random | every_kth | largest | field

[output]
formats = ["svg", "dxf", "png"]
layers = { CUT = "frame" }   # layer name -> frame | openings | cells | edges | sites | boundary
kerf = 0.0                 # laser kerf: compensated on SVG/DXF export

[fabrication]
min_web = 3                # thinnest material between two cuts
min_opening = 6            # smallest opening (inscribed circle diameter)
tool_radius = 1.5          # CNC: smallest inside-corner radius the tool can cut
"""


def write_starter(path="design.toml", *, overwrite: bool = False) -> Path:
    """Write the commented starter design (:data:`STARTER`) to ``path``.

    Raises
    ------
    ValueError
        When the file exists and ``overwrite`` is false.
    """
    path = Path(path)
    if path.exists() and not overwrite:
        raise ValueError(f"{path}: already exists (use --force to overwrite)")
    path.write_text(STARTER, encoding="utf-8")
    return path
