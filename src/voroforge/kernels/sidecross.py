"""Bisectors' crossings with a box side, rounded to the nearest double.

Where the bisector of two sites crosses a side of the box is named by the pair and the side
(:func:`.vertex.box_crossing`), so every cell at it gets the same bits. The float formula
is off by up to a couple of ulps, and two crossings of one side less than an ulp apart can
then come out in the wrong order: the cell between the two bisectors runs backwards along
the side and folds (issue 15: a float circle of 1,000 sites of radius 1e-7 at (5e5, 4e6),
phase 0.05, crossings 118.79 and 118.25 ulps above the centre rounded to 118 and 119; the
ring of the site between them was dropped and left a hole). The double nearest to each
crossing keeps every pair in order (rounding to nearest is monotone), or puts both on one
point. Only sites a few ulps apart (``SIDE_NEAREST_ULPS``) need it; farther pairs keep the
float formula's bits.

On a vertical side ``x = X`` the crossing is

    y = ((ax - bx) (2 X - ax - bx) + (by - ay) (by + ay)) / (2 (by - ay))

(a horizontal side swaps the axes). The numerator is a sum of 20 exact products of doubles
(``two_diff``, ``two_sum``, ``two_product``), the denominator ``2 (by - ay)`` two doubles.
The float estimate is moved to the double nearest the quotient by the signs of
``N - m D`` at the midpoints ``m`` beside it: each sign is a compensated sum with a proven
error bound (Ogita, Rump and Oishi's Sum2), or, where that bound cannot decide it, exact
(Shewchuk's growth of an expansion). In a box below ~1e-270 the products of a midpoint
would lose their error terms to underflow: every part is then scaled by one power of two
first (exact), which lifts them out of it, so crossings down to subnormal ones (a box
1e-320 wide) are the nearest double too. Only a part that still underflows (a site's
difference far below the others') is allowed for with a slack of ``2^-1060``, which only
a midpoint that close to the crossing reaches (the float formula is kept there).

Power bisectors (unequal weights, issue 15 power6) add ``w_a - w_b`` to the numerator as
two more exact parts (zero for Voronoi, which then keeps its bits):
:func:`nearest_power_crossing`, and :func:`power_side`, the exact side of a point, which
is ``D y - N`` on the line ``x = X`` through it.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..config import NJIT, SIDE_BOX_RTOL, SIDE_NEAREST_ULPS
from ..config import SIDE_NEAREST_MAX_STEPS as _MAX_STEPS
from .expansion import grow, rounded_sum, two_diff, two_product, two_sum

_U = 2.0**-53
_TINY = 2.0**-900  # a product below this may lose its error term to underflow
_SLACK = 2.0**-1060  # what underflowed products' parts may lose, all together (< 2^-1066)
_NT = 22  # exact parts of the numerator (the last two: the weight difference, 0 for Voronoi)
_TOP_BITS = 900  # where scaled parts top out (Dekker splits of them stay finite)


@njit(**NJIT)
def _put(t, k, a, b):
    """Write ``a * b`` as two exact parts at ``t[k:k + 2]``; False where it may underflow."""
    hi, lo = two_product(a, b)
    t[k] = hi
    t[k + 1] = lo
    return hi == 0.0 or abs(hi) >= _TINY


@njit(**NJIT)
def _numerator(ax, ay, bx, by, x, t, e, d1, d0):
    """The numerator's exact parts, times ``2^e``, into ``t[:_NT]``; False where one may be inexact.

    Each part is the product of two doubles, the second scaled by ``2^e`` (exact): a box
    below ~1e-270 has parts whose error terms underflow unscaled. ``d1 + d0`` is the power
    weights' difference ``w_a - w_b`` (exactly; 0 for a Voronoi bisector: zero parts change
    no sum and no sign, so the Voronoi crossings keep their bits).
    """
    p1, p0 = two_diff(ax, bx)
    s1, s0 = two_sum(-ax, -bx)
    q2, q1 = two_sum(2.0 * x, s1)  # 2 X - ax - bx = q2 + q1 + s0, exactly
    r1, r0 = two_diff(by, ay)
    u1, u0 = two_sum(by, ay)
    if e != 0:
        q2, q1, s0 = math.ldexp(q2, e), math.ldexp(q1, e), math.ldexp(s0, e)
        u1, u0 = math.ldexp(u1, e), math.ldexp(u0, e)
    ok = _put(t, 0, p1, q2) & _put(t, 2, p1, q1) & _put(t, 4, p1, s0)
    ok &= _put(t, 6, p0, q2) & _put(t, 8, p0, q1) & _put(t, 10, p0, s0)
    ok &= _put(t, 12, r1, u1) & _put(t, 14, r1, u0) & _put(t, 16, r0, u1)
    ok &= _put(t, 18, r0, u0)
    if e != 0:
        d1, d0 = math.ldexp(d1, e), math.ldexp(d0, e)
    t[20] = d1
    t[21] = d0
    return ok


@njit(**NJIT)
def _scale_for(t):
    """The power of two that brings the largest of ``t[:_NT]`` near ``2^_TOP_BITS`` (or 0)."""
    top = 0.0
    for k in range(_NT):
        top = max(top, abs(t[k]))
    if not top > 0.0:
        return 0
    return max(0, _TOP_BITS - math.frexp(top)[1])


@njit(**NJIT)
def _sign_past(t, m, h2, r1, r0, w, exact, e):
    """Sign of ``N - (m + h2 / 2) D`` with ``D = 2 (r1 + r0)``; 2 where underflow hides it.

    ``t[:_NT]`` holds ``N``'s parts times ``2^e`` (``exact``: none underflowed), and ``m``,
    ``h2`` are scaled alike (exact); ``h2`` is a power of two (or 0), so ``h2 D / 2`` is exact
    but for underflow. Sum2 (a chain of ``two_sum``) decides the sign unless its error
    bound, ``u |s| + gamma_{25}^2 sum |x_i|`` (doubled here, plus ``_SLACK`` where a part
    underflowed), reaches the sum; then ``w`` grows the exact expansion of the parts, whose
    sign stands where it is past ``_SLACK``.
    """
    if e != 0:
        m = math.ldexp(m, e)
        h2 = math.ldexp(h2, e)
    ok = _put(t, _NT, -2.0 * m, r1) & _put(t, _NT + 2, -2.0 * m, r0) & exact
    t[_NT + 4] = -h2 * r1
    t[_NT + 5] = -h2 * r0
    for k in range(_NT + 4, _NT + 6):
        ok &= t[k] == 0.0 or abs(t[k]) >= _TINY
    return _sum_sign(t, _NT + 6, w, ok)


@njit(**NJIT)
def _sum_sign(t, n, w, ok):
    """The sign of ``sum t[:n]`` (see :func:`_sign_past`); 2 where underflow hides it."""
    slack = 0.0 if ok else _SLACK
    s = 0.0
    c = 0.0
    a = 0.0
    for k in range(n):
        s, e = two_sum(s, t[k])
        c += e
        a += abs(t[k])
    r = s + c
    if abs(r) > 4.0 * _U * abs(r) + 1024.0 * _U * _U * a + slack:
        return 1 if r > 0.0 else -1
    size = 0
    for k in range(n):
        size = grow(w, size, t[k])
    top = w[size - 1]  # the largest component carries the sign
    if not ok and abs(top) <= 2.0 * slack:
        return 2
    return 1 if top > 0.0 else (-1 if top < 0.0 else 0)


@njit(**NJIT)
def _even(v):
    """Whether ``v``'s significand is even (the tie's winner under round-to-nearest-even)."""
    m, _ = math.frexp(v)
    return np.int64(abs(m) * 2.0**53) % 2 == 0


@njit(**NJIT)
def _parts(ax, ay, bx, by, x, t, d1, d0):
    """:func:`_numerator` into ``t``, scaled out of underflow where it needs it; ``(exact, e)``."""
    exact = _numerator(ax, ay, bx, by, x, t, 0, d1, d0)
    e = 0
    if not exact:
        # a box below ~1e-270: every part scaled by one power of two lifts the products'
        # error terms out of underflow (the crossing's midpoints are scaled alike)
        e = _scale_for(t)
        if e > 0:
            exact = _numerator(ax, ay, bx, by, x, t, e, d1, d0)
    return exact, e


@njit(**NJIT)
def _lifted(ax, ay, bx, by, x, t, exact, e, d1, d0, m, r1, power):
    """``(exact, e)``, the parts rescaled where a power crossing ``m`` would underflow.

    A power bisector's numerator can be exact unscaled (its weights' difference, products
    of sites apart in ``y`` only) while the crossing, and so its midpoints' products with
    ``D``, lie below ``2^-900`` (power6: sites (3, -4), (3, 4) with weights 1.2e-304,
    1.6e-304 cross a box 1e-305 wide at 2.5e-306, and the float formula gave 0.0). Only
    for power bisectors (``power``): the Voronoi crossings keep their bits.
    """
    if e != 0 or not power or m == 0.0 or abs(m * r1) >= _TINY * 2.0**60:
        return exact, e
    top = abs(2.0 * m * r1)
    for k in range(_NT):
        top = max(top, abs(t[k]))
    # capped so the scaled factors (``2 X - ax - bx``, ``by + ay``, the weights' difference,
    # the midpoints) stay below 2^990: a zero product (``ax == bx``) hides a big factor
    big = max(2.0 * abs(x) + abs(ax) + abs(bx), abs(ay) + abs(by))
    big = max(big, max(abs(d1), 4.0 * abs(m)))
    e = max(0, min(_TOP_BITS - math.frexp(top)[1], 990 - math.frexp(big)[1]))
    if e > 0:
        exact = _numerator(ax, ay, bx, by, x, t, e, d1, d0)
    return exact, e


@njit(**NJIT)
def _nearest(ax, ay, bx, by, x, y, d1, d0):
    """The double nearest ``y`` on the line ``x = X`` of the bisector; ``y`` its estimate.

    ``d1 + d0``: the weights' difference of a power bisector (0 for Voronoi). Returns ``y``
    unchanged where underflow hides a sign or the walk does not settle.
    """
    if not (y == y and abs(y) < np.inf):
        return y
    # the parts, then room for the exact sum: every slot is written before it is read
    buf = np.empty(2 * _NT + 13)  # noqa: TID251
    t = buf[: _NT + 6]
    w = buf[_NT + 6 :]
    exact, e = _parts(ax, ay, bx, by, x, t, d1, d0)
    r1, r0 = two_diff(by, ay)
    sd = 1 if r1 > 0.0 else -1
    # start from the numerator's exact sum, rounded (an ill-conditioned float formula, a
    # bisector nearly parallel to the side, is off by dozens of ulps; a crossing in a box
    # far smaller than the sites cancels all but the last bits of the parts)
    v = rounded_sum(t, _NT, w) / (2.0 * (r1 + r0))
    if e != 0:
        v = math.ldexp(v, -e)
    if not (v == v and abs(v) < np.inf):
        return y
    exact, e = _lifted(ax, ay, bx, by, x, t, exact, e, d1, d0, v, r1, d1 != 0.0)
    for _ in range(_MAX_STEPS):
        up = np.nextafter(v, np.inf)
        dn = np.nextafter(v, -np.inf)
        s = _sign_past(t, v, up - v, r1, r0, w, exact, e)
        if s == 2:
            return y
        s *= sd  # sign of (exact - midpoint above v)
        if s > 0:
            v = up
            continue
        if s == 0:
            return v if _even(v) else up
        s = _sign_past(t, v, dn - v, r1, r0, w, exact, e)
        if s == 2:
            return y
        s *= sd
        if s < 0:
            v = dn
            continue
        if s == 0:
            return v if _even(v) else dn
        return v
    return y


@njit(**NJIT)
def nearest_crossing(ax, ay, bx, by, side, box, x, y):
    """The crossing ``(x, y)`` of ``side`` (-1..-4) by the bisector of ``a, b``, nearest.

    ``(x, y)`` is the float formula's (NaN where the bisector is parallel to the side);
    for sites within ``SIDE_NEAREST_ULPS`` ulps of their magnitude of each other (a few
    ulps apart, where the formula's error is the crossings' spacing), and for a box whose
    extent is under ``1 / SIDE_BOX_RTOL`` ulps of the sites (a window far smaller than the
    sites' spacing: the formula's error is then part of the box), the coordinate along
    the side is replaced by the double nearest the exact one.
    """
    if x != x or y != y:
        return x, y
    big = max(max(abs(ax), abs(ay)), max(abs(bx), abs(by)))
    # a box far smaller than the sites' magnitude (issue 15, window at a circle's centre):
    # the formula's error, ulps of the sites, is then a visible part of the box
    ext = max(box[2] - box[0], box[3] - box[1])
    near = abs(bx - ax) + abs(by - ay) <= SIDE_NEAREST_ULPS * np.spacing(big)
    if not near and not np.spacing(big) > SIDE_BOX_RTOL * ext:
        return x, y
    if side == -1 or side == -3:
        return x, _nearest(ax, ay, bx, by, x, y, 0.0, 0.0)
    return _nearest(ay, ax, by, bx, y, x, 0.0, 0.0), y


@njit(**NJIT)
def nearest_power_crossing(ax, ay, aw, bx, by, bw, side, box, x, y):
    """:func:`nearest_crossing` for the power bisector of ``a, b`` with unequal weights.

    The bisector ``|p - a|^2 - w_a = |p - b|^2 - w_b`` crosses ``x = X`` at ``y = N / D``
    with the Voronoi numerator plus ``w_a - w_b`` (two exact parts). ``(x, y)`` is the
    float formula's crossing. Replaced by the double nearest the exact one for sites a few
    ulps apart and for a box whose extent is under ``1 / SIDE_BOX_RTOL`` ulps of the sites
    or of the float formula's midpoint (weights that move the bisector far out: the
    formula's error is then ulps of that point).
    """
    if x != x or y != y:
        return x, y
    big = max(max(abs(ax), abs(ay)), max(abs(bx), abs(by)))
    ext = max(box[2] - box[0], box[3] - box[1])
    near = abs(bx - ax) + abs(by - ay) <= SIDE_NEAREST_ULPS * np.spacing(big)
    far = max(big, max(abs(x), abs(y)))
    if not near and not np.spacing(far) > SIDE_BOX_RTOL * ext:
        return x, y
    d1, d0 = two_diff(aw, bw)
    if side == -1 or side == -3:
        return x, _nearest(ax, ay, bx, by, x, y, d1, d0)
    return _nearest(ay, ax, by, bx, y, x, d1, d0), y


@njit(**NJIT)
def power_side(ax, ay, aw, bx, by, bw, px, py):
    """Exact sign of ``(|p - a|^2 - w_a) - (|p - b|^2 - w_b)``; 2 where underflow hides it.

    Positive: ``p`` is nearer ``b`` in power (off cell ``a``). On the line ``x = p_x`` the
    difference is ``D p_y - N`` (``N``, ``D`` of :func:`nearest_power_crossing`), so the
    crossing's exact sums decide it (with its scaling out of underflow); sites level in
    ``y`` (``D = 0``) take the line ``y = p_y``.
    """
    buf = np.empty(2 * _NT + 13)  # noqa: TID251  (every slot read is written first)
    t = buf[: _NT + 6]
    w = buf[_NT + 6 :]
    d1, d0 = two_diff(aw, bw)
    if ay == by:
        if ax == bx:
            return 0 if d1 == 0.0 else (-1 if d1 > 0.0 else 1)
        ax, ay, bx, by, px, py = ay, ax, by, bx, py, px
    exact, e = _parts(ax, ay, bx, by, px, t, d1, d0)
    r1, r0 = two_diff(by, ay)
    exact, e = _lifted(ax, ay, bx, by, px, t, exact, e, d1, d0, py, r1, True)
    s = _sign_past(t, py, 0.0, r1, r0, w, exact, e)
    return s if s == 2 else -s
