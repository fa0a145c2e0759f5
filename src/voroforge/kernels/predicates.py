"""Robust geometric predicates: a floating-point filter with an exact fallback.

``orient2d(a, b, c)`` is positive when ``a, b, c`` turn counter-clockwise, negative when
clockwise and zero when collinear. ``incircle(a, b, c, d)`` is positive when ``d`` lies
strictly inside the circle through the counter-clockwise triangle ``a, b, c``. Both are
*exact*: the fast filter answers when its error bound proves the sign, and otherwise the
sign is computed with floating-point expansions (``kernels/expansion``; Shewchuk, "Adaptive
Precision Floating-Point Arithmetic and Fast Robust Geometric Predicates", 1997). The exact
code lives in separate, non-inlined functions so that the hot path stays small. Circumcentres
are in ``kernels/vertex`` (one routine for every vertex of every diagram).

Like Shewchuk's, the arithmetic is exact only when no product underflows: every coordinate
must be 0 or at least ``2**-188`` in magnitude, and below ``2**200``. The engine guarantees
that by passing coordinates through ``engine.inputs.working_frame`` (an exact power-of-two
scaling that rounds only values below ``1e-57`` of the extent).

Never compile these with ``fastmath``: the error-free transformations below depend on
IEEE round-to-nearest and on the absence of fused multiply-add contraction.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT
from .expansion import (
    cross,
    drop_zeros,
    expansion_sum,
    grow,
    multiply,
    square_sum,
    sum3,
    two_diff,
    two_product,
)

_EPS = 2.0**-53
_CCW_BOUND = (3.0 + 16.0 * _EPS) * _EPS
_ICC_BOUND = (10.0 + 96.0 * _EPS) * _EPS
# Shewchuk's stage B and C bounds for incircle (see ``_incircle_adapt``); stage C's is
# padded from his 44 + 576 eps to leave room for the rounding of the bound itself.
_ICC_BOUND_B = (4.0 + 48.0 * _EPS) * _EPS
_ICC_BOUND_C = (48.0 + 1024.0 * _EPS) * _EPS * _EPS
_RESULT_BOUND = (3.0 + 8.0 * _EPS) * _EPS


@njit(**NJIT)
def _orient_exact(ax, ay, bx, by, cx, cy):
    """Exact sign of orient2d from the untranslated 3x3 determinant."""
    t1 = np.zeros(4)
    t2 = np.zeros(4)
    t3 = np.zeros(4)
    s = np.zeros(8)
    r = np.zeros(12)
    cross(ax, ay, bx, by, t1)
    cross(bx, by, cx, cy, t2)
    cross(cx, cy, ax, ay, t3)
    four = np.int64(4)  # not a literal: numba would compile the callee once more for it
    slen = expansion_sum(t1, four, t2, four, s)
    rlen = expansion_sum(s, slen, t3, four, r)
    return r[rlen - 1]


@njit(**NJIT)
def orient2d(ax, ay, bx, by, cx, cy):
    """Sign-exact orientation of ``a, b, c``: > 0 counter-clockwise, < 0 clockwise, 0 collinear."""
    detleft = (ax - cx) * (by - cy)
    detright = (ay - cy) * (bx - cx)
    det = detleft - detright
    detsum = abs(detleft) + abs(detright)
    if abs(det) >= _CCW_BOUND * detsum:
        return det
    return _orient_exact(ax, ay, bx, by, cx, cy)


@njit(**NJIT)
def _incircle_translated_exact(adx, ady, bdx, bdy, cdx, cdy):
    """Exact incircle of the differences ``adx = ax - dx`` etc. taken as exact doubles.

    Returns ``(top, estimate, length)``: the most significant component of the exact
    determinant (its sign is the determinant's), the floating-point sum of all components
    and the number of components (for the estimate's error bound).
    """
    # one allocation, carved into views: a product of 4- by 4-component expansions has at
    # most 32 components, the sum of three at most 96
    buf = np.zeros(16 + 3 * 128)
    lift = buf[0:4]
    minor = buf[4:8]
    tmp = buf[8:16]
    acc = buf[16:144]
    prod = buf[144:272]
    total = buf[272:400]
    tlen = np.int64(0)
    for k in range(3):
        if k == 0:
            llen = square_sum(adx, ady, lift)
            cross(bdx, bdy, cdx, cdy, minor)
        elif k == 1:
            llen = square_sum(bdx, bdy, lift)
            cross(cdx, cdy, adx, ady, minor)
        else:
            llen = square_sum(cdx, cdy, lift)
            cross(adx, ady, bdx, bdy, minor)
        # differences with few bits or zeros (grids, integers) leave zero components:
        # dropping them makes the product cheaper
        mlen = drop_zeros(minor, np.int64(4))
        llen = drop_zeros(lift, llen)
        if mlen * llen <= 8:
            # few components (grids, integers): add the exact partial products to the total
            # one by one, cheaper than forming the product expansion and merging it
            for i in range(mlen):
                for j in range(llen):
                    p1, p0 = two_product(minor[i], lift[j])
                    tlen = grow(total, tlen, p0)
                    tlen = grow(total, tlen, p1)
            continue
        plen = multiply(minor, mlen, lift, llen, prod, tmp, acc)
        nlen = expansion_sum(total, tlen, prod, plen, acc)
        for i in range(nlen):
            total[i] = acc[i]
        tlen = nlen
    est = 0.0
    for i in range(tlen):
        est += total[i]
    return total[tlen - 1], est, tlen


@njit(**NJIT)
def _incircle_full_exact(ax, ay, bx, by, cx, cy, dx, dy):
    """Exact incircle from the untranslated 4x4 lifted determinant.

    Expanding along the lifted column gives
    ``lift(a) o(b,c,d) - lift(b) o(a,c,d) + lift(c) o(a,b,d) - lift(d) o(a,b,c)`` where
    ``o(p,q,r) = pq + qr + rp`` and ``pq = px * qy - qx * py``.
    """
    # one allocation, carved into views (see the sizes below)
    buf = np.zeros(32 + 8 + 12 + 4 + 24 + 3 * 400)
    ab = buf[0:4]
    bc = buf[4:8]
    cd = buf[8:12]
    da = buf[12:16]
    ac = buf[16:20]
    ca = buf[20:24]
    bd = buf[24:28]
    db = buf[28:32]
    cross(ax, ay, bx, by, ab)
    cross(bx, by, cx, cy, bc)
    cross(cx, cy, dx, dy, cd)
    cross(dx, dy, ax, ay, da)
    cross(ax, ay, cx, cy, ac)
    cross(bx, by, dx, dy, bd)
    for i in range(4):
        ca[i] = -ac[i]
        db[i] = -bd[i]
    tmp8 = buf[32:40]
    minor = buf[40:52]  # sum of three 4-component expansions
    lift = buf[52:56]
    stmp = buf[56:80]  # a 12-component minor scaled by one double
    acc = buf[80:480]  # products have at most 96 components, their sum at most 384
    prod = buf[480:880]
    total = buf[880:1280]
    tlen = np.int64(0)
    four = np.int64(4)
    for k in range(4):
        if k == 0:
            mlen = sum3(bc, four, cd, four, db, four, minor, tmp8)
            llen = square_sum(ax, ay, lift)
            sign = 1.0
        elif k == 1:
            mlen = sum3(ac, four, cd, four, da, four, minor, tmp8)
            llen = square_sum(bx, by, lift)
            sign = -1.0
        elif k == 2:
            mlen = sum3(ab, four, bd, four, da, four, minor, tmp8)
            llen = square_sum(cx, cy, lift)
            sign = 1.0
        else:
            mlen = sum3(ab, four, bc, four, ca, four, minor, tmp8)
            llen = square_sum(dx, dy, lift)
            sign = -1.0
        for i in range(llen):
            lift[i] = sign * lift[i]
        plen = multiply(minor, mlen, lift, llen, prod, stmp, acc)
        nlen = expansion_sum(total, tlen, prod, plen, acc)
        for i in range(nlen):
            total[i] = acc[i]
        tlen = nlen
    return total[tlen - 1]


@njit(**NJIT)
def _incircle_adapt(ax, ay, bx, by, cx, cy, dx, dy, permanent):
    """Incircle after the float filter failed: Shewchuk's stages B and C, then exact.

    ``permanent`` is :func:`_incircle_float`'s. Let ``D`` be the true determinant, ``adx``
    etc. the rounded differences and ``adxt`` etc. their tails, ``|adxt| <= eps |adx|``.

    * Stage B: ``B``, the determinant of the rounded differences, is computed exactly. Each
      of its 12 degree-4 monomials moves by a relative ``(1 + eps)**4 - 1`` when the tails
      are added, so ``|D - B| <= (4 + 48 eps) eps * permanent`` (the permanent's own 7
      roundings included). With no tails ``B`` is ``D``. The estimate ``E`` (the float sum
      of ``B``'s ``n`` components, nonoverlapping so their magnitudes add up to less than
      ``2 |top|``) is within ``slack = (2 n + 4) eps |top|`` of ``B``.
    * Stage C: ``E`` plus the first-order terms in the tails; what is left out is below
      ``6 eps**2 * permanent``, and the rounding of the first-order terms below
      ``34 eps**2 * permanent`` (bounded by Shewchuk's ``(44 + 576 eps) eps**2``, padded
      here), plus ``slack`` and Shewchuk's ``(3 + 8 eps) eps |E|`` for the final sum.
    * Otherwise the untranslated 4x4 determinant in expansion arithmetic decides.
    """
    adx, adxt = two_diff(ax, dx)
    ady, adyt = two_diff(ay, dy)
    bdx, bdxt = two_diff(bx, dx)
    bdy, bdyt = two_diff(by, dy)
    cdx, cdxt = two_diff(cx, dx)
    cdy, cdyt = two_diff(cy, dy)
    top, est, n = _incircle_translated_exact(adx, ady, bdx, bdy, cdx, cdy)
    if adxt == 0.0 and adyt == 0.0 and bdxt == 0.0 and bdyt == 0.0 and cdxt == 0.0 and cdyt == 0.0:
        return top
    slack = (2.0 * n + 4.0) * _EPS * abs(top)
    if abs(est) > _ICC_BOUND_B * permanent + slack:
        return est
    alift = adx * adx + ady * ady
    blift = bdx * bdx + bdy * bdy
    clift = cdx * cdx + cdy * cdy
    det = est + (
        (
            alift * ((bdx * cdyt + cdy * bdxt) - (bdy * cdxt + cdx * bdyt))
            + 2.0 * (adx * adxt + ady * adyt) * (bdx * cdy - bdy * cdx)
        )
        + (
            blift * ((cdx * adyt + ady * cdxt) - (cdy * adxt + adx * cdyt))
            + 2.0 * (bdx * bdxt + bdy * bdyt) * (cdx * ady - cdy * adx)
        )
        + (
            clift * ((adx * bdyt + bdy * adxt) - (ady * bdxt + bdx * adyt))
            + 2.0 * (cdx * cdxt + cdy * cdyt) * (adx * bdy - ady * bdx)
        )
    )
    if abs(det) > _ICC_BOUND_C * permanent + _RESULT_BOUND * abs(est) + slack:
        return det
    return _incircle_full_exact(ax, ay, bx, by, cx, cy, dx, dy)


@njit(**NJIT)
def _incircle_float(ax, ay, bx, by, cx, cy, dx, dy):
    """The incircle determinant in floating point and its permanent (for the error bound)."""
    adx = ax - dx
    ady = ay - dy
    bdx = bx - dx
    bdy = by - dy
    cdx = cx - dx
    cdy = cy - dy
    bdxcdy = bdx * cdy
    cdxbdy = cdx * bdy
    alift = adx * adx + ady * ady
    cdxady = cdx * ady
    adxcdy = adx * cdy
    blift = bdx * bdx + bdy * bdy
    adxbdy = adx * bdy
    bdxady = bdx * ady
    clift = cdx * cdx + cdy * cdy
    det = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady)
    permanent = (
        (abs(bdxcdy) + abs(cdxbdy)) * alift
        + (abs(cdxady) + abs(adxcdy)) * blift
        + (abs(adxbdy) + abs(bdxady)) * clift
    )
    return det, permanent


@njit(**NJIT)
def incircle(ax, ay, bx, by, cx, cy, dx, dy):
    """Sign-exact incircle test: > 0 when ``d`` is inside the circle of CCW ``a, b, c``."""
    det, permanent = _incircle_float(ax, ay, bx, by, cx, cy, dx, dy)
    if abs(det) > _ICC_BOUND * permanent:
        return det
    return _incircle_adapt(ax, ay, bx, by, cx, cy, dx, dy, permanent)


@njit(**NJIT)
def orient2d_fast(ax, ay, bx, by, cx, cy):
    """Filtered orient2d: the value when its sign is certain, else NaN (no exact fallback).

    Kernels that run a fast pass first use this and redo the work with :func:`orient2d` when
    they see a NaN, so that the large exact code stays out of their hot loop.
    """
    detleft = (ax - cx) * (by - cy)
    detright = (ay - cy) * (bx - cx)
    det = detleft - detright
    if abs(det) >= _CCW_BOUND * (abs(detleft) + abs(detright)) and det != 0.0:
        return det
    return np.nan


@njit(**NJIT)
def incircle_fast(ax, ay, bx, by, cx, cy, dx, dy):
    """Filtered incircle: the value when its sign is certain, else NaN (see orient2d_fast)."""
    det, permanent = _incircle_float(ax, ay, bx, by, cx, cy, dx, dy)
    if abs(det) > _ICC_BOUND * permanent:
        return det
    return np.nan


@njit(**NJIT)
def _cross_diff_exact(ax, ay, bx, by, cx, cy, dx, dy):
    """Exact sign of ``(bx - ax) (dy - cy) - (by - ay) (dx - cx)`` by expansions."""
    p = np.zeros(2)
    q = np.zeros(2)
    h1 = np.zeros(8)
    h2 = np.zeros(8)
    tmp = np.zeros(8)
    acc = np.zeros(16)
    out = np.zeros(16)
    two = np.int64(2)  # not a literal (see _orient_exact)
    p[1], p[0] = two_diff(bx, ax)
    q[1], q[0] = two_diff(dy, cy)
    l1 = multiply(p, two, q, two, h1, tmp, acc)
    p[1], p[0] = two_diff(ay, by)  # the second product negated
    q[1], q[0] = two_diff(dx, cx)
    l2 = multiply(p, two, q, two, h2, tmp, acc)
    n = expansion_sum(h1, l1, h2, l2, out)
    return out[n - 1]


@njit(**NJIT)
def cross_diff(ax, ay, bx, by, cx, cy, dx, dy):
    """Sign-exact cross product of the vectors ``b - a`` and ``d - c``.

    Positive when ``d - c`` points to the left of ``b - a``. All eight values are floats; the
    differences are not rounded first (a float filter, the exact expansion when it cannot
    decide).
    """
    ux = bx - ax
    uy = by - ay
    vx = dx - cx
    vy = dy - cy
    left = ux * vy
    right = uy * vx
    det = left - right
    if abs(det) >= 8.0 * _EPS * (abs(left) + abs(right)) and det == det:
        return det
    return _cross_diff_exact(ax, ay, bx, by, cx, cy, dx, dy)


@njit(**NJIT)
def _parabola_gap_exact(sx, px, py, qx, qy, sweep):
    """Exact sign of :func:`parabola_gap` by expansions of the differences."""
    hp = np.zeros(2)
    hq = np.zeros(2)
    d = np.zeros(2)
    sq1 = np.zeros(8)
    sq2 = np.zeros(8)
    s = np.zeros(16)
    t1 = np.zeros(64)
    t2 = np.zeros(64)
    tmp = np.zeros(32)
    acc = np.zeros(64)
    out = np.zeros(128)
    two = np.int64(2)  # not a literal (see _orient_exact)
    hp[1], hp[0] = two_diff(sweep, py)
    hq[1], hq[0] = two_diff(sweep, qy)
    d[1], d[0] = two_diff(sx, qx)
    n1 = multiply(d, two, d, two, sq1, tmp, acc)
    n2 = multiply(hq, two, hq, two, sq2, tmp, acc)
    ns = expansion_sum(sq1, n1, sq2, n2, s)
    l1 = multiply(s, ns, hp, two, t1, tmp, acc)
    d[1], d[0] = two_diff(sx, px)
    n1 = multiply(d, two, d, two, sq1, tmp, acc)
    n2 = multiply(hp, two, hp, two, sq2, tmp, acc)
    ns = expansion_sum(sq1, n1, sq2, n2, s)
    hq[0] = -hq[0]  # the second product negated
    hq[1] = -hq[1]
    l2 = multiply(s, ns, hq, two, t2, tmp, acc)
    n = expansion_sum(t1, l1, t2, l2, out)
    return out[n - 1]


#: :func:`parabola_gap`'s filter, relative to ``t1 + t2`` (six roundings in each product of
#: rounded differences, one in their difference).
_GAP_BOUND = (8.0 + 64.0 * _EPS) * _EPS


@njit(**NJIT)
def parabola_gap(sx, px, py, qx, qy, sweep):
    """Sign-exact ``hp ((sx - qx)^2 + hq^2) - hq ((sx - px)^2 + hp^2)``.

    ``hp = sweep - py > 0`` and ``hq = sweep - qy > 0`` are the sites' distances below a
    sweep line ``y = sweep``. Divided by ``2 hp hq`` it is ``dq - dp``, where
    ``dp = ((sx - px)^2 + hp^2) / (2 hp)`` is how far below the line ``p``'s parabola (the
    points as far from ``p`` as from the line) lies at ``x = sx``: negative when ``q``'s
    parabola is nearer the line there (Fortune's breakpoint test,
    ``kernels/fortune._right_of``). A float filter, the exact expansion when it cannot
    decide.
    """
    u = sx - px
    v = sx - qx
    hp = sweep - py
    hq = sweep - qy
    t1 = hp * (v * v + hq * hq)
    t2 = hq * (u * u + hp * hp)
    f = t1 - t2
    if abs(f) >= _GAP_BOUND * (t1 + t2):
        return f
    return _parabola_gap_exact(sx, px, py, qx, qy, sweep)
