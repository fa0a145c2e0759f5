"""Wrapped periodic cells whose pieces touch: united in shapely, many cells per GEOS call.

A wrapped cell (``wrap=True``) is the pieces of its copies' cells cut to the box
(:func:`.periodic._box_pieces`). Where a cell borders its own image (sites on a vertical
line: each cell a strip as wide as the box, cut at both sides) its pieces touch along an
edge, their multipolygon is invalid, and they are united. :func:`united_pieces` unites
every such cell in one vectorised ``union_all`` (the same GEOS unary union of each cell's
pieces as one call per cell, 4,323 Python calls for 1e4 sites on a vertical line plus one
off it) and drops the slivers that rounding leaves (:func:`without_slivers`) only where
a result has a hole, several parts or is narrow.
"""

from __future__ import annotations

import numpy as np
import shapely


def united_pieces(merged: np.ndarray, rounding: float) -> np.ndarray:
    """Each multipolygon of ``merged`` (a cell's touching pieces) as one geometry.

    Parameters
    ----------
    merged : (k,) object
        Multipolygons, each the pieces of one cell.
    rounding : float
        How wide a part or hole may be and still be rounding noise (dropped).

    Returns
    -------
    (k,) object
        Per cell, the union of its pieces without rounding slivers: the same geometries as
        :func:`one_united` of each.
    """
    parts, which = shapely.get_parts(merged, return_index=True)
    count = np.bincount(which, minlength=len(merged))
    table = np.full((len(merged), int(count.max(initial=0))), None, dtype=object)
    table[which, np.arange(len(which)) - np.repeat(np.cumsum(count) - count, count)] = parts
    try:
        united = shapely.union_all(table, axis=1)
    except shapely.errors.GEOSException:
        # a piece that is not a valid polygon (a spike of an ulp): one cell at a time
        return np.array([one_united(g, rounding) for g in merged], dtype=object)
    out = np.full(len(merged), None, dtype=object)
    b = shapely.bounds(united)
    narrow = shapely.area(united) <= rounding * np.fmax(b[:, 2] - b[:, 0], b[:, 3] - b[:, 1])
    plain = (
        (shapely.get_type_id(united) == 3) & (shapely.get_num_interior_rings(united) == 0) & ~narrow
    )
    out[plain] = united[plain]
    for j in np.flatnonzero(~plain):
        out[j] = without_slivers(united[j], rounding)
    return out


def one_united(geom, rounding: float):
    """The union of the parts of ``geom`` without rounding slivers (one cell)."""
    parts = shapely.get_parts(geom)
    try:
        united = shapely.union_all(parts)
    except shapely.errors.GEOSException:
        # a piece that is not a valid polygon (a spike of an ulp): GEOS cannot assign its
        # holes; the pieces made valid unite
        united = shapely.union_all(shapely.make_valid(parts))
    return without_slivers(united, rounding)


def _narrow(poly, rounding: float) -> bool:
    """Whether ``poly`` is at most ``rounding`` wide: its area against its longer extent."""
    x0, y0, x1, y1 = poly.bounds
    return poly.area <= rounding * max(x1 - x0, y1 - y0)


def without_slivers(geom, rounding: float):
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
