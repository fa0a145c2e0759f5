"""A seed drag without recomputing the whole diagram: the cells near the seed, certified.

Moving one site ``i`` from ``a`` to ``b`` changes only the cells that meet the region ``i``
owned before or owns after. :func:`move` computes the diagram of the sites within a radius
``R`` of the move (``voroforge.voronoi`` on that window, clipped to the domain's bounding
box, the box the engine clips every cell to first) and keeps a window cell only where it is
*certified*: for every vertex ``v`` of the (convex) cell, ``|v - c| + |v - s_j| < R`` (``c``
the window's centre). A site outside the window is then farther from every point of the
cell than ``s_j`` is (the condition is convex in ``v``), so it cannot cut the cell: the
window cell is the whole diagram's cell, vertex for vertex (the engine makes Voronoi
vertices canonical), except that the ring may start at another vertex. A cell that crosses
the outline or a hole of a polygonal domain is then cut by GEOS against the whole domain,
where the engine cuts it against a local piece: such a vertex may lie an ulp or so away. The
cells that can have changed are those whose old or new bounding box meets the bounding box
of the old and new cell of ``i``; all of them must be certified, else the window grows (and
after a few tries the caller recomputes everything).

:func:`update` does the same for many changed sites at once (sites moved, appended or
dropped from the end, as a ``seeds.count`` step of a random seed stream does): a window per
change, one diagram of their sites, a cell certified by any window whose condition it meets.
When the windows hold more than half the sites, the whole diagram is computed against the
box (every cell exact, only the cut ones through GEOS).

The result is marked ``extra["provisional"]``: its cells are the full diagram's to rounding,
and the inset/fillet of a cell whose ring differs was computed from that ring.
:meth:`voroforge.studio.session.Session.settle` replaces it by
:func:`voroforge.design.compute.compute`'s own result (reusing every cell whose raw ring is
byte-identical) once the edits pause, so what the page shows at rest, what is checked, saved
and exported is exactly the full computation.
"""

from __future__ import annotations

import numpy as np
import shapely

from ..design import compute as dc
from ..design.compute import Result

__all__ = ["eligible", "move", "update"]

#: Window radius when the old cells give none, in site spacings (sqrt(area / n)) past the move.
START_SPACINGS = 4.0
#: Tries (the radius grows by GROWTH each time) before the caller recomputes everything.
TRIES = 4
GROWTH = 1.5


def eligible(result: Result) -> bool:
    """Whether :func:`move` can update ``result``: one plain Voronoi diagram, cell per site."""
    d = result.design
    return (
        d.recursion.depth == 0
        and not d.voronoi.periodic
        and d.voronoi.power_radius is None
        and len(result.raw) == len(result.sites) == len(result.cells)
        and "raw_wkb" in result.extra
    )


def _bounds(result: Result) -> np.ndarray:
    b = result.extra.get("raw_bounds")
    if b is None:
        b = shapely.bounds(result.raw)
        result.extra["raw_bounds"] = b
    return b


#: ``[openings] select`` values whose flag of a cell depends on that cell only.
_PER_CELL = ("all", "area", "field")


def _live(result: Result) -> np.ndarray:
    """Which operated cells are not empty (kept in ``extra["live"]``)."""
    live = result.extra.get("live")
    if live is None or len(live) != len(result.cells):
        live = ~shapely.is_empty(result.cells)
        result.extra["live"] = live
    return live


def _overlap(boxes: np.ndarray, box) -> np.ndarray:
    """Which (n, 4) boxes meet ``box`` (empty geometries have NaN bounds: never)."""
    return (
        (boxes[:, 0] <= box[2])
        & (boxes[:, 2] >= box[0])
        & (boxes[:, 1] <= box[3])
        & (boxes[:, 3] >= box[1])
    )


def _first_radius(result: Result, boxes, i: int, a, b, c) -> float | None:
    """A window radius that certifies the old cells near the move (the new ones are alike).

    The cells whose old box meets the moved cell's box (grown to the new position) are the
    ones the window must certify; their old vertices give the radius they would need.
    """
    box = boxes[i]
    if not np.isfinite(box).all():
        return None
    region = (min(box[0], b[0]), min(box[1], b[1]), max(box[2], b[0]), max(box[3], b[1]))
    near = np.flatnonzero(_overlap(boxes, region))
    coords, owner = shapely.get_coordinates(result.raw[near], return_index=True)
    if not len(coords):
        return None
    own = result.sites[near][owner]
    score = np.hypot(coords[:, 0] - c[0], coords[:, 1] - c[1]) + np.hypot(
        coords[:, 0] - own[:, 0], coords[:, 1] - own[:, 1]
    )
    return 1.25 * float(score.max()) + 0.5 * float(np.hypot(*(b - a)))


def _same(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Elementwise: the same point set and rings (any first vertex, any part order)."""
    return shapely.to_wkb(shapely.normalize(a)) == shapely.to_wkb(shapely.normalize(b))


def _frame_of(result: Result) -> tuple[tuple[float, float, float, float], bool, object]:
    """The domain's bounding box, whether the domain is that box, and the box beyond it.

    The last is what the box holds outside the domain (its holes, and past a polygonal
    outline), prepared; all three are cached in ``extra``.
    """
    known = result.extra.get("domain_box")
    if known is None or known[0] is not result.domain:
        box = tuple(float(v) for v in result.domain.bounds)
        rect = bool(shapely.equals(result.domain, shapely.box(*box)))
        shapely.prepare(result.domain)  # containment tests of every drag step
        outside = shapely.difference(shapely.box(*box), result.domain)
        shapely.prepare(outside)
        known = (result.domain, box, rect, outside)
        result.extra["domain_box"] = known
    return known[1], known[2], known[3]


def _clip(cells: np.ndarray, domain, outside) -> np.ndarray:
    """Box-clipped convex cells cut to a polygonal ``domain`` (inside the box).

    Only the cells that meet ``outside`` (the box's part beyond the domain, see
    :func:`_frame_of`) go through an overlay, oriented as the engine orients its cells
    (exterior CCW); the rest lie in the domain and stay as they are, those along the box's
    sides too (an overlay gave them back vertex for vertex, at ~0.4 ms a drag step near the
    outline).
    """
    out = cells.copy()
    if not len(cells):
        return out
    live = ~shapely.is_empty(cells)
    cut = np.flatnonzero(live & shapely.intersects(outside, cells))
    if len(cut):
        pieces = shapely.intersection(cells[cut], domain)
        bad = np.flatnonzero(~np.isin(shapely.get_type_id(pieces), (3, 6)))
        for k in bad:  # a collection with stray lines or points: keep the polygons
            polys = [g for g in shapely.get_parts(pieces[k]) if shapely.get_type_id(g) in (3, 6)]
            pieces[k] = shapely.union_all(polys) if polys else shapely.Polygon()
        out[cut] = shapely.orient_polygons(pieces)
    return out


def _worst(cells: np.ndarray, own: np.ndarray, c) -> np.ndarray:
    """Per cell, the largest ``|v - c| + |v - own|`` over its vertices (-inf: no vertex)."""
    coords, owner = shapely.get_coordinates(cells, return_index=True)
    site = own[owner]
    score = np.hypot(coords[:, 0] - c[0], coords[:, 1] - c[1]) + np.hypot(
        coords[:, 0] - site[:, 0], coords[:, 1] - site[:, 1]
    )
    worst = np.full(len(cells), -np.inf)
    np.maximum.at(worst, owner, score)
    return worst


def _window(sites: np.ndarray, window: np.ndarray, box, algorithm: str):
    """Convex cells of the sites ``window``, clipped to the domain's bounding box."""
    import voroforge as vf

    local = vf.voronoi(sites[window], box, algorithm=algorithm)
    return np.asarray(local.cells, dtype=object)


def move(result: Result, i: int, xy, field_fn=None) -> tuple[Result, np.ndarray] | None:
    """``result`` with site ``i`` moved to ``xy``, recomputing only the cells near it.

    Parameters
    ----------
    result : Result
        The current geometry (:func:`eligible`); not modified.
    i : int
        The site that moves.
    xy : (2,) float
        Its new position (inside the domain).
    field_fn : callable, optional
        The design's attractor field (``compute.attractor_field``), for the changed cells' values.

    Returns
    -------
    (Result, changed) or None
        The new (provisional) result and the indices of the cells that changed (geometry or
        opening mask); None when the window could not be certified (recompute in full).
    """
    sites = np.array(result.sites, dtype=np.float64)
    sites[i] = np.asarray(xy, dtype=np.float64).reshape(2)
    return update(result, sites, field_fn)


#: At most this many changed sites (moved, added or removed), and this share of them, for
#: :func:`update`; more is cheaper as a whole new diagram.
MAX_CHANGES = 256
MAX_SHARE = 0.1


def _changes(old: np.ndarray, new: np.ndarray):
    """Sites that moved (index < both counts), were added (new tail) or removed (old tail)."""
    m = min(len(old), len(new))
    moved = np.flatnonzero((old[:m] != new[:m]).any(axis=1))
    return moved, np.arange(m, len(new)), np.arange(m, len(old))


def _resized(arr: np.ndarray, n: int, fill) -> np.ndarray:
    """A copy of ``arr`` with ``n`` rows: cut, or grown with ``fill``."""
    if n <= len(arr):
        return arr[:n].copy()
    extra = np.empty((n - len(arr), *arr.shape[1:]), dtype=arr.dtype)  # noqa: TID251
    extra[...] = fill
    return np.concatenate((arr, extra))


def update(
    result: Result, sites, field_fn=None, *, design=None
) -> tuple[Result, np.ndarray] | None:
    """``result`` with new ``sites``, recomputing only the cells near the sites that changed.

    The sites are compared with ``result.sites`` index by index: sites that moved, sites
    appended (a larger count of a random seed stream, which keeps its first seeds) and
    sites dropped from the end. Each change gets a window (see the module docstring); the
    windows' sites go through one diagram, and a cell is certified by any window whose
    condition it meets (every site within that window's radius is among the sites).

    Parameters
    ----------
    result : Result
        The current geometry (:func:`eligible`); not modified.
    sites : (m, 2) array_like
        The new sites (inside the domain).
    field_fn : callable, optional
        The design's attractor field, for the changed cells' values.
    design : Design, optional
        The new design when it differs from ``result.design`` only in how the sites were
        made (``[seeds]``, ``[relax]``, ``design.seed``); the opening flags follow it.

    Returns
    -------
    (Result, changed) or None
        As :func:`move`; None also when too many sites changed.
    """
    design = result.design if design is None else design
    old = result.sites
    sites = np.array(sites, dtype=np.float64).reshape(-1, 2)
    n0, n = len(old), len(sites)
    moved, added, removed = _changes(old, sites)
    k_changes = len(moved) + len(added) + len(removed)
    if not k_changes or k_changes > min(MAX_CHANGES, MAX_SHARE * max(n, n0)) or not n:
        return None if k_changes else (result, np.zeros(0, dtype=np.int32))
    domain = result.domain
    box, rect, outside = _frame_of(result)
    spacing = float(np.sqrt(domain.area / max(n, 1)))
    old_boxes = _bounds(result)
    # one window per change: its centre, a first radius, and the region it can change
    centres, radii, regions = [], [], []
    for i in moved:
        a, b = old[i], sites[i]
        c = 0.5 * (a + b)
        r = _first_radius(result, old_boxes, i, a, b, c)
        centres.append(c)
        radii.append(r or 0.5 * float(np.hypot(*(b - a))) + START_SPACINGS * spacing)
        regions.append((i, old_boxes[i], b))
    for i in added:  # the old cell it falls in gives the first radius, as for a move
        p = sites[i]
        j = int(np.argmin(np.hypot(old[:, 0] - p[0], old[:, 1] - p[1])))
        centres.append(p)
        radii.append(_first_radius(result, old_boxes, j, p, p, p) or START_SPACINGS * spacing)
        regions.append((i, None, p))
    for i in removed:
        c = old[i]
        r = _first_radius(result, old_boxes, i, c, c, c)
        centres.append(c)
        radii.append(r or START_SPACINGS * spacing)
        regions.append((None, old_boxes[i], c))
    centres = np.array(centres)
    radii = np.array(radii)
    dist = np.hypot(
        sites[:, 0][:, None] - centres[:, 0][None, :], sites[:, 1][:, None] - centres[:, 1][None, :]
    )
    for _ in range(TRIES):
        window = np.flatnonzero((dist <= radii).any(axis=1))
        if len(window) > n // 2:  # the whole diagram against the box: every cell is exact
            window = np.arange(n)
        cells = _window(sites, window, box, design.voronoi.algorithm)
        cut = np.zeros(len(window), dtype=bool)
        if len(window) == n:
            ok = np.ones(n, dtype=bool)
        else:
            ok = _certified(cells, sites[window], centres, radii)
        if not rect and len(window) < n:
            # A cell the domain cuts needs certifying only where it is inside the domain:
            # cut the uncertified ones and score their pieces' vertices instead.
            redo = np.flatnonzero(~ok)
            cells[redo] = _clip(cells[redo], domain, outside)
            ok[redo] = _certified(cells[redo], sites[window[redo]], centres, radii)
            cut[redo] = True
        pos = np.full(n, -1, dtype=np.int64)
        pos[window] = np.arange(len(window))
        new_boxes = shapely.bounds(cells)
        need = _needed(regions, pos, ok, old_boxes, new_boxes, window, n)
        if need is not None:
            break
        radii = radii * GROWTH
    else:
        return None
    if not rect:
        late = pos[need][~cut[pos[need]]]
        cells[late] = _clip(cells[late], domain, outside)
    return _assemble(result, design, sites, need, cells[pos[need]], field_fn, n0)


def _certified(cells, own, centres, radii) -> np.ndarray:
    """Per cell: whether some window's condition holds at every vertex (see the module)."""
    coords, owner = shapely.get_coordinates(cells, return_index=True)
    ok = np.ones(len(cells), dtype=bool)
    if not len(coords):
        return ok
    site = own[owner]
    to_site = np.hypot(coords[:, 0] - site[:, 0], coords[:, 1] - site[:, 1])
    ok[:] = False
    seen = np.zeros(len(cells), dtype=bool)
    seen[owner] = True
    ok[~seen] = True  # no vertex: nothing to prove
    for c, r in zip(centres, radii, strict=True):
        score = np.hypot(coords[:, 0] - c[0], coords[:, 1] - c[1]) + to_site
        worst = np.full(len(cells), -np.inf)
        np.maximum.at(worst, owner, score)
        ok |= seen & (worst < r * (1.0 - 1e-9))
    return ok


def _needed(regions, pos, ok, old_boxes, new_boxes, window, n):
    """The cells that can have changed, or None when one of them is not certified yet.

    For each change, the cells whose old or new box meets the box of its site's old and new
    cell (and its old and new position) must be certified window cells.
    """
    need = []
    for i, old_box, point in regions:
        parts = [np.array([point[0], point[1], point[0], point[1]])]
        if old_box is not None and np.isfinite(old_box).all():
            parts.append(old_box)
        if i is not None:
            k = pos[i]
            if k < 0 or not ok[k]:
                return None
            if np.isfinite(new_boxes[k]).all():
                parts.append(new_boxes[k])
        ab = np.vstack(parts)
        region = (ab[:, 0].min(), ab[:, 1].min(), ab[:, 2].max(), ab[:, 3].max())
        olds = np.flatnonzero(_overlap(old_boxes, region))
        need.append(olds[olds < n])
        need.append(window[_overlap(new_boxes, region)])
    need = np.unique(np.concatenate(need))
    if (pos[need] < 0).any() or not ok[pos[need]].all():
        return None
    return need


def _assemble(result: Result, design, sites, need, fresh, field_fn, n0):
    """The provisional result: ``result``'s cells with the ``need`` ones from ``fresh``."""
    n = len(sites)
    if n > n0 and not np.isin(np.arange(n0, n), need).all():
        return None  # every new site's cell must be among the computed ones
    empty = shapely.Polygon()
    old_raw = _resized(result.raw, n, empty)
    differ = np.ones(len(need), dtype=bool)
    kept = need < n0
    differ[kept] = ~_same(old_raw[need[kept]], fresh[kept])
    changed_site = np.zeros(n, dtype=bool)
    m = min(n, n0)
    changed_site[:m] = (result.sites[:m] != sites[:m]).any(axis=1)
    differ |= changed_site[need]  # a moved site's own cell (and site) always travels
    redo = need[differ]
    raw = old_raw
    raw[redo] = fresh[differ]
    values = _resized(result.values, n, 0.0)
    if field_fn is not None and len(redo):
        values[redo] = dc.cell_values(raw[redo], field_fn)
    seed = design.design.seed
    old_mask = _resized(result.mask, n, False)
    if design.openings.select in _PER_CELL and design.design.seed == result.design.design.seed:
        mask = old_mask.copy()
        mask[redo] = dc.opening_mask(design, raw[redo], values[redo], seed)
    else:  # random, every_kth, largest: by index or rank, over all cells
        mask = dc.opening_mask(design, raw, values, seed)
    out = _resized(result.cells, n, empty)
    live = _resized(_live(result), n, False)
    if len(redo):
        out[redo] = dc.operate_cells(design, raw[redo], values[redo], field_fn is not None)
        live[redo] = ~shapely.is_empty(out[redo])
    open_cells = np.flatnonzero(mask & live)
    extra = {k: v for k, v in result.extra.items() if k not in ("edges", "frame_fast")}
    wkb = _resized(result.extra["raw_wkb"], n, b"")
    wkb[redo] = shapely.to_wkb(raw[redo])
    boxes = _resized(_bounds(result), n, np.nan)
    boxes[redo] = shapely.bounds(raw[redo])
    extra.update(raw_wkb=wkb, raw_bounds=boxes, redone=redo, open_cells=open_cells, live=live)
    extra["provisional"] = True
    new = Result(
        design,
        result.boundary,
        result.domain,
        sites,
        raw,
        out,
        mask,
        values,
        np.zeros(n, dtype=result.level.dtype),
        np.asarray(out[open_cells], dtype=object),
        None,
        extra,
        None,
    )
    flipped = np.flatnonzero(mask[:m] != result.mask[:m])
    changed = np.union1d(np.union1d(redo, flipped), np.arange(n0, n)).astype(np.int32)
    return new, changed
