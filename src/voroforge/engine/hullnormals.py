"""Doubles nearly parallel to an exact integer normal: the walls of a thin hull.

A :class:`~.containers.Convex` hull's wall is the plane through three of its points; its
normal, the exact cross product of their differences, needs about twice a double's bits.
Rounded once, it tilts the plane by up to an ulp (1e-16), and the wall, moved out to hold
its corners, leaves a wedge over its face ~1e-16 of the face's size thick. For a fat hull
that is a rounding of its volume; for one 1e-9 as thin as it is wide, 1e-7 of it (checker33
F1: a rotated disk's rows 3e-8..1.5e-7 above its exact hull).

A double vector is integers ``k_i`` times powers of two, one per component. With the
components' exponents made equal (``m_i`` shifted to the bit length of the largest), the
best direction of 53-bit integers is a simultaneous rational approximation of the two
ratios ``m_i / m_j``: Dirichlet's theorem gives a tilt of about ``2**-79.5`` (1e-24) where
rounding gives ``2**-53``, and lattice reduction (LLL on three integer vectors, Cohen's
integral version: exact, ~0.2 ms a wall) finds it. The candidate with the smallest exact
tilt wins, rounding included, so the result is never worse than the rounded normal.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np

#: the lattice search's integers' bits, tried in turn (a double holds 53)
_BITS = (52, 50, 46)


def _dot(a, b) -> int:
    return sum(x * y for x, y in zip(a, b, strict=True))


def lll(basis: list[list[int]]) -> list[list[int]]:
    """The LLL-reduced basis (delta 3/4) of independent integer vectors, exactly.

    Cohen, *A Course in Computational Algebraic Number Theory*, algorithm 2.6.7 (integral
    LLL): Gram-Schmidt kept as integers ``d`` and ``lam``, so no rational arithmetic.
    """
    n = len(basis)
    b = [None] + [list(v) for v in basis]
    d = [1] + [0] * n
    lam = [[0] * (n + 1) for _ in range(n + 1)]
    d[1] = _dot(b[1], b[1])
    k, kmax = 2, 1

    def reduce(k: int, j: int) -> None:
        if 2 * abs(lam[k][j]) > d[j]:
            q = (2 * lam[k][j] + d[j]) // (2 * d[j])
            b[k] = [x - q * y for x, y in zip(b[k], b[j], strict=True)]
            lam[k][j] -= q * d[j]
            for i in range(1, j):
                lam[k][i] -= q * lam[j][i]

    def swap(k: int) -> None:
        b[k], b[k - 1] = b[k - 1], b[k]
        for j in range(1, k - 1):
            lam[k][j], lam[k - 1][j] = lam[k - 1][j], lam[k][j]
        la = lam[k][k - 1]
        B = (d[k - 2] * d[k] + la * la) // d[k - 1]
        for i in range(k + 1, kmax + 1):
            t = lam[i][k]
            lam[i][k] = (d[k] * lam[i][k - 1] - la * t) // d[k - 1]
            lam[i][k - 1] = (B * t + la * lam[i][k]) // d[k]
        d[k - 1] = B

    while k <= n:
        if k > kmax:
            kmax = k
            for j in range(1, k + 1):
                u = _dot(b[k], b[j])
                for i in range(1, j):
                    u = (d[i] * u - lam[k][i] * lam[j][i]) // d[i - 1]
                if j < k:
                    lam[k][j] = u
                else:
                    d[k] = u
        while True:
            reduce(k, k - 1)
            if 4 * d[k] * d[k - 2] < 3 * d[k - 1] ** 2 - 4 * lam[k][k - 1] ** 2:
                swap(k)
                k = max(2, k - 1)
            else:
                for j in range(k - 2, 0, -1):
                    reduce(k, j)
                k += 1
                break
    return b[1:]


def _tilt(k: list[int], m: list[int]) -> Fraction:
    """The squared sine of the angle between the integer vectors ``k`` and ``m``."""
    c = (k[1] * m[2] - k[2] * m[1], k[2] * m[0] - k[0] * m[2], k[0] * m[1] - k[1] * m[0])
    return Fraction(_dot(c, c), _dot(k, k) * _dot(m, m))


def close_normal(m) -> np.ndarray:
    """A double vector nearly parallel to the integer vector ``m`` (3,), pointing its way.

    Scaled by a power of two so that its largest component lies in [1, 2); exact (``m``
    itself, scaled) where ``m``'s direction fits doubles.
    """
    m = [int(x) for x in m]
    nz = [i for i in range(3) if m[i]]
    top = max(abs(m[i]).bit_length() for i in nz)
    shift = [top - abs(m[i]).bit_length() if m[i] else 0 for i in range(3)]
    s = max(shift)
    cands = []
    if len(nz) > 1:
        mp = [m[i] << shift[i] for i in nz]  # equal bit lengths
        j = max(range(len(nz)), key=lambda t: abs(mp[t]))
        rest = [t for t in range(len(nz)) if t != j]
        for bits in _BITS:  # the reduced vectors lie about 2**bits long: fewer if past 53
            C = 1 << (bits * len(nz) // (len(nz) - 1))
            basis = [[mp[j]] + [C * mp[t] for t in rest]]
            for r in range(len(rest)):
                row = [0] * len(nz)
                row[1 + r] = -C * mp[j]
                basis.append(row)
            for v in lll(basis):
                kp = [0] * len(nz)
                kp[j] = v[0] // mp[j]  # v[0] is q times mp[j]
                for t in rest:
                    kp[t] = (2 * kp[j] * mp[t] + mp[j]) // (2 * mp[j])  # nearest
                if kp[j] == 0 or max(abs(x) for x in kp).bit_length() > 53:
                    continue
                k = [0, 0, 0]
                for t, i in enumerate(nz):
                    k[i] = kp[t] << (s - shift[i])  # the same direction, in common units
                cands.append(k)
            if cands:
                break
    # the exact quotients rounded once (the plain rounded normal), as a fallback
    big = max(abs(x) for x in m)
    r = [Fraction(x, big) for x in m]
    cands.append([int(Fraction(float(x)) * (1 << 1100)) for x in r])
    best = None
    for k in cands:
        if _dot(k, m) < 0:
            k = [-x for x in k]
        if not any(k):
            continue
        t = _tilt(k, m)
        if best is None or t < best[0]:
            best = (t, k)
    k = best[1]
    e = max(abs(x) for x in k).bit_length()
    # each has at most 53 significant bits: the quotients are exact
    return np.array([float(Fraction(x, 1 << (e - 1))) for x in k])
