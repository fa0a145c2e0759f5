"""Exact distance comparisons for the raster's near ties (Euclidean, Manhattan, Chebyshev).

The raster's float keys (squared distance, or the distance for the other metrics) decide a
pixel's nearest site wherever the two smallest differ by more than their rounding. Where
they do not (a float tie, or keys within a few ulps), :func:`settle` decides among the
candidates within that band exactly: each offset ``p - s`` is an exact two-component
expansion (Knuth's two-difference), squares and sums are expansions, and the sign of a
difference of two keys is the sign of its largest component. Exact ties still go to the
lowest index, so the labels are the exactly nearest site of each float pixel centre, the
site ``Diagram.locate`` returns for it.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT
from .expansion import expansion_sum, multiply, two_diff

_U = 2.0**-53
#: keys within this relative band (plus :data:`BAND_TINY`) of the smallest may be nearer
#: exactly: a float key is within 4 ulps of the exact one, so 16 ulps cover two of them
BAND_REL = 16.0 * _U
BAND_TINY = 1e-320  # keys that underflow: a few subnormal ulps absolute


@njit(**NJIT)
def float_key(dx, dy, metric):
    """Comparison key of offset ``(dx, dy)``: squared length (Euclidean) or the distance."""
    if metric == 0:
        return dx * dx + dy * dy
    adx = abs(dx)
    ady = abs(dy)
    if metric == 1:
        return adx + ady
    return max(adx, ady)


@njit(**NJIT)
def _offset(a, b, out, neg):
    """``|a - b|`` (``neg``: ``-|a - b|``) exactly as two components in ``out``; returns 2."""
    hi, lo = two_diff(a, b)
    if (hi < 0.0) != neg:
        hi = -hi
        lo = -lo
    out[0] = lo
    out[1] = hi
    return np.int64(2)


@njit(**NJIT)
def top_sign(e, elen):
    """Sign of a nonoverlapping expansion: the sign of its largest nonzero component."""
    for i in range(elen - 1, -1, -1):
        if e[i] > 0.0:
            return 1
        if e[i] < 0.0:
            return -1
    return 0


@njit(**NJIT)
def _key(px, py, sx, sy, metric, neg, out, w):
    """The exact key of site ``s`` (negated with ``neg``) into ``out``; returns its length.

    ``w`` is scratch: ``(6, 64)``.
    """
    dx = w[0]
    dy = w[1]
    _offset(px, sx, dx, False)
    _offset(py, sy, dy, False)
    if metric == 0:
        xx = w[2]
        yy = w[3]
        nx = multiply(dx, np.int64(2), dx, np.int64(2), xx, w[4], w[5])
        ny = multiply(dy, np.int64(2), dy, np.int64(2), yy, w[4], w[5])
        n = expansion_sum(xx, nx, yy, ny, out)
    elif metric == 1:
        n = expansion_sum(dx, np.int64(2), dy, np.int64(2), out)
    else:
        _offset(py, sy, w[2], True)
        m = expansion_sum(dx, np.int64(2), w[2], np.int64(2), w[3])
        src = dx if top_sign(w[3], m) >= 0 else dy
        out[0] = src[0]
        out[1] = src[1]
        n = np.int64(2)
    if neg:
        for i in range(n):
            out[i] = -out[i]
    return n


@njit(**NJIT)
def compare(px, py, ax, ay, bx, by, metric, w):
    """Sign of ``key(a) - key(b)`` at pixel ``(px, py)``, exactly; ``w`` scratch ``(9, 64)``."""
    na = _key(px, py, ax, ay, metric, False, w[6], w)
    nb = _key(px, py, bx, by, metric, True, w[7], w)
    n = expansion_sum(w[6], na, w[7], nb, w[8])
    return top_sign(w[8], n)


@njit(**NJIT)
def settle(px, py, cx, cy, cid, count, metric, b1):
    """The exactly nearest of the first ``count`` candidates whose float key is near ``b1``.

    Exact ties go to the lowest ``cid``. Returns ``(t, k1, k2)``: the winner's slot, its
    float key, and the smallest float key of the other candidates (the second nearest, for
    F2).
    """
    w = np.zeros((9, 64))  # scratch of compare (settle runs only at near ties: rare)
    lim = b1 * (1.0 + BAND_REL) + BAND_TINY
    best = -1
    for t in range(count):
        if float_key(px - cx[t], py - cy[t], metric) > lim:
            continue
        if best < 0:
            best = t
            continue
        s = compare(px, py, cx[t], cy[t], cx[best], cy[best], metric, w)
        if s < 0 or (s == 0 and cid[t] < cid[best]):
            best = t
    k2 = np.inf
    for t in range(count):
        k = float_key(px - cx[t], py - cy[t], metric)
        if t != best and k < k2:
            k2 = k
    return best, float_key(px - cx[best], py - cy[best], metric), k2
