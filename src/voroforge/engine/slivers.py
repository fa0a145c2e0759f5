"""Exact owners of the sliver faces of an arrangement (issue 15, polygon domains).

:func:`.assemble._clip_arranged` nodes the boundaries of a few cells and of the domain
together and hands each face of the arrangement to the cell that holds it, testing one
interior point per face (``shapely.point_on_surface``). A face a fraction of an ulp wide
(the piece of a strip cell between two crossings of the domain's boundary that round an
ulp apart) has no float point inside it: its point fell on or outside its boundary, so
the face was given to no cell, or thrown away as outside the domain, and the two cells on
either side of the strip were left with a gap between their crossings. Here such a face
gets a rational point strictly inside it (the centroid of an ear), and every decision on
it is exact: inside the domain's piece, inside which rings, and, where no ring or several
hold it, the exactly nearest site among the rings that touch it.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import shapely

__all__ = ["inner_point", "inside", "sliver_owner"]


def _orient(a, b, c):
    """Twice the signed area of ``a, b, c`` (rationals): > 0 where they turn left."""
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])


def inner_point(ring):
    """A rational point strictly inside a simple closed ring of floats, or None.

    The centroid of an ear: three consecutive vertices turning the ring's way whose closed
    triangle holds no other vertex (a simple polygon has one unless it has no area).
    """
    pts = [(Fraction(float(x)), Fraction(float(y))) for x, y in np.asarray(ring)[:-1]]
    m = len(pts)
    if m < 3:
        return None
    area2 = sum(_orient((0, 0), pts[i], pts[(i + 1) % m]) for i in range(m))
    if area2 == 0:
        return None
    sign = 1 if area2 > 0 else -1
    for i in range(m):
        a, b, c = pts[i - 1], pts[i], pts[(i + 1) % m]
        if sign * _orient(a, b, c) <= 0:
            continue
        if any(
            sign * _orient(a, b, q) >= 0
            and sign * _orient(b, c, q) >= 0
            and sign * _orient(c, a, q) >= 0
            for q in pts
            if q not in (a, b, c)
        ):
            continue
        return ((a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3)
    return None


def inside(p, geom) -> bool:
    """Whether the rational point ``p`` is inside polygonal ``geom`` (even-odd, exact).

    ``p`` is assumed off the boundary (a face's inner point is off every noded edge).
    """
    px, py = p
    odd = False
    for part in shapely.get_parts(geom):
        for ring in (part.exterior, *part.interiors):
            xy = np.asarray(ring.coords)
            for (ax, ay), (bx, by) in zip(xy[:-1].tolist(), xy[1:].tolist(), strict=True):
                if (ay > py) == (by > py):
                    continue
                o = (Fraction(bx) - Fraction(ax)) * (py - Fraction(ay)) - (
                    Fraction(by) - Fraction(ay)
                ) * (px - Fraction(ax))
                if (o > 0) == (by > ay):
                    odd = not odd
    return odd


def sliver_owner(face, local, piece, origin, xy, reach):
    """The ring owning a thin arrangement face, -1 (outside the piece or no ring's), or None.

    Parameters
    ----------
    face : shapely.Polygon
        A face of the arrangement (no holes), in the local frame.
    local : (r,) object
        The rings, in the local frame.
    piece : shapely geometry
        The domain's piece, in the local frame.
    origin : (2,) float64
        The local frame's origin.
    xy : (r, 2) float64
        The rings' sites (not shifted).
    reach : float
        How near (in the local frame) a ring that holds no point of the face must be to be a
        candidate for it.

    Returns
    -------
    int or None
        The owner: the one ring that holds the face's inner point, else the ring, among
        those holding it or (none holding it) those within ``reach`` of the face, whose site
        is exactly nearest to it; -1 where the point is outside the piece or no ring is near;
        None where the face has no inner point (no area).
    """
    p = inner_point(shapely.get_coordinates(face.exterior))
    if p is None:
        return None
    if not inside(p, piece):
        return -1
    held = [j for j, r in enumerate(local) if inside(p, r)]
    if len(held) == 1:
        return held[0]
    cand = held or np.flatnonzero(shapely.dwithin(local, face, reach)).tolist()
    if not cand:
        return -1
    # squared distances from the point (moved back to the sites' frame, exactly) to each site
    x, y = p[0] + Fraction(float(origin[0])), p[1] + Fraction(float(origin[1]))
    d2 = [(x - Fraction(float(xy[j, 0]))) ** 2 + (y - Fraction(float(xy[j, 1]))) ** 2 for j in cand]
    return cand[d2.index(min(d2))]
