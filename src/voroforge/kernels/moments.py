"""Moments of rings and of ragged cells: areas, centroids, first and second moments.

Cells come in the GeoArrow multipolygon layout (``coords``, ``ring_offsets``,
``polygon_offsets``, ``geom_offsets``); the first ring of a polygon is its exterior, the rest
are holes, and ring orientation does not matter. One shoelace sum (:func:`ring_sums`) gives
every moment; sums are taken relative to an origin (a cell's site or first vertex) so large
coordinates keep their precision and the CVT energy ``∫ |x - z_g|^2`` needs no cancellation.

Moment outputs per cell: ``mass`` (∫ρ), ``first (2,)`` (∫ρ (x - z)) and ``second``
(∫ρ |x - z|^2).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from ..config import MOMENTS_CANCEL, MOMENTS_FAR_PART, NJIT, NJIT_PARALLEL


@njit(**NJIT)
def ring_sums(xs, ys, a, b, ox, oy, closed):
    """Raw shoelace sums of the ring ``(xs, ys)[a:b]`` relative to ``(ox, oy)``.

    Returns ``(2 A, 6 Mx, 6 My, 12 M2)``: twice the signed area, six times the first moments
    and twelve times the polar second moment. ``closed``: the last vertex repeats the first
    (else the edge back to ``a`` is added).
    """
    m0 = 0.0
    mx = 0.0
    my = 0.0
    m2 = 0.0
    end = b - 1 if closed else b
    for k in range(a, end):
        kn = k + 1 if (closed or k + 1 < b) else a
        x0 = xs[k] - ox
        y0 = ys[k] - oy
        x1 = xs[kn] - ox
        y1 = ys[kn] - oy
        cr = x0 * y1 - x1 * y0
        m0 += cr
        mx += (x0 + x1) * cr
        my += (y0 + y1) * cr
        m2 += (x0 * x0 + x0 * x1 + x1 * x1 + y0 * y0 + y0 * y1 + y1 * y1) * cr
    return m0, mx, my, m2


@njit(**NJIT)
def ring_moments(xs, ys, a, b, ox, oy, closed):
    """Signed area, first and second moments of a ring (see :func:`ring_sums`)."""
    m0, mx, my, m2 = ring_sums(xs, ys, a, b, ox, oy, closed)
    return m0 / 2.0, mx / 6.0, my / 6.0, m2 / 12.0


@njit(**NJIT)
def neumaier_add(total, comp, x):
    """``(total + x, comp)`` with ``comp`` gathering the rounding error (Neumaier's summation)."""
    t = total + x
    if abs(total) >= abs(x):
        comp += (total - t) + x
    else:
        comp += (x - t) + total
    return t, comp


@njit(**NJIT_PARALLEL)
def area_centroid(coords, ring_offsets, polygon_offsets, geom_offsets):
    """Area and area centroid of each geometry.

    The first ring of every polygon is its exterior, the others are holes; ring orientation
    does not matter. Each polygon's sums are taken relative to its own first vertex, so
    coordinates like 500000/4000000 keep their precision, and so does a cell with parts far
    apart (a MultiPolygon domain's parts 1e12 apart). Empty geometries get area 0 and a NaN
    centroid.
    """
    n = geom_offsets.shape[0] - 1
    xs = coords[:, 0]
    ys = coords[:, 1]
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
            own = coords[ring_offsets[polygon_offsets[p]]]
            px = own[0]
            py = own[1]
            ap = 0.0
            sxp = 0.0
            syp = 0.0
            for r in range(polygon_offsets[p], polygon_offsets[p + 1]):
                a, sx, sy, _ = ring_sums(xs, ys, ring_offsets[r], ring_offsets[r + 1], px, py, True)
                sign = 1.0 if a >= 0.0 else -1.0
                if r != polygon_offsets[p]:
                    sign = -sign  # holes subtract
                ap += sign * a
                sxp += sign * sx
                syp += sign * sy
            a_tot += ap
            # the part's first moments moved from its own vertex to the geometry's (exact
            # zero shift for the first part: one-part cells sum as before, bit for bit)
            mx += sxp + 3.0 * ap * (px - ox)
            my += syp + 3.0 * ap * (py - oy)
        area[g] = 0.5 * a_tot
        if a_tot != 0.0:
            cen[g, 0] = ox + mx / (3.0 * a_tot)
            cen[g, 1] = oy + my / (3.0 * a_tot)
    return area, cen


@njit(**NJIT)
def _far_part(xs, ys, a, b, ox, oy):
    """Whether ring ``(xs, ys)[a:b]`` is more than ``MOMENTS_FAR_PART`` x its extent from ``o``.

    Measured from its first vertex, in the max norm; the extent is its bounding box's longer
    side.
    """
    if b <= a:
        return False
    x0 = xs[a]
    y0 = ys[a]
    lo_x = x0
    hi_x = x0
    lo_y = y0
    hi_y = y0
    for k in range(a + 1, b):
        lo_x = min(lo_x, xs[k])
        hi_x = max(hi_x, xs[k])
        lo_y = min(lo_y, ys[k])
        hi_y = max(hi_y, ys[k])
    reach = max(abs(x0 - ox), abs(y0 - oy))
    return reach > MOMENTS_FAR_PART * max(hi_x - lo_x, hi_y - lo_y)


@njit(**NJIT)
def _ring_spread(xs, ys, a, b, ox, oy):
    """``sum |x0 y1 - x1 y0|`` over the closed ring ``(xs, ys)[a:b]`` about ``(ox, oy)``.

    Twice the area the shoelace's terms would cover without cancelling: its ratio to the
    ring's own twice-area bounds the sums' relative rounding (in ulps).
    """
    total = 0.0
    for k in range(a, b - 1):
        total += abs((xs[k] - ox) * (ys[k + 1] - oy) - (xs[k + 1] - ox) * (ys[k] - oy))
    return total


@njit(**NJIT)
def _part_moments(xs, ys, ring_offsets, r0, r1, ox, oy):
    """Signed moments ``(mass, first x, first y, second)`` of the polygon of rings ``r0:r1``.

    About ``(ox, oy)``; the first ring is the exterior, the others holes.
    """
    s0 = 0.0
    sx = 0.0
    sy = 0.0
    s2 = 0.0
    for r in range(r0, r1):
        a0, ax, ay, a2 = ring_moments(xs, ys, ring_offsets[r], ring_offsets[r + 1], ox, oy, True)
        sign = 1.0 if a0 >= 0.0 else -1.0
        if r != r0:
            sign = -sign  # holes subtract
        s0 += sign * a0
        sx += sign * ax
        sy += sign * ay
        s2 += sign * a2
    return s0, sx, sy, s2


@njit(**NJIT_PARALLEL)
def uniform_moments(
    coords, ring_offsets, polygon_offsets, geom_offsets, origin, mass, first, second
):
    """Exact (closed-form) moments of unit density; writes into ``mass``, ``first``, ``second``.

    Sums are taken about the cell's origin (its site). Where their terms cancel (they cover
    more than ``MOMENTS_CANCEL`` x the cell's area: a part of a MultiPolygon domain across
    a gap of 1e12, whose terms are the gap times the part's size; the mass was 6e-5 off),
    each polygon farther than ``MOMENTS_FAR_PART`` x its extent from the origin is summed
    about its own first vertex instead and its moments moved to the origin (``first + A d``,
    ``second + 2 d . first + A |d|^2``).
    """
    n = geom_offsets.shape[0] - 1
    xs = coords[:, 0]
    ys = coords[:, 1]
    for g in prange(n):
        ox = origin[g, 0]
        oy = origin[g, 1]
        s0 = 0.0
        sx = 0.0
        sy = 0.0
        s2 = 0.0
        spread = 0.0
        for p in range(geom_offsets[g], geom_offsets[g + 1]):
            for r in range(polygon_offsets[p], polygon_offsets[p + 1]):
                a0, ax, ay, a2 = ring_moments(
                    xs, ys, ring_offsets[r], ring_offsets[r + 1], ox, oy, True
                )
                sign = 1.0 if a0 >= 0.0 else -1.0
                if r != polygon_offsets[p]:
                    sign = -sign  # holes subtract
                s0 += sign * a0
                sx += sign * ax
                sy += sign * ay
                s2 += sign * a2
                spread += 0.5 * _ring_spread(xs, ys, ring_offsets[r], ring_offsets[r + 1], ox, oy)
        if spread > MOMENTS_CANCEL * abs(s0):
            s0 = 0.0
            sx = 0.0
            sy = 0.0
            s2 = 0.0
            for p in range(geom_offsets[g], geom_offsets[g + 1]):
                r0 = polygon_offsets[p]
                vx = ox
                vy = oy
                if _far_part(xs, ys, ring_offsets[r0], ring_offsets[r0 + 1], ox, oy):
                    vx = xs[ring_offsets[r0]]
                    vy = ys[ring_offsets[r0]]
                p0, px, py, p2 = _part_moments(
                    xs, ys, ring_offsets, r0, polygon_offsets[p + 1], vx, vy
                )
                # moved from the part's vertex to the origin (zero shift for a near part)
                dx = vx - ox
                dy = vy - oy
                s0 += p0
                sx += px + p0 * dx
                sy += py + p0 * dy
                s2 += p2 + 2.0 * (dx * px + dy * py) + p0 * (dx * dx + dy * dy)
        mass[g] = s0
        first[g, 0] = sx
        first[g, 1] = sy
        second[g] = s2


@njit(**NJIT)
def _clip_axis(px, py, m, qx, qy, axis, value, keep_below):
    """Sutherland-Hodgman against one axis-parallel line (exact for moment integrals).

    Keeps ``coord <= value`` (``keep_below``) or ``coord >= value`` of the open ring ``p``.
    Non-convex rings may gain zero-width bridges along the line; their signed integrals are
    still those of the clipped region.
    """
    out = 0
    if m == 0:
        return 0
    sp = (px[m - 1] if axis == 0 else py[m - 1]) - value
    if not keep_below:
        sp = -sp
    for k in range(m):
        kp = k - 1 if k > 0 else m - 1
        s = (px[k] if axis == 0 else py[k]) - value
        if not keep_below:
            s = -s
        if (sp <= 0.0) != (s <= 0.0):
            t = sp / (sp - s)
            if axis == 0:
                qx[out] = value
                qy[out] = py[kp] + t * (py[k] - py[kp])
            else:
                qx[out] = px[kp] + t * (px[k] - px[kp])
                qy[out] = value
            out += 1
        if s <= 0.0:
            qx[out] = px[k]
            qy[out] = py[k]
            out += 1
        sp = s
    return out


@njit(**NJIT)
def raster_moments(
    coords, ring_offsets, polygon_offsets, geom_offsets, origin, raster, rbox, mass, first, second
):
    """Moments of a piecewise-constant density, integrated exactly over every cell.

    ``raster (h, w)`` covers ``rbox = (xmin, ymin, xmax, ymax)``; row 0 is the top
    (``y = ymax``), as in an image; outside the box the density is 0. Each ring is cut into
    pixel rows, each row piece into pixels, and each pixel piece's moments are weighted by
    that pixel's value. Where the rings' shoelace terms about the origin cancel (see
    :func:`uniform_moments`), a polygon far from it is cut about its own first vertex and each
    piece's moments moved to the origin.
    """
    n = geom_offsets.shape[0] - 1
    xs = coords[:, 0]
    ys = coords[:, 1]
    h, w = raster.shape
    dxp = (rbox[2] - rbox[0]) / w
    dyp = (rbox[3] - rbox[1]) / h
    # typed values, not literals: numba would compile _clip_axis once per literal pair
    x_axis = np.int64(0)
    y_axis = np.int64(1)
    below = np.bool_(True)
    above = np.bool_(False)
    for g in range(n):
        ox = origin[g, 0]
        oy = origin[g, 1]
        s0 = 0.0
        sx = 0.0
        sy = 0.0
        s2 = 0.0
        spread = 0.0
        signed = 0.0
        for p in range(geom_offsets[g], geom_offsets[g + 1]):
            for r in range(polygon_offsets[p], polygon_offsets[p + 1]):
                ring2 = ring_sums(xs, ys, ring_offsets[r], ring_offsets[r + 1], ox, oy, True)[0]
                hole = r != polygon_offsets[p]
                signed += -abs(ring2) if hole else abs(ring2)
                spread += _ring_spread(xs, ys, ring_offsets[r], ring_offsets[r + 1], ox, oy)
        recenter = spread > MOMENTS_CANCEL * abs(signed)
        for p in range(geom_offsets[g], geom_offsets[g + 1]):
            r0 = polygon_offsets[p]
            vx = ox
            vy = oy
            if recenter and _far_part(xs, ys, ring_offsets[r0], ring_offsets[r0 + 1], ox, oy):
                vx = xs[ring_offsets[r0]]
                vy = ys[ring_offsets[r0]]
            dx = vx - ox  # each piece's moments moved to the origin (0 for a near part)
            dy = vy - oy
            for r in range(polygon_offsets[p], polygon_offsets[p + 1]):
                a = ring_offsets[r]
                b = ring_offsets[r + 1] - 1  # open ring: drop the closing vertex
                m = b - a
                if m < 3:
                    continue
                # a cut at most doubles the vertex count (one crossing per edge)
                rx = np.zeros(m)
                ry = np.zeros(m)
                t1x = np.zeros(2 * m)
                t1y = np.zeros(2 * m)
                t2x = np.zeros(4 * m)
                t2y = np.zeros(4 * m)
                t3x = np.zeros(8 * m)
                t3y = np.zeros(8 * m)
                t4x = np.zeros(16 * m)
                t4y = np.zeros(16 * m)
                ylo = np.inf
                yhi = -np.inf
                area2 = 0.0
                for k in range(m):
                    rx[k] = coords[a + k, 0] - vx
                    ry[k] = coords[a + k, 1] - vy
                    ylo = min(ylo, coords[a + k, 1])
                    yhi = max(yhi, coords[a + k, 1])
                for k in range(m):
                    kn = k + 1 if k + 1 < m else 0
                    area2 += rx[k] * ry[kn] - rx[kn] * ry[k]
                sign = 1.0 if area2 >= 0.0 else -1.0
                if r != polygon_offsets[p]:
                    sign = -sign
                r0 = max(int(np.floor((rbox[3] - yhi) / dyp)), 0)
                r1 = min(int(np.floor((rbox[3] - ylo) / dyp)), h - 1)
                for row in range(r0, r1 + 1):
                    top = rbox[3] - row * dyp - vy
                    bot = rbox[3] - (row + 1) * dyp - vy
                    m1 = _clip_axis(rx, ry, m, t1x, t1y, y_axis, top, below)
                    m2 = _clip_axis(t1x, t1y, m1, t2x, t2y, y_axis, bot, above)
                    if m2 < 3:
                        continue
                    xlo = np.inf
                    xhi = -np.inf
                    for k in range(m2):
                        xlo = min(xlo, t2x[k])
                        xhi = max(xhi, t2x[k])
                    c0 = max(int(np.floor((xlo + vx - rbox[0]) / dxp)), 0)
                    c1 = min(int(np.floor((xhi + vx - rbox[0]) / dxp)), w - 1)
                    for col in range(c0, c1 + 1):
                        val = raster[row, col]
                        if val == 0.0:
                            continue
                        left = rbox[0] + col * dxp - vx
                        right = rbox[0] + (col + 1) * dxp - vx
                        m3 = _clip_axis(t2x, t2y, m2, t3x, t3y, x_axis, right, below)
                        m4 = _clip_axis(t3x, t3y, m3, t4x, t4y, x_axis, left, above)
                        if m4 < 3:
                            continue
                        a0, ax, ay, a2 = ring_moments(t4x, t4y, 0, m4, 0.0, 0.0, False)
                        f = sign * val
                        s0 += f * a0
                        sx += f * (ax + a0 * dx)
                        sy += f * (ay + a0 * dy)
                        s2 += f * (a2 + 2.0 * (dx * ax + dy * ay) + a0 * (dx * dx + dy * dy))
        mass[g] = s0
        first[g, 0] = sx
        first[g, 1] = sy
        second[g] = s2


@njit(**NJIT)
def farthest(coords, start, xy):  # pragma: no cover
    """``max |coords[k] - xy[i]|`` over ring ``i``'s vertices ``start[i]:start[i + 1]``.

    The radius of a cell about its site (0 for an empty ring). By ``hypot``, not the square
    root of a sum of squares: squares underflow to 0 below ~1e-154 (every cell would pass a
    certificate with radius 0) and overflow past ~1e154.
    """
    r = np.zeros(len(start) - 1)
    for i in range(len(start) - 1):
        best = 0.0
        for k in range(start[i], start[i + 1]):
            best = max(best, math.hypot(coords[k, 0] - xy[i, 0], coords[k, 1] - xy[i, 1]))
        r[i] = best
    return r
