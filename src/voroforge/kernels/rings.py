"""Areas and centroids of ragged (GeoArrow multipolygon) cells, with holes and parts."""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..config import NJIT_PARALLEL


@njit(**NJIT_PARALLEL)
def area_centroid(coords, ring_offsets, polygon_offsets, geom_offsets):
    """Area and area centroid of each geometry.

    The first ring of every polygon is its exterior, the others are holes; ring orientation
    does not matter. Sums are taken relative to the geometry's first vertex, so coordinates
    like 500000/4000000 keep their precision. Empty geometries get area 0 and a NaN centroid.
    """
    n = geom_offsets.shape[0] - 1
    area = np.zeros(n)
    cen = np.full((n, 2), np.nan)
    for g in prange(n):
        p0 = geom_offsets[g]
        p1 = geom_offsets[g + 1]
        if p0 == p1:
            continue
        first = coords[ring_offsets[polygon_offsets[p0]]]
        ox = first[0]
        oy = first[1]
        a_tot = 0.0
        mx = 0.0
        my = 0.0
        for p in range(p0, p1):
            for r in range(polygon_offsets[p], polygon_offsets[p + 1]):
                a = 0.0
                sx = 0.0
                sy = 0.0
                for k in range(ring_offsets[r], ring_offsets[r + 1] - 1):
                    x0 = coords[k, 0] - ox
                    y0 = coords[k, 1] - oy
                    x1 = coords[k + 1, 0] - ox
                    y1 = coords[k + 1, 1] - oy
                    cr = x0 * y1 - x1 * y0
                    a += cr
                    sx += (x0 + x1) * cr
                    sy += (y0 + y1) * cr
                sign = 1.0 if a >= 0.0 else -1.0
                if r != polygon_offsets[p]:
                    sign = -sign  # holes subtract
                a_tot += sign * a
                mx += sign * sx
                my += sign * sy
        area[g] = 0.5 * a_tot
        if a_tot != 0.0:
            cen[g, 0] = ox + mx / (3.0 * a_tot)
            cen[g, 1] = oy + my / (3.0 * a_tot)
    return area, cen
