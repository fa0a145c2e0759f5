"""Exact 3D predicates (kernels/predicates3d) against fractions on near-degenerate input."""

from __future__ import annotations

from fractions import Fraction as Q

import numpy as np
import pytest

from voroforge.kernels.predicates3d import bisector_side, insphere, orient3d, scratch


def _det(m):
    """Exact determinant of a small square matrix of Fractions (Laplace)."""
    n = len(m)
    if n == 1:
        return m[0][0]
    return sum(
        (-1) ** c * m[0][c] * _det([row[:c] + row[c + 1 :] for row in m[1:]]) for c in range(n)
    )


def _sgn(x):
    return (x > 0) - (x < 0)


def _orient_ref(a, b, c, d):
    d = [Q(v) for v in d]
    return _sgn(_det([[Q(p[k]) - d[k] for k in range(3)] for p in (a, b, c)]))


def _insphere_ref(p5):
    e = [Q(v) for v in p5[4]]
    rows = []
    for p in p5[:4]:
        r = [Q(p[k]) - e[k] for k in range(3)]
        rows.append(r + [sum(x * x for x in r)])
    return _sgn(_det(rows))


def _row_ref(key, i, P, W, WP, ns):
    if key < ns:
        r = [Q(P[key][k]) - Q(P[i][k]) for k in range(3)]
        return r, (sum(x * x for x in r) + Q(W[i]) - Q(W[key])) / 2
    n = [Q(v) for v in WP[key - ns][:3]]
    return n, Q(WP[key - ns][3]) - sum(n[k] * Q(P[i][k]) for k in range(3))


def _side_ref(i, k0, k1, k2, j, P, W, WP, ns):
    rows = [_row_ref(k, i, P, W, WP, ns) for k in (k0, k1, k2)]
    m = [r for r, _ in rows]
    d = _det(m)
    if d == 0:
        return 2
    y = []
    for c in range(3):  # Cramer
        mc = [row[:c] + [t] + row[c + 1 :] for row, (_, t) in zip(m, rows, strict=True)]
        y.append(_det(mc) / d)
    rj, tj = _row_ref(j, i, P, W, WP, ns)
    return _sgn(sum(rj[k] * y[k] for k in range(3)) - tj)


def _ulps(x, k):
    for _ in range(abs(k)):
        x = np.nextafter(x, np.inf if k > 0 else -np.inf)
    return x


OFFSETS = [(0.0, 0.0, 0.0), (500000.0, 4000000.0, 100.0), (-3.0, 7.0, 1e-3)]


@pytest.mark.parametrize("off", OFFSETS)
@pytest.mark.parametrize("scale", [1e-9, 1.0, 1e9])
def test_orient3d_near_coplanar(off, scale):
    rng = np.random.default_rng(3)
    o = np.array(off) * scale
    for _ in range(40):
        a, b, c = (o + rng.integers(-8, 9, 3) * scale * 0.125 for _ in range(3))
        u, v = rng.integers(-4, 5, 2) / 4
        d = a + u * (b - a) + v * (c - a)  # coplanar when the sums are exact
        for k in (0, 1, -1, 2):
            dd = d.copy()
            if dd[k % 3] == 0.0:
                continue  # ulps of 0 are subnormal: outside the predicates' range
            dd[k % 3] = _ulps(dd[k % 3], k)
            got = orient3d(*a, *b, *c, *dd)
            assert np.sign(got) == _orient_ref(a, b, c, dd)


# Pythagorean quadruples a^2 + b^2 + c^2 = r^2: points of one sphere
_QUAD = [(1, 2, 2, 3), (2, 3, 6, 7), (1, 4, 8, 9), (4, 4, 7, 9), (2, 6, 9, 11), (6, 6, 7, 11)]


def _sphere_points(rng, k):
    pts = []
    for _ in range(k):
        a, b, c, r = _QUAD[rng.integers(len(_QUAD))]
        v = np.array([a, b, c], float)[rng.permutation(3)] * rng.choice([-1, 1], 3) / r
        pts.append(v * 693.0)  # 693 = 3 * 7 * 9 * 11: integer points on one sphere
    return np.array(pts)


@pytest.mark.parametrize("off", OFFSETS)
def test_insphere_cospherical_and_perturbed(off):
    rng = np.random.default_rng(5)
    zeros = 0
    for t in range(60):
        p5 = _sphere_points(rng, 5) + np.array(off)
        if t % 3:
            r, c = rng.integers(5), rng.integers(3)
            p5[r, c] = _ulps(p5[r, c], int(rng.choice([-2, -1, 1, 2])))
        want = _insphere_ref(p5)
        zeros += want == 0
        assert np.sign(insphere(np.ascontiguousarray(p5))) == want
    assert zeros >= 10  # the exact zeros were exercised


def test_insphere_sign_convention():
    tet = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    a, b, c, d = tet
    if orient3d(*a, *b, *c, *d) < 0:
        tet[[1, 2]] = tet[[2, 1]]
    inside = np.vstack([tet, [[0.25, 0.25, 0.25]]])
    outside = np.vstack([tet, [[2.0, 2.0, 2.0]]])
    assert insphere(inside) > 0 > insphere(outside)


def _lattice(kind, h, off):
    g = np.arange(-2, 3)
    pts = np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3).astype(float)
    if kind == "bcc":
        pts = np.vstack([pts, pts[:64] + 0.5])
    return pts * h + np.array(off)


@pytest.mark.parametrize("kind", ["cubic", "bcc"])
@pytest.mark.parametrize("h,off", [(0.1, (0, 0, 0)), (1.0, (500000.0, 4000000.0, 100.0))])
def test_bisector_side_on_lattices(kind, h, off):
    """Vertices of lattice cells against every nearby plane, walls included: exact answers."""
    P = _lattice(kind, h, off)
    ns = len(P)
    W = np.zeros(ns)
    lo = P.min(axis=0) + 0.5 * h
    hi = P.max(axis=0) - 0.5 * h
    WP = np.array(
        [
            [-1, 0, 0, -lo[0]],
            [1, 0, 0, hi[0]],
            [0, -1, 0, -lo[1]],
            [0, 1, 0, hi[1]],
            [0, 0, -1, -lo[2]],
            [0, 0, 1, hi[2]],
        ]
    )
    rows = np.zeros((2, 4, 4))
    buf = scratch()
    rng = np.random.default_rng(7)
    i = int(np.argmin(np.linalg.norm(P - P.mean(axis=0), axis=1)))
    near = np.argsort(np.linalg.norm(P - P[i], axis=1))[1:19]
    keys = np.concatenate([near, ns + np.arange(6)])
    counts = {-1: 0, 0: 0, 1: 0, 2: 0}
    for _ in range(150):
        k0, k1, k2, j = (int(k) for k in rng.choice(keys, 4, replace=False))
        got = bisector_side(i, k0, k1, k2, j, P, W, WP, ns, rows, buf)
        want = _side_ref(i, k0, k1, k2, j, P, W, WP, ns)
        assert got == want, (k0, k1, k2, j)
        counts[want] += 1
    assert counts[2] > 0 and counts[1] > 0 and counts[-1] > 0
    assert counts[0] > 0 or kind == "bcc"  # the cubic grid's 8 co-spherical sites per vertex


def test_bisector_side_weights_and_ulps():
    """Power bisectors, one coordinate moved by ulps: the sign flips exactly when it should."""
    rng = np.random.default_rng(11)
    base = _lattice("cubic", 0.5, (1e3, -2e3, 3e3))
    ns = len(base)
    WP = np.zeros((0, 4))
    rows = np.zeros((2, 4, 4))
    buf = scratch()
    i = 62  # the centre of the 5x5x5 block
    for t in range(80):
        P = base.copy()
        W = np.zeros(ns) if t % 2 else rng.integers(-3, 4, ns) * 0.03125
        k0, k1, k2, j = (int(k) for k in rng.choice(np.delete(np.arange(ns), i), 4, replace=False))
        if t % 4 < 2:
            P[j, t % 3] = _ulps(P[j, t % 3], int(rng.choice([-1, 1])))
        got = bisector_side(i, k0, k1, k2, j, P, W, WP, ns, rows, buf)
        assert got == _side_ref(i, k0, k1, k2, j, P, W, WP, ns)
