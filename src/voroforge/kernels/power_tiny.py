"""Power cells' pieces for boxes far smaller than the sites' ulp (issue 15, power6).

:func:`.power.box_cell` cuts a box with power bisectors in floats relative to each site. In
a box 1e-300 wide seen from sites on a circle of radius 5 (weights of the box's size, so
every bisector passes through it) each plane value is the rounding of 25, each crossing
the float formula's, and each ring's area from its site 0: cells were lost and the areas
did not sum to the box. Unequal weights now take the exact side of a vertex whose value is
within rounding of 0 (:func:`exact_power_signs`), the double nearest each crossing of a box
side (:func:`crossing`), and a ring's area from its own first vertex
(:func:`tiny_ring_area`). Equal weights are untouched (``box_crossing``'s bits).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..config import NJIT, SIDE_BOX_RTOL
from .expansion import rounded_sum, two_diff, two_product, two_sum
from .sidecross import nearest_power_crossing, power_side
from .vertex import before, power_box_crossing, power_vertex, sorted_triple

_U = 2.0**-53  # unit roundoff of float64


@njit(**NJIT)
def exact_power_signs(i, j, xs, ys, ws, px, py, m, dx, dy, h, ss, smax):
    """:func:`.power._exact_signs` for unequal weights: :func:`.sidecross.power_side` decides.

    A value within its rounding bound of 0 in a box far smaller than the sites' spacing
    (power6: sites on a circle of radius 5, weights of the size of a box 1e-300 wide, every
    value the rounding of 25) takes the exact side of its vertex; where underflow hides
    that side the float value stays. Returns the largest value.
    """
    smax = -np.inf
    for v in range(m):
        sv = ss[v]
        e = 8.0 * _U * (abs(dx * (px[v] - xs[i])) + abs(dy * (py[v] - ys[i])) + abs(h))
        if abs(sv) <= e:
            t = power_side(xs[i], ys[i], ws[i], xs[j], ys[j], ws[j], px[v], py[v])
            if t == 0:
                sv = 0.0
            elif t != 2 and ((t > 0) != (sv > 0.0) or sv == 0.0):
                sv = max(e, 1e-300) if t > 0 else -max(e, 1e-300)
            ss[v] = sv
        smax = max(smax, sv)
    return smax


@njit(**NJIT)
def crossing(i, j, xs, ys, ws, side, box):
    """Where the power bisector of ``i`` and ``j`` crosses box side ``side`` (-1..-4).

    :func:`.vertex.power_box_crossing`; for unequal weights in a box far smaller than the
    sites' ulp, or sites a few ulps apart, the double nearest the exact crossing
    (:func:`.sidecross.nearest_power_crossing`): the float formula was off by many
    crossings' spacings there (power6: in a box 1e-300 wide, cells lost and areas not
    summing to the box). Equal weights: :func:`.vertex.box_crossing`'s bits.
    """
    x, y = power_box_crossing(i, j, xs, ys, ws, side, box)
    if ws[i] == ws[j]:
        return x, y
    a = np.int64(i)
    b = np.int64(j)
    if before(b, a, xs, ys):
        a, b = b, a
    return nearest_power_crossing(xs[a], ys[a], ws[a], xs[b], ys[b], ws[b], side, box, x, y)


@njit(**NJIT)
def tiny_ring_area(px, py, b, k, ox, oy):
    """Twice the area of ring ``b:b + k`` (scaled), where it is far smaller than its site's ulp.

    Else 0.0: the site's frame (:func:`.power._compact`) decided.

    From a site ``1 / SIDE_BOX_RTOL`` ring widths away every ``p - o`` rounds to the same
    value and the area to 0 (power6: sites on a circle of radius 5 in a box 1e-300 wide,
    the cells of 2 of 4 sites dropped).
    """
    ext = 0.0
    for v in range(1, k):
        ext = max(ext, max(abs(px[b + v] - px[b]), abs(py[b + v] - py[b])))
    if not np.spacing(max(abs(ox), abs(oy))) > SIDE_BOX_RTOL * ext:
        return 0.0
    # differences scaled to about 1 (exact): their products would underflow in a box 1e-300
    e = -math.frexp(ext)[1]
    area2 = 0.0
    x0 = px[b]
    y0 = py[b]
    for v in range(1, k - 1):
        ax = math.ldexp(px[b + v] - x0, e)
        ay = math.ldexp(py[b + v] - y0, e)
        bx = math.ldexp(px[b + v + 1] - x0, e)
        by = math.ldexp(py[b + v + 1] - y0, e)
        area2 += ax * by - bx * ay
    return area2


@njit(**NJIT)
def _k_parts(ax, ay, aw, bx, by, bw, k, out):
    """``|b|^2 - |a|^2 + w_a - w_b`` as 18 exact parts (before scaling by ``2^k``)."""
    n = 0
    for t in range(2):
        p, q = (ax, bx) if t == 0 else (ay, by)
        d1, d0 = two_diff(q, p)
        s1, s0 = two_sum(q, p)
        for u in (d1, d0):
            for v in (s1, s0):
                hi, lo = two_product(u, math.ldexp(v, k))
                out[n] = hi
                out[n + 1] = lo
                n += 2
    w1, w0 = two_diff(aw, bw)
    out[n] = math.ldexp(w1, k)
    out[n + 1] = math.ldexp(w0, k)
    return n + 2


@njit(**NJIT)
def _times(src, n, c1, c0, sign, out, m):
    """Append ``sign (src[:n]) (c1 + c0)`` to ``out`` from ``m`` as exact parts; new count."""
    for t in range(n):
        for c in (c1, c0):
            hi, lo = two_product(src[t], sign * c)
            out[m] = hi
            out[m + 1] = lo
            m += 2
    return m


@njit(**NJIT)
def _centre(ax, ay, aw, bx, by, bw, cx, cy, cw):
    """Power centre of three sites from exact parts (Cramer's rule), to an ulp or two.

    NaN where the sites are collinear.
    The rows ``2 (q - a).p = |q|^2 - |a|^2 + w_a - w_q`` in absolute coordinates (a centre
    in a box 1e-300 wide seen from sites at 5: relative to a site it is lost to rounding),
    their right sides scaled by ``2^k`` (exact) so no product's error term underflows.
    """
    kb = np.empty(18)  # noqa: TID251  (every slot read is written first)
    kc = np.empty(18)  # noqa: TID251
    n = _k_parts(ax, ay, aw, bx, by, bw, 0, kb)
    _k_parts(ax, ay, aw, cx, cy, cw, 0, kc)
    top = 0.0
    for t in range(n):
        top = max(top, max(abs(kb[t]), abs(kc[t])))
    k = 0 if not top > 0.0 else max(0, 900 - math.frexp(top)[1])
    if k > 0:
        _k_parts(ax, ay, aw, bx, by, bw, k, kb)
        _k_parts(ax, ay, aw, cx, cy, cw, k, kc)
    ex1, ex0 = two_diff(bx, ax)
    ey1, ey0 = two_diff(by, ay)
    fx1, fx0 = two_diff(cx, ax)
    fy1, fy0 = two_diff(cy, ay)
    parts = np.empty(4 * n * 2)  # noqa: TID251
    w = np.empty(4 * n * 2 + 1)  # noqa: TID251
    # det / 2 = ex fy - fx ey (the rows' factor 2 in both)
    m = 0
    for u in (ex1, ex0):
        for v in (fy1, fy0):
            hi, lo = two_product(u, v)
            parts[m] = hi
            parts[m + 1] = lo
            m += 2
    for u in (fx1, fx0):
        for v in (ey1, ey0):
            hi, lo = two_product(-u, v)
            parts[m] = hi
            parts[m + 1] = lo
            m += 2
    det = rounded_sum(parts, m, w)
    if det == 0.0:
        return np.nan, np.nan
    # x = (kb fy - kc ey) / (2 det), y = (ex kc - fx kb) / (2 det)
    m = _times(kb, n, fy1, fy0, 1.0, parts, 0)
    m = _times(kc, n, ey1, ey0, -1.0, parts, m)
    x = rounded_sum(parts, m, w) / (2.0 * det)
    m = _times(kc, n, ex1, ex0, 1.0, parts, 0)
    m = _times(kb, n, fx1, fx0, -1.0, parts, m)
    y = rounded_sum(parts, m, w) / (2.0 * det)
    return math.ldexp(x, -k) + 0.0, math.ldexp(y, -k) + 0.0  # no -0.0


@njit(**NJIT)
def vertex(i, a, b, xs, ys, ws, box):
    """:func:`.vertex.power_vertex`, or :func:`_centre` in a box nearer 0 than the sites' ulp.

    There the float centre, rounded relative to the sites, was (0, 0) for every triple
    (power6: sites on a circle of radius 5, weights ~1e-300, centres ~3e-301). Computed
    from the triple in canonical order (every cell gets the same bits); three equal
    weights keep :func:`.vertex.power_vertex` (the Voronoi vertex's bits).
    """
    if ws[i] == ws[a] and ws[i] == ws[b]:
        return power_vertex(i, a, b, xs, ys, ws)
    big = 0.0
    for q in (i, a, b):
        big = max(big, max(abs(xs[q]), abs(ys[q])))
    # the box's coordinates (where its vertices lie), not its extent: a box 1 wide at 4e6
    # with sites a few ulps apart keeps the float centre (the absolute rows lose to it)
    far = max(max(abs(box[0]), abs(box[1])), max(abs(box[2]), abs(box[3])))
    if not np.spacing(big) > SIDE_BOX_RTOL * far:
        return power_vertex(i, a, b, xs, ys, ws)
    p, q, r = sorted_triple(i, a, b, xs, ys)
    x, y = _centre(xs[p], ys[p], ws[p], xs[q], ys[q], ws[q], xs[r], ys[r], ws[r])
    if not (abs(x) < np.inf and abs(y) < np.inf):
        return power_vertex(i, a, b, xs, ys, ws)
    return x, y
