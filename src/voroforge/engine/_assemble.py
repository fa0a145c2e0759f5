"""From convex cells (the kernels' output) to clipped cells in the GeoArrow multipolygon layout.

The kernels return, per site, one open counter-clockwise ring clipped to the domain's bounding
box, with the neighbour that owns each edge. This module expands those rings to all input
sites (duplicates get empty cells), clips them to non-rectangular domains, and extracts the
unique shared edges.
"""

from __future__ import annotations

import numpy as np
import shapely

from ..config import EDGE_LENGTH_RTOL
from ..kernels.domain_grid import classify, mark_segments
from .domain import Domain


def expand_to_sites(n, unique, coords, offsets, owner):
    """Re-index kernel output (over distinct sites) to all ``n`` input sites."""
    if len(unique) == n:
        return coords, offsets, owner.astype(np.int64)
    counts = np.zeros(n, dtype=np.int64)
    counts[unique] = np.diff(offsets)
    full = np.zeros(n + 1, dtype=np.int64)
    np.cumsum(counts, out=full[1:])
    own = owner.astype(np.int64)
    mask = own >= 0
    own[mask] = unique[own[mask]]
    return coords, full, own


def _close_rings(coords, offsets, cells):
    """Closed-ring coordinates of the open rings of ``cells`` (non-empty), and ring lengths."""
    starts = offsets[cells]
    counts = offsets[cells + 1] - starts
    total = int(counts.sum())
    # positions of the open vertices inside the closed output
    ring_start_out = np.zeros(len(cells) + 1, dtype=np.int64)
    np.cumsum(counts + 1, out=ring_start_out[1:])
    out = np.zeros((total + len(cells), 2))
    ring_id = np.repeat(np.arange(len(cells)), counts)
    local = np.arange(total) - np.repeat(np.cumsum(counts) - counts, counts)
    out[ring_start_out[:-1][ring_id] + local] = coords[np.repeat(starts, counts) + local]
    out[ring_start_out[1:] - 1] = coords[starts]
    return out, counts + 1


def rings_to_geoarrow(coords, offsets):
    """GeoArrow multipolygon buffers for cells that are single open rings (or empty)."""
    n = len(offsets) - 1
    counts = np.diff(offsets)
    nonempty = np.flatnonzero(counts > 0)
    closed, lengths = _close_rings(coords, offsets, nonempty)
    ring_offsets = np.zeros(len(nonempty) + 1, dtype=np.int64)
    np.cumsum(lengths, out=ring_offsets[1:])
    polygon_offsets = np.arange(len(nonempty) + 1, dtype=np.int64)
    geom_offsets = np.zeros(n + 1, dtype=np.int64)
    np.cumsum(counts > 0, out=geom_offsets[1:])
    return closed, ring_offsets, polygon_offsets, geom_offsets


def _grid_for(dom: Domain, n_hint: int):
    x0, y0, x1, y1 = dom.bounds
    side = max(x1 - x0, y1 - y0)
    g = int(min(max(np.sqrt(max(n_hint, 1)), 8), 2048))
    h = side / g
    gx = int(np.ceil((x1 - x0) / h)) + 1
    gy = int(np.ceil((y1 - y0) / h)) + 1
    rings = shapely.get_rings(shapely.get_parts(dom.geometry))
    pts = [shapely.get_coordinates(r) for r in rings]
    segs = np.concatenate([np.hstack((p[:-1], p[1:])) for p in pts])
    marked = mark_segments(np.ascontiguousarray(segs), x0, y0, h, gx, gy)
    cx = x0 + (np.arange(gx) + 0.5) * h
    cy = y0 + (np.arange(gy) + 0.5) * h
    xx, yy = np.meshgrid(cx, cy)
    inside = np.zeros((gy, gx), dtype=np.bool_)
    free = ~marked
    shapely.prepare(dom.geometry)
    inside[free] = shapely.contains_xy(dom.geometry, xx[free], yy[free])
    return marked, inside, x0, y0, h


def clip_to_polygon(dom: Domain, coords, offsets):
    """Clip convex open rings to a polygonal domain; returns GeoArrow buffers for all cells."""
    n = len(offsets) - 1
    marked, inside, x0, y0, h = _grid_for(dom, n)
    status = classify(coords, offsets, marked, inside, x0, y0, h)
    simple = np.flatnonzero(status == 1)
    hard = np.flatnonzero(status == 2)

    # simple cells: closed rings
    s_coords, s_len = _close_rings(coords, offsets, simple)
    # hard cells: shapely intersection, oriented (exterior CCW) and exploded to buffers
    if len(hard):
        h_closed, h_len = _close_rings(coords, offsets, hard)
        ring_off = np.zeros(len(hard) + 1, dtype=np.int64)
        np.cumsum(h_len, out=ring_off[1:])
        convex = shapely.from_ragged_array(
            shapely.GeometryType.POLYGON, h_closed, (ring_off, np.arange(len(hard) + 1))
        )
        clipped = shapely.intersection(convex, dom.geometry)
        clipped = _polygonal(clipped)
        clipped = shapely.orient_polygons(clipped)
        parts, idx = shapely.get_parts(clipped, return_index=True)
        keep = ~shapely.is_empty(parts)
        parts = parts[keep]
        idx = idx[keep]
        multi = np.full(len(hard), shapely.MultiPolygon(), dtype=object)
        cut = np.flatnonzero(np.diff(idx)) + 1
        for group, k in zip(
            np.split(parts, cut), idx[np.r_[0, cut]] if len(idx) else [], strict=True
        ):
            multi[k] = shapely.multipolygons(group)
        _, c_coords, (c_ring, c_poly, c_geom) = shapely.to_ragged_array(multi)
    else:
        c_coords = np.zeros((0, 2))
        c_ring = np.zeros(1, dtype=np.int64)
        c_poly = np.zeros(1, dtype=np.int64)
        c_geom = np.zeros(1, dtype=np.int64)
    polys_per_hard = np.diff(c_geom)
    rings_per_poly = np.diff(c_poly)
    len_per_ring = np.diff(c_ring)

    # merge, ordered by cell id (stable: within one source items are already in cell order)
    poly_cell = np.concatenate((simple, np.repeat(hard, polys_per_hard)))
    poly_rings = np.concatenate((np.ones(len(simple), dtype=np.int64), rings_per_poly))
    ring_cell = np.concatenate((simple, np.repeat(poly_cell[len(simple) :], rings_per_poly)))
    ring_len = np.concatenate((s_len, len_per_ring))
    coord_cell = np.concatenate(
        (np.repeat(simple, s_len), np.repeat(ring_cell[len(simple) :], len_per_ring))
    )
    all_coords = np.concatenate((s_coords, c_coords))

    po = np.argsort(poly_cell, kind="stable")
    ro = np.argsort(ring_cell, kind="stable")
    co = np.argsort(coord_cell, kind="stable")
    out_coords = all_coords[co]
    ring_offsets = np.zeros(len(ring_len) + 1, dtype=np.int64)
    np.cumsum(ring_len[ro], out=ring_offsets[1:])
    polygon_offsets = np.zeros(len(poly_rings) + 1, dtype=np.int64)
    np.cumsum(poly_rings[po], out=polygon_offsets[1:])
    geom_offsets = np.zeros(n + 1, dtype=np.int64)
    np.cumsum(np.bincount(poly_cell, minlength=n), out=geom_offsets[1:])
    return out_coords, ring_offsets, polygon_offsets, geom_offsets


def _polygonal(geoms):
    """Keep only the polygonal parts of overlay results (drop stray lines and points)."""
    out = np.empty(len(geoms), dtype=object)  # noqa: TID251 - every slot is filled below
    for k, g in enumerate(geoms):
        if shapely.get_type_id(g) in (3, 6):
            out[k] = g
        else:
            parts = [p for p in shapely.get_parts(g) if shapely.get_type_id(p) in (3, 6)]
            out[k] = shapely.union_all(parts) if parts else shapely.Polygon()
    return out


def shared_edges(dom: Domain, coords, offsets, owner):
    """Unique shared edges ``(m, 2, 2)`` and their cell pairs ``(m, 2)``, clipped to the domain.

    Each pair ``(i, j)`` with ``i < j`` is taken from cell ``i``'s ring. Edges shorter than
    ``EDGE_LENGTH_RTOL`` times the domain's size are point contacts and are left out.
    """
    n = len(offsets) - 1
    counts = np.diff(offsets)
    cell = np.repeat(np.arange(n), counts)
    k = np.arange(len(coords))
    nxt = k + 1
    last = offsets[1:][counts > 0] - 1
    nxt[last] = offsets[:-1][counts > 0]
    sel = np.flatnonzero(owner > cell)
    a = coords[sel]
    b = coords[nxt[sel]]
    pairs = np.stack((cell[sel], owner[sel]), axis=1)
    x0, y0, x1, y1 = dom.bounds
    tol = EDGE_LENGTH_RTOL * max(x1 - x0, y1 - y0)
    if not dom.is_rect and len(sel):
        a, b, pairs = _clip_segments(dom, a, b, pairs)
    length = np.hypot(b[:, 0] - a[:, 0], b[:, 1] - a[:, 1])
    keep = length > tol
    seg = np.stack((a[keep], b[keep]), axis=1)
    return seg, pairs[keep].astype(np.int64)


def _clip_segments(dom: Domain, a, b, pairs):
    marked, inside, x0, y0, h = _grid_for(dom, len(a) // 3)
    two = np.ascontiguousarray(np.stack((a, b), axis=1).reshape(-1, 2))
    offs = np.arange(0, 2 * len(a) + 1, 2, dtype=np.int64)
    status = classify(two, offs, marked, inside, x0, y0, h)
    keep = status == 1
    hard = np.flatnonzero(status == 2)
    out_a = [a[keep]]
    out_b = [b[keep]]
    out_p = [pairs[keep]]
    if len(hard):
        lines = shapely.linestrings(np.stack((a[hard], b[hard]), axis=1))
        cut = shapely.intersection(lines, dom.geometry)
        parts, idx = shapely.get_parts(cut, return_index=True)
        is_line = (shapely.get_type_id(parts) == 1) & ~shapely.is_empty(parts)
        parts = parts[is_line]
        idx = idx[is_line]
        # a straight segment intersected with a region gives straight pieces: keep end points
        starts = shapely.get_coordinates(shapely.get_point(parts, 0))
        ends = shapely.get_coordinates(shapely.get_point(parts, -1))
        out_a.append(starts)
        out_b.append(ends)
        out_p.append(pairs[hard[idx]])
    return np.concatenate(out_a), np.concatenate(out_b), np.concatenate(out_p)
