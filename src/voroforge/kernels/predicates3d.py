"""Exact 3D predicates: orient3d, insphere and the cell cut's "which side of a bisector".

All three are signs of determinants of one shape: rows ``(r_k, t_k)``, ``k = 0..3``, with
``r`` a 3-vector and ``t`` a number,

- ``D3 = det(r_0; r_1; r_2)`` and
- ``D4 = det[[r_0, t_0]; ...; [r_3, t_3]]``.

``orient3d(a, b, c, d)`` is ``D3`` of the rows ``a - d, b - d, c - d``: positive when ``d`` lies
below the plane through ``a, b, c`` (they turn counter-clockwise seen from above; Shewchuk's
convention). ``insphere(a, b, c, d, e)`` is ``D4`` of the rows ``(p - e, |p - e|^2)``: positive
when ``e`` lies inside the sphere through ``a, b, c, d`` if ``orient3d(a, b, c, d) > 0``.

:func:`bisector_side` is the decision of the 3D cell cut. Cell ``i``'s vertex ``x`` is where
three *owner* planes meet, each the power bisector of ``i`` and a site ``k``
(``r = p_k - p_i``, ``t = |r|^2 + w_i - w_k``: ``2 r . (x - p_i) = t``) or a container wall
``n . x <= d`` (``r = n``, ``t = 2 (d - n . p_i)``, the same equation scaled by 2). The sign of
``s = r_j . y - t_j / 2`` (``y = x - p_i``) for a fourth key ``j`` says whether ``x`` is beyond
``j``'s plane (> 0), on it (0: the vertex is equidistant from five sites, the 3D analogue of
insphere) or inside (< 0); by Cramer's rule ``2 s = -D4 / D3``.

Each is a floating-point filter (the determinant and a bound on its rounding error, from
the permanent: the same expression on absolute values) with an exact fallback on
expansions (:mod:`kernels.expansion`, Shewchuk 1997). The fallback takes every input
difference as a two-component expansion, so it is exact for any doubles; it allocates its
scratch (``scratch()``) once per caller. ``insphere`` tries a double-double evaluation with
a proven bound between the two (:mod:`.insphere_dd`: points rounded onto a sphere). As
everywhere in the package the arithmetic is exact only when no product underflows or
overflows (the engine's working frame sees to it).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import NJIT
from .expansion import expansion_sum, multiply, two_diff, two_product
from .frame3d import frame_lift as frame_lift  # the cell cut's band tests (re-exported)
from .frame3d import frame_offset as frame_offset
from .frame3d import frame_side as frame_side
from .frame3d import offset_side as offset_side
from .insphere_dd import insphere_dd
from .vertexdd3d import nearest, vertex_dd

_EPS = 2.0**-53
#: filter bounds (relative to the permanent). Shewchuk's orient3d bound is (7 + 56 eps) eps;
#: D3/D4 of the bisector rows carry at most 8 / 18 roundings on their longest path
#: (differences, squares, sums, 2x2 and 3x3 minors, the last column), padded
_O3D_BOUND = (8.0 + 64.0 * _EPS) * _EPS
_D3_BOUND = 12.0 * _EPS
_D4_BOUND = 32.0 * _EPS

#: scratch layout (components): rows' entries (4 x 3 x 2), last column (4 x 64),
#: 2x2 minors (18 x 16), 3x3 minors (4 x 192), one product, the running sum and two temps,
#: then lengths as int64 bits (the rows' 4 x 3 entries and 4 last-column values; the 18
#: 2x2 and 4 3x3 minors), so that the exact stage allocates nothing
_T = 64
_M2 = 16
_M3 = 192
_PROD = 2 * _T * _M3
_SUM = 4 * _PROD
_OFF_E = 0
_OFF_T = _OFF_E + 24
_OFF_M2 = _OFF_T + 4 * _T
_OFF_M3 = _OFF_M2 + 18 * _M2
_OFF_P = _OFF_M3 + 4 * _M3
_OFF_S = _OFF_P + _PROD
_OFF_A = _OFF_S + _SUM
_OFF_B = _OFF_A + _SUM
_OFF_L = _OFF_B + _SUM
_OFF_ML = _OFF_L + 16
#: :func:`vertex_offset`'s cache: ``_CACHE`` entries by a hash of the query, a site column
#: (-1 when the scratch is made: no entry), the rest of each entry (written before read)
_CACHE = 65536
_ENTRY = 13
_OFF_CA = _OFF_ML + 22
_OFF_CE = _OFF_CA + _CACHE
_OFF_Q = _OFF_CE + _CACHE * _ENTRY  # the query (vertex_offset)
_SCRATCH = _OFF_Q + 11
#: the 2x2 minors' row pairs, in the order used below
_PAIRS = ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3))


@njit(**NJIT)
def scratch():
    """A scratch buffer for the exact stage (9.9 MB, untouched until the exact stage runs).

    Every component is written before it is read, so it is left uninitialised: pages the
    exact stage never reaches are never touched, but for :func:`vertex_offset`'s cache's
    site column (512 KB, set to -1). A scratch serves one build (its sites, weights, walls).
    """
    buf = np.empty(_SCRATCH)  # noqa: TID251 - every component is written before it is read
    buf[_OFF_CA:_OFF_CE] = -1.0
    return buf


@njit(**NJIT)
def _sign(e, n):
    top = e[n - 1]
    return 1 if top > 0.0 else (-1 if top < 0.0 else 0)


@njit(**NJIT)
def _negate(e, n):
    for q in range(n):
        e[q] = -e[q]


@njit(**NJIT)
def _pair_index(a, b):
    if a == 0:
        return b - 1
    if a == 1:
        return b + 1
    return 5


@njit(**NJIT)
def _minor2(buf, EL, a, b, c0, c1, out):
    """``out = e[a, c0] e[b, c1] - e[a, c1] e[b, c0]`` (exact); returns its length."""
    E = buf[_OFF_E : _OFF_E + 24]
    A = buf[_OFF_A : _OFF_A + _SUM]
    B = buf[_OFF_B : _OFF_B + _SUM]
    P = buf[_OFF_P : _OFF_P + _PROD]
    tmp = buf[_OFF_S : _OFF_S + _SUM]
    ea = E[(a * 3 + c0) * 2 : (a * 3 + c0) * 2 + 2]
    eb = E[(b * 3 + c1) * 2 : (b * 3 + c1) * 2 + 2]
    la = multiply(ea, EL[a, c0], eb, EL[b, c1], A, tmp, P)
    ea = E[(a * 3 + c1) * 2 : (a * 3 + c1) * 2 + 2]
    eb = E[(b * 3 + c0) * 2 : (b * 3 + c0) * 2 + 2]
    lb = multiply(ea, EL[a, c1], eb, EL[b, c0], B, tmp, P)
    _negate(B, lb)
    return expansion_sum(A, la, B, lb, out)


@njit(**NJIT)
def _minor3(buf, EL, M2L, a, b, c, out):
    """``out = det(e rows a, b, c)`` from the 2x2 minors of rows ``b, c``; returns length."""
    E = buf[_OFF_E : _OFF_E + 24]
    M2 = buf[_OFF_M2 : _OFF_M2 + 18 * _M2]
    A = buf[_OFF_A : _OFF_A + _SUM]
    B = buf[_OFF_B : _OFF_B + _SUM]
    tmp = buf[_OFF_S : _OFF_S + _SUM]
    pr = _pair_index(b, c)
    n = np.int64(0)
    for col in range(3):
        # cofactors along row a: + x * m(yz) - y * m(xz) + z * m(xy)
        m = pr * 3 + col
        mm = M2[m * _M2 : m * _M2 + M2L[m]]
        ea = E[(a * 3 + col) * 2 : (a * 3 + col) * 2 + 2]
        lp = multiply(mm, M2L[m], ea, EL[a, col], A, tmp, B)
        if col == 1:
            _negate(A, lp)
        ln = expansion_sum(out, n, A, lp, B)
        for q in range(ln):
            out[q] = B[q]
        n = ln
    return n


@njit(**NJIT)
def exact_dets(buf, EL, TL, need4):
    """Exact signs ``(sign D3, sign D4)`` of the rows stored in ``buf`` (0 for D4 if not needed).

    ``buf[_OFF_E:]`` holds the entries ``e[k, c]`` as expansions of ``EL[k, c] <= 2``
    components at ``(3 k + c) * 2``; ``buf[_OFF_T + 64 k:]`` the last column's ``t_k`` with
    ``TL[k]`` components.
    """
    n3, n4 = _dets(buf, EL, TL, need4, np.bool_(True))  # (fresh given: one signature)
    s3 = _sign(buf[_OFF_M3 + 3 * _M3 : _OFF_M3 + 4 * _M3], n3)
    if not need4:
        return s3, 0
    return s3, _sign(buf[_OFF_S : _OFF_S + _SUM], n4)


@njit(**NJIT)
def _dets(buf, EL, TL, need4, fresh=True):
    """The expansions behind :func:`exact_dets`; returns their lengths (D4: 0 if not needed).

    D3 is left in ``buf[_OFF_M3 + 3 * _M3:]``, D4 in ``buf[_OFF_S:]``; only the 2x2 minors
    the 3x3 ones read are made. Not ``fresh``: only row 3 is new (:func:`vertex_offset`),
    so D3 and the minors of rows 1-2 stand.
    """
    M2 = buf[_OFF_M2 : _OFF_M2 + 18 * _M2]
    M3 = buf[_OFF_M3 : _OFF_M3 + 4 * _M3]
    S = buf[_OFF_S : _OFF_S + _SUM]
    P = buf[_OFF_P : _OFF_P + _PROD]
    A = buf[_OFF_A : _OFF_A + _SUM]
    B = buf[_OFF_B : _OFF_B + _SUM]
    T = buf[_OFF_T : _OFF_T + 4 * _T]
    ml = buf[_OFF_ML : _OFF_ML + 22].view(np.int64)
    if fresh:
        ml[:] = 0
    M2L = ml[:18]
    M3L = ml[18:22]
    rows = 4 if need4 else 3
    for p in range(3, 6):  # (1, 2), (1, 3), (2, 3): the pairs _minor3 reads
        a, b = _PAIRS[p]
        if b >= rows or (p == 3 and not fresh):
            continue
        for cp in range(3):
            # column pairs: (y, z), (x, z), (x, y)
            c0 = 1 if cp == 0 else 0
            c1 = 1 if cp == 2 else 2
            m = p * 3 + cp
            M2L[m] = _minor2(buf, EL, a, b, c0, c1, M2[m * _M2 : (m + 1) * _M2])
    # 3x3 minors: M3[k] leaves row k out; D3 is M3[3]
    for k in range(4):
        if (k < 3 and not need4) or (k == 3 and not fresh):
            continue
        r0 = 1 if k == 0 else 0
        r1 = 2 if k <= 1 else 1
        r2 = 3 if k <= 2 else 2
        M3L[k] = _minor3(buf, EL, M2L, r0, r1, r2, M3[k * _M3 : (k + 1) * _M3])
    if not need4:
        return M3L[3], np.int64(0)
    # D4 = -t0 M0 + t1 M1 - t2 M2 + t3 M3
    n = np.int64(0)
    for k in range(4):
        lp = multiply(M3[k * _M3 : (k + 1) * _M3], M3L[k], T[k * _T : (k + 1) * _T], TL[k], P, A, B)
        if k % 2 == 0:
            _negate(P, lp)
        ln = expansion_sum(S, n, P, lp, A)
        for q in range(ln):
            S[q] = A[q]
        n = ln
    return M3L[3], n


@njit(**NJIT)
def _put_diff(buf, EL, k, c, a, b):
    """Entry ``e[k, c] = a - b`` as an exact expansion."""
    x, y = two_diff(a, b)
    o = _OFF_E + (k * 3 + c) * 2
    if y != 0.0:
        buf[o] = y
        buf[o + 1] = x
        EL[k, c] = 2
    else:
        buf[o] = x
        EL[k, c] = 1


@njit(**NJIT)
def _put_lift(buf, EL, TL, k, wdiff_hi, wdiff_lo):
    """``t_k = |e[k]|^2 + wdiff`` (exact), from the entries already stored."""
    T = buf[_OFF_T + k * _T : _OFF_T + (k + 1) * _T]
    A = buf[_OFF_A : _OFF_A + _SUM]
    B = buf[_OFF_B : _OFF_B + _SUM]
    P = buf[_OFF_P : _OFF_P + _PROD]
    tmp = buf[_OFF_S : _OFF_S + _SUM]
    n = np.int64(0)
    if wdiff_hi != 0.0:
        if wdiff_lo != 0.0:
            A[0] = wdiff_lo
            A[1] = wdiff_hi
            n = 2
        else:
            A[0] = wdiff_hi
            n = np.int64(1)
    for c in range(3):
        o = _OFF_E + (k * 3 + c) * 2
        e = buf[o : o + 2]
        lp = multiply(e, EL[k, c], e, EL[k, c], P, tmp, B)
        ln = expansion_sum(A, n, P, lp, B)
        for q in range(ln):
            A[q] = B[q]
        n = ln
    if n == 0:
        A[0] = 0.0
        n = np.int64(1)
    for q in range(n):
        T[q] = A[q]
    TL[k] = n


@njit(**{**NJIT, "inline": "always"})
def wall_lift(WP, w, px, py, pz):
    """``d - n . (p - o)`` of wall ``w`` (float): how far inside it the point ``p`` lies.

    ``WP`` rows are ``(n, d)`` (``n . x <= d``) or ``(n, d, o)`` (``n . (x - o) <= d``, a
    Convex far from the origin: engine.containers); with 4 columns the same operations as
    ``d - n . p``.
    """
    if WP.shape[1] > 4:
        px = px - WP[w, 4]
        py = py - WP[w, 5]
        pz = pz - WP[w, 6]
    return WP[w, 3] - (WP[w, 0] * px + WP[w, 1] * py + WP[w, 2] * pz)


@njit(**NJIT)
def _put_wall(buf, EL, TL, k, nx, ny, nz, d, px, py, pz, ox, oy, oz):
    """Row ``k`` of wall ``n . (x - o) <= d`` for base ``p``: ``(n, 2 (d - n . (p - o)))``.

    Exact; ``o`` is 0 for a wall in absolute coordinates (then no term is added for it).
    """
    o = _OFF_E + k * 3 * 2
    buf[o] = nx
    buf[o + 2] = ny
    buf[o + 4] = nz
    EL[k, 0] = 1
    EL[k, 1] = 1
    EL[k, 2] = 1
    T = buf[_OFF_T + k * _T : _OFF_T + (k + 1) * _T]
    A = buf[_OFF_A : _OFF_A + _SUM]
    B = buf[_OFF_B : _OFF_B + _SUM]
    A[0] = 2.0 * d
    n = np.int64(1)
    for c in range(3):
        nc = nx if c == 0 else (ny if c == 1 else nz)
        pc = px if c == 0 else (py if c == 1 else pz)
        h, lo = two_product(-2.0 * nc, pc)
        B[0] = lo
        B[1] = h
        lb = 2
        if lo == 0.0:
            B[0] = h
            lb = 1
        ln = expansion_sum(A, n, B, lb, T)
        for q in range(ln):
            A[q] = T[q]
        n = ln
        oc = ox if c == 0 else (oy if c == 1 else oz)
        if oc != 0.0:
            h, lo = two_product(2.0 * nc, oc)
            B[0] = lo
            B[1] = h
            lb = 2
            if lo == 0.0:
                B[0] = h
                lb = 1
            ln = expansion_sum(A, n, B, lb, T)
            for q in range(ln):
                A[q] = T[q]
            n = ln
    for q in range(n):
        T[q] = A[q]
    TL[k] = n


@njit(**NJIT)
def orient3d(ax, ay, az, bx, by, bz, cx, cy, cz, dx, dy, dz):
    """Sign-exact ``det(a - d; b - d; c - d)``: > 0 when ``d`` is below the plane of ``a, b, c``.

    Returns the filtered float value when its sign is certain, else -1.0, 0.0 or 1.0 exactly.
    """
    adx = ax - dx
    ady = ay - dy
    adz = az - dz
    bdx = bx - dx
    bdy = by - dy
    bdz = bz - dz
    cdx = cx - dx
    cdy = cy - dy
    cdz = cz - dz
    bc = bdy * cdz - bdz * cdy
    ca = cdy * adz - cdz * ady
    ab = ady * bdz - adz * bdy
    det = adx * bc + bdx * ca + cdx * ab
    perm = (
        abs(adx) * (abs(bdy * cdz) + abs(bdz * cdy))
        + abs(bdx) * (abs(cdy * adz) + abs(cdz * ady))
        + abs(cdx) * (abs(ady * bdz) + abs(adz * bdy))
    )
    if abs(det) > _O3D_BOUND * perm:
        return det
    buf = np.empty(_OFF_CA)  # noqa: TID251 - scratch() less vertex_offset's cache (unused)
    EL = np.zeros((4, 3), np.int64)
    TL = np.zeros(4, np.int64)
    for c in range(3):
        dc = dx if c == 0 else (dy if c == 1 else dz)
        _put_diff(buf, EL, np.int64(0), c, ax if c == 0 else (ay if c == 1 else az), dc)
        _put_diff(buf, EL, np.int64(1), c, bx if c == 0 else (by if c == 1 else bz), dc)
        _put_diff(buf, EL, np.int64(2), c, cx if c == 0 else (cy if c == 1 else cz), dc)
    s3, _ = exact_dets(buf, EL, TL, np.bool_(False))
    return float(s3)


@njit(**NJIT)
def insphere(P5):
    """Sign-exact insphere of the rows of ``P5 (5, 3)`` = ``a, b, c, d, e``.

    ``det[(p - e, |p - e|^2)]`` over ``p = a, b, c, d``: > 0 when ``e`` is inside the sphere
    through ``a, b, c, d`` and ``orient3d(a, b, c, d) > 0``. Returns the float value when its
    sign is certain, else -1.0, 0.0 or 1.0 exactly.
    """
    W0 = np.zeros(5)
    val, perm = _d4_float(P5, W0, 4, 0, 1, 2, 3)
    if abs(val) > _D4_BOUND * perm:
        return val
    dd = insphere_dd(P5)
    if dd != 0.0:
        return dd
    buf = np.empty(_OFF_CA)  # noqa: TID251 - as orient3d's
    EL = np.zeros((4, 3), np.int64)
    TL = np.zeros(4, np.int64)
    for k in range(4):
        for c in range(3):
            _put_diff(buf, EL, k, c, P5[k, c], P5[4, c])
        _put_lift(buf, EL, TL, k, 0.0, 0.0)
    _, s4 = exact_dets(buf, EL, TL, np.bool_(True))
    return float(s4)


@njit(**NJIT)
def _d4_float(P, W, base, k0, k1, k2, k3):
    """Float ``D4`` of site rows ``k0..k3`` around ``base`` and its permanent."""
    r = np.zeros((4, 4))
    ra = np.zeros((4, 4))
    for q in range(4):
        k = k0 if q == 0 else (k1 if q == 1 else (k2 if q == 2 else k3))
        x = P[k, 0] - P[base, 0]
        y = P[k, 1] - P[base, 1]
        z = P[k, 2] - P[base, 2]
        r[q, 0] = x
        r[q, 1] = y
        r[q, 2] = z
        r[q, 3] = x * x + y * y + z * z + (W[base] - W[k])
        ra[q, 0] = abs(x)
        ra[q, 1] = abs(y)
        ra[q, 2] = abs(z)
        ra[q, 3] = x * x + y * y + z * z + abs(W[base]) + abs(W[k])
    return _det4(r), _perm4(ra)


@njit(**{**NJIT, "inline": "always"})
def _det3_rows(r, a, b, c):
    return (
        r[a, 0] * (r[b, 1] * r[c, 2] - r[b, 2] * r[c, 1])
        - r[a, 1] * (r[b, 0] * r[c, 2] - r[b, 2] * r[c, 0])
        + r[a, 2] * (r[b, 0] * r[c, 1] - r[b, 1] * r[c, 0])
    )


@njit(**{**NJIT, "inline": "always"})
def _perm3_rows(r, a, b, c):
    """The permanent of rows of absolute values (all terms added)."""
    return (
        r[a, 0] * (r[b, 1] * r[c, 2] + r[b, 2] * r[c, 1])
        + r[a, 1] * (r[b, 0] * r[c, 2] + r[b, 2] * r[c, 0])
        + r[a, 2] * (r[b, 0] * r[c, 1] + r[b, 1] * r[c, 0])
    )


@njit(**NJIT)
def _det4(r):
    """``det`` of ``r (4, 4)``, expanded along the last column."""
    return (
        -r[0, 3] * _det3_rows(r, 1, 2, 3)
        + r[1, 3] * _det3_rows(r, 0, 2, 3)
        - r[2, 3] * _det3_rows(r, 0, 1, 3)
        + r[3, 3] * _det3_rows(r, 0, 1, 2)
    )


@njit(**NJIT)
def _perm4(ra):
    """The permanent of ``ra (4, 4)`` (absolute values): a bound on every term of ``_det4``."""
    return (
        ra[0, 3] * _perm3_rows(ra, 1, 2, 3)
        + ra[1, 3] * _perm3_rows(ra, 0, 2, 3)
        + ra[2, 3] * _perm3_rows(ra, 0, 1, 3)
        + ra[3, 3] * _perm3_rows(ra, 0, 1, 2)
    )


@njit(**NJIT)
def _row_float(key, i, P, W, WP, ns, r, ra, q):
    """Float row ``q`` for owner ``key`` around site ``i`` (and its absolute values)."""
    if key < ns:
        x = P[key, 0] - P[i, 0]
        y = P[key, 1] - P[i, 1]
        z = P[key, 2] - P[i, 2]
        r[q, 0] = x
        r[q, 1] = y
        r[q, 2] = z
        r[q, 3] = x * x + y * y + z * z + (W[i] - W[key])
        ra[q, 0] = abs(x)
        ra[q, 1] = abs(y)
        ra[q, 2] = abs(z)
        ra[q, 3] = x * x + y * y + z * z + abs(W[i]) + abs(W[key])
    else:
        w = key - ns
        nx = WP[w, 0]
        ny = WP[w, 1]
        nz = WP[w, 2]
        px = P[i, 0]
        py = P[i, 1]
        pz = P[i, 2]
        if WP.shape[1] > 4:  # about the wall's origin (wall_lift): one rounding more a term
            px = px - WP[w, 4]
            py = py - WP[w, 5]
            pz = pz - WP[w, 6]
        r[q, 0] = nx
        r[q, 1] = ny
        r[q, 2] = nz
        r[q, 3] = 2.0 * (WP[w, 3] - (nx * px + ny * py + nz * pz))
        ra[q, 0] = abs(nx)
        ra[q, 1] = abs(ny)
        ra[q, 2] = abs(nz)
        ra[q, 3] = 2.0 * (abs(WP[w, 3]) + abs(nx * px) + abs(ny * py) + abs(nz * pz))


@njit(**NJIT)
def _row_exact(key, i, P, W, WP, ns, buf, EL, TL, q):
    if key < ns:
        for c in range(3):
            _put_diff(buf, EL, q, c, P[key, c], P[i, c])
        wh, wl = two_diff(W[i], W[key])
        _put_lift(buf, EL, TL, q, wh, wl)
    else:
        w = key - ns
        ox = oy = oz = 0.0
        if WP.shape[1] > 4:
            ox = WP[w, 4]
            oy = WP[w, 5]
            oz = WP[w, 6]
        n0 = WP[w, 0]
        n1 = WP[w, 1]
        n2 = WP[w, 2]
        _put_wall(buf, EL, TL, q, n0, n1, n2, WP[w, 3], P[i, 0], P[i, 1], P[i, 2], ox, oy, oz)


@njit(**NJIT)
def bisector_side(i, k0, k1, k2, j, P, W, WP, ns, rows, buf):
    """Exact side of the vertex of cell ``i`` named by owners ``k0, k1, k2`` against key ``j``.

    Keys below ``ns`` are sites (power bisector with ``i``), the others walls ``key - ns``
    of ``WP (m, 4)`` (or ``(m, 7)``: :func:`wall_lift`). Returns 1 (beyond ``j``'s plane:
    the cut removes the vertex), 0 (on it), -1 (inside), or 2 when the three owner planes
    do not meet in one point.
    ``rows (2, 4, 4)`` and ``buf`` (:func:`scratch`) are scratch.
    """
    r = rows[0]
    ra = rows[1]
    _row_float(k0, i, P, W, WP, ns, r, ra, np.int64(0))
    _row_float(k1, i, P, W, WP, ns, r, ra, np.int64(1))
    _row_float(k2, i, P, W, WP, ns, r, ra, np.int64(2))
    _row_float(j, i, P, W, WP, ns, r, ra, np.int64(3))
    d3 = _det3_rows(r, 0, 1, 2)
    p3 = _perm3_rows(ra, 0, 1, 2)
    d4 = _det4(r)
    p4 = _perm4(ra)
    if abs(d3) > _D3_BOUND * p3 and abs(d4) > _D4_BOUND * p4:
        s3 = 1 if d3 > 0.0 else -1
        s4 = 1 if d4 > 0.0 else -1
        return -s3 * s4
    # the lengths live in the scratch (each is written below before it is read)
    lens = buf[_OFF_L : _OFF_L + 16].view(np.int64)
    EL = lens[:12].reshape((4, 3))
    TL = lens[12:16]
    _row_exact(k0, i, P, W, WP, ns, buf, EL, TL, np.int64(0))
    _row_exact(k1, i, P, W, WP, ns, buf, EL, TL, np.int64(1))
    _row_exact(k2, i, P, W, WP, ns, buf, EL, TL, np.int64(2))
    _row_exact(j, i, P, W, WP, ns, buf, EL, TL, np.int64(3))
    s3, s4 = exact_dets(buf, EL, TL, np.bool_(True))
    if s3 == 0:
        return 2
    return -s3 * s4


@njit(**NJIT)
def exact_point(a, k0, k1, k2, P, W, WP, ns, buf, x):
    """The vertex of site ``a``'s owners ``k0, k1, k2`` into ``x (3,)``, from exact expansions.

    Coordinate ``c`` is ``s`` of :func:`bisector_side` for the plane ``x_c = 0`` (a wall
    row ``(e_c, 2 (0 - p_a,c))``): ``x_c = -D4 / (2 D3)`` with both determinants exact,
    each rounded to its nearest double, then divided, so ``x`` is right to ~1.5 ulps of
    itself, however much of the sites' magnitude cancels (a vertex 1e-17 from the origin
    among sites on the unit sphere: the float solve's error is 1e-16). Returns False when
    the planes do not meet in one point (``D3 == 0``). ``buf`` is :func:`scratch`.
    """
    return vertex_offset(a, k0, k1, k2, P, W, WP, ns, buf, 0.0, 0.0, 0.0, x)


@njit(**NJIT)
def vertex_offset(a, k0, k1, k2, P, W, WP, ns, buf, cx, cy, cz, x):
    """The vertex of site ``a``'s owners ``k0, k1, k2`` less the point ``c``, into ``x (3,)``.

    :func:`exact_point` with the planes ``x_c = c_c``: each coordinate of ``vertex - c`` is
    ``-D4 / (2 D3)`` of exact determinants, each rounded to its nearest double
    (:func:`.vertexdd3d.nearest`) before the one division: right to ~1.5 ulps of itself
    however small the offset, and a function of the exact determinants alone, so that the
    double-double stage (:func:`.vertexdd3d.vertex_dd`) gives the same bits where it can
    prove them. Returns False when the planes do not meet in one point (``D3 == 0``).

    Cached in ``buf`` by the query (with the arrays' addresses): each cell at a vertex names
    it with the same query, and a cell past its slots is built again; a hit returns the
    same bits.
    """
    Q = buf[_OFF_Q : _OFF_Q + 11]  # the query: a, k0, k1, k2, c (bits), arrays, lengths
    QI = Q.view(np.int64)
    Q[4] = cx
    Q[5] = cy
    Q[6] = cz
    QI[0] = a
    QI[1] = k0
    QI[2] = k1
    QI[3] = k2
    QI[7] = P.ctypes.data ^ (W.ctypes.data << 1) ^ (WP.ctypes.data << 2)
    QI[8] = P.shape[0]
    QI[9] = WP.shape[0]
    h = np.uint64(0x9E3779B97F4A7C15)  # a SplitMix-style mix of the query: its entry
    for q in range(7):
        h ^= np.uint64(QI[q])
        h *= np.uint64(0xBF58476D1CE4E5B9)
        h ^= h >> np.uint64(31)
    e = np.int64(h & np.uint64(_CACHE - 1))
    E = buf[_OFF_CE + e * _ENTRY : _OFF_CE + (e + 1) * _ENTRY]
    EI = E.view(np.int64)
    hit = buf[_OFF_CA + e] == a
    for q in range(1, 10):
        hit = hit and EI[q - 1] == QI[q]
    if hit:
        for q in range(3 if EI[9] else 0):  # (no point: x as it was)
            x[q] = E[10 + q]
        return EI[9] != 0
    ok = _vertex_offset(a, k0, k1, k2, P, W, WP, ns, buf, cx, cy, cz, x)
    buf[_OFF_CA + e] = a
    for q in range(1, 10):
        EI[q - 1] = QI[q]
    EI[9] = ok
    for q in range(3 if ok else 0):
        E[10 + q] = x[q]
    return ok


@njit(**NJIT)
def _vertex_offset(a, k0, k1, k2, P, W, WP, ns, buf, cx, cy, cz, x):
    """:func:`vertex_offset` solved (not cached): double-double where it proves the bits.

    Tried about the site (resettle, naming) or the origin (:func:`exact_point`) only: about
    a float vertex (a band vertex's offset of an ulp) ``D4`` cancels to its last bits and
    the stage decided none of 669,920 such queries (random and near-degenerate).
    """
    at_site = cx == P[a, 0] and cy == P[a, 1] and cz == P[a, 2]
    if at_site or (cx == 0.0 and cy == 0.0 and cz == 0.0):
        R = buf[_OFF_A : _OFF_A + 63]
        if vertex_dd(a, k0, k1, k2, P, W, WP, ns, cx, cy, cz, R, x):
            return True
    return vertex_exact(a, k0, k1, k2, P, W, WP, ns, buf, cx, cy, cz, x)


@njit(**NJIT)
def vertex_exact(a, k0, k1, k2, P, W, WP, ns, buf, cx, cy, cz, x):
    """:func:`vertex_offset` from exact expansions (not cached)."""
    lens = buf[_OFF_L : _OFF_L + 16].view(np.int64)
    EL = lens[:12].reshape((4, 3))
    TL = lens[12:16]
    tmp = buf[_OFF_A : _OFF_A + _SUM]  # nearest's (the determinants are made before)
    _row_exact(k0, a, P, W, WP, ns, buf, EL, TL, np.int64(0))
    _row_exact(k1, a, P, W, WP, ns, buf, EL, TL, np.int64(1))
    _row_exact(k2, a, P, W, WP, ns, buf, EL, TL, np.int64(2))
    d3 = 0.0
    for c in range(3):  # rows 0-2 stay: only row 3 and the minors with it are made again
        n0 = 1.0 if c == 0 else 0.0
        n1 = 1.0 if c == 1 else 0.0
        n2 = 1.0 if c == 2 else 0.0
        d = cx if c == 0 else (cy if c == 1 else cz)
        _put_wall(buf, EL, TL, np.int64(3), n0, n1, n2, d, P[a, 0], P[a, 1], P[a, 2], 0.0, 0.0, 0.0)
        n3, n4 = _dets(buf, EL, TL, np.bool_(True), c == 0)
        if c == 0:
            d3 = nearest(buf[_OFF_M3 + 3 * _M3 : _OFF_M3 + 4 * _M3], n3, tmp)
            if d3 == 0.0:
                return False
        x[c] = -nearest(buf[_OFF_S : _OFF_S + _SUM], n4, tmp) / (2.0 * d3)
    return True
