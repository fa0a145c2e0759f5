"""Periodic (toroidal) Voronoi diagrams: ``vf.voronoi(points, box, periodic=True)``.

The diagram of sites on a torus is the ordinary diagram of the sites and all their
periodic images, restricted to one copy. Only the images within a margin of the box are
used; the margin is proved large enough afterwards: every vertex ``v`` of a kept cell with
site ``p`` must have its empty disk (centre ``v``, radius ``|v - p|``) inside the region
where every image was included. Then no left-out image could have cut the cell, so it is the
torus cell. When the proof fails (few sites, large empty regions) the margin doubles and
the diagram is computed again.
"""

from __future__ import annotations

import numpy as np
import shapely

from ..config import PERIODIC_PROOF_RTOL, PERIODIC_SLIVER_ULPS
from .assemble import first_cells, from_shapely
from .diagram import Diagram, Edges, buffers, frame_exponent
from .domain import Domain, make_domain
from .inputs import as_points
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
        A new array.
    """
    lo = np.array(box[:2], dtype=np.float64)
    size = np.array([box[2] - box[0], box[3] - box[1]], dtype=np.float64)
    out = lo + np.mod(points - lo, size)
    hi = lo + size
    out = np.where(out >= hi, lo, out)  # rounding can land on the upper edge
    return np.where(out < lo, lo, out)


def _images(sites: np.ndarray, box, margin: float):
    """Sites first (copy 0), then every image inside the box grown by ``margin``.

    Returns ``(ext (N, 2), source (N,) int64, shift (N, 2) int64)``.
    """
    x0, y0, x1, y1 = box
    w = x1 - x0
    h = y1 - y0
    ax = int(np.ceil(margin / w))
    ay = int(np.ceil(margin / h))
    n = len(sites)
    idx = np.arange(n)
    ext = [sites]
    source = [idx]
    shift = [np.zeros((n, 2), dtype=np.int64)]
    for a in range(-ax, ax + 1):
        for b in range(-ay, ay + 1):
            if a == 0 and b == 0:
                continue
            img = sites + np.array([a * w, b * h])
            keep = (
                (img[:, 0] >= x0 - margin)
                & (img[:, 0] <= x1 + margin)
                & (img[:, 1] >= y0 - margin)
                & (img[:, 1] <= y1 + margin)
            )
            if keep.any():
                ext.append(img[keep])
                source.append(idx[keep])
                shift.append(np.tile(np.array([a, b], dtype=np.int64), (int(keep.sum()), 1)))
    return np.concatenate(ext), np.concatenate(source), np.concatenate(shift)


def _proved(d: Diagram, cells: np.ndarray, box, margin: float) -> bool:
    """True when every vertex of ``cells`` has its empty disk inside the complete region."""
    coords, (ring, poly, geom) = d.to_geoarrow()
    if not len(cells):
        return True
    lo = ring[poly[geom[cells]]]
    per_cell = ring[poly[geom[cells + 1]]] - lo
    total = int(per_cell.sum())
    if not total:
        return True
    if len(cells) == len(geom) - 1 or (cells[-1] == len(cells) - 1 and lo[0] == 0):
        v = coords[:total]  # the cells are a prefix of the buffers
    else:
        v = coords[np.repeat(lo - np.cumsum(per_cell) + per_cell, per_cell) + np.arange(total)]
    x0, y0, x1, y1 = box
    room = np.minimum(
        np.minimum(v[:, 0] - (x0 - margin), (x1 + margin) - v[:, 0]),
        np.minimum(v[:, 1] - (y0 - margin), (y1 + margin) - v[:, 1]),
    )
    owner = np.repeat(cells, per_cell)
    side = max(x1 - x0, y1 - y0)  # squares in units of the box: no overflow at 1e300
    room = room / side
    diff = (v - d.sites[owner]) / side
    r2 = diff[:, 0] * diff[:, 0] + diff[:, 1] * diff[:, 1]
    return bool((room >= 0).all() and (room * room >= r2 * (1.0 + PERIODIC_PROOF_RTOL)).all())


def _gather(d: Diagram, source: np.ndarray, n: int, keep: np.ndarray, rounding: float):
    """Buffers of ``n`` cells, cell ``i`` made of the pieces ``keep[source[keep] == i]``."""
    keep = keep[np.argsort(source[keep], kind="stable")]
    pieces = d.cells[keep]
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
        bad = ~shapely.is_valid(merged)
        # pieces of one cell that touch along an edge (a cell bordering its own image)
        for j in np.flatnonzero(bad):
            parts = shapely.get_parts(merged[j])
            try:
                united = shapely.union_all(parts)
            except shapely.errors.GEOSException:
                # a piece that is not a valid polygon (a spike of an ulp): GEOS cannot
                # assign its holes; the pieces made valid unite
                united = shapely.union_all(shapely.make_valid(parts))
            merged[j] = _without_slivers(united, rounding)
        out[groups[0]] = merged
    return from_shapely(out)


def _rounding(box) -> float:
    """A length below which features in the box are rounding noise of its coordinates."""
    x0, y0, x1, y1 = box
    size = max(x1 - x0, y1 - y0)
    ulps = PERIODIC_SLIVER_ULPS * np.finfo(np.float64).eps
    return ulps * max(abs(x0), abs(y0), abs(x1), abs(y1), size)


def _thick_pieces(d: Diagram, box, n: int) -> np.ndarray:
    """Indices of the copies whose piece in the box is more than rounding noise.

    An image whose cell passes the box edge only by the rounding of its site (``0.9 - 1`` is
    not ``-0.1`` in floats) leaves a sliver a few ulps wide inside the box: no part of the
    cell on the torus, but an extra polygon part. Original copies (``< n``) are kept.
    """
    x0, y0, x1, y1 = box
    coords, (ring, poly, geom) = d.to_geoarrow()
    img = np.arange(n, len(geom) - 1)
    img = img[geom[img + 1] > geom[img]]
    # shoelace of each image piece's (first, closed) ring, about its first vertex
    lo = ring[poly[geom[img]]]
    length = ring[poly[geom[img]] + 1] - lo - 1
    k = (
        np.repeat(lo, length)
        + np.arange(int(length.sum()))
        - np.repeat(np.cumsum(length) - length, length)
    )
    side = max(x1 - x0, y1 - y0)  # in box units: no under- or overflow at 1e+-300
    base = np.repeat(coords[lo], length, axis=0)
    a = (coords[k] - base) / side
    b = (coords[k + 1] - base) / side
    area = 0.5 * np.abs(
        np.bincount(
            np.repeat(np.arange(len(img)), length),
            a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0],
            minlength=len(img),
        )
    )
    # a piece is a sliver when it is narrow, however long: its area against its extent
    # (its farthest vertex from the first one, at least half its longer side)
    extent = np.zeros(len(img))
    if len(img):
        extent = np.maximum.reduceat(np.abs(a).max(axis=1), np.cumsum(length) - length)
    thick = img[area > (_rounding(box) / side) * extent]
    return np.concatenate((np.arange(n), thick))


def _gather_pieces(d: Diagram, source: np.ndarray, n: int, keep: np.ndarray):
    """Buffers of ``n`` cells made of the non-empty cells of copies ``keep``, in copy order.

    Every cell of ``d`` is one convex polygon (or empty), so each piece is one ring.
    """
    coords, (ring, poly, geom) = d.to_geoarrow()
    parts = np.diff(geom)
    full = keep[parts[keep] > 0]
    order = full[np.argsort(source[full], kind="stable")]
    first_ring = poly[geom[order]]
    lo = ring[first_ring]
    length = ring[first_ring + 1] - lo
    total = int(length.sum())
    take = np.repeat(lo - np.cumsum(length) + length, length) + np.arange(total)
    new_ring = np.zeros(len(order) + 1, dtype=np.int64)
    np.cumsum(length, out=new_ring[1:])
    new_geom = np.zeros(n + 1, dtype=np.int64)
    np.cumsum(np.bincount(source[order], minlength=n), out=new_geom[1:])
    new_poly = np.arange(len(order) + 1, dtype=np.int64)
    return np.ascontiguousarray(coords[take]), new_ring, new_poly, new_geom


def _narrow(poly, rounding: float) -> bool:
    """Whether ``poly`` is at most ``rounding`` wide: its area against its longer extent."""
    x0, y0, x1, y1 = poly.bounds
    return poly.area <= rounding * max(x1 - x0, y1 - y0)


def _without_slivers(geom, rounding: float):
    """``geom`` without the holes and parts that are at most ``rounding`` wide.

    Pieces of one cell meet along an edge computed in two positions, whose end points can
    differ by rounding: their union can keep a sliver hole there. A small piece is kept
    when it is wider than rounding (a corner of a cell that just reaches across the wrap).
    """
    polys = []
    for part in shapely.get_parts(geom):
        if _narrow(part, rounding):
            continue
        holes = [r for r in part.interiors if not _narrow(shapely.Polygon(r), rounding)]
        polys.append(shapely.Polygon(part.exterior, holes))
    if not polys:
        return shapely.Polygon()
    return polys[0] if len(polys) == 1 else shapely.MultiPolygon(polys)


def _torus_edges(d: Diagram, source, shift, n: int, wrap: bool, pieces=None) -> Edges:
    pairs = d.edges.pairs
    coords = d.edges.coords
    a = pairs[:, 0]
    b = pairs[:, 1]
    sa = source[a]
    sb = source[b]
    if wrap:
        # not the edges of rounding slivers (see _thick_pieces)
        kept = np.zeros(len(d.sites), dtype=bool)
        kept[pieces] = True
        keep = kept[a] & kept[b]
    else:
        # each torus edge once: where the lower-index cell is the original copy (a self
        # edge, between a cell and its own image, where the image lies on the positive side)
        lower_is_a = (sa < sb) | ((sa == sb) & _positive(shift[b] - shift[a]))
        low = np.where(lower_is_a, a, b)
        keep = low < n
    lo = np.minimum(sa, sb)[keep]
    hi = np.maximum(sa, sb)[keep]
    return Edges(np.ascontiguousarray(coords[keep]), np.stack((lo, hi), axis=1).astype(np.int64))


def _positive(s: np.ndarray) -> np.ndarray:
    return (s[:, 0] > 0) | ((s[:, 0] == 0) & (s[:, 1] > 0))


def periodic_voronoi(points, boundary, *, algorithm: str = "delaunay", wrap: bool = False):
    """Voronoi diagram on the torus made by identifying opposite edges of ``boundary``.

    See :func:`voroforge.voronoi` (``periodic=True``) for the public description.
    """
    tile = _tile_of(boundary)
    box = tile.bounds
    pts = wrap_points(as_points(points), box)
    n = len(pts)
    x0, y0, x1, y1 = box
    if n == 0:
        d = build(pts, tile, algorithm)
        d.periodic = True
        d.wrapped = wrap
        return d
    # the area in units of the longer side: (x1 - x0) * (y1 - y0) overflows at 1e300
    side = max(x1 - x0, y1 - y0)
    area = ((x1 - x0) / side) * ((y1 - y0) / side)
    # a few typical cell sizes, and at least ~2.5 radii of the largest empty circle expected
    # among n uniform sites (sqrt(area log n / (pi n))), so one pass is usually enough
    margin = side * max(
        _MARGIN_CELLS * np.sqrt(area / n), 2.5 * np.sqrt(area * np.log(n + 1) / (np.pi * n))
    )
    for _ in range(_MAX_TRIES):
        ext, source, shift = _images(pts, box, margin)
        if wrap:
            d = build(ext, tile, algorithm)
            owners = np.flatnonzero(d.duplicate_of < 0)
        else:
            grown = make_domain((x0 - margin, y0 - margin, x1 + margin, y1 + margin), ext)
            d = build(ext, grown, algorithm)
            owners = np.flatnonzero(d.duplicate_of[:n] < 0)
        if _proved(d, owners, box, margin):
            break
        margin *= 2.0
    else:  # pragma: no cover - the margin reaches the box diagonal long before
        raise RuntimeError("periodic diagram: could not prove the margin")
    if wrap:
        pairs = d.edges.pairs
        keep = _thick_pieces(d, box, n)
        if (source[pairs[:, 0]] == source[pairs[:, 1]]).any():
            # some cell borders its own image: unite its touching pieces (few sites)
            bufs = _gather(d, source, n, keep, _rounding(box))
        else:
            bufs = _gather_pieces(d, source, n, keep)
    else:
        bufs = first_cells(buffers(d), n)
    edges = _torus_edges(d, source, shift, n, wrap, keep if wrap else None)
    # a site is unresolved when the copy its cell comes from is (unwrapped: the original;
    # wrapped: any copy, whose piece is then missing)
    lost = d.unresolved if wrap else d.unresolved[d.unresolved < n]
    out = Diagram(
        np.ascontiguousarray(d.sites[:n]),
        np.ascontiguousarray(d.duplicate_of[:n]),
        tile,
        bufs,
        edges,
        algorithm,
        frame_exponent(d),
        np.unique(source[lost]).astype(np.int64),
    )
    out.periodic = True
    out.wrapped = wrap
    return out
