"""Periodic (toroidal) Voronoi diagrams: ``vf.voronoi(points, box, periodic=True)``.

The diagram of sites on a torus is the ordinary diagram of the sites and all their
periodic images, restricted to one copy. Only the images within a margin of the box are
used (a margin per axis, at most ~1.6 periods); the margin is proved large enough
afterwards: no left-out image is nearer a vertex of a kept cell than its site, by the empty
disk where the vertex has room for it, or else by bracketing the image with one a whole
period nearer on that axis (:func:`_proved`). Then no left-out image could have cut the
cell, so it is the torus cell. When the proof fails (few sites, large empty regions) the
margins double and the diagram is computed again.

The copies are numbered source-major, so that a vertex and its image by a box shift are
named and computed alike (exact shifts of each other where the copies are exact shifts);
the wrapped cells are the cells of the copies cut to the box.

Where the box crosses a power of two and its size is an odd number of ulps of the coarser
floats, two copies of a vertex a box size apart beyond it cannot both be floats: the
unwrapped cells there leave a gap or an overlap of an ulp between a vertex and its image.
Their sites are listed in ``Diagram.unresolved`` (each cell with a vertex whose copies are
not exact shifts of each other, decided exactly: :func:`.periodic_frame.mismatched`); the
cells are valid, and the wrapped cells (``wrap=True``) tile the box exactly.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import shapely

from ..config import (
    PERIODIC_CAP_PERIODS,
    PERIODIC_CUT_CELLS,
    PERIODIC_EXTRA_SITES,
    PERIODIC_PROOF_RTOL,
    PERIODIC_SLIVER_MAX_SIDE,
    PERIODIC_SLIVER_ULPS,
)
from .assemble import from_shapely
from .diagram import Diagram, Edges, buffers, frame_exponent
from .domain import Domain, make_domain
from .inputs import as_points, working_frame
from .periodic_chord import chord_clear, shortfall
from .periodic_edges import snap_ends
from .periodic_exact import exact_vertices
from .periodic_frame import cells_to_user_frame, corner_frame, to_local, two_sum_error
from .periodic_lines import line_start
from .periodic_retry import cut_off, cut_off_twice, next_try, on_sides, same_copies
from .periodic_ties import tie_images
from .periodic_union import united_pieces
from .planar import build

#: Initial margin, in typical cell diameters ``sqrt(area / n)``.
_MARGIN_CELLS = 3.0
_MAX_TRIES = 30


def _tile_of(boundary) -> Domain:
    if boundary is None or isinstance(boundary, shapely.Geometry):
        raise ValueError(
            "periodic=True needs boundary=(xmin, ymin, xmax, ymax), the box that tiles the "
            f"plane; got {type(boundary).__name__}"
        )
    return make_domain(boundary, np.zeros((0, 2)))


def wrap_points(points: np.ndarray, box) -> np.ndarray:
    """Sites taken modulo the box: each coordinate in ``[min, max)``.

    Parameters
    ----------
    points : (n, 2) float64
    box : (xmin, ymin, xmax, ymax)

    Returns
    -------
    (n, 2) float64
        A new array. Coordinates already in ``[min, max)`` are kept bit for bit
        (``lo + mod(p - lo, size)`` rounds: a site an ulp below ``max`` moved onto its
        neighbour an ulp lower, a false duplicate, or one below ``max`` of y to ``min``).
    """
    lo = np.array(box[:2], dtype=np.float64)
    top = np.array(box[2:], dtype=np.float64)
    size = np.array([box[2] - box[0], box[3] - box[1]], dtype=np.float64)
    out = lo + np.mod(points - lo, size)
    hi = lo + size
    out = np.where(out >= hi, lo, out)  # rounding can land on the upper edge
    out = np.where(out < lo, lo, out)
    return np.where((points >= lo) & (points < top), points, out)


def _images(sites: np.ndarray, box, margin, extra=None):
    """Every copy of the sites inside the box grown by ``margin = (mx, my)``, source-major.

    ``extra = (mask, caps)``: the sites ``mask`` also have every copy inside the box grown
    by ``caps`` (a site off a line whose copies cut the line's cells from afar; see
    :func:`.periodic_chord.shortfall`).

    Returns ``(ext (N, 2), source (N,) int64, shift (N, 2) int64, exact)`` ordered by
    source, then by shift (``exact``: every copy is its site shifted by whole box sizes
    without rounding): the copies of site 0 first, then those of site 1, ... A cell builder names a
    vertex where several sites are (nearly) cocircular by its lowest-numbered sites; in this
    order the copies around a vertex and around its image by a shift are numbered alike, so
    both get the same name and their coordinates differ by the exact shift (with the
    originals first, an original and the images of others named it differently, an ulp
    apart at 4e12: cells that did not tile the torus).
    """
    x0, y0, x1, y1 = box
    mx, my = margin
    w = x1 - x0
    h = y1 - y0
    wide = extra is not None and extra[0].any()
    ax = int(np.ceil(max(mx, extra[1][0] if wide else 0.0) / w))
    ay = int(np.ceil(max(my, extra[1][1] if wide else 0.0) / h))
    n = len(sites)
    idx = np.arange(n)
    ext = []
    source = []
    shift = []
    exact = Fraction(x1) - Fraction(x0) == w and Fraction(y1) - Fraction(y0) == h
    for a in range(-ax, ax + 1):
        for b in range(-ay, ay + 1):
            t = np.array([a * w, b * h])
            img = sites + t if (a or b) else sites
            keep = (
                (img[:, 0] >= x0 - mx)
                & (img[:, 0] <= x1 + mx)
                & (img[:, 1] >= y0 - my)
                & (img[:, 1] <= y1 + my)
            )
            if a == 0 and b == 0:
                keep[:] = True
            elif wide:
                cx, cy = extra[1]
                keep |= (
                    extra[0]
                    & (img[:, 0] >= x0 - cx)
                    & (img[:, 0] <= x1 + cx)
                    & (img[:, 1] >= y0 - cy)
                    & (img[:, 1] <= y1 + cy)
                )
            if keep.any() and exact and (a or b):
                exact = Fraction(t[0]) == a * Fraction(w) and Fraction(t[1]) == b * Fraction(h)
                exact = exact and not two_sum_error(sites[keep], t).any()
            if keep.any():
                ext.append(img[keep])
                source.append(idx[keep])
                shift.append(np.tile(np.array([a, b], dtype=np.int64), (int(keep.sum()), 1)))
    ext = np.concatenate(ext)
    source = np.concatenate(source)
    shift = np.concatenate(shift)
    # stable: within a source the copies stay in (a, b) order, the same for every source
    order = np.argsort(source, kind="stable")
    return np.ascontiguousarray(ext[order]), source[order], shift[order], exact


def _one_grid(lo: float, hi: float) -> bool:
    """Whether the floats from ``lo`` to ``hi`` are evenly spaced (one sign, one binade)."""
    return (lo > 0 or hi < 0) and abs(np.spacing(lo)) == abs(np.spacing(hi))


def _odd_period(box) -> bool:
    """Whether the box is an odd number of its floats' ulps across on an axis (one grid)."""
    x0, y0, x1, y1 = box
    for a, b in ((x0, x1), (y0, y1)):
        if _one_grid(a, b):
            steps = (b - a) / abs(np.spacing(a))
            if steps == np.floor(steps) and steps % 2 == 1:
                return True
    return False


def _margins(box, n: int):
    """First margins ``(mx, my)`` around the box, each at most its cap (:func:`_caps`).

    A few typical cell sizes, and at least ~2.5 radii of the largest empty circle expected
    among ``n`` uniform sites, so one pass is usually enough. Where that exceeds the cap of
    one axis (a thin box: the cells span its short side), the cells are strips across the
    box, ~``long / n`` wide, and the long axis gets a few times the largest expected gap.
    """
    x0, y0, x1, y1 = box
    w = x1 - x0
    h = y1 - y0
    # the area in units of the longer side: w * h overflows at 1e300
    side = max(w, h)
    area = (w / side) * (h / side)
    m = side * max(
        _MARGIN_CELLS * np.sqrt(area / n), 2.5 * np.sqrt(area * np.log(n + 1) / (np.pi * n))
    )
    cx, cy = _caps(box)
    if m >= min(cx, cy):
        strip = _MARGIN_CELLS * side * np.log(n + 1) / n
        m = max(m if m < max(cx, cy) else 0.0, strip)
        return (min(cx, m), cy) if w >= h else (cx, min(cy, m))
    return (m, m)


def _caps(box):
    """The largest margins ever needed: ``PERIODIC_CAP_PERIODS`` box sizes on each axis.

    A cell lies within half a period of its site on each axis (the bisector with its own
    image), so with more than 1.5 periods every vertex passes :func:`_proved`'s bracket test.
    """
    x0, y0, x1, y1 = box
    # plus the bracket test's slack: a box a few ulps tall at 1e6 (1 x 3e-9) failed the
    # proof at 1.6 periods and raised
    slack = 2.0 * _rounding(box)
    return (PERIODIC_CAP_PERIODS * (x1 - x0) + slack, PERIODIC_CAP_PERIODS * (y1 - y0) + slack)


def _proved(d: Diagram, cells: np.ndarray, box, margin, sites=None, extra=None) -> bool:
    """True when no copy left out of ``d`` can be nearer a vertex of ``cells`` than its site.

    A vertex ``v`` of cell ``p`` has every copy in ``d`` at least ``r = |v - p|`` away. A copy
    ``q`` left out lies past the complete region on an axis; on each axis either

    - ``v`` has room ``>= r`` to that side of the region (the old disk test), so ``q`` is
      ``>= r`` away, or
    - ``v`` lies a whole period inside the region on that axis: the copy of ``q``'s site
      that is shifted along this axis towards ``v`` by whole periods to within one period of
      ``v`` is in the region on this axis, is no farther from ``v`` than ``q``, and differs
      from ``q`` only on this axis (the bracket test).

    - (``sites``: the sites in the box) no copy past the margin can be in the disk: the
      chord of the disk there is clear of every copy's other coordinate
      (:func:`.periodic_chord.chord_clear`; or, where a few sites' coordinates fall in it,
      their copies past the margin are measured), so ``q`` is ``>= r`` away.

    ``extra = (mask, caps)``: those sites' copies are in ``d`` to the caps, and the chord
    test measures theirs past the caps (where the bracket test holds for every vertex).
    Applying this to ``x`` then to ``y`` ends at a copy in ``d``, so ``|v - q| >= r``. The
    bracket test makes the margin of a thin box's short side a period or two, however long
    the cells' empty disks are.

    ``cells`` are copy indices, or, for the wrapped diagram, the pieces of
    :func:`_box_pieces`: the copies' cells cut to the box. A piece is convex and inside its
    copy's cell, so when its vertices are proved every point of it is (the cells'
    half-planes hold at the vertices): only the part of a cell in the box needs its margin.
    """
    if isinstance(cells, tuple):
        v, owner = _piece_vertices(d, cells)
    else:
        v, owner = _vertices(d, cells)
    if not len(v):
        return True
    x0, y0, x1, y1 = box
    mx, my = margin
    side = max(x1 - x0, y1 - y0)  # squares in units of the box: no overflow at 1e300
    ok = np.ones(len(v), dtype=bool)
    diff = (v - d.sites[owner]) / side
    r2 = (diff[:, 0] * diff[:, 0] + diff[:, 1] * diff[:, 1]) * (1.0 + PERIODIC_PROOF_RTOL)
    slack = _rounding(box)  # the copies' coordinates are rounded sums
    for k, (a, b, m) in enumerate(((x0, x1, mx), (y0, y1, my))):
        room = np.minimum(v[:, k] - (a - m), (b + m) - v[:, k])
        if (room < 0).any():
            return False
        bracket = room >= (b - a) + slack
        room = room / side
        good = bracket | (room * room >= r2)
        if sites is not None and not good.all():
            ek = None if extra is None else (extra[0], extra[1][k])
            good |= chord_clear(v, r2, room, sites, box, k, m, side, slack, ~good, ek)
        ok &= good
    return bool(ok.all())


def _vertices(d: Diagram, cells: np.ndarray):
    """The vertices of ``cells`` of ``d`` and, for each, its cell."""
    coords, (ring, poly, geom) = d.to_geoarrow()
    if not len(cells):
        return coords[:0], cells
    lo = ring[poly[geom[cells]]]
    per_cell = ring[poly[geom[cells + 1]]] - lo
    total = int(per_cell.sum())
    if len(cells) == len(geom) - 1 or (cells[-1] == len(cells) - 1 and lo[0] == 0):
        v = coords[:total]  # the cells are a prefix of the buffers
    else:
        v = coords[np.repeat(lo - np.cumsum(per_cell) + per_cell, per_cell) + np.arange(total)]
    return v, np.repeat(cells, per_cell)


def _gather(pieces, source: np.ndarray, n: int, keep: np.ndarray, rounding: float):
    """Buffers of ``n`` cells, cell ``i`` made of the pieces ``keep[source[keep] == i]``."""
    keep = keep[np.argsort(source[keep], kind="stable")]
    pieces = pieces[keep]
    owner = source[keep]
    nonempty = ~shapely.is_empty(pieces)
    pieces = pieces[nonempty]
    owner = owner[nonempty]
    counts = np.bincount(owner, minlength=n)
    out = np.full(n, shapely.Polygon(), dtype=object)
    single = counts[owner] == 1
    out[owner[single]] = pieces[single]
    multi = ~single
    if multi.any():
        groups = np.unique(owner[multi], return_inverse=True)
        merged = shapely.multipolygons(pieces[multi], indices=groups[1])
        bad = np.flatnonzero(~shapely.is_valid(merged))
        # pieces of one cell that touch along an edge (a cell bordering its own image)
        if len(bad):
            merged[bad] = united_pieces(merged[bad], rounding)
        out[groups[0]] = merged
    return from_shapely(out)


def _rounding(box) -> float:
    """A length below which features in the box are rounding noise of its coordinates."""
    x0, y0, x1, y1 = box
    size = max(x1 - x0, y1 - y0)
    ulps = PERIODIC_SLIVER_ULPS * np.finfo(np.float64).eps
    return ulps * max(abs(x0), abs(y0), abs(x1), abs(y1), size)


def _sliver_width(box) -> float:
    """How wide a wrapped piece or hole may be and still be rounding noise.

    :func:`_rounding`, but at most a quarter of the box's shorter side: a box at (4e12,
    2e12) 0.003 tall (12 ulps of its y) is thinner than the rounding of its x coordinates
    (7 ulps of 4e12), and every piece of its 30 cells, each bordering its own image across
    the height, was dropped as a sliver (28 cells empty, area 2% of the box).
    """
    x0, y0, x1, y1 = box
    return min(_rounding(box), PERIODIC_SLIVER_MAX_SIDE * min(x1 - x0, y1 - y0))


def _box_pieces(d: Diagram, box):
    """The copies' cells cut to the box: ``(inside, cross, cut)``.

    ``inside``: the copies whose whole cell lies in the box (their piece is the cell, kept
    in the buffers); ``cross``: those whose cell crosses a side, ``cut`` their pieces
    (GEOS, empty where only a side or a corner is shared). The cells come from the diagram
    in the grown box, where a copy and its image share their vertices up to the exact
    shift; the pieces of two neighbours meet where GEOS cuts their shared edge, once.
    (Clipping every copy to the box in the planar build instead lost copies at 1e15, where
    the box is 24 ulps wide.)
    """
    x0, y0, x1, y1 = box
    coords, (ring, poly, geom) = d.to_geoarrow()
    lo = ring[poly[geom[:-1]]]
    hi = ring[poly[geom[1:]]]
    full = np.flatnonzero(hi > lo)
    b = np.full((len(lo), 4), np.nan)
    if len(full):
        start = lo[full]
        b[full, 0] = np.minimum.reduceat(coords[: hi[full[-1]], 0], start)
        b[full, 1] = np.minimum.reduceat(coords[: hi[full[-1]], 1], start)
        b[full, 2] = np.maximum.reduceat(coords[: hi[full[-1]], 0], start)
        b[full, 3] = np.maximum.reduceat(coords[: hi[full[-1]], 1], start)
    ok = ~np.isnan(b[:, 0])
    inside = ok & (b[:, 0] >= x0) & (b[:, 2] <= x1) & (b[:, 1] >= y0) & (b[:, 3] <= y1)
    meets = ok & (b[:, 0] < x1) & (b[:, 2] > x0) & (b[:, 1] < y1) & (b[:, 3] > y0)
    cross = np.flatnonzero(meets & ~inside)
    length = hi[cross] - lo[cross]
    take = np.repeat(lo[cross] - np.cumsum(length) + length, length) + np.arange(length.sum())
    cells = shapely.polygons(
        shapely.linearrings(coords[take], indices=np.repeat(np.arange(len(cross)), length))
    )
    cut = shapely.intersection(cells, shapely.box(x0, y0, x1, y1))
    flat = shapely.area(cut) <= 0
    cut[flat] = shapely.Polygon()
    for k in np.flatnonzero(~flat & (shapely.get_type_id(cut) != 3)):
        # a collection: its polygons (GEOS can add a lower-dimension part)
        parts = [q for q in shapely.get_parts(cut[k]) if q.geom_type == "Polygon"]
        cut[k] = parts[0] if len(parts) == 1 else shapely.MultiPolygon(parts)
    return np.flatnonzero(inside), cross, cut


def _piece_vertices(d: Diagram, pieces):
    """The vertices of the pieces ``(inside, cross, cut)`` and, for each, its copy."""
    inside, cross, cut = pieces
    v, owner = _vertices(d, inside)
    w, k = shapely.get_coordinates(cut, return_index=True)
    return np.concatenate((v, w)), np.concatenate((owner, cross[k]))


def _wrapped_cells(d: Diagram, pieces, source, n: int, rounding: float):
    """Buffers of the ``n`` wrapped cells from the pieces, and the copies kept.

    Each piece is one ring, except where a cell borders its own image (few sites): then the
    touching pieces are united in shapely (:func:`_gather`).
    """
    inside, cross, cut = pieces
    live = ~shapely.is_empty(cut)
    keep = np.sort(np.concatenate((inside, cross[live])))
    pairs = d.edges.pairs
    single = (shapely.get_type_id(cut[live]) == 3).all()
    if single and not (source[pairs[:, 0]] == source[pairs[:, 1]]).any():
        coords, (ring, poly, geom) = d.to_geoarrow()
        # rings in copy order: inside cells from the buffers, cut ones from GEOS (one
        # gather: a Python loop over the rings took 0.5 s of 3e4 sites on a line, wrapped)
        cw = shapely.get_coordinates(shapely.get_exterior_ring(cut[live]), return_index=True)
        at = np.searchsorted(keep, cross[live])
        ends = np.searchsorted(cw[1], np.arange(len(at) + 1))
        start = np.zeros(len(keep), dtype=np.int64)
        length = np.zeros(len(keep), dtype=np.int64)
        where = np.searchsorted(keep, inside)
        start[where] = ring[poly[geom[inside]]]
        length[where] = ring[poly[geom[inside + 1]]] - start[where]
        start[at] = len(coords) + ends[:-1]  # the GEOS rings follow the buffers
        length[at] = np.diff(ends)
        order = np.argsort(source[keep], kind="stable")
        length = length[order]
        new_ring = np.zeros(len(order) + 1, dtype=np.int64)
        np.cumsum(length, out=new_ring[1:])
        new_geom = np.zeros(n + 1, dtype=np.int64)
        np.cumsum(np.bincount(source[keep], minlength=n), out=new_geom[1:])
        take = np.repeat(start[order] - new_ring[:-1], length) + np.arange(int(new_ring[-1]))
        out = np.concatenate((coords, cw[0]))[take] if len(order) else np.zeros((0, 2))
        new_poly = np.arange(len(order) + 1, dtype=np.int64)
        return (np.ascontiguousarray(out), new_ring, new_poly, new_geom), keep
    shapes = np.full(len(source), shapely.Polygon(), dtype=object)
    shapes[inside] = d.cells[inside]
    shapes[cross] = cut
    return _gather(shapes, source, n, keep, rounding), keep


def _slivers(pieces, box, is_orig) -> None:
    """Empty the cut image pieces that are rounding noise: at most ``_sliver_width`` wide.

    An image whose cell passes the box edge only by the rounding of its site (``0.9 - 1`` is
    not ``-0.1`` in floats) leaves a sliver a few ulps wide inside the box: no part of the
    cell on the torus (its original's part past the other side rounds away), but an extra
    polygon part. A piece is a sliver when it is narrow, however long: its area against its
    longer extent.
    """
    _, cross, cut = pieces
    b = shapely.bounds(cut)
    extent = np.fmax(b[:, 2] - b[:, 0], b[:, 3] - b[:, 1])
    thin = shapely.area(cut) <= _sliver_width(box) * extent  # NaN (empty): False
    cut[thin & ~is_orig[cross]] = shapely.Polygon()


def _torus_edges(d: Diagram, source, shift, is_orig, wrap: bool, pieces, box, cut=None) -> Edges:
    pairs = d.edges.pairs
    coords = d.edges.coords
    if wrap:
        kept = np.zeros(len(d.sites), dtype=bool)
        kept[pieces] = True
        side = _side_edges(coords, pairs, kept, box)
        coords, inside, clipped = _clip_segments(coords, box)
        pairs = pairs[inside]
        # the ends on the sides at the cut cells' own vertices (checker35 F2: 2 ulps off)
        coords = snap_ends(coords, pairs, clipped, cut, box, _sliver_width(box))
    a = pairs[:, 0]
    b = pairs[:, 1]
    sa = source[a]
    sb = source[b]
    if wrap:
        # the edges between copies that left a piece in the box (see _slivers)
        keep = kept[a] & kept[b]
        sc, sp = side
        coords = np.concatenate((coords[keep], sc))
        sa = np.concatenate((sa[keep], source[sp[:, 0]]))
        sb = np.concatenate((sb[keep], source[sp[:, 1]]))
    else:
        # each torus edge once: where the lower-index cell is the original copy (a self
        # edge, between a cell and its own image, where the image lies on the positive side)
        lower_is_a = (sa < sb) | ((sa == sb) & _positive(shift[b] - shift[a]))
        low = np.where(lower_is_a, a, b)
        keep = is_orig[low]
        coords, sa, sb = coords[keep], sa[keep], sb[keep]
    lo = np.minimum(sa, sb)
    hi = np.maximum(sa, sb)
    return Edges(np.ascontiguousarray(coords), np.stack((lo, hi), axis=1).astype(np.int64))


def _side_edges(seg: np.ndarray, pairs: np.ndarray, kept: np.ndarray, box):
    """The torus edges along the box's sides (a square grid's, a hex tile's seams), once.

    Such an edge lies between a copy with a piece in the box and one without, and again on
    the opposite side between the other two copies; the box clip keeps one, both or (an ulp
    outside) neither of them. Kept here from the lower sides (x0, y0), within rounding of
    the side, moved onto it and cut to the box.
    """
    x0, y0, x1, y1 = box
    w = _sliver_width(box)
    one = kept[pairs[:, 0]] != kept[pairs[:, 1]]
    out, which = [], []
    for k, (at, lo, hi) in enumerate(((x0, y0, y1), (y0, x0, x1))):
        along = one & (np.abs(seg[:, :, k] - at) <= w).all(axis=1)
        s = seg[along].copy()
        s[:, :, k] = at
        s[:, :, 1 - k] = np.clip(s[:, :, 1 - k], lo, hi)
        long = s[:, 0, 1 - k] != s[:, 1, 1 - k]
        out.append(s[long])
        which.append(np.flatnonzero(along)[long])
    return np.concatenate(out), pairs[np.concatenate(which)]


def _clip_segments(seg: np.ndarray, box):
    """Segments ``(m, 2, 2)`` cut to the box (Liang-Barsky), which keep a length, and ends cut.

    A segment inside the box keeps its end points' bits; ``(k, 2)`` bool: which ends of the
    kept segments the cut moved.
    """
    x0, y0, x1, y1 = box
    p = seg[:, 0]
    q = seg[:, 1]
    dv = q - p
    t0 = np.zeros(len(seg))
    t1 = np.ones(len(seg))
    with np.errstate(divide="ignore", invalid="ignore"):
        for k, (lo, hi) in enumerate(((x0, x1), (y0, y1))):
            for edge, sign in ((lo, -1.0), (hi, 1.0)):
                num = sign * (edge - p[:, k])  # >= 0 where p is inside this side
                den = sign * dv[:, k]
                t = num / den
                t0 = np.where(den < 0, np.maximum(t0, t), t0)
                t1 = np.where(den > 0, np.minimum(t1, t), t1)
                t1 = np.where((den == 0) & (num < 0), -1.0, t1)
    keep = t1 > t0
    out = seg.copy()
    a = t0 > 0
    b = t1 < 1
    out[a, 0] = p[a] + t0[a, None] * dv[a]
    out[b, 1] = p[b] + t1[b, None] * dv[b]
    out[:, :, 0] = np.clip(out[:, :, 0], x0, x1)
    out[:, :, 1] = np.clip(out[:, :, 1], y0, y1)
    keep &= (out[:, 0] != out[:, 1]).any(axis=1)
    return np.ascontiguousarray(out[keep]), keep, np.column_stack((a, b))[keep]


def _positive(s: np.ndarray) -> np.ndarray:
    return (s[:, 0] > 0) | ((s[:, 0] == 0) & (s[:, 1] > 0))


def _cells_at(bufs, cells: np.ndarray):
    """Fresh buffers ``(coords, ring, poly, geom)`` of the cells ``cells`` of ``bufs``."""
    coords, ring, poly, geom = bufs
    npoly = geom[cells + 1] - geom[cells]
    p = np.repeat(geom[cells] - np.cumsum(npoly) + npoly, npoly) + np.arange(int(npoly.sum()))
    nring = poly[p + 1] - poly[p]
    r = np.repeat(poly[p] - np.cumsum(nring) + nring, nring) + np.arange(int(nring.sum()))
    npts = ring[r + 1] - ring[r]
    k = np.repeat(ring[r] - np.cumsum(npts) + npts, npts) + np.arange(int(npts.sum()))
    new_geom = np.zeros(len(cells) + 1, dtype=np.int64)
    np.cumsum(npoly, out=new_geom[1:])
    new_poly = np.zeros(len(p) + 1, dtype=np.int64)
    np.cumsum(nring, out=new_poly[1:])
    new_ring = np.zeros(len(r) + 1, dtype=np.int64)
    np.cumsum(npts, out=new_ring[1:])
    return np.ascontiguousarray(coords[k]), new_ring, new_poly, new_geom


def _wrap_exponent(box) -> int:
    """A power of two that brings an extreme box near size 1 for the wrapped pieces, or 0.

    The wrapped cells are cut and measured by GEOS in the user's coordinates, whose areas
    under- or overflow beyond about 1e+-150 (a box of side 1e-300 had pieces of area 0 and
    lost some).
    """
    size = max(box[2] - box[0], box[3] - box[1])
    far = max(abs(v) for v in box)
    if 2.0**-400 < size and far < 2.0**400:
        return 0
    return -int(np.frexp(size)[1])


def _rescaled(pts, tile, shift: int, algorithm: str) -> Diagram:
    """The wrapped diagram computed at ``2**shift`` times the input, scaled back exactly."""
    box = np.ldexp(np.array(tile.bounds), shift)
    inner = periodic_voronoi(np.ldexp(pts, shift), tuple(box), algorithm=algorithm, wrap=True)
    coords, ring, poly, geom = buffers(inner)
    e = inner.edges
    out = Diagram(
        pts,
        inner.duplicate_of,
        tile,
        (np.ldexp(coords, -shift), ring, poly, geom),
        Edges(np.ldexp(e.coords, -shift), e.pairs),
        algorithm,
        frame_exponent(inner) + shift,
        inner.unresolved,
    )
    out.periodic = True
    out.wrapped = True
    return out


def _translated(pts, tile, corner, algorithm: str, wrap: bool) -> Diagram:
    """The diagram computed in the frame of ``corner`` (:mod:`.periodic_frame`), moved back."""
    box = tile.bounds
    local, local_box = to_local(pts, box, corner)
    inner = _periodic(local, make_domain(local_box, np.zeros((0, 2))), algorithm, wrap, False)
    coords, ring, poly, geom = buffers(inner)
    e = inner.edges
    bufs, seg, apart = cells_to_user_frame(
        coords, (ring, poly, geom), e.coords.reshape(-1, 2), box, corner, not wrap
    )
    seg = seg.reshape(-1, 2, 2)
    live = (seg[:, 0] != seg[:, 1]).any(axis=1)
    # a cell narrower than the user's floats rounds away: its site is unresolved there;
    # so is a site whose unwrapped cell has a vertex that cannot be an exact shift of its
    # image in another cell (an ulp of gap or overlap between them: the copies' floats
    # cannot agree, see periodic_frame.mismatched)
    gone = np.flatnonzero((np.diff(geom) > 0) & (np.diff(bufs[3]) == 0))
    lost = np.union1d(np.union1d(inner.unresolved, gone), apart).astype(np.int64)
    out = Diagram(
        pts,
        inner.duplicate_of,
        tile,
        bufs,
        Edges(np.ascontiguousarray(seg[live]), np.ascontiguousarray(e.pairs[live])),
        algorithm,
        working_frame(pts, np.array(box))[1],
        lost,
    )
    out.periodic = True
    out.wrapped = wrap
    return out


def periodic_voronoi(points, boundary, *, algorithm: str = "delaunay", wrap: bool = False):
    """Voronoi diagram on the torus made by identifying opposite edges of ``boundary``.

    See :func:`voroforge.voronoi` (``periodic=True``) for the public description.
    """
    tile = _tile_of(boundary)
    return _periodic(as_points(points), tile, algorithm, wrap, True)


def _periodic(points, tile, algorithm: str, wrap: bool, may_move: bool) -> Diagram:
    """:func:`periodic_voronoi` of ``points`` in ``tile``.

    ``may_move``: the diagram may be computed in a frame where every copy is exact
    (:func:`_translated`), used where the copies or their vertices are not exact shifts in
    the user's frame, or where sites are too close for it.
    """
    box = tile.bounds
    pts = wrap_points(points, box)
    n = len(pts)
    x0, y0, x1, y1 = box
    shift = _wrap_exponent(box) if wrap and n else 0
    if shift:
        return _rescaled(pts, tile, shift, algorithm)
    if n == 0:
        d = build(pts, tile, algorithm)
        d.periodic = True
        d.wrapped = wrap
        return d
    mx, my = _margins(box, n)
    cx, cy = _caps(box)
    extra = (np.zeros(n, dtype=bool), (cx, cy))  # sites whose copies go to the caps
    grew = [False, False]  # whether each margin grew before (:func:`.periodic_retry.next_try`)
    start = line_start(pts, box, (mx, my), (cx, cy), PERIODIC_EXTRA_SITES)
    if start is not None:  # sites on a line: the margins its cells need, at once
        (mx, my), extra[0][:] = start
    last = None  # the copies of the last try, where its diagram may stand for the next
    for _ in range(_MAX_TRIES):
        ext, source, shift, exact = _images(pts, box, (mx, my), extra)
        ex, ey = (max(mx, cx), max(my, cy)) if extra[0].any() else (mx, my)
        one = exact and _one_grid(x0 - ex, x1 + ex) and _one_grid(y0 - ey, y1 + ey)
        if may_move and not (one and not _odd_period(box)):
            # the copies or their vertices are rounded on two grids: a vertex and its image
            # by a box shift are not exact shifts of each other; or the box is an odd
            # number of ulps across, where a vertex half-way between two floats rounds to
            # even one way and its image the other (4e12, a box 123 ulps tall: a corner at
            # 110 ulps and its image at -14; the cell builder then kept a vertex in one
            # copy's cell and folded it away in the other's, Euler 4)
            corner = corner_frame(pts, box)
            if corner is not None:
                return _translated(pts, tile, corner, algorithm, wrap)
            may_move = False
        is_orig = ~shift.any(axis=1)
        orig = np.flatnonzero(is_orig)  # the original of site i is copy orig[i]
        if not same_copies(last, source, shift):
            grown = make_domain((x0 - mx, y0 - my, x1 + mx, y1 + my), ext)
            d = build(ext, grown, algorithm, split=False)
        if may_move and len(d.unresolved):
            # sites a few ulps apart (a box 24 x 16 ulps at 1e15): where the frame is exact,
            # its finer floats resolve them
            corner = corner_frame(pts, box)
            if corner is not None:
                return _translated(pts, tile, corner, algorithm, wrap)
            may_move = False
        if wrap:
            pieces = _box_pieces(d, box)
            owners = pieces
        else:
            owners = orig[d.duplicate_of[orig] < 0]
        if _proved(d, owners, box, (mx, my), pts, extra):
            break
        if mx >= cx and my >= cy:  # pragma: no cover - the bracket test passes at the caps
            raise RuntimeError("periodic diagram: could not prove the margin")
        v, owner = _piece_vertices(d, owners) if wrap else _vertices(d, owners)
        most = PERIODIC_EXTRA_SITES - int(extra[0].sum())
        cut = cut_off(d, owner, box, (mx, my), _rounding(box)) if wrap else None
        (grow_x, grow_y), asked = shortfall(
            v, d.sites[owner], box, (mx, my), pts, _rounding(box), extra, most, owner, cut
        )
        asked = asked[~extra[0][asked]]
        extra[0][asked] = True
        # the few cells cut off on both axes bring their sites' copies now, not a build later
        twice = cut_off_twice(v, owner, box, (mx, my), _rounding(box), PERIODIC_CUT_CELLS, cut)
        # the grown box's next copies may be these: then this diagram stands (no kept cell
        # ends at its sides), proved again with the larger margins
        last = None if on_sides(v, box, (mx, my), _rounding(box)) else (source, shift)
        (mx, my), changed = next_try(
            (mx, my),
            (cx, cy),
            (grow_x, grow_y),
            grew,
            source[twice],
            extra,
            PERIODIC_EXTRA_SITES,
            lambda m: len(_images(pts, box, m, extra)[0]),
        )
        if not changed and not len(asked):  # pragma: no cover - the old rule: both double
            mx, my = min(2.0 * mx, cx), min(2.0 * my, cy)
    else:  # pragma: no cover - the margins reach their caps long before
        raise RuntimeError("periodic diagram: could not prove the margin")
    # a vertex that rounded copies moved by more than a few ulps (two sites 5e-9 apart: 3e-8
    # off a period over), recomputed from the exact images (periodic_exact)
    fixed, far = exact_vertices(d, source, shift, box)
    if fixed is not d:
        d = fixed
        if wrap:
            pieces = _box_pieces(d, box)
    if wrap:
        # where every copy is an exact shift and the box lies in one binade on each axis, a
        # piece a few ulps wide is the part of a cell whose original passes the opposite
        # side by as much, on the same grid: kept (at 4e12 such a piece, 1 ulp wide, was
        # dropped: a gap of 6e-7 of the box)
        if not (exact and _one_grid(x0, x1) and _one_grid(y0, y1)):
            _slivers(pieces, box, is_orig)
        bufs, keep = _wrapped_cells(d, pieces, source, n, _sliver_width(box))
    else:
        # a vertex and its images made exact shifts of each other (periodic_ties)
        copies = (buffers(d), d.sites, source, shift)
        bufs = tie_images(_cells_at(buffers(d), orig), box, copies)
    edges = _torus_edges(
        d, source, shift, is_orig, wrap, keep if wrap else None, box, pieces if wrap else None
    )
    # a site is unresolved when the copy its cell comes from is (unwrapped: the original;
    # wrapped: any copy, whose piece is then missing)
    lost = d.unresolved
    if wrap:
        # a copy's cell is within half a period of its site on each axis
        q = d.sites[lost]
        w2, h2 = 0.5 * (x1 - x0), 0.5 * (y1 - y0)
        lost = lost[
            (q[:, 0] > x0 - w2) & (q[:, 0] < x1 + w2) & (q[:, 1] > y0 - h2) & (q[:, 1] < y1 + h2)
        ]
    else:
        lost = lost[is_orig[lost]]
    dup = d.duplicate_of[orig]
    # an original's duplicate is the same copy of an earlier site: its original
    dup = np.where(dup < 0, -1, source[np.maximum(dup, 0)])
    out = Diagram(
        np.ascontiguousarray(d.sites[orig]),
        np.ascontiguousarray(dup, dtype=d.duplicate_of.dtype),
        tile,
        bufs,
        edges,
        algorithm,
        frame_exponent(d),
        np.union1d(source[lost], far).astype(np.int64),
    )
    out.periodic = True
    out.wrapped = wrap
    return out
