"""insphere's middle stage: the determinant in double-double with a proven bound.

Between :func:`.predicates3d.insphere`'s float filter and its exact expansions. Points
rounded onto a sphere are cospherical to ~1 ulp: their insphere determinant is ~1e-16 of
its permanent, below the float filter's bound, and every test of their Delaunay
triangulation (``vf.delaunay3d``, :mod:`.candidates3d`) took the expansions (~12 us a
test; 20,000 sphere points: 1.9 s against 0.4 s for uniform points). In double-double the
error is ~1e-30 of the permanent: the stage decides nearly all of them at ~0.35 us.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT
from .expansion import two_diff, two_product, two_sum

_EPS = 2.0**-53

#: :func:`insphere_dd`'s bound relative to the permanent: each double-double operation
#: errs by at most 8 u^2 (u = 2**-53) of its operands' magnitudes (the sum's or the
#: product's), so a circuit of depth d errs by at most ((1 + 8 u^2)**d - 1) of the permanent;
#: the determinant's longest path is 11 operations (a 2x2 minor's product and sum, its
#: product with an entry, three sums, the product with the lift, four sums): 16 padded
_DD_BOUND = 16.0 * 8.0 * _EPS * _EPS * (1.0 + 1e-12)


@njit(**{**NJIT, "inline": "always"})
def _dd_add(ah, al, bh, bl):
    """``a + b`` in double-double; errs by at most ``4 u^2 (|a| + |b|)``.

    The heads' exact sum, the tails added once, renormalised exactly (two_sum).
    """
    s, e = two_sum(ah, bh)
    e = e + (al + bl)
    return two_sum(s, e)


@njit(**{**NJIT, "inline": "always"})
def _dd_mul(ah, al, bh, bl):
    """``a b`` in double-double; errs by at most ``8 u^2 |a| |b|``.

    The heads' exact product, the cross terms rounded, the tails' product left out (tails
    are below ``u`` of their heads).
    """
    p, e = two_product(ah, bh)
    e = e + (ah * bl + al * bh)
    return two_sum(p, e)


@njit(**NJIT)
def insphere_dd(P5):
    """The sign of :func:`.predicates3d.insphere` in double-double (+-1.0), or 0.0 (unsure).

    The rows ``p - e`` are exact two-term differences; the lifts, minors and the
    expansion along the lift column are evaluated in double-double, the permanent (the
    same circuit on absolute values) in floats, padded. Points cospherical to rounding
    (a float sphere: every test of its Delaunay triangulation) have a determinant of ~1e-16
    of the permanent, which the float filter cannot tell but this does at ~1e-30, ~20x
    cheaper than the expansions; an exact 0 (and anything within the bound) is left to them.
    """
    H = np.empty((4, 4))  # noqa: TID251 (every entry written below)
    L = np.empty((4, 4))  # noqa: TID251 (as H)
    A = np.empty((4, 4))  # noqa: TID251 (as H)
    for k in range(4):
        for c in range(3):
            h, lo = two_diff(P5[k, c], P5[4, c])
            H[k, c] = h
            L[k, c] = lo
            A[k, c] = abs(h)
        lh, ll = _dd_mul(H[k, 0], L[k, 0], H[k, 0], L[k, 0])
        for c in range(1, 3):
            qh, ql = _dd_mul(H[k, c], L[k, c], H[k, c], L[k, c])
            lh, ll = _dd_add(lh, ll, qh, ql)
        H[k, 3] = lh
        L[k, 3] = ll
        A[k, 3] = A[k, 0] * A[k, 0] + A[k, 1] * A[k, 1] + A[k, 2] * A[k, 2]
    dh = 0.0
    dl = 0.0
    perm = 0.0
    for k in range(4):  # D4 = sum_k (-1)**(k + 1) t_k M_k, M_k the rows other than k
        a = 1 if k == 0 else 0
        b = 2 if k <= 1 else 1
        c = 3 if k <= 2 else 2
        mh = 0.0
        ml = 0.0
        mp = 0.0
        for col in range(3):
            c0 = 1 if col == 0 else 0
            c1 = 1 if col == 2 else 2
            xh, xl = _dd_mul(H[b, c0], L[b, c0], H[c, c1], L[c, c1])
            yh, yl = _dd_mul(H[b, c1], L[b, c1], H[c, c0], L[c, c0])
            m2h, m2l = _dd_add(xh, xl, -yh, -yl)
            th, tl = _dd_mul(H[a, col], L[a, col], m2h, m2l)
            if col == 1:
                th = -th
                tl = -tl
            mh, ml = _dd_add(mh, ml, th, tl)
            mp += A[a, col] * (A[b, c0] * A[c, c1] + A[b, c1] * A[c, c0])
        th, tl = _dd_mul(H[k, 3], L[k, 3], mh, ml)
        if k % 2 == 0:
            th = -th
            tl = -tl
        dh, dl = _dd_add(dh, dl, th, tl)
        perm += A[k, 3] * mp
    val = dh + dl
    # the heads' magnitudes bound the rows' to (1 + u): (1 + u)**5 on a degree-5 term
    bound = _DD_BOUND * perm * (1.0 + 8.0 * _EPS) + 1e-290
    if val > bound:
        return 1.0
    if val < -bound:
        return -1.0
    return 0.0
