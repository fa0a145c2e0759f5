"""The inside-corner check of :func:`voroforge.design.fabrication.check`.

Where a round tool of radius ``r`` leaves material: inside an opening, the opening minus its
morphological opening by ``r`` (the tool's envelope); on the outline, cut from outside, the
closing by ``r`` minus the part. Either way a corner's depth is the distance from the
material left to the tool's envelope, so the same notch reads the same in an opening and in
the outline; a corner's value is the largest tool radius that leaves it no deeper than
``corner_tolerance``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import shapely

from .. import config

if TYPE_CHECKING:
    from .fabrication import Violation

__all__ = ["corners", "deepest"]


def deepest(pieces: np.ndarray, rim, tolerance: float) -> list[tuple[float, tuple[float, float]]]:
    """Leftover pieces deeper than ``tolerance``: (depth, deepest vertex) for each.

    Depth: the largest distance of a piece's vertices from ``rim`` (the reach's or the
    outline's boundary, which each piece touches: a piece whose bounding box's diagonal is
    within ``tolerance`` cannot be deeper). Distances come from an index of the rim's
    segments (GEOS scans every segment for every vertex: smoothed cells were 30x slower).
    """
    pieces = np.asarray(pieces, dtype=object)
    lo_x, lo_y, hi_x, hi_y = shapely.bounds(pieces).T
    pieces = pieces[np.hypot(hi_x - lo_x, hi_y - lo_y) > tolerance]
    xy, owner = shapely.get_coordinates(pieces, return_index=True)
    lines = [np.asarray(r.coords) for r in shapely.get_parts(rim) if len(r.coords) > 1]
    if not len(xy) or not lines:
        return []
    segs = shapely.linestrings(np.concatenate([np.stack((c[:-1], c[1:]), 1) for c in lines]))
    hit, d = shapely.STRtree(segs).query_nearest(
        shapely.points(xy), return_distance=True, all_matches=False
    )
    depth = np.full(len(xy), -np.inf)
    depth[hit[0]] = d
    # each piece's deepest vertex: the first of its largest (rows sorted by piece, then depth)
    order = np.lexsort((np.arange(len(xy)), -depth, owner))
    first = order[np.r_[True, owner[order][1:] != owner[order][:-1]]]
    first = first[depth[first] > tolerance]
    return [(float(depth[j]), (float(xy[j, 0]), float(xy[j, 1]))) for j in first.tolist()]


def corners(holes: np.ndarray, outline, radius: float, tolerance: float) -> list[Violation]:
    """Corner violations of ``holes`` (openings) and ``outline`` for a tool of ``radius``."""
    from .fabrication import Violation, inscribed_circles  # (that module imports this one)

    out: list[Violation] = []
    spots: list[tuple[int, tuple[float, float]]] = []  # (opening or -1, deepest point)
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
            rim = shapely.boundary(reach[i])
            spots += [(i, xy) for _, xy in deepest(shapely.get_parts(left[i]), rim, tolerance)]
    if not outline.is_empty:
        # The outline is cut from outside: the tool cannot enter concave notches of the part.
        closed = outline.buffer(radius, quad_segs=quad).buffer(-radius, quad_segs=quad)
        extra = shapely.get_parts(closed.difference(outline))
        # depths to the tool's envelope, as in an opening (the part's edge gave a 90-degree
        # notch 1 - 1/sqrt 2 of the tool radius, not sqrt 2 - 1: a different value)
        spots += [(-1, xy) for _, xy in deepest(extra, closed.boundary, tolerance)]
    if spots:
        shapes = np.asarray([holes[i] if i >= 0 else outline for i, _ in spots], dtype=object)
        xy = np.asarray([p for _, p in spots], dtype=np.float64)
        inside = np.asarray([i >= 0 for i, _ in spots])
        radii = _corner_radii(shapes, xy, inside, radius, tolerance, quad)
        for (i, p), r in zip(spots, radii.tolist(), strict=True):
            out.append(Violation("corner", p, r, radius, (i,)))
    return out


def _corner_radii(shapes, xy, inside, radius: float, tolerance: float, quad: int) -> np.ndarray:
    """The inside radius of each corner: the largest tool radius that reaches it.

    Bisection on the tool radius ``t`` in ``[0, radius]``: a corner is reached when the
    material a tool of radius ``t`` leaves near it (within ``2 radius``; the opening minus
    its opening by ``t`` inside a hole, the closing by ``t`` minus the part outside the
    outline) is no deeper than ``tolerance``, measured to the tool's envelope either way.
    """
    lo = np.zeros(len(xy))
    hi = np.full(len(xy), float(radius))
    pts = shapely.points(xy)
    near = shapely.buffer(pts, 2.0 * radius, quad_segs=quad)
    for _ in range(config.FAB_CORNER_BISECTIONS):
        t = 0.5 * (lo + hi)
        grown = shapely.buffer(shapes, np.where(inside, -t, t), quad_segs=quad)
        back = shapely.buffer(grown, np.where(inside, t, -t), quad_segs=quad)
        left = np.where(inside, shapely.difference(shapes, back), shapely.difference(back, shapes))
        left = shapely.intersection(left, near)
        target = np.where(inside, back, shapely.boundary(back))  # outline: inside ``back``
        coords, idx = shapely.get_coordinates(left, return_index=True)
        depth = np.zeros(len(xy))
        if len(coords):
            d = shapely.distance(shapely.points(coords), target[idx])
            np.maximum.at(depth, idx, np.nan_to_num(d, nan=np.inf))
        ok = depth <= tolerance
        lo = np.where(ok, t, lo)
        hi = np.where(ok, hi, t)
    return lo
