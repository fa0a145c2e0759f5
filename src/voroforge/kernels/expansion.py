"""Exact floating-point expansions: the arithmetic under the robust predicates.

An *expansion* is a sum of doubles ordered by increasing magnitude whose components do not
overlap; it represents a real number exactly. The error-free transformations (``two_sum``,
``two_product``) and the expansion operations here (sum, scaling, product, growth by one
double) are Shewchuk's ("Adaptive Precision Floating-Point Arithmetic and Fast Robust
Geometric Predicates", 1997). ``predicates`` builds orient2d and incircle from them (and
orient3d/insphere will be built the same way).

Never compile these with ``fastmath``: they depend on IEEE round-to-nearest and on the
absence of fused multiply-add contraction.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT

_SPLITTER = 2.0**27 + 1.0


@njit(**NJIT)
def two_sum(a, b):
    """``a + b`` as the double nearest to it and the exact error (Knuth)."""
    x = a + b
    bv = x - a
    av = x - bv
    return x, (a - av) + (b - bv)


@njit(**NJIT)
def two_diff(a, b):
    """``a - b`` as the double nearest to it and the exact error."""
    x = a - b
    bv = a - x
    av = x + bv
    return x, (a - av) + (bv - b)


@njit(**NJIT)
def split(a):
    """``a`` as two halves of 26 bits each, ``hi + lo == a`` (Dekker)."""
    c = _SPLITTER * a
    big = c - a
    hi = c - big
    return hi, a - hi


@njit(**NJIT)
def two_product(a, b):
    """``a * b`` as the double nearest to it and the exact error (Dekker)."""
    x = a * b
    ahi, alo = split(a)
    bhi, blo = split(b)
    err = x - ahi * bhi
    err -= alo * bhi
    err -= ahi * blo
    return x, alo * blo - err


@njit(**NJIT)
def two_two_diff(a1, a0, b1, b0, out):
    """Store the 4-component expansion ``(a1 + a0) - (b1 + b0)`` in ``out``."""
    i, x0 = two_diff(a0, b0)
    j, r0 = two_sum(a1, i)
    i, x1 = two_diff(r0, b1)
    x3, x2 = two_sum(j, i)
    out[0] = x0
    out[1] = x1
    out[2] = x2
    out[3] = x3
    return np.int64(4)  # typed: a literal return makes callers compile for Literal[int](4)


@njit(**NJIT)
def expansion_sum(e, elen, f, flen, h):
    """Exact sum of two nonoverlapping expansions into ``h``; returns its length.

    Zero components are dropped. ``h`` needs room for ``elen + flen`` components.
    """
    if elen == 0:
        for i in range(flen):
            h[i] = f[i]
        return flen
    if flen == 0:
        for i in range(elen):
            h[i] = e[i]
        return elen
    ei = 0
    fi = 0
    enow = e[0]
    fnow = f[0]
    if (fnow > enow) == (fnow > -enow):
        q = enow
        ei += 1
    else:
        q = fnow
        fi += 1
    hlen = 0
    if ei < elen and fi < flen:
        enow = e[ei]
        fnow = f[fi]
        if (fnow > enow) == (fnow > -enow):
            q, hh = two_sum(enow, q)  # fast_two_sum is valid here but two_sum is safe
            ei += 1
        else:
            q, hh = two_sum(fnow, q)
            fi += 1
        if hh != 0.0:
            h[hlen] = hh
            hlen += 1
        while ei < elen and fi < flen:
            enow = e[ei]
            fnow = f[fi]
            if (fnow > enow) == (fnow > -enow):
                q, hh = two_sum(q, enow)
                ei += 1
            else:
                q, hh = two_sum(q, fnow)
                fi += 1
            if hh != 0.0:
                h[hlen] = hh
                hlen += 1
    while ei < elen:
        q, hh = two_sum(q, e[ei])
        ei += 1
        if hh != 0.0:
            h[hlen] = hh
            hlen += 1
    while fi < flen:
        q, hh = two_sum(q, f[fi])
        fi += 1
        if hh != 0.0:
            h[hlen] = hh
            hlen += 1
    if q != 0.0 or hlen == 0:
        h[hlen] = q
        hlen += 1
    return hlen


@njit(**NJIT)
def scale_expansion(e, elen, b, h):
    """Exact product of an expansion and a double into ``h`` (room for ``2 * elen``)."""
    bhi, blo = split(b)
    hlen = 0
    x = e[0] * b
    ahi, alo = split(e[0])
    err = x - ahi * bhi
    err -= alo * bhi
    err -= ahi * blo
    q = x
    hh = alo * blo - err
    if hh != 0.0:
        h[hlen] = hh
        hlen += 1
    for i in range(1, elen):
        enow = e[i]
        p1 = enow * b
        ahi, alo = split(enow)
        err = p1 - ahi * bhi
        err -= alo * bhi
        err -= ahi * blo
        p0 = alo * blo - err
        s, hh = two_sum(q, p0)
        if hh != 0.0:
            h[hlen] = hh
            hlen += 1
        q = p1 + s
        hh = s - (q - p1)
        if hh != 0.0:
            h[hlen] = hh
            hlen += 1
    if q != 0.0 or hlen == 0:
        h[hlen] = q
        hlen += 1
    return hlen


@njit(**NJIT)
def multiply(e, elen, f, flen, h, tmp, acc):
    """Exact product of two expansions into ``h``; ``tmp``/``acc`` are scratch buffers."""
    hlen = np.int64(0)  # not a literal: numba would compile expansion_sum once more for it
    for k in range(flen):
        tlen = scale_expansion(e, elen, f[k], tmp)
        alen = expansion_sum(h, hlen, tmp, tlen, acc)
        for i in range(alen):
            h[i] = acc[i]
        hlen = alen
    return hlen


@njit(**NJIT)
def cross(ax, ay, bx, by, out):
    """4-component expansion of ``ax * by - bx * ay``."""
    p1, p0 = two_product(ax, by)
    q1, q0 = two_product(bx, ay)
    return two_two_diff(p1, p0, q1, q0, out)


@njit(**NJIT)
def sum3(p, plen, q, qlen, r, rlen, out, tmp):
    """``out = p + q + r`` for expansions (used for the 3x3 minors of incircle)."""
    tlen = expansion_sum(p, plen, q, qlen, tmp)
    return expansion_sum(tmp, tlen, r, rlen, out)


@njit(**NJIT)
def square_sum(x, y, out):
    """4-component expansion of ``x * x + y * y`` (Two-Two-Sum of the exact squares)."""
    x1, x0 = two_product(x, x)
    y1, y0 = two_product(y, y)
    i, o0 = two_sum(x0, y0)
    j, r0 = two_sum(x1, i)
    i, o1 = two_sum(r0, y1)
    o3, o2 = two_sum(j, i)
    out[0] = o0
    out[1] = o1
    out[2] = o2
    out[3] = o3
    return np.int64(4)  # typed (see two_two_diff)


@njit(**NJIT)
def drop_zeros(e, elen):
    """Remove the zero components of ``e`` in place (keeping one if all are zero)."""
    n = 0
    for i in range(elen):
        if e[i] != 0.0:
            e[n] = e[i]
            n += 1
    if n == 0:
        e[0] = 0.0
        n = 1
    return n


@njit(**NJIT)
def grow(e, elen, b):
    """Add the double ``b`` to the expansion ``e`` exactly, in place; returns the new length.

    Zero components are dropped; ``e`` needs room for ``elen + 1`` components.
    """
    q = b
    hlen = 0
    for i in range(elen):
        q, hh = two_sum(q, e[i])
        if hh != 0.0:
            e[hlen] = hh  # hlen <= i: e[i] was read already
            hlen += 1
    if q != 0.0 or hlen == 0:
        e[hlen] = q
        hlen += 1
    return hlen


@njit(**NJIT)
def estimate(e, elen):
    """The double nearest the expansion's value, to a couple of ulps (summed smallest first)."""
    s = 0.0
    for i in range(elen):
        s += e[i]
    return s


@njit(**NJIT)
def rounded_sum(parts, n, w):
    """The sum of the doubles ``parts[:n]``, within an ulp or so.

    Grown exactly into ``w`` (room for ``n`` components), then :func:`estimate`.
    """
    size = 0
    for k in range(n):
        size = grow(w, size, parts[k])
    return estimate(w, size)


@njit(**NJIT)
def _neg(e, elen):
    for i in range(elen):
        e[i] = -e[i]


@njit(**NJIT)
def _diff2(a, b, out):
    """``a - b`` exactly as an expansion of up to two components; returns its length."""
    hi, lo = two_diff(a, b)
    out[0] = lo
    out[1] = hi
    return drop_zeros(out, np.int64(2))


@njit(**NJIT)
def exact_circumcenter(ax, ay, bx, by, cx, cy):
    """Circumcentre of ``a, b, c`` from exact expansions: each coordinate to a few ulps of itself.

    The centre is ``a + (Ey |D|^2 - Dy |E|^2, Dx |E|^2 - Ex |D|^2) / (2 (Dx Ey - Dy Ex))``
    with ``D = b - a``, ``E = c - a``. Numerators ``ax den + num`` and the denominator are
    exact expansions, so only their two estimates and one division round: the result is
    accurate relative to the centre's own magnitude, not to the sites'. A float formula
    loses all of a sliver's centre to cancellation (sites on a circle: centres meant to lie
    within 1e-16 of each other scatter over 1e-11); this one keeps their order. Collinear
    sites give non-finite coordinates. The argument order changes no bit when the callers
    sort the owners first.
    """
    buf = np.zeros((14, 512))
    # rows by index, not by unpacking: unpacked rows are typed as non-contiguous arrays, and
    # every expansion routine would be compiled once more for them
    dx, dy, ex, ey, t0, t1, t2 = buf[0], buf[1], buf[2], buf[3], buf[4], buf[5], buf[6]
    d2, e2, det, nx, ny, acc, tmp = buf[7], buf[8], buf[9], buf[10], buf[11], buf[12], buf[13]
    ndx = _diff2(bx, ax, dx)
    ndy = _diff2(by, ay, dy)
    nex = _diff2(cx, ax, ex)
    ney = _diff2(cy, ay, ey)
    # det = Dx Ey - Dy Ex
    n0 = multiply(dx, ndx, ey, ney, t0, tmp, acc)
    n1 = multiply(dy, ndy, ex, nex, t1, tmp, acc)
    _neg(t1, n1)
    ndet = expansion_sum(t0, n0, t1, n1, det)
    # |D|^2 and |E|^2
    n0 = multiply(dx, ndx, dx, ndx, t0, tmp, acc)
    n1 = multiply(dy, ndy, dy, ndy, t1, tmp, acc)
    nd2 = expansion_sum(t0, n0, t1, n1, d2)
    n0 = multiply(ex, nex, ex, nex, t0, tmp, acc)
    n1 = multiply(ey, ney, ey, ney, t1, tmp, acc)
    ne2 = expansion_sum(t0, n0, t1, n1, e2)
    # x numerator: 2 ax det + Ey |D|^2 - Dy |E|^2
    n0 = multiply(ey, ney, d2, nd2, t0, tmp, acc)
    n1 = multiply(dy, ndy, e2, ne2, t1, tmp, acc)
    _neg(t1, n1)
    nn = expansion_sum(t0, n0, t1, n1, t2)
    n0 = scale_expansion(det, ndet, 2.0 * ax, t0)
    nnx = expansion_sum(t0, n0, t2, nn, nx)
    # y numerator: 2 ay det + Dx |E|^2 - Ex |D|^2
    n0 = multiply(dx, ndx, e2, ne2, t0, tmp, acc)
    n1 = multiply(ex, nex, d2, nd2, t1, tmp, acc)
    _neg(t1, n1)
    nn = expansion_sum(t0, n0, t1, n1, t2)
    n0 = scale_expansion(det, ndet, 2.0 * ay, t0)
    nny = expansion_sum(t0, n0, t2, nn, ny)
    den = 2.0 * estimate(det, ndet)
    return estimate(nx, nnx) / den, estimate(ny, nny) / den
