"""The exactly nearest of a few candidate sites to one query (``locate``'s near ties).

``locate`` finds candidates with float distances; where several are within rounding of the
nearest (a query equidistant from thousands of sites on a circle), :func:`nearest_of` decides
them in one compiled pass: a float filter on ``|q - p|^2 - w`` with a proven error bound,
then, for the candidates it cannot separate, the exact key as an expansion (each offset
``q - p`` is an exact two-component difference, its square three exact products, the weight
one more component) compared by the sign of a difference of expansions (as the raster's
:mod:`.distance_exact` does). Exact ties go to the lowest site index.

Everything is scaled by one power of two first (exact) so that the squares neither overflow
nor underflow; where the candidates' offsets span too many binades for that (a component
below ``2**-480`` of the scaled frame, an offset that overflows), the kernel answers -1 and
the caller falls back to rationals.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..config import NJIT
from .distance_exact import top_sign
from .expansion import expansion_sum, grow, two_diff, two_product, two_sum

#: the largest scaled offset or ``sqrt(|w|)``: squares and their sums stay
#: below ``2**902``, far from overflow
TOP_EXPONENT = 450
#: nonzero scaled offset components below ``2**-MIN_EXPONENT`` could make a
#: product's error term subnormal (inexact): such candidate sets go back to the caller
MIN_EXPONENT = 480
_U = 2.0**-53
#: float keys within this relative band of their terms' sizes may be exactly nearer (each
#: is a rounded square per axis, a sum and a difference: 16 ulps is generous)
FILTER_ULPS = 16.0
#: the double-double key's rounding, in eps**2 of its terms' sizes (about 5d + 4 roundings
#: of terms below 6 eps of them: under 45 for d = 3, 128 is generous)
DD_ULPS = 128.0
#: absolute part of the float bound: squares of scaled offsets down to 2**-480 may underflow
FILTER_TINY = 2.0**-900


@njit(**NJIT)
def _exact_key(hi, lo, c, wc, out):
    """``sum_a (hi[c, a] + lo[c, a])**2 - wc`` exactly into ``out``; returns its length."""
    n = np.int64(1)
    out[0] = -wc
    for a in range(hi.shape[1]):
        h = hi[c, a]
        g = lo[c, a]
        x, y = two_product(h, h)
        n = grow(out, n, y)
        n = grow(out, n, x)
        if g != 0.0:
            x, y = two_product(2.0 * h, g)
            n = grow(out, n, y)
            n = grow(out, n, x)
            x, y = two_product(g, g)
            n = grow(out, n, y)
            n = grow(out, n, x)
    return n


@njit(**NJIT)
def _dd_key(hi, lo, c, wc):
    """The key of candidate ``c`` as ``t + r`` to about ``2**-100`` of its terms, and a bound.

    ``t`` sums ``-wc`` and the rounded squares ``hi**2`` exactly but for its own rounding,
    whose error goes into ``r`` with the squares' errors and the ``2 hi lo + lo**2`` terms:
    every term of ``r`` is within a few ulps of the key's terms, so ``r``'s rounding is
    below ``DD_ULPS * eps**2`` of them.
    """
    t = -wc
    r = 0.0
    size = abs(wc)
    for a in range(hi.shape[1]):
        h = hi[c, a]
        g = lo[c, a]
        x, y = two_product(h, h)
        t, e = two_sum(t, x)
        r += e + y + (2.0 * h * g + g * g)
        size += x
    return t, r, DD_ULPS * _U * _U * size + FILTER_TINY


@njit(**NJIT)
def nearest_of(q, cand, sites, w):
    """The site of ``cand`` exactly nearest to ``q`` by ``|q - p|^2 - w[p]``, or -1.

    ``q (d,)``, ``cand (k,)`` int64 indices into ``sites (n, d)``, ``w (n,)`` weights or an
    empty array (none). Exact ties go to the lowest index. -1: the offsets cannot be held
    exactly in one scaled frame (see the module docstring); decide in rationals.
    """
    k = len(cand)
    d = len(q)
    weighted = len(w) > 0
    hi = np.zeros((k, d))
    lo = np.zeros((k, d))
    top = 0.0
    for j in range(k):
        c = cand[j]
        for a in range(d):
            x, y = two_diff(q[a], sites[c, a])
            if not math.isfinite(x) or not math.isfinite(y):
                return np.int64(-1)
            hi[j, a] = x
            lo[j, a] = y
            top = max(top, abs(x))
        if weighted:
            if not math.isfinite(w[c]):
                return np.int64(-1)
            top = max(top, math.sqrt(abs(w[c])))
    e = 0
    if top > 0.0:
        e = TOP_EXPONENT - math.frexp(top)[1]
    floor = math.ldexp(1.0, -MIN_EXPONENT)
    ws = np.zeros(k)
    # lossy: a component below the floor once scaled (rounded, or gone to 0 in the scaling,
    # or its square's error term subnormal); the float filter's bound still holds for it
    lossy = np.zeros(k, np.bool_)
    for j in range(k):
        for a in range(d):
            for v in (hi[j, a], lo[j, a]):
                if v != 0.0 and abs(math.ldexp(v, e)) < floor:
                    lossy[j] = True
            hi[j, a] = math.ldexp(hi[j, a], e)
            lo[j, a] = math.ldexp(lo[j, a], e)
        if weighted:
            ws[j] = math.ldexp(w[cand[j]], 2 * e)
            if w[cand[j]] != 0.0 and abs(ws[j]) < 2.0**-1022:
                lossy[j] = True  # a weight that lost bits in the scaling
    # float filter: key = sum hi^2 - w, within FILTER_ULPS of its terms' sizes of the exact
    f = np.zeros(k)
    err = np.zeros(k)
    bound = np.inf
    for j in range(k):
        s = 0.0
        for a in range(d):
            s += hi[j, a] * hi[j, a]
        f[j] = s - ws[j]
        err[j] = FILTER_ULPS * _U * (s + abs(ws[j])) + FILTER_TINY
        bound = min(bound, f[j] + err[j])
    buf = np.zeros((3, 16 * d + 8))  # keys: 6d + 1 components; their difference twice that
    best = -1
    nb = np.int64(-1)  # length of best's exact key in buf[0]; -1: not computed yet
    tb = rb = eb = 0.0
    for j in range(k):
        if f[j] - err[j] > bound:
            continue
        if lossy[j]:
            return np.int64(-1)
        t, r, ej = _dd_key(hi, lo, j, ws[j])
        if best < 0:
            best, tb, rb, eb = j, t, r, ej
            continue
        # double-double filter: sign of key(j) - key(best) where the bounds decide it
        dh, dl = two_diff(t, tb)
        v = dh + (dl + (r - rb))
        margin = ej + eb + 3.0 * _U * (abs(dl) + abs(r) + abs(rb)) + 2.0 * _U * abs(v)
        if v > margin:
            continue
        if v < -margin:
            best, tb, rb, eb, nb = j, t, r, ej, np.int64(-1)
            continue
        if nb < 0:
            nb = _exact_key(hi, lo, best, ws[best], buf[0])
        nc = _exact_key(hi, lo, j, ws[j], buf[1])
        for i in range(nb):
            buf[0, i] = -buf[0, i]
        m = expansion_sum(buf[1], nc, buf[0], nb, buf[2])
        for i in range(nb):
            buf[0, i] = -buf[0, i]
        sign = top_sign(buf[2], m)
        if sign < 0 or (sign == 0 and cand[j] < cand[best]):
            best, tb, rb, eb = j, t, r, ej
            for i in range(nc):
                buf[0, i] = buf[1, i]
            nb = nc
    return cand[best]
