"""Compute a design: boundary -> seeds -> relax -> Voronoi -> field -> cell operations.

:func:`compute` turns a validated :class:`~voroforge.design.schema.Design` into geometry
(:class:`Result`) in memory and writes no files: it is what a build, a check, a GIF frame and
an interactive editor call on every change. Every random choice comes from the design's
seed, so the same design gives the same geometry. Writing outputs is
:mod:`voroforge.design.build`'s business.

Examples
--------
>>> from voroforge.design.designfile import load
>>> design, base = load({
...     "boundary": {"shape": "rectangle", "width": 120, "height": 80},
...     "seeds": {"method": "poisson", "radius": 12},
...     "cells": {"web": 3, "fillet": 1.5},
... })
>>> result = compute(design, base)
>>> len(result.openings) == len(result.sites), result.frame.area < result.boundary.area
(True, True)
"""

from __future__ import annotations

from collections.abc import Callable
from contextlib import contextmanager, nullcontext
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import shapely

from .. import config
from .boundary import MM_PER_UNIT
from .designfile import DesignError, find_file
from .recursive import tiled_holes
from .schema import Design, Graded

__all__ = ["MM_PER_UNIT", "Result", "SeedTable", "Stage", "compute", "outline"]

#: A progress callback: called with the name of each stage.
Stage = Callable[[str], None]


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
    frame : shapely geometry or None
        The boundary minus the openings (None from ``compute(..., frame=False)``).
    extra : dict
        Recursion levels (``"levels"``), the cell edges along the seed curves
        (``"curve_edges"``, for ``seeds.method = "curves"``), the seed file's rows
        (``"seed_table"``, a :class:`SeedTable`, for ``seeds.method = "file"``) and cached
        derived data.
    diagram : Diagram or None
        The engine's diagram of ``sites`` (Voronoi, power or periodic); None with recursion,
        whose leaves come from one diagram per subdivided cell.
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
    diagram: object = None

    @property
    def edges(self):
        """The unique edges of the raw cells (each shared edge once), computed on first use.

        The engine's exact shared edges (``Diagram.edges``) plus the domain's outline; with
        recursion, the cells' ring segments merged where they meet (:func:`cellops.explode`).
        """
        if "edges" not in self.extra:
            self.extra["edges"] = _edges(self)
        return self.extra["edges"]


def _edges(result: Result):
    from . import cellops

    d = result.diagram
    if d is None:
        return cellops.edges_to_lines(cellops.explode(result.raw))
    seg = d.edges.coords
    if d.periodic:  # the edges of the cells cut into the tile; the outline draws its sides
        from ..engine.periodic import periodic_voronoi

        x0, y0, x1, y1 = tile = result.extra["tile"]
        seg = periodic_voronoi(d.sites, tile, algorithm=d.algorithm, wrap=True).edges.coords
        on = [(seg[:, :, k] == v).all(axis=1) for k, v in ((0, x0), (1, y0), (0, x1), (1, y1))]
        seg = seg[~np.logical_or.reduce(on)]
    return cellops.edges_to_lines(np.concatenate((seg, _outline(result.domain))))


def _outline(geom) -> np.ndarray:
    """(m, 2, 2) segments of every ring of a polygonal geometry, without zero-length ones."""
    rings = shapely.get_rings(shapely.get_parts(geom))
    coords, ring = shapely.get_coordinates(rings, return_index=True)
    same = ring[1:] == ring[:-1]
    seg = np.stack((coords[:-1][same], coords[1:][same]), axis=1)
    return seg[(seg[:, 0] != seg[:, 1]).any(axis=1)]


# --- boundary and seeds -----------------------------------------------------------------


def outline(design: Design, base: Path | None = None):
    """``(boundary, domain)`` of ``design`` as :func:`compute` makes them, without its cells.

    For an animation frame whose boundary moves (relaxed in its own domain). Raises
    DesignError at ``boundary`` (or ``boundary.file``) for a boundary it cannot make.
    """
    with as_design_error("boundary.file" if design.boundary.shape == "file" else "boundary"):
        return _boundary(design, base)


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
        geom = bd.load_in_units(
            find_file(base, spec.file, "boundary.file"), design.design.units, spec.close_tolerance
        )
    if spec.corner_radius > 0:
        r = spec.corner_radius
        core = geom.buffer(-r, join_style="mitre")
        if core.is_empty:
            # r = half the width (a stadium, a disc): the core is a segment or a point, which
            # GEOS drops; a slightly smaller r keeps a sliver of it (and the outline inside)
            r = r * (1 - config.CORNER_RADIUS_SHRINK)
            core = geom.buffer(-r, join_style="mitre")
        geom = core.buffer(r, quad_segs=16)
        if geom.is_empty:
            raise DesignError.at(
                "boundary.corner_radius", f"{spec.corner_radius} is too large for the boundary"
            )
    domain = geom
    if spec.margin > 0:
        x0, y0, x1, y1 = geom.bounds
        # past half the boundary's width nothing is left (and a huge margin overflows GEOS)
        margin = min(spec.margin, max(x1 - x0, y1 - y0))
        domain = geom.buffer(-margin, join_style="mitre")
        if domain.is_empty:
            raise DesignError.at("boundary.margin", f"{spec.margin} leaves nothing of the boundary")
    return geom, domain


def _curve(a, base: Path | None, key: str, units: str = "mm"):
    """The polyline(s) of a curve attractor: points, SVG path data or a file."""
    from . import boundary as bd

    if getattr(a, "points", None) is not None:
        return np.asarray(a.points, dtype=np.float64)
    if a.path is not None:
        lines = bd.path_lines(a.path)
        if not lines:
            raise DesignError.at(f"{key}.path", "the SVG path data draws nothing")
        return shapely.MultiLineString([np.asarray(x)[:, :2] for x in lines])
    path = find_file(base, a.file, f"{key}.file")
    if path.suffix.lower() == ".svg":
        return bd.svg_in_units(bd.curves_from_svg(path), path, units)
    geom = shapely.union_all(shapely.get_parts(shapely.from_geojson(path.read_text("utf-8"))))
    lines = [g.boundary if g.geom_type.endswith("Polygon") else g for g in shapely.get_parts(geom)]
    merged = shapely.union_all([g for g in lines if "LineString" in g.geom_type])
    if merged.is_empty:
        raise DesignError.at(f"{key}.file", "no lines or polygons in the file")
    return merged


def _seed_curves(design: Design, base: Path | None):
    """The curves of ``seeds.method = "curves"`` as shapely lines."""
    s = design.seeds
    if s.curves is not None:
        return shapely.MultiLineString([np.asarray(c, dtype=np.float64) for c in s.curves])
    with as_design_error("seeds.path" if s.path is not None else "seeds.file"):
        got = _curve(s, base, "seeds", design.design.units)
    if isinstance(got, np.ndarray):
        return shapely.MultiLineString([got])
    return got


def _curve_edges(design: Design, points: np.ndarray, domain, diagram, base: Path | None):
    """The cell edges that trace the seed curves (``populate.crossing_edges``)."""
    import voroforge as vf

    from .populate import crossing_edges

    if diagram is None:  # recursion: level 0 is the diagram of the same sites
        diagram = vf.voronoi(points, domain)
    return crossing_edges(diagram, _seed_curves(design, base))


def attractor_field(design: Design, base: Path | None = None):
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


def make_seeds(design: Design, domain, field_fn, base: Path | None) -> np.ndarray:
    """The sites ``[seeds]`` asks for (at most ``DESIGN_MAX_CELLS``, ``seeds.count`` first)."""
    m = design.seeds.method
    key = "count" if m in ("random", "density", "image") else _SIZE_KEY.get(m, "spacing")
    n = design.seeds.count if key == "count" else 0  # refused before drawing 1.5e7 (11 s)
    with as_design_error(f"seeds.{key}") if key in ("spacing", "radius") else nullcontext():
        pts = _make_seeds(design, domain, field_fn, base) if n <= config.DESIGN_MAX_CELLS else ()
    if max(len(pts), n) > config.DESIGN_MAX_CELLS:
        why = f"{max(len(pts), n):,} seeds, at most {config.DESIGN_MAX_CELLS:,} in a design"
        raise DesignError.at(f"seeds.{key}", why)
    return pts


_SIZE_KEY = {"poisson": "radius", "file": "file"}


def _make_seeds(design: Design, domain, field_fn, base: Path | None) -> np.ndarray:
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
            raise DesignError.at("seeds.use_field", "needs at least one [[attractors]] table")
        return populate.poisson(domain, s.radius, seed=seed, field=use, radius_max=s.radius_max)
    if s.method == "density":
        if field_fn is None:
            raise DesignError.at(
                "seeds.method", "'density' needs at least one [[attractors]] table"
            )
        return populate.by_density(domain, s.count, field_fn, seed=seed)
    if s.method == "curves":  # mirrored pairs along curves (+ an optional Poisson fill)
        return populate.along_curves(
            domain,
            _seed_curves(design, base),
            s.spacing,
            distance=s.distance,
            radius=s.radius,
            seed=seed,
        )
    if s.method == "image":  # density from a greyscale image stretched over the domain's box
        from .stipple import image_seeds

        with as_design_error("seeds.file"):
            return image_seeds(find_file(base, s.file, "seeds.file"), domain, s.count, seed=seed)
    return _file_seeds(design, domain, base)[0]


@dataclass(frozen=True)
class SeedTable:
    """The rows of a ``seeds.method = "file"`` file, for outputs that join back to it.

    Attributes
    ----------
    points : (r, 2) float64
        Every row's point, in file order (row ``i`` of the file is ``points[i]``).
    rows : (n,) int64
        The file row of each site (the rows inside the boundary, in file order).
    attributes : dict of name -> list
        Every other CSV column or GeoJSON property, one value per file row.
    """

    points: np.ndarray
    rows: np.ndarray
    attributes: dict


def _file_seeds(design: Design, domain, base: Path | None) -> tuple[np.ndarray, SeedTable]:
    """The seed file's points inside the domain, and the whole file as a :class:`SeedTable`."""
    from ..io.readers import read_point_table

    with as_design_error("seeds.file"):
        pts, attributes = read_point_table(find_file(base, design.seeds.file, "seeds.file"))
    # on the outline counts as inside: such a site owns the part of the domain nearest it
    rows = np.flatnonzero(shapely.intersects_xy(domain, pts[:, 0], pts[:, 1]))
    return pts[rows], SeedTable(pts, rows, attributes)


def _relax(design: Design, points: np.ndarray, domain) -> np.ndarray:
    r = design.relax
    if r.iterations == 0 and r.tolerance is None:
        return points
    from .relax import relax

    iterations = r.iterations if r.iterations else 50
    return relax(points, domain, iterations=iterations, tol=r.tolerance)


# --- cells --------------------------------------------------------------------------------


def _voronoi(design: Design, points: np.ndarray, domain, field_fn=None):
    """The diagram of the design's sites: Voronoi, power (Laguerre) or periodic on the tile."""
    import voroforge as vf

    algorithm = design.voronoi.algorithm
    radius = design.voronoi.power_radius
    if radius is not None:  # power (Laguerre) cells: a site of weight r^2 acts like a disc
        values = np.zeros(len(points)) if field_fn is None else field_fn(points)
        r = _graded(
            radius,
            np.asarray(values, dtype=np.float64),
            "voronoi.power_radius",
            field_fn is not None,
        )
        weights = np.broadcast_to(np.asarray(r, dtype=np.float64) ** 2, (len(points),))
        return vf.power(points, weights, domain)
    if not design.voronoi.periodic:
        return vf.voronoi(points, domain, algorithm=algorithm)
    return vf.voronoi(points, _tile(design, domain), algorithm=algorithm, periodic=True)


def _tile(design: Design, domain) -> tuple[float, float, float, float]:
    if (
        design.boundary.shape != "rectangle"
        or design.boundary.corner_radius
        or design.boundary.margin
    ):
        raise DesignError.at("voronoi.periodic", "a periodic tile needs a plain rectangle boundary")
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


def cell_values(cells: np.ndarray, field_fn) -> np.ndarray:
    """The field at a point on each cell (zeros without a field; empty cells get 0)."""
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
        raise DesignError.at(key, "near/far values need at least one [[attractors]] table")
    return value.far + (value.near - value.far) * values


def _recurse(design: Design, domain, points, field_fn, seed):
    """Recursion levels -> (leaf cells, their openings, level per cell, the levels)."""
    rec = design.recursion
    from . import cellops
    from .recursive import check_size, subdivide

    count_spec = rec.count
    if count_spec.graded and field_fn is None:
        raise DesignError.at(
            "recursion.count", "near/far values need at least one [[attractors]] table"
        )

    def count(region) -> int:
        if not count_spec.graded:
            return max(0, int(round(count_spec.value)))
        v = float(cell_values(np.asarray([region], dtype=object), field_fn)[0])
        return max(0, int(round(count_spec.far + (count_spec.near - count_spec.far) * v)))

    prob_spec = rec.probability
    if prob_spec.graded and field_fn is None:
        raise DesignError.at(
            "recursion.probability", "near/far values need at least one [[attractors]] table"
        )

    def select(level):
        live = ~shapely.is_empty(np.asarray(level.openings, dtype=object))
        if not prob_spec.graded and prob_spec.value >= 1.0:
            return live
        prob = prob_spec.value
        if prob_spec.graded:  # each cell's chance from the field at the cell
            values = cell_values(np.asarray(level.cells, dtype=object), field_fn)
            prob = np.clip(prob_spec.far + (prob_spec.near - prob_spec.far) * values, 0.0, 1.0)
        # A fresh, reproducible draw per level.
        draw = cellops.random(len(level), prob, seed=seed * 1009 + level.depth)
        return np.asarray(draw, dtype=bool) & live

    if not count_spec.graded and not prob_spec.graded:  # refuse before any work
        with as_design_error("recursion.depth"):
            check_size(len(points), rec.depth, count_spec.value, prob_spec.value)
    webs = list(rec.web)
    if len(webs) not in (0, 1, rec.depth + 1):
        raise DesignError.at(
            "recursion.web", f"give one width or depth + 1 = {rec.depth + 1} widths"
        )
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


def opening_mask(design: Design, cells: np.ndarray, values: np.ndarray, seed: int) -> np.ndarray:
    """Which cells ``[openings]`` selects (``values``: :func:`cell_values`); never empty ones."""
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
            raise DesignError.at(
                "openings.select", "'field' needs at least one [[attractors]] table"
            )
        mask = values >= o.threshold
    mask = np.asarray(mask, dtype=bool) & live
    return ~mask & live if o.invert else mask


def operate_cells(design: Design, cells: np.ndarray, values: np.ndarray, has_field: bool):
    """``[cells]``' operations (inset or web, scale, smooth, fillet) applied to every cell."""
    from . import cellops

    c = design.cells
    out = cells
    amount = c.inset_amount()
    scaled = c.scale.graded or c.scale.value != 1.0
    filleted = c.fillet.graded or c.fillet.value
    if amount is not None:
        key = "cells.web" if c.web is not None else "cells.inset"
        d = _graded(amount, values, key, has_field)
        if np.any(np.asarray(d) < 0):
            raise DesignError.at(key, "must be >= 0 (use cells.scale > 1 to grow cells)")
        if filleted and not scaled and not c.smooth:  # the same cells, in one pass
            r = _fillet_radii(c, values, has_field)
            out = cellops.inset_fillet(out, d, r, join=c.join)
            filleted = False
        else:
            out = cellops.inset(out, d, join=c.join)
    if scaled:
        factor = _graded(c.scale, values, "cells.scale", has_field)
        if np.any(np.asarray(factor) < 0):
            raise DesignError.at("cells.scale", "scale factors must be >= 0")
        out = cellops.scale(out, factor)
    if c.smooth:
        out = cellops.smooth(out, iterations=c.smooth)
    if filleted:
        out = cellops.fillet(out, _fillet_radii(c, values, has_field))
    out = np.asarray(out, dtype=object)
    if c.min_area > 0:
        out[shapely.area(out) < c.min_area] = shapely.Polygon()
    if c.min_size > 0:  # openings narrower than min_size (inscribed circle) stay solid
        live = np.flatnonzero(~shapely.is_empty(out))
        if len(live):
            from .fabrication import inscribed_circles

            _, radii = inscribed_circles(out[live], tolerance=c.min_size * config.MIN_SIZE_RTOL)
            thin = 2.0 * radii < c.min_size
            out[live[thin]] = shapely.Polygon()
    return np.asarray(out, dtype=object)


def _fillet_radii(c, values: np.ndarray, has_field: bool):
    r = _graded(c.fillet, values, "cells.fillet", has_field)
    if np.any(np.asarray(r) < 0):
        raise DesignError.at("cells.fillet", "fillet radii must be >= 0")
    return r


#: Fewest cells per thread when ``compute(workers=...)`` splits the cell operations.
_CELLS_PER_WORKER = 256


def _operate_split(design, cells, values, has_field, workers: int):
    """:func:`operate_cells` over up to ``workers`` threads (GEOS runs without the GIL).

    Every operation is per cell, so the cells are the same bytes as from one call.
    """
    k = min(int(workers), len(cells) // _CELLS_PER_WORKER)
    if k < 2:
        return operate_cells(design, cells, values, has_field)
    from concurrent.futures import ThreadPoolExecutor

    parts = np.array_split(np.arange(len(cells)), k)
    with ThreadPoolExecutor(k) as pool:
        done = list(
            pool.map(lambda p: operate_cells(design, cells[p], values[p], has_field), parts)
        )
    out = np.empty(len(cells), dtype=object)  # noqa: TID251 - every slot is filled below
    for p, part in zip(parts, done, strict=True):
        out[p] = part
    return out


def _operate_reusing(design, cells, values, has_field, reuse, extra, workers: int = 1):
    """:func:`operate_cells`, redoing only cells whose raw ring or value changed since ``reuse``.

    Keys of the cells are their WKB (kept in ``extra["raw_wkb"]`` for the next call); only
    plain diagrams (no recursion, no periodic wrap) are reused.
    """
    if design.recursion.depth > 0 or design.voronoi.periodic or not len(cells):
        return operate_cells(design, cells, values, has_field)
    keys = shapely.to_wkb(cells)
    extra["raw_wkb"] = keys
    old = reuse.extra.get("raw_wkb") if reuse is not None else None
    if old is None or reuse.design.cells != design.cells or len(reuse.cells) != len(reuse.raw):
        return _operate_split(design, cells, values, has_field, workers)
    n = min(len(old), len(cells))
    same = np.zeros(len(cells), dtype=bool)
    same[:n] = (keys[:n] == old[:n]) & (values[:n] == reuse.values[:n])
    out = np.array(cells, dtype=object)
    out[same] = reuse.cells[np.flatnonzero(same)]
    redo = np.flatnonzero(~same)
    if len(redo):
        out[redo] = _operate_split(design, cells[redo], values[redo], has_field, workers)
    extra["redone"] = redo
    return out


@contextmanager
def as_design_error(key: str):
    """Turn a library ``ValueError`` raised while building ``key`` into a DesignError."""
    try:
        yield
    except DesignError:
        raise
    except ValueError as exc:
        raise DesignError.at(key, str(exc)) from None


def compute(
    design: Design,
    base: Path | None = None,
    *,
    progress: Stage | None = None,
    sites: np.ndarray | None = None,
    reuse: Result | None = None,
    frame: bool = True,
    workers: int = 1,
) -> Result:
    """Compute the geometry of a validated design.

    Parameters
    ----------
    design : Design
        From :func:`voroforge.design.designfile.load`.
    base : Path, optional
        Folder that relative file names in the design are read from.
    progress : callable, optional
        Called with the name of each stage.
    sites : (n, 2) array_like, optional
        Use these sites as they are instead of the ``[seeds]`` and ``[relax]`` sections
        (an editor's dragged seeds); the caller keeps them inside the boundary.
    reuse : Result, optional
        A previous result of a design with the same ``[cells]`` section: cells whose raw
        geometry and field value are unchanged keep its operated cells (inset, fillet, ...
        are per cell, so the geometry is the same as computed afresh, only faster).
    frame : bool
        False leaves ``Result.frame`` None (an editor that draws the openings does not need
        the boundary minus their union, the slowest step for cells without webs).
    workers : int
        Threads for the cell operations (inset, fillet, ...) of many cells; the result is
        the same with any count (GEOS's buffers run in parallel; the convex cells' numpy
        mostly holds the GIL, so the studio passes 1).

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
    boundary, domain = outline(design, base)
    with as_design_error("attractors"):
        field_fn = attractor_field(design, base)
    stage("seeds")
    extra: dict = {}
    with as_design_error("seeds"):
        if sites is None and design.seeds.method == "file":  # rows kept for the outputs
            points, extra["seed_table"] = _file_seeds(design, domain, base)
        elif sites is None:
            points = make_seeds(design, domain, field_fn, base)
        else:
            points = np.array(sites, dtype=np.float64)
            if points.ndim != 2 or points.shape[1:] != (2,) or not np.isfinite(points).all():
                raise ValueError(f"sites must be finite (n, 2) coordinates; got {points.shape}")
        points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    if len(points) < 1:
        raise DesignError.at("seeds", "no seeds fall inside the boundary; need 1 or more")
    if sites is None:
        with as_design_error("relax"):
            points = _relax(design, points, domain)
    stage(f"{len(points)} Voronoi cells")
    diagram = None
    if design.recursion.depth > 0:
        if design.voronoi.periodic:
            raise DesignError.at(
                "recursion.depth", "recursion and periodic tiles do not combine yet"
            )
        if design.cells.inset_amount() is not None:
            raise DesignError.at("cells.web", "with [recursion], give the webs as recursion.web")
        with as_design_error("recursion"):
            raw, inset_cells, level, extra["levels"] = _recurse(
                design, domain, points, field_fn, seed
            )
    else:
        with as_design_error("voronoi"):
            diagram = _voronoi(design, points, domain, field_fn)
        raw = np.asarray(diagram.cells, dtype=object)
        inset_cells = raw
        level = np.zeros(len(raw), dtype=np.int64)
    if design.seeds.method == "curves" and sites is None:
        extra["curve_edges"] = _curve_edges(design, points, domain, diagram, base)
    values = cell_values(raw, field_fn)
    with as_design_error("openings"):
        mask = opening_mask(design, raw, values, seed)
    stage("cell operations")
    with as_design_error("cells"):
        cells = _operate_reusing(
            design, inset_cells, values, field_fn is not None, reuse, extra, workers
        )
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
    open_cells = np.flatnonzero(mask & ~shapely.is_empty(cells)) if len(cells) else mask[:0]
    # openings that tile what they divide count as it (no slivers of rounding along seams)
    whole = tiled_holes(domain, raw, cells, mask, extra.get("levels")) if frame else None
    fresh = _fresh(reuse, boundary, extra, open_cells) if whole is None and frame else None
    frame = _frame(boundary, openings if whole is None else whole, fresh, extra) if frame else None
    extra["open_cells"] = open_cells
    return Result(
        design,
        boundary,
        domain,
        points,
        raw,
        cells,
        mask,
        values,
        level,
        openings,
        frame,
        extra,
        diagram,
    )


def _fresh(reuse, boundary, extra, open_cells):
    """Which openings are new since ``reuse`` (whose frame took the fast path), or None (all)."""
    redo = extra.get("redone")
    if redo is None or not reuse.extra.get("frame_fast"):
        return None
    if not shapely.equals_exact(reuse.boundary, boundary, 0.0):
        return None
    return ~np.isin(open_cells, reuse.extra["open_cells"]) | np.isin(open_cells, redo)


def _frame(boundary, openings: np.ndarray, fresh: np.ndarray | None = None, extra=None):
    """Boundary minus openings; disjoint holes strictly inside become holes directly (fast).

    ``fresh`` marks the openings to test (the others were tested by an earlier call and are
    unchanged); ``extra["frame_fast"]`` records whether the fast path was taken.
    """
    if not len(openings):
        return boundary
    simple = (
        boundary.geom_type == "Polygon"
        and (shapely.get_type_id(openings) == 3).all()
        and (shapely.get_num_interior_rings(openings) == 0).all()
    )
    if simple:
        shapely.prepare(boundary)
        test = np.arange(len(openings)) if fresh is None else np.flatnonzero(fresh)
        if shapely.contains_properly(boundary, openings[test]).all():
            left, right = shapely.STRtree(openings).query(openings[test], predicate="intersects")
            if (test[left] == right).all():
                if extra is not None:
                    extra["frame_fast"] = True
                rings = [*boundary.interiors, *(o.exterior for o in openings)]
                return shapely.Polygon(boundary.exterior, rings)
    from .boundary import union_all_checked

    return boundary.difference(union_all_checked(openings))
