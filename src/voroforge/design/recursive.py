"""Recursive subdivision: chosen cells get their own seeds and are divided again.

Level 0 is the Voronoi diagram of the given points in the boundary. At each further level,
every chosen cell of the level above is first shrunk by half that level's web width (its
*opening*), then new seeds are placed inside the opening and their Voronoi diagram is
clipped to it. So the cells of a level tile the openings of their parents exactly, and
webs nest: a thick web around each parent, thinner webs inside it.

Examples
--------
>>> import shapely
>>> levels = subdivide(shapely.box(0, 0, 100, 100), 8, depth=2, count=5, seed=1, web=[2, 1, 0.5])
>>> [lv.depth for lv in levels], len(levels[1].cells) <= 8 * 5
([0, 1, 2], True)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely

import voroforge

from .. import config
from . import cellops, populate

__all__ = ["Level", "count_by_area", "count_by_field", "leaves", "subdivide", "tiled_holes"]


@dataclass(frozen=True)
class Level:
    """One level of a recursive subdivision.

    Attributes
    ----------
    depth : int
        0 for the first diagram, 1 for its subdivision, ...
    cells : (n,) object array of Polygon/MultiPolygon
        The cells of this level; at depth >= 1 the cells of each parent tile that parent's
        opening.
    sites : (n, 2) float64
        The seed of each cell.
    parent : (n,) int64
        Index of each cell's parent in the level above (-1 at depth 0).
    web : float
        This level's web width.
    openings : (n,) object array
        ``cells`` inset by ``web / 2`` (empty where a cell vanished): the holes to cut, and
        the regions the next level subdivides.
    """

    depth: int
    cells: np.ndarray
    sites: np.ndarray
    parent: np.ndarray
    web: float = 0.0
    openings: np.ndarray | None = None

    def __len__(self) -> int:
        return len(self.cells)


def count_by_area(per_area, *, minimum: int = 0, maximum: int | None = None):
    """A ``count`` rule: ``round(area * per_area)`` seeds per cell, clipped to the bounds.

    Parameters
    ----------
    per_area : float
        Seeds per unit area (for example ``1 / 400`` for one seed per 20 × 20 mm).
    minimum, maximum : int
        Bounds of the count (``maximum=None``: unbounded).

    Returns
    -------
    callable
        ``rule(cell) -> int``.
    """
    rate = float(per_area)
    if not (math.isfinite(rate) and rate >= 0):
        raise ValueError(f"per_area must be a finite number >= 0, got {per_area!r}")

    def rule(cell) -> int:
        n = int(round(cell.area * rate))
        n = n if maximum is None else min(n, int(maximum))
        return max(n, int(minimum))

    return rule


def count_by_field(field, lo: int, hi: int):
    """A ``count`` rule: ``lo`` seeds where ``field`` is 0 up to ``hi`` where it is 1.

    The field (an attractor, say) is evaluated at a point inside each cell (its centroid, or
    a point on its surface when the centroid falls outside).

    Returns
    -------
    callable
        ``rule(cell) -> int``.
    """
    if not callable(field):
        raise ValueError("field must be callable field(xy) -> values in [0, 1]")
    lo, hi = int(lo), int(hi)
    if lo < 0 or hi < 0:
        raise ValueError("lo and hi must be >= 0")

    def rule(cell) -> int:
        p = cell.centroid
        if not cell.contains(p):
            p = cell.point_on_surface()
        v = float(np.clip(np.asarray(field(np.array([[p.x, p.y]])), dtype=np.float64)[0], 0, 1))
        return int(round(lo + (hi - lo) * v))

    return rule


def _per_level(value, n: int, name: str, check):
    """A scalar/callable for every level, or a sequence with one entry per level."""
    if isinstance(value, list | tuple | np.ndarray):
        if len(value) != n:
            raise ValueError(f"{name} needs one entry per level ({n}), got {len(value)}")
        return [check(v) for v in value]
    return [check(value)] * n


def _web(v) -> float:
    w = float(v)
    if not (math.isfinite(w) and w >= 0):
        raise ValueError(f"web must be a finite number >= 0, got {v!r}")
    return w


def _count_rule(v):
    if callable(v):
        return v
    if isinstance(v, bool) or int(v) != v or v < 0:
        raise ValueError(f"count must be an integer >= 0 or a callable(cell) -> int, got {v!r}")
    n = int(v)
    return lambda cell: n


def _level(depth, cells, sites, parent, web, join):
    cells = cellops.as_cells(cells)
    sites = np.asarray(sites, dtype=np.float64).reshape(-1, 2)
    parent = np.asarray(parent, dtype=np.int64)
    opened = cellops.inset(cells, web / 2.0, join=join) if web > 0 else cells.copy()
    for arr in (sites, parent):
        arr.setflags(write=False)
    return Level(depth, cells, sites, parent, web, opened)


def _clipped(diagram, region) -> np.ndarray:
    """The diagram's cells, guaranteed inside ``region`` and tiling it.

    Guard against engine cells that escape a thin polygon domain (seen with sites in a
    sliver triangle): such cells are intersected with the region; if the pieces still do
    not tile it, GEOS's Voronoi diagram of the same sites is used.
    """
    cells = np.asarray(diagram.cells, dtype=object)
    total = region.area
    # shapely's areas of the cells already built, not diagram.areas: that parallel kernel
    # costs a thread wake-up per call (~10 ms on a busy machine, x thousands of cells here).
    if abs(float(shapely.area(cells).sum()) - total) <= config.TILING_AREA_RTOL * total:
        return cells
    cells = cellops.clean(shapely.intersection(cells, region))
    if abs(float(shapely.area(cells).sum()) - total) <= config.TILING_AREA_RTOL * total:
        return cells
    sites = shapely.points(diagram.sites)
    polys = shapely.get_parts(
        shapely.voronoi_polygons(shapely.multipoints(diagram.sites), extend_to=region)
    )
    owner = np.array([np.flatnonzero(shapely.contains(p, sites))[0] for p in polys])
    out = np.full(len(sites), shapely.Polygon(), dtype=object)
    out[owner] = shapely.intersection(polys, region)
    return cellops.clean(out)


def subdivide(
    boundary,
    points,
    *,
    depth: int,
    count,
    seed: int,
    select=None,
    web=0.0,
    relax: int = 0,
    join: str = "mitre",
) -> list[Level]:
    """Voronoi cells divided recursively: each chosen cell gets its own seeds and diagram.

    Parameters
    ----------
    boundary : shapely Polygon/MultiPolygon or (xmin, ymin, xmax, ymax)
        The outline.
    points : (n, 2) array_like or int
        Seeds of level 0, or a number of random seeds.
    depth : int
        Number of subdivision rounds; the result has ``depth + 1`` levels.
    count : int, callable or sequence
        Seeds per subdivided cell: an int, ``rule(region) -> int`` where ``region`` is the
        cell's opening (see :func:`count_by_area`, :func:`count_by_field`), or one of these
        per round (length ``depth``). A cell whose count is 0 is not subdivided; a count of 1
        gives one child equal to the region.
    seed : int
        Random seed (all levels derive their seeds from it).
    select : callable, optional
        ``select(level) -> (n,) bool``: which cells of ``level`` are subdivided (default:
        all non-empty ones), e.g. ``lambda lv: cellops.by_area(lv.openings, min=50)``.
    web : float or sequence of floats
        Web width of each level (one value, or ``depth + 1`` values from level 0 down).
    relax : int
        Lloyd iterations for the seeds inside each parent (0: plain random seeds).
    join : {"mitre", "round"}
        Corner style of the openings.

    Returns
    -------
    list of Level
        ``depth + 1`` levels (a level with no subdivided parent is empty, and so are the
        levels below it).
    """
    from .relax import relax as lloyd

    geom = populate.as_region(boundary)
    if isinstance(depth, bool) or int(depth) != depth or depth < 0:
        raise ValueError(f"depth must be an integer >= 0, got {depth!r}")
    depth = int(depth)
    if isinstance(relax, bool) or int(relax) != relax or relax < 0:
        raise ValueError(f"relax must be an integer >= 0, got {relax!r}")
    if select is not None and not callable(select):
        raise ValueError("select must be a callable select(level) -> (n,) bool mask")
    webs = _per_level(web, depth + 1, "web", _web)
    rules = _per_level(count, depth, "count", _count_rule) if depth else []
    rng = np.random.default_rng(seed)
    if isinstance(points, int | np.integer) and not isinstance(points, bool):
        pts = populate.random(geom, int(points), seed=int(rng.integers(2**63)))
    else:
        pts = np.asarray(points, dtype=np.float64)
        if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) == 0:
            raise ValueError(f"points must be a non-empty (n, 2) array, got shape {pts.shape}")
    if relax:
        pts = lloyd(pts, geom, iterations=int(relax))
    d = voroforge.voronoi(pts, geom)
    levels = [_level(0, d.cells, d.sites, np.full(len(pts), -1), webs[0], join)]
    for k in range(1, depth + 1):
        prev = levels[-1]
        mask = np.ones(len(prev), dtype=bool) if select is None else np.asarray(select(prev))
        if mask.shape != (len(prev),) or mask.dtype != bool:
            raise ValueError(f"select must return a boolean mask of shape ({len(prev)},)")
        cells, sites, parent = [], [], []
        total = 0
        for i in np.flatnonzero(mask):
            region = prev.openings[i]
            child_seed = int(rng.integers(2**63))  # drawn for every chosen cell: stable
            if region.is_empty:
                continue
            n = rules[k - 1](region)
            if isinstance(n, bool) or int(n) != n or n < 0:
                raise ValueError(f"count rule returned {n!r} for cell {i}; need an int >= 0")
            n = int(n)
            total += n
            if total > config.RECURSION_MAX_CELLS:
                raise ValueError(
                    f"recursion level {k} would hold over {config.RECURSION_MAX_CELLS:,} cells "
                    f"({total:,} so far); use a smaller depth or count"
                )
            if n == 0:
                continue
            if n == 1:
                p = region.point_on_surface()
                cells.append(np.array([region], dtype=object))
                sites.append(np.array([[p.x, p.y]]))
                parent.append([i])
                continue
            seeds = populate.random(region, n, seed=child_seed)
            if relax:
                seeds = lloyd(seeds, region, iterations=int(relax))
            sub = voroforge.voronoi(seeds, region)
            cells.append(_clipped(sub, region))
            sites.append(np.asarray(sub.sites))
            parent.append(np.full(n, i))
        if cells:
            level = _level(
                k,
                np.concatenate(cells),
                np.concatenate(sites),
                np.concatenate(parent),
                webs[k],
                join,
            )
        else:
            level = _level(k, [], np.zeros((0, 2)), np.zeros(0, np.int64), webs[k], join)
        levels.append(level)
    return levels


def check_size(sites: int, depth: int, count: float, probability: float = 1.0) -> None:
    """Refuse, before any work, a recursion whose last level would pass the cell limit.

    About ``sites * (count * probability) ** depth`` cells (``RECURSION_MAX_CELLS``).
    """
    grow = max(0.0, round(count)) * min(max(probability, 0.0), 1.0)
    expected = sites * grow ** float(depth)
    if expected > config.RECURSION_MAX_CELLS:
        raise ValueError(
            f"depth {depth} with count {round(count)} on {sites:,} seeds makes about "
            f"{expected:,.0f} cells, at most {config.RECURSION_MAX_CELLS:,}: use a smaller "
            "depth or count"
        )


def leaves(levels) -> np.ndarray:
    """The openings to cut: at every level, the openings of cells that were not subdivided.

    ``cellops.frame(boundary, leaves(levels))`` is the finished part, with thick webs
    around the first level's cells and thinner ones inside them.

    Parameters
    ----------
    levels : list of Level
        From :func:`subdivide`.

    Returns
    -------
    (k,) object array of non-empty Polygon/MultiPolygon
    """
    out = []
    for k, level in enumerate(levels):
        divided = np.zeros(len(level), dtype=bool)
        if k + 1 < len(levels) and len(levels[k + 1]):
            divided[levels[k + 1].parent] = True
        out.append(level.openings[~divided])
    arr = np.concatenate(out) if out else np.zeros(0, dtype=object)
    return arr[~shapely.is_empty(arr)] if len(arr) else arr


def tiled_holes(region, raw, holes, chosen, levels=None) -> np.ndarray | None:
    """The holes to take out of the boundary for the frame, openings that tile merged.

    Where every cell dividing a parent (or every cell of the diagram, which tiles
    ``region``) is cut whole, the cells' union is the parent's opening (``region``): that
    opening is returned instead of them. Boundary minus the cells themselves left GEOS
    slivers of rounding along their seams (clipped cells meet the parent's edges only to
    rounding): loose "islands" of 1e-13 mm^2 and cut paths of nothing.

    Parameters
    ----------
    region : shapely geometry
        What the first level's cells tile (the design's domain).
    raw : (n,) object array
        The leaf cells, in the order of ``compute`` (level by level, undivided cells in order).
    holes : (n,) object array
        What is cut of each leaf (its operated cell).
    chosen : (n,) bool
        Which leaves are openings.
    levels : list of Level, optional
        From :func:`subdivide` (None: ``raw`` is one diagram of ``region``).

    Returns
    -------
    (m,) object array, or None when no cells merge (take the openings as they are).
    """
    raw = np.asarray(raw, dtype=object).reshape(-1)
    holes = np.asarray(holes, dtype=object).reshape(-1)
    if not len(raw) or len(holes) != len(raw):
        return None
    chosen = np.asarray(chosen, dtype=bool) & ~shapely.is_empty(holes)
    empty = shapely.is_empty(raw)
    whole = empty | (chosen & shapely.equals_exact(holes, raw, 0.0))  # cut as the cell itself
    if not whole[~empty].any():
        return None
    if levels is None:
        levels = [Level(0, raw, np.zeros((len(raw), 2)), np.full(len(raw), -1), 0.0, raw)]
    split, start = [], [0]  # which cells are divided; where each level's leaves begin in raw
    for k, lv in enumerate(levels):
        split.append(np.zeros(len(lv), dtype=bool))
        if k + 1 < len(levels) and len(levels[k + 1]):
            split[k][levels[k + 1].parent] = True
        start.append(start[-1] + int((~split[k]).sum()))
    if start[-1] != len(raw):
        return None

    def tiles(cells, parent, n, area):  # the children of each parent sum to its area
        got = np.zeros(n)
        np.add.at(got, parent, shapely.area(cells))
        return np.abs(got - area) <= config.TILING_AREA_RTOL * area

    full, merged = [None] * len(levels), [None] * len(levels)
    for k in reversed(range(len(levels))):
        lv = levels[k]
        full[k] = np.zeros(len(lv), dtype=bool)  # its hole is the cell itself, or empty
        full[k][~split[k]] = whole[start[k] : start[k + 1]]
        merged[k] = np.zeros(len(lv), dtype=bool)  # its children merge into its opening
        if k + 1 < len(levels) and len(levels[k + 1]):
            child = levels[k + 1]
            every = np.ones(len(lv), dtype=bool)
            np.logical_and.at(every, child.parent, full[k + 1])
            area = shapely.area(lv.openings)
            merged[k] = split[k] & every & tiles(child.cells, child.parent, len(lv), area)
            full[k] |= merged[k] & (lv.web == 0)  # (a web of 0: the opening is the cell)
    top = np.asarray(levels[0].cells, dtype=object)
    if full[0].all() and tiles(top, np.zeros(len(top), dtype=np.int64), 1, region.area)[0]:
        return np.asarray([region], dtype=object)
    if not any(m.any() for m in merged):
        return None
    out, covered = [], np.zeros(len(levels[0]), dtype=bool)  # under a merged ancestor
    for k, lv in enumerate(levels):
        out.extend(lv.openings[merged[k] & ~covered])
        out.extend(
            holes[start[k] : start[k + 1]][(chosen[start[k] : start[k + 1]]) & ~covered[~split[k]]]
        )
        if k + 1 < len(levels) and len(levels[k + 1]):
            covered = (covered | merged[k])[levels[k + 1].parent]
    return np.asarray(out, dtype=object)
