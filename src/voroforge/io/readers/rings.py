"""Closed rings to a polygon by the even-odd rule (a ring inside another is a hole)."""

from __future__ import annotations

import numpy as np
import shapely

__all__ = ["even_odd", "polygonal_part"]


def polygonal_part(geom):
    """The polygonal part of a GEOS result (drops stray lines/points of collections).

    Parameters
    ----------
    geom : shapely geometry
        A GEOS result, for example of ``make_valid`` or a union.

    Returns
    -------
    shapely.Polygon or shapely.MultiPolygon
        Empty when there is no polygonal part.
    """
    if isinstance(geom, shapely.Polygon | shapely.MultiPolygon):
        return geom
    parts = [g for g in getattr(geom, "geoms", []) if isinstance(g, shapely.Polygon)]
    parts += [
        p
        for g in getattr(geom, "geoms", [])
        if isinstance(g, shapely.MultiPolygon)
        for p in g.geoms
    ]
    if not parts:
        return shapely.Polygon()
    return parts[0] if len(parts) == 1 else shapely.MultiPolygon(parts)


def even_odd(rings) -> shapely.Polygon | shapely.MultiPolygon:
    """Combine closed rings by the even-odd rule (nested ring = hole, and so on).

    Parameters
    ----------
    rings : sequence of (k, 2) float64
        Closed curves (closing vertex optional). Self-intersecting rings are repaired
        with ``shapely.make_valid`` (both lobes kept).

    Returns
    -------
    shapely.Polygon or shapely.MultiPolygon
        Possibly empty when no ring encloses area.
    """
    result = shapely.Polygon()
    for ring in rings:
        arr = np.asarray(ring, dtype=np.float64)
        if len(arr) >= 2 and (arr[0] == arr[-1]).all():
            arr = arr[:-1]
        if len(arr) < 3:
            continue
        poly = shapely.Polygon(arr)
        if not poly.is_valid:
            poly = polygonal_part(shapely.make_valid(poly))
        if poly.is_empty or poly.area <= 0:
            continue
        result = shapely.symmetric_difference(result, poly)
    result = polygonal_part(result)
    return shapely.orient_polygons(result) if not result.is_empty else result
