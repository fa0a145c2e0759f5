"""Cells that meet a long polygonal boundary, clipped by the segments near each one.

Above ``PIECE_SMALL`` vertices a cell that meets the domain's boundary is cut by the
boundary segments in the grid buckets over its box (:func:`.kernels.polyclip.clip_cells`),
in time proportional to the segments near it: a comb whose outline meets every cell no
longer pays a GEOS overlay per cell (0.6 ms each on a comb of 1,000 teeth). A cell that no
segment meets is wholly inside or outside, which one of its vertices tells (exact, local:
:meth:`.pieces.Pieces.holds`); the domain's rings wholly inside a cell become its holes
or parts (:func:`_with_loops`, GEOS's exact predicates place them, nothing is computed);
a cell the kernel leaves (two chain ends the floats cannot order, a crossing that rounds
past its segments' ends) or whose result is not valid takes the overlay with its piece of
the domain as before (:meth:`.pieces.Pieces.intersect`). The diagram's shared edges are
cut by the same crossings (:func:`clip_edges`), so they end at the cells' vertices.
"""

from __future__ import annotations

import numpy as np
import shapely

from ..kernels.edgeclip import HARD as EDGE_HARD
from ..kernels.edgeclip import NONE as EDGE_NONE
from ..kernels.edgeclip import clip_edges as edge_kernel
from ..kernels.polyclip import DONE, HARD, LOOPS, NONE, box_sides, bucket_segments, clip_cells


def clip_convex(pieces, convex, ring_xy, ring_off, cells):
    """``convex[k] ∩ domain`` for closed convex rings in the boxes of cells ``cells[k]``.

    Parameters
    ----------
    pieces : Pieces
        The domain and its pieces.
    convex : (u,) object
        The rings as shapely polygons.
    ring_xy : (k, 2) float64
        The same rings, closed and counter-clockwise, ring ``i`` at
        ``ring_off[i]:ring_off[i + 1]``.
    ring_off : (u + 1,) int64
    cells : (u,) int64
        Each ring's cell (whose piece the overlay reads).

    Returns
    -------
    (u,) object
        Polygons, MultiPolygons or empty polygons.
    """
    empty = shapely.Polygon()
    if pieces.whole or not len(convex):
        return pieces.intersect(convex, cells, empty)
    seg, nxt = _segments(pieces.geometry)
    grid = _grid(shapely.bounds(convex), len(convex))
    boff, bids = bucket_segments(seg, *grid[:3], int(grid[3]), int(grid[4]))
    box = np.ascontiguousarray(pieces.box, dtype=np.float64)
    status, xy, off, owner, loop = clip_cells(
        np.ascontiguousarray(ring_xy, dtype=np.float64),
        np.ascontiguousarray(ring_off, dtype=np.int64),
        seg,
        nxt,
        boff,
        bids,
        grid,
        box,
        box_sides(seg, nxt, box),
    )
    out = np.empty(len(convex), dtype=object)  # noqa: TID251 - every slot is filled below
    count = np.bincount(owner, minlength=len(convex))
    looped = np.flatnonzero(status == LOOPS)
    if len(looped):
        first = np.concatenate(([0], np.cumsum(count)))
        for i in looped:
            rings = [xy[off[r] : off[r + 1]] for r in range(first[i], first[i + 1])]
            got = _with_loops(convex[i], rings, loop[first[i] : first[i + 1]])
            if got is None:
                status[i] = HARD
            else:
                out[i] = got
                status[i] = DONE
        done = np.setdiff1d(np.flatnonzero(status == DONE), looped)
    else:
        done = np.flatnonzero(status == DONE)
    if len(done):
        mine = np.isin(owner, done)
        rings = np.flatnonzero(mine)
        r_off = np.concatenate(([0], np.cumsum(off[rings + 1] - off[rings])))
        pick = np.repeat(off[rings] - r_off[:-1], np.diff(r_off)) + np.arange(r_off[-1])
        geom = np.concatenate(([0], np.cumsum(count[done])))
        got = shapely.from_ragged_array(
            shapely.GeometryType.MULTIPOLYGON, xy[pick], (r_off, np.arange(len(r_off)), geom)
        )
        one = count[done] == 1
        got[one] = shapely.get_geometry(got[one], 0)
        out[done] = got
    done = np.flatnonzero(status == DONE)
    if len(done):
        # a crossing rounded across a feature about an ulp away folds a ring (or makes two
        # parts overlap): that cell takes the overlay
        status[done[~shapely.is_valid(out[done])]] = HARD
    free = np.flatnonzero(status == NONE)
    if len(free):
        held = pieces.holds(ring_xy[ring_off[free]])
        out[free[held]] = convex[free[held]]
        out[free[~held]] = empty
    hard = np.flatnonzero(status > NONE)
    if len(hard):
        out[hard] = pieces.intersect(convex[hard], cells[hard], empty)
    return out


def clip_edges(pieces, edges):
    """Shared edges ``(m, 2, 2)`` cut to the domain by the exact kernel, where it decides.

    Each crossing is computed as the cells' clip computes it (:func:`clip_convex`), so the
    pieces end at the clipped cells' vertices bit for bit (:func:`.kernels.edgeclip.clip_edges`).

    Returns
    -------
    got : (r, 2, 2) float64
        The pieces in the domain of the edges the kernel decided, each edge's in order.
    owner : (r,) int64
        The edge of each piece.
    hard : (h,) int64
        The edges left to the overlay (a boundary segment along one, two crossings the
        floats cannot order, a rounded crossing past a segment's end).
    """
    seg, nxt = _segments(pieces.geometry)
    edges = np.ascontiguousarray(edges, dtype=np.float64)
    grid = _grid(np.hstack((edges.min(axis=1), edges.max(axis=1))), len(edges))
    boff, bids = bucket_segments(seg, *grid[:3], int(grid[3]), int(grid[4]))
    status, got, owner = edge_kernel(edges, seg, nxt, boff, bids, grid)
    # an edge no segment meets is wholly inside or outside: its first end tells (exact)
    free = np.flatnonzero(status == EDGE_NONE)
    free = free[pieces.holds(edges[free, 0])]
    got = np.concatenate((got, edges[free]))
    owner = np.concatenate((owner, free))
    order = np.argsort(owner, kind="stable")
    return got[order], owner[order], np.flatnonzero(status == EDGE_HARD)


def _segments(geom):
    """The boundary's segments ``(m, 4)``, the domain on their left, and each one's next."""
    rings = shapely.get_rings(shapely.get_parts(shapely.orient_polygons(geom)))
    xy, at = shapely.get_coordinates(rings, return_index=True)
    # (repeated points dropped: a segment of no length has no side)
    keep = np.ones(len(xy), dtype=np.bool_)
    keep[1:] = (xy[1:] != xy[:-1]).any(axis=1) | (at[1:] != at[:-1])
    xy, at = xy[keep], at[keep]
    last = np.r_[at[1:] != at[:-1], True]  # each ring's closing repeat
    idx = np.flatnonzero(~last)
    seg = np.ascontiguousarray(np.hstack((xy[idx], xy[idx + 1])))
    ring = at[idx]
    first = np.r_[True, ring[1:] != ring[:-1]]
    start = np.flatnonzero(first)
    nxt = np.arange(1, len(idx) + 1, dtype=np.int64)
    ends = np.r_[start[1:], len(idx)] - 1
    nxt[ends] = start
    return seg, nxt


def _grid(boxes, count):
    """``(x0, y0, h, nx, ny)``: squares over the cells' boxes, about one cell per square."""
    x0, y0 = boxes[:, 0].min(), boxes[:, 1].min()
    x1, y1 = boxes[:, 2].max(), boxes[:, 3].max()
    w, hgt = max(x1 - x0, 0.0), max(y1 - y0, 0.0)
    h = np.sqrt(w * hgt / count) if w * hgt > 0 else max(w, hgt, 1.0)
    if not h > 0:
        h = 1.0
    nx = min(int(w / h) + 1, 4096)
    ny = min(int(hgt / h) + 1, 4096)
    h = max(h, w / nx, hgt / ny) * (1 + 2.0**-40)
    return np.array([x0, y0, h, nx, ny], dtype=np.float64)


def _with_loops(cell, rings, loop):
    """A cell's polygon(s) from its clipped rings and the domain's rings wholly inside it.

    ``rings`` are closed coordinate arrays, ``loop`` flags the domain's rings (shells
    counter-clockwise, holes clockwise); the others are the shells the chains cut. Without
    those, the cell's own ring is a shell where the outermost loops are holes. Each hole
    goes to the smallest shell that holds it (GEOS's exact predicates). None where the
    loops do not nest that way, or the result is not valid (the overlay then decides).
    """
    ring = [shapely.linearrings(r) for r in rings]
    ccw = np.array([bool(shapely.is_ccw(r)) for r in ring])
    shells = [shapely.polygons(r) for r, lp in zip(ring, loop, strict=True) if not lp]
    loops = [shapely.polygons(r) for r, lp in zip(ring, loop, strict=True) if lp]
    kind = ccw[loop]
    shells += [p for p, k in zip(loops, kind, strict=True) if k]
    if not (~loop).any():
        held = [any(shapely.contains(q, p) for q in loops if q is not p) for p in loops]
        outer = {bool(k) for k, h in zip(kind, held, strict=True) if not h}
        if outer == {False}:
            shells.insert(0, cell)
        elif outer != {True}:
            return None
    holes = [[] for _ in shells]
    areas = shapely.area(shells)
    for p, k in zip(loops, kind, strict=True):
        if k:
            continue
        cand = [j for j, q in enumerate(shells) if shapely.contains(q, p)]
        if not cand:
            return None
        holes[min(cand, key=lambda j: areas[j])].append(shapely.get_exterior_ring(p))
    polys = [
        shapely.polygons(shapely.get_exterior_ring(q), h) if h else q
        for q, h in zip(shells, holes, strict=True)
    ]
    got = polys[0] if len(polys) == 1 else shapely.multipolygons(polys)
    return got if shapely.is_valid(got) else None
