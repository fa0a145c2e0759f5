"""Side tests of a point known as a float plus an exact vertex offset (double-double).

The cell cut's band vertices (:mod:`.cellcut3d`) are kept as a float point ``c`` and the
offset ``d`` of their owners' exact point from it (:func:`.predicates3d.vertex_offset`,
correctly rounded from exact determinants). :func:`offset_side` decides a bisector against
``c + d`` in double-double; :func:`frame_lift`, :func:`frame_offset` and :func:`frame_side`
move a cell's planes into a frame at its first such vertex once and decide each band
vertex there in floats with a proven bound. Each returns 0 where its bound cannot tell
(then the exact test decides), so every decision is the exact one.
"""

from __future__ import annotations

from numba import njit

from ..config import NJIT
from .expansion import two_diff, two_product, two_sum

_EPS = 2.0**-53

#: the relative error of :func:`.predicates3d.vertex_offset`'s offsets taken by
#: :func:`offset_side` (two determinants rounded to nearest and a division: 1.5 ulps;
#: padded)
_OFFSET_RERR = 64.0 * _EPS
#: the inputs :func:`offset_side` sums (11 an axis, 2 for the weights)
_OFFSET_TERMS = 35
_OFFSET_GAMMA = _OFFSET_TERMS * _EPS / (1.0 - _OFFSET_TERMS * _EPS)


@njit(**{**NJIT, "inline": "always"})
def _sum2(hi, lo, absum, t):
    """One step of Ogita, Rump and Oishi's Sum2: ``hi + lo`` gains ``t`` (and ``|t|``)."""
    hi, e = two_sum(hi, t)
    return hi, lo + e, absum + abs(t)


@njit(**NJIT)
def offset_side(i, j, cx, cy, cz, dx, dy, dz, P, W):
    """Side of the point ``x = c + d`` against site ``j``'s bisector with ``i``, or 0 (unsure).

    The sign of ``2 s = 2 (x - p_i) . r - |r|^2 - (w_i - w_j)`` (``r = p_j - p_i``; as
    :func:`.predicates3d.bisector_side`: 1 beyond, -1 inside) in double-double:
    ``c - p_i`` and ``r`` are exact two-term differences, the big products exact
    (two-product), the rest rounded once, ``d`` (:func:`.predicates3d.vertex_offset`) right
    to ``_OFFSET_RERR`` of itself, all summed by Sum2 (error
    ``eps |s| + gamma_{n-1}^2 sum |t|``). Where the vertex is known far better than its
    float coordinates (a vertex near the origin among sites on the unit sphere, whose every
    bisector passes within an ulp of it) this decides what the float filter cannot, at the
    cost of a few dozen flops instead of exact determinants; returns 0 when the bound
    cannot tell (then decide exactly).
    """
    hi = 0.0
    lo = 0.0
    absum = 0.0
    small = 0.0  # bound on the rounding of the terms that are not exact
    for k in range(3):
        ck = cx if k == 0 else (cy if k == 1 else cz)
        dk = dx if k == 0 else (dy if k == 1 else dz)
        rh, rl = two_diff(P[j, k], P[i, k])
        uh, ul = two_diff(ck, P[i, k])
        a1, a2 = two_product(2.0 * uh, rh)
        b1, b2 = two_product(rh, rh)
        hi, lo, absum = _sum2(hi, lo, absum, a1)
        hi, lo, absum = _sum2(hi, lo, absum, a2)
        hi, lo, absum = _sum2(hi, lo, absum, -b1)
        hi, lo, absum = _sum2(hi, lo, absum, -b2)
        t1 = 2.0 * uh * rl
        t2 = 2.0 * ul * rh
        t3 = 2.0 * ul * rl
        t4 = 2.0 * dk * rh
        t5 = 2.0 * dk * rl
        t6 = -2.0 * rh * rl
        t7 = -rl * rl
        hi, lo, absum = _sum2(hi, lo, absum, t1)
        hi, lo, absum = _sum2(hi, lo, absum, t2)
        hi, lo, absum = _sum2(hi, lo, absum, t3)
        hi, lo, absum = _sum2(hi, lo, absum, t4)
        hi, lo, absum = _sum2(hi, lo, absum, t5)
        hi, lo, absum = _sum2(hi, lo, absum, t6)
        hi, lo, absum = _sum2(hi, lo, absum, t7)
        small += _EPS * (abs(t1) + abs(t2) + abs(t3) + abs(t6) + abs(t7))
        small += (_EPS + 1.01 * _OFFSET_RERR) * (abs(t4) + abs(t5))
    wh, wl = two_diff(W[i], W[j])
    hi, lo, absum = _sum2(hi, lo, absum, -wh)
    hi, lo, absum = _sum2(hi, lo, absum, -wl)
    res = hi + lo
    # |res - s| <= eps |s| + g: with |s| <= (|res| + g) / (1 - eps), 2 eps covers eps / (1 - eps);
    # 1e-290 covers products that fall below the normal range (then two_product is not exact)
    g = _OFFSET_GAMMA * _OFFSET_GAMMA * absum + small
    bound = 2.0 * _EPS * (abs(res) + g) + g + 1e-290
    if res > bound:
        return 1
    if res < -bound:
        return -1
    return 0


#: the inputs :func:`frame_lift` sums (4 an axis for each site, 2 for the weights)
_LIFT_TERMS = 26
_LIFT_GAMMA = _LIFT_TERMS * _EPS / (1.0 - _LIFT_TERMS * _EPS)
_GAMMA5 = 5.0 * _EPS / (1.0 - 5.0 * _EPS)


@njit(**NJIT)
def frame_lift(i, j, ox, oy, oz, P, W):
    """``K = |p_j - o|^2 - |p_i - o|^2 + w_i - w_j`` and a bound on its error: ``(K, err)``.

    The constant of ``j``'s bisector with ``i`` in a frame at ``o``: a point ``x`` is beyond
    it when ``2 (x - o) . (p_j - p_i) > K`` (see :func:`frame_side`). Differences from ``o``
    are exact two-term expansions, their squares' big parts exact (two-product), summed by
    Sum2 as in :func:`offset_side`.
    """
    hi = 0.0
    lo = 0.0
    absum = 0.0
    small = 0.0
    for k in range(3):
        ok = ox if k == 0 else (oy if k == 1 else oz)
        for site, sg in ((j, 1.0), (i, -1.0)):
            ah, al = two_diff(P[site, k], ok)
            s1, s2 = two_product(ah, ah)
            t1 = sg * 2.0 * ah * al
            t2 = sg * al * al
            hi, lo, absum = _sum2(hi, lo, absum, sg * s1)
            hi, lo, absum = _sum2(hi, lo, absum, sg * s2)
            hi, lo, absum = _sum2(hi, lo, absum, t1)
            hi, lo, absum = _sum2(hi, lo, absum, t2)
            small += _EPS * (abs(t1) + abs(t2))
    wh, wl = two_diff(W[i], W[j])
    hi, lo, absum = _sum2(hi, lo, absum, wh)
    hi, lo, absum = _sum2(hi, lo, absum, wl)
    res = hi + lo
    g = _LIFT_GAMMA * _LIFT_GAMMA * absum + small
    return res, 2.0 * _EPS * (abs(res) + g) + g + 1e-290


@njit(**NJIT)
def frame_offset(cx, cy, cz, dx, dy, dz, ox, oy, oz, out):
    """``e = c + d - o`` into ``out[0:3]`` and a bound on its error into ``out[3:6]``.

    ``d`` is :func:`.predicates3d.vertex_offset`'s, right to ``_OFFSET_RERR`` of itself;
    ``c - o`` is an exact two-term difference; two roundings.
    """
    for k in range(3):
        ck = cx if k == 0 else (cy if k == 1 else cz)
        dk = dx if k == 0 else (dy if k == 1 else dz)
        ok = ox if k == 0 else (oy if k == 1 else oz)
        hi, lo = two_diff(ck, ok)
        e = hi + (lo + dk)
        out[k] = e
        out[3 + k] = 2.0 * _EPS * (abs(e) + abs(lo) + abs(dk)) + 1.01 * _OFFSET_RERR * abs(dk)


@njit(**{**NJIT, "inline": "always"})
def frame_side(E, rh0, rh1, rh2, rl0, rl1, rl2, K, kerr):
    """Side of the point ``o + e`` against the bisector of :func:`frame_lift`'s ``K``, or 0.

    ``E = (e, its error)`` (:func:`frame_offset`), ``r = p_j - p_i = rh + rl`` exactly:
    1 beyond, -1 inside, 0 when the float value ``2 e . rh - K`` and its bound (``gamma_5``
    of its terms, plus the errors of ``e``, ``rl`` and ``K``) cannot tell.
    """
    a0 = E[0] * rh0
    a1 = E[1] * rh1
    a2 = E[2] * rh2
    g = 2.0 * (a0 + a1 + a2) - K
    b = _GAMMA5 * (2.0 * (abs(a0) + abs(a1) + abs(a2)) + abs(K))
    b += 2.0 * (E[3] * (abs(rh0) + abs(rl0)) + E[4] * (abs(rh1) + abs(rl1)))
    b += 2.0 * E[5] * (abs(rh2) + abs(rl2))
    b += 2.0 * (abs(E[0] * rl0) + abs(E[1] * rl1) + abs(E[2] * rl2)) + kerr
    b = b * (1.0 + 16.0 * _EPS) + 1e-290
    if g > b:
        return 1
    if g < -b:
        return -1
    return 0
