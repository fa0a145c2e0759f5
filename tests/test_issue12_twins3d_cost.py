"""Issue 12: the twins fix's shortcuts decide as the full tests they stand in for.

``kernels.vertex3d._ill`` (the cut's re-solve test from squares, no square roots) against the
test with roots it replaces and against the exact rational relative determinant;
``engine.diagram3d._clearly_not_flat`` (a face's area proven nonzero from its own fan, so
the canonical fan is not summed) against the exact rational area vector of the ring and the
canonical fan's float sum, on faces a few ulps wide.
"""

from __future__ import annotations

from fractions import Fraction as Fr

import numpy as np

from voroforge.config import CUT_EXACT_DET_RTOL
from voroforge.engine.diagram3d import _clearly_not_flat, _flat, _flat_fan
from voroforge.kernels.vertex3d import _ill

WP = np.array([[1.0, 0.0, 0.0, 1.0], [0.0, -1.0, 0.0, 0.0], [0.6, 0.8, 0.0, 0.9]])


def _roots_test(P, a, b, c):
    """The test with square roots (vertex3d's ``_rel_det``), normals of site 0's cell."""
    n = [P[k] - P[0] if k < len(P) else WP[k - len(P), :3] for k in (a, b, c)]
    (ax, ay, az), (bx, by, bz), (cx, cy, cz) = n
    det = ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx)
    nrm = np.sqrt((ax * ax + ay * ay + az * az) * (bx * bx + by * by + bz * bz))
    return abs(det) < CUT_EXACT_DET_RTOL * (nrm * np.sqrt(cx * cx + cy * cy + cz * cz))


def _exact_ratio2(P, a, b, c):
    """The exact squared relative determinant of the three normals (Fractions)."""
    n = []
    for k in (a, b, c):
        if k < len(P):
            n.append([Fr(float(P[k, q])) - Fr(float(P[0, q])) for q in range(3)])
        else:
            n.append([Fr(float(x)) for x in WP[k - len(P), :3]])
    (ax, ay, az), (bx, by, bz), (cx, cy, cz) = n
    det = ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx)
    den = 1
    for x in n:
        den *= sum(v * v for v in x)
    return det * det / den


def test_ill_is_the_roots_test_and_exact_away_from_the_threshold():
    rng = np.random.default_rng(12)
    rt2 = Fr(CUT_EXACT_DET_RTOL) ** 2
    near = 0
    for trial in range(3000):
        scale = 10.0 ** rng.integers(-3, 4)
        P = rng.random((4, 3)) * scale
        # the third normal in the plane of the first two plus the multiple of their cross
        # product that makes the relative determinant ``rel``: around the threshold
        n1 = P[1] - P[0]
        n2 = P[2] - P[0]
        cr = np.cross(n1, n2)
        t = rng.random()
        c = t * n1 + (1 - t) * n2
        rel = CUT_EXACT_DET_RTOL * (1.0 + rng.choice([-1, 1]) * 10.0 ** rng.uniform(-12, 0))
        k = rel * np.linalg.norm(n1) * np.linalg.norm(n2) / np.linalg.norm(cr)
        c = c + k * np.linalg.norm(c) / np.sqrt(1 - k * k) * cr / np.linalg.norm(cr)
        P[3] = P[0] + c
        ns = len(P)
        for a, b, cc in ((1, 2, 3), (1, 3, ns + trial % 3), (ns, ns + 1, ns + 2)):
            got = _ill(0, a, b, cc, P, WP, ns)
            assert got == _roots_test(P, a, b, cc), (trial, a, b, cc)
            r = _exact_ratio2(P, a, b, cc)
            if abs(r - rt2) > rt2 * Fr(1, 10**9):
                assert got == (r < rt2), (trial, a, b, cc)
            else:
                near += 1
    assert near > 10  # the threshold's neighbourhood was visited


def _exact_area(Q):
    """Twice the exact area vector of the ring ``Q`` (Fractions of its doubles)."""
    F = [[Fr(float(x)) for x in q] for q in Q]
    s = [Fr(0)] * 3
    for k in range(len(F)):
        u, w = F[k], F[(k + 1) % len(F)]
        s[0] += u[1] * w[2] - u[2] * w[1]
        s[1] += u[2] * w[0] - u[0] * w[2]
        s[2] += u[0] * w[1] - u[1] * w[0]
    return s


def _rings():
    """Faces a few ulps wide (nearly collinear rings), plane polygons, at several scales."""
    rng = np.random.default_rng(5)
    for trial in range(1500):
        n = int(rng.integers(3, 9))
        o = rng.random(3) * 10.0 ** rng.integers(-2, 7)
        e = rng.normal(size=3) * 10.0 ** rng.integers(-3, 2)
        if trial % 3 == 0:  # a plane polygon
            f = rng.normal(size=3) * np.linalg.norm(e)
            ang = np.sort(rng.random(n)) * 2 * np.pi
            Q = o + np.cos(ang)[:, None] * e + np.sin(ang)[:, None] * f
        else:  # points on a segment moved by a few ulps: zero, or a few ulps^2 of area
            t = np.sort(rng.random(n))
            if trial % 6 == 1:  # along an axis: exactly collinear unless moved
                e = np.eye(3)[trial % 3 - 1] * e[0]
            Q = o + t[:, None] * e
            k = int(rng.integers(0, 3)) * (trial % 3)
            Q = Q + rng.integers(-k, k + 1, Q.shape) * np.spacing(Q)
        yield Q


def test_clearly_not_flat_only_where_the_exact_area_and_every_fan_are_nonzero():
    proven = unproven_nonzero = zero = 0
    for Q in _rings():
        n = len(Q)
        roff = np.array([0, n], np.int64)
        for ring in (np.arange(n), np.arange(n)[::-1].copy(), np.roll(np.arange(n), 2)):
            vid = np.arange(n, dtype=np.int64)
            ring = ring.astype(np.int64)
            cnf = _clearly_not_flat(Q, roff, ring, 0, vid, 0, 1.0)
            ex = _exact_area(Q[ring])
            if cnf:
                proven += 1
                assert any(x != 0 for x in ex)
                assert not _flat_fan(Q, roff, ring, 0, vid, 0, 1.0)
            elif any(x != 0 for x in ex):
                unproven_nonzero += 1
            else:
                zero += 1
            assert _flat(Q, roff, ring, 0, vid, 0, 1.0) == _flat_fan(Q, roff, ring, 0, vid, 0, 1.0)
    # both sides of the shortcut were met, and exactly flat rings
    assert proven > 1500 and unproven_nonzero > 300 and zero > 100, (proven, unproven_nonzero, zero)
