"""The exact vertex solve's rounding, and its double-double stage with a proven bound.

:func:`.predicates3d.vertex_offset` solves the vertex of three owner planes less a point
``c``: coordinate ``q`` is ``-D4_q / (2 D3)`` of exact determinants (Cramer's rule, rows as
in :mod:`.predicates3d`), and each determinant is rounded to its nearest double
(:func:`nearest`, ties to even) before the one division. The value is then a function of
the exact determinants alone, not of how they were summed, so a cheaper evaluation that
proves it knows the nearest double gives the same bits: :func:`vertex_dd` evaluates the
determinants in double-double with a proven bound and returns their nearest doubles when
no rounding boundary lies within the bound (a many-faced cell's vertices: their
determinants are ill-conditioned to ~1e-3 of their terms, and double-double keeps ~1e-30),
else leaves them to the expansions.
"""

from __future__ import annotations

import numba
import numpy as np
from llvmlite import ir
from numba import njit, types
from numba.core import cgutils
from numba.extending import intrinsic

from ..config import NJIT
from .expansion import estimate, expansion_sum, two_diff, two_product, two_sum

_EPS = 2.0**-53
#: every double-double operation errs by at most 8 u^2 of its operands' magnitudes (the
#: sum's or the product's; u = 2**-53: see :mod:`.insphere_dd`), so a value whose circuit
#: multiplies and adds with an exponent ``e`` (a product adds its operands' exponents plus
#: one, a sum takes the larger plus one) errs by at most ``((1 + 8 u^2)**e - 1)`` of its
#: permanent (the same circuit on absolute values). The largest here is 12 (a wall's lift:
#: six sums; times a 2x2 minor, 2; three sums; plus ``t D3``): 24, padded
_DD_REL = 24.0 * 8.0 * _EPS * _EPS * (1.0 + 1e-12)
#: the permanents are taken from the heads (``|h + l| <= (1 + u) |h|``, degree <= 5) and
#: summed in floats (<= 20 roundings): their own padding
_PERM_PAD = 1.0 + 64.0 * _EPS


@njit(**NJIT)
def nearest(e, n, tmp):
    """The double nearest to the expansion ``e[:n]`` (ties to even): its correct rounding.

    ``estimate`` (the components summed smallest first) is within an ulp of it; the exact
    signs of ``e`` less the midpoints beside that candidate (each a two-term expansion)
    move it to the nearest. ``tmp`` needs ``n + 2`` components. Exact unless the midpoints
    fall below the normal range (the working frame keeps the determinants above it).
    """
    h = estimate(e, n)
    mid = tmp[n + 2 : n + 4]
    for _ in range(4):
        if h == 0.0 or not abs(h) < np.inf:
            return h
        up = np.nextafter(h, np.inf)
        dn = np.nextafter(h, -np.inf)
        mid[0] = -0.5 * (up - h)  # e - (h + (up - h) / 2), exactly
        mid[1] = -h
        m = expansion_sum(e, n, mid, 2, tmp)
        s_up = tmp[m - 1]
        if s_up > 0.0:
            h = up
            continue
        mid[0] = 0.5 * (h - dn)  # e - (h - (h - dn) / 2)
        m = expansion_sum(e, n, mid, 2, tmp)
        s_dn = tmp[m - 1]
        if s_dn < 0.0:
            h = dn
            continue
        if s_up == 0.0 or s_dn == 0.0:  # a tie: the neighbour of even significand
            mid[0] = h
            if mid[0:1].view(np.int64)[0] & 1:
                h = up if s_up == 0.0 else dn
        return h
    return h


@njit(**{**NJIT, "inline": "always"})
def _dd_add(ah, al, bh, bl):
    """``a + b`` in double-double (errs by at most ``4 u^2 (|a| + |b|)``; as insphere_dd)."""
    s, e = two_sum(ah, bh)
    e = e + (al + bl)
    return two_sum(s, e)


@njit(**{**NJIT, "inline": "always"})
def _dd_mul(ah, al, bh, bl):
    """``a b`` in double-double (errs by at most ``8 u^2 |a| |b|``; as insphere_dd)."""
    p, e = two_product(ah, bh)
    e = e + (ah * bl + al * bh)
    return two_sum(p, e)


@intrinsic
def _fma(typingctx, a, b, c):
    """``a * b + c`` rounded once (llvm.fma.f64)."""
    sig = types.float64(types.float64, types.float64, types.float64)

    def codegen(context, builder, signature, args):
        d = ir.DoubleType()
        fnty = ir.FunctionType(d, [d, d, d])
        fn = cgutils.get_or_insert_function(builder.module, fnty, "llvm.fma.f64")
        return builder.call(fn, args)

    return sig, codegen


@njit(**{**NJIT, "inline": "always"})
def _two_product_fma(a, b):
    """``a * b`` and its exact error (one fused multiply-add): :func:`two_product`'s values."""
    x = a * b
    return x, _fma(a, b, -x)


if numba.config.DISABLE_JIT:  # kernels run as Python (coverage): Dekker's, the same values

    def _two_product_fma(a, b):
        return two_product(a, b)


@njit(**{**NJIT, "inline": "always"})
def _dd_mul_fma(ah, al, bh, bl):
    """:func:`_dd_mul` with the fused product: the same values (the error term is exact)."""
    p, e = _two_product_fma(ah, bh)
    e = e + (ah * bl + al * bh)
    return two_sum(p, e)


@njit(**{**NJIT, "inline": "always"})
def _sure(hi, lo, perm):
    """Whether ``hi`` is the nearest double of every value within the bound of ``hi + lo``.

    The values lie within ``lo`` plus the bound of ``hi``; they round to ``hi`` when they
    stay short of the midpoints to its neighbours (half of each gap: exact powers of two).
    The two sums with ``lo`` round by at most ``u`` of themselves (then ``4 u`` off the gap
    covers it; a negative sum is below it whatever its rounding).
    """
    if not abs(hi) > 1e-250:
        return False
    err = (_DD_REL * perm * _PERM_PAD + 1e-290) * (1.0 + 4.0 * _EPS)
    half_up = 0.5 * (np.nextafter(hi, np.inf) - hi) * (1.0 - 4.0 * _EPS)
    half_dn = 0.5 * (hi - np.nextafter(hi, -np.inf)) * (1.0 - 4.0 * _EPS)
    return lo + err < half_up and lo - err > -half_dn


@njit(**NJIT)
def _row(key, a, P, W, WP, ns, R, q):
    """Owner ``key``'s row around site ``a`` into ``R``: heads, tails, magnitudes (4 each).

    A site: ``r = p_key - p_a`` (exact two-term), ``t = |r|^2 + w_a - w_key``; a wall
    ``n . (x - o) <= d``: ``r = n``, ``t = 2 d - 2 n . p_a + 2 n . o`` (the exact stage's
    ``_put_wall``). ``R[0:12]`` heads, ``R[12:24]`` tails, ``R[24:36]`` magnitudes.
    """
    H = R[q * 4 : q * 4 + 4]
    L = R[12 + q * 4 : 12 + q * 4 + 4]
    A = R[24 + q * 4 : 24 + q * 4 + 4]
    if key < ns:
        th, tl = two_diff(W[a], W[key])
        A[3] = abs(W[a]) + abs(W[key])
        for c in range(3):
            h, lo = two_diff(P[key, c], P[a, c])
            H[c] = h
            L[c] = lo
            A[c] = abs(h)
            sh, sl = _dd_mul(h, lo, h, lo)
            th, tl = _dd_add(th, tl, sh, sl)
            A[3] += A[c] * A[c]
    else:
        w = key - ns
        th = 2.0 * WP[w, 3]
        tl = 0.0
        A[3] = abs(th)
        for c in range(3):
            nc = WP[w, c]
            H[c] = nc
            L[c] = 0.0
            A[c] = abs(nc)
            ph, pl = two_product(-2.0 * nc, P[a, c])
            th, tl = _dd_add(th, tl, ph, pl)
            A[3] += abs(ph)
            if WP.shape[1] > 4 and WP[w, 4 + c] != 0.0:
                ph, pl = two_product(2.0 * nc, WP[w, 4 + c])
                th, tl = _dd_add(th, tl, ph, pl)
                A[3] += abs(ph)
    H[3] = th
    L[3] = tl


@njit(**NJIT)
def vertex_dd(a, k0, k1, k2, P, W, WP, ns, cx, cy, cz, R, x):
    """:func:`.predicates3d.vertex_offset`'s value from double-double, or False (unsure).

    The same ``x_q = -RN(D4_q) / (2 RN(D3))`` (RN: the nearest double) as the exact stage,
    written into ``x (3,)`` only when each of the four determinants' nearest double is
    proven (:func:`_sure`); a zero ``D3`` (no vertex) is always left to the exact stage.
    ``D4_q`` is expanded along the row of the plane ``x_q = c_q``:
    ``(-1)**(q + 1) M_q + t D3`` with ``M_q`` the rows' minor without column ``q`` and
    ``t = 2 (c_q - p_a,q)`` (exact two-term). ``R`` is scratch of 63 components.
    """
    _row(k0, a, P, W, WP, ns, R, np.int64(0))  # not literals: one compile of _row, not three
    _row(k1, a, P, W, WP, ns, R, np.int64(1))
    _row(k2, a, P, W, WP, ns, R, np.int64(2))
    H = R[0:12]
    L = R[12:24]
    A = R[24:36]
    M = R[36:63]  # the 2x2 minors of r without row k and column q: head, tail, permanent
    for k in range(3):
        b = 1 if k == 0 else 0
        e = 1 if k == 2 else 2
        for q in range(3):
            c0 = 1 if q == 0 else 0
            c1 = 1 if q == 2 else 2
            xh, xl = _dd_mul(H[b * 4 + c0], L[b * 4 + c0], H[e * 4 + c1], L[e * 4 + c1])
            yh, yl = _dd_mul(H[b * 4 + c1], L[b * 4 + c1], H[e * 4 + c0], L[e * 4 + c0])
            mh, ml = _dd_add(xh, xl, -yh, -yl)
            m = (k * 3 + q) * 3
            M[m] = mh
            M[m + 1] = ml
            M[m + 2] = A[b * 4 + c0] * A[e * 4 + c1] + A[b * 4 + c1] * A[e * 4 + c0]
    d3h = 0.0
    d3l = 0.0
    p3 = 0.0
    for q in range(3):  # D3 along row 0: + r00 m(0, 0) - r01 m(0, 1) + r02 m(0, 2)
        th, tl = _dd_mul(H[q], L[q], M[q * 3], M[q * 3 + 1])
        if q == 1:
            th = -th
            tl = -tl
        d3h, d3l = _dd_add(d3h, d3l, th, tl)
        p3 += A[q] * M[q * 3 + 2]
    if not _sure(d3h, d3l, p3):
        return False
    for q in range(3):
        # M_q along the lift column: t0 m(0, q) - t1 m(1, q) + t2 m(2, q)
        sh = 0.0
        sl = 0.0
        ps = 0.0
        for k in range(3):
            m = (k * 3 + q) * 3
            th, tl = _dd_mul(H[k * 4 + 3], L[k * 4 + 3], M[m], M[m + 1])
            if k == 1:
                th = -th
                tl = -tl
            sh, sl = _dd_add(sh, sl, th, tl)
            ps += A[k * 4 + 3] * M[m + 2]
        if q != 1:  # (-1)**(q + 1)
            sh = -sh
            sl = -sl
        cq = cx if q == 0 else (cy if q == 1 else cz)
        uh, ul = two_diff(cq, P[a, q])
        uh *= 2.0
        ul *= 2.0
        th, tl = _dd_mul(uh, ul, d3h, d3l)
        sh, sl = _dd_add(sh, sl, th, tl)
        ps += abs(uh) * p3
        if not _sure(sh, sl, ps):
            return False
        R[q] = sh  # (rows' heads are no longer read)
    for q in range(3):
        x[q] = -R[q] / (2.0 * d3h)
    return True


@njit(**{**NJIT, "inline": "always"})
def _site_row(key, a, P, W, WP, ns):
    """:func:`_row` in locals: ``(h0, h1, h2, l0, l1, l2, m0, m1, m2, th, tl, m3)``.

    Heads, tails and magnitudes of the normal, then the lift's head, tail and magnitude,
    by the same operations in the same order.
    """
    if key < ns:
        th, tl = two_diff(W[a], W[key])
        m3 = abs(W[a]) + abs(W[key])
        h0, l0 = two_diff(P[key, 0], P[a, 0])
        h1, l1 = two_diff(P[key, 1], P[a, 1])
        h2, l2 = two_diff(P[key, 2], P[a, 2])
        m0 = abs(h0)
        m1 = abs(h1)
        m2 = abs(h2)
        sh, sl = _dd_mul_fma(h0, l0, h0, l0)
        th, tl = _dd_add(th, tl, sh, sl)
        m3 += m0 * m0
        sh, sl = _dd_mul_fma(h1, l1, h1, l1)
        th, tl = _dd_add(th, tl, sh, sl)
        m3 += m1 * m1
        sh, sl = _dd_mul_fma(h2, l2, h2, l2)
        th, tl = _dd_add(th, tl, sh, sl)
        m3 += m2 * m2
        return h0, h1, h2, l0, l1, l2, m0, m1, m2, th, tl, m3
    w = key - ns
    th = 2.0 * WP[w, 3]
    tl = 0.0
    m3 = abs(th)
    for c in range(3):
        nc = WP[w, c]
        ph, pl = _two_product_fma(-2.0 * nc, P[a, c])
        th, tl = _dd_add(th, tl, ph, pl)
        m3 += abs(ph)
        if WP.shape[1] > 4 and WP[w, 4 + c] != 0.0:
            ph, pl = _two_product_fma(2.0 * nc, WP[w, 4 + c])
            th, tl = _dd_add(th, tl, ph, pl)
            m3 += abs(ph)
    n0 = WP[w, 0]
    n1 = WP[w, 1]
    n2 = WP[w, 2]
    return n0, n1, n2, 0.0, 0.0, 0.0, abs(n0), abs(n1), abs(n2), th, tl, m3


@njit(**{**NJIT, "inline": "always"})
def _minor(bh0, bh1, bl0, bl1, bm0, bm1, eh0, eh1, el0, el1, em0, em1):
    """The 2x2 minor ``b0 e1 - b1 e0`` in double-double, and its permanent."""
    xh, xl = _dd_mul_fma(bh0, bl0, eh1, el1)
    yh, yl = _dd_mul_fma(bh1, bl1, eh0, el0)
    mh, ml = _dd_add(xh, xl, -yh, -yl)
    return mh, ml, bm0 * em1 + bm1 * em0


@njit(**{**NJIT, "_nrt": False})
def vertex_dd_site(a, k0, k1, k2, P, W, WP, ns):
    """:func:`vertex_dd` about site ``a`` itself (``c = p_a``), without scratch.

    The resettle's and the naming's query (:func:`.predicates3d.vertex_offset` with
    ``c = p_a``): ``t = 2 (c_q - p_a,q)`` is 0, so ``D4_q`` is ``(-1)**(q + 1) M_q`` alone.
    The same double-double operations as :func:`vertex_dd` but that zero term (which
    changes no head or tail; each product's error by one fused multiply-add, the same exact
    term as Dekker's: ``_two_product_fma``), so the same bound holds; each determinant is
    returned only as its proven nearest double, which is what the exact stage returns, so a
    caller may
    fall back on :func:`.predicates3d.vertex_offset` where this is unsure and gets the
    same bits either way. Returns ``(ok, x0, x1, x2)``: ``x = vertex - p_a``.
    """
    a0, a1, a2, al0, al1, al2, am0, am1, am2, at, atl, am3 = _site_row(k0, a, P, W, WP, ns)
    b0, b1, b2, bl0, bl1, bl2, bm0, bm1, bm2, bt, btl, bm3 = _site_row(k1, a, P, W, WP, ns)
    c0, c1, c2, cl0, cl1, cl2, cm0, cm1, cm2, ct, ctl, cm3 = _site_row(k2, a, P, W, WP, ns)
    # minors m(k, q): rows other than k, columns other than q (vertex_dd's M)
    m00h, m00l, m00p = _minor(b1, b2, bl1, bl2, bm1, bm2, c1, c2, cl1, cl2, cm1, cm2)
    m01h, m01l, m01p = _minor(b0, b2, bl0, bl2, bm0, bm2, c0, c2, cl0, cl2, cm0, cm2)
    m02h, m02l, m02p = _minor(b0, b1, bl0, bl1, bm0, bm1, c0, c1, cl0, cl1, cm0, cm1)
    m10h, m10l, m10p = _minor(a1, a2, al1, al2, am1, am2, c1, c2, cl1, cl2, cm1, cm2)
    m11h, m11l, m11p = _minor(a0, a2, al0, al2, am0, am2, c0, c2, cl0, cl2, cm0, cm2)
    m12h, m12l, m12p = _minor(a0, a1, al0, al1, am0, am1, c0, c1, cl0, cl1, cm0, cm1)
    m20h, m20l, m20p = _minor(a1, a2, al1, al2, am1, am2, b1, b2, bl1, bl2, bm1, bm2)
    m21h, m21l, m21p = _minor(a0, a2, al0, al2, am0, am2, b0, b2, bl0, bl2, bm0, bm2)
    m22h, m22l, m22p = _minor(a0, a1, al0, al1, am0, am1, b0, b1, bl0, bl1, bm0, bm1)
    # D3 along row 0: + r00 m(0, 0) - r01 m(0, 1) + r02 m(0, 2)
    d3h = 0.0
    d3l = 0.0
    th, tl = _dd_mul_fma(a0, al0, m00h, m00l)
    d3h, d3l = _dd_add(d3h, d3l, th, tl)
    p3 = am0 * m00p
    th, tl = _dd_mul_fma(a1, al1, m01h, m01l)
    d3h, d3l = _dd_add(d3h, d3l, -th, -tl)
    p3 += am1 * m01p
    th, tl = _dd_mul_fma(a2, al2, m02h, m02l)
    d3h, d3l = _dd_add(d3h, d3l, th, tl)
    p3 += am2 * m02p
    if not _sure(d3h, d3l, p3):
        return False, 0.0, 0.0, 0.0
    # M_q along the lift column: t0 m(0, q) - t1 m(1, q) + t2 m(2, q), negated for q != 1
    s0h, s0l, s0p = _lift(
        at,
        atl,
        am3,
        bt,
        btl,
        bm3,
        ct,
        ctl,
        cm3,
        m00h,
        m00l,
        m00p,
        m10h,
        m10l,
        m10p,
        m20h,
        m20l,
        m20p,
    )
    if not _sure(s0h, s0l, s0p):
        return False, 0.0, 0.0, 0.0
    s1h, s1l, s1p = _lift(
        at,
        atl,
        am3,
        bt,
        btl,
        bm3,
        ct,
        ctl,
        cm3,
        m01h,
        m01l,
        m01p,
        m11h,
        m11l,
        m11p,
        m21h,
        m21l,
        m21p,
    )
    if not _sure(s1h, s1l, s1p):
        return False, 0.0, 0.0, 0.0
    s2h, s2l, s2p = _lift(
        at,
        atl,
        am3,
        bt,
        btl,
        bm3,
        ct,
        ctl,
        cm3,
        m02h,
        m02l,
        m02p,
        m12h,
        m12l,
        m12p,
        m22h,
        m22l,
        m22p,
    )
    if not _sure(s2h, s2l, s2p):
        return False, 0.0, 0.0, 0.0
    # x_q = -D4_q / (2 D3), D4_q = -M_q for q = 0, 2 and +M_1
    d = 2.0 * d3h
    return True, s0h / d, -s1h / d, s2h / d


@njit(**{**NJIT, "inline": "always"})
def _lift(at, atl, am3, bt, btl, bm3, ct, ctl, cm3, mah, mal, map_, mbh, mbl, mbp, mch, mcl, mcp):
    """``t0 m(0, q) - t1 m(1, q) + t2 m(2, q)`` in double-double, and its permanent."""
    sh = 0.0
    sl = 0.0
    th, tl = _dd_mul_fma(at, atl, mah, mal)
    sh, sl = _dd_add(sh, sl, th, tl)
    ps = am3 * map_
    th, tl = _dd_mul_fma(bt, btl, mbh, mbl)
    sh, sl = _dd_add(sh, sl, -th, -tl)
    ps += bm3 * mbp
    th, tl = _dd_mul_fma(ct, ctl, mch, mcl)
    sh, sl = _dd_add(sh, sl, th, tl)
    ps += cm3 * mcp
    return sh, sl, ps
