"""Issue 12 (3D exactness): vertices near the origin solved exactly, locate far out."""

from __future__ import annotations

import itertools
import warnings
from fractions import Fraction

import numpy as np
import pytest

import voroforge as vf
from voroforge.kernels.predicates3d import exact_point, scratch


def _sphere(n, seed, r=1.0, off=0.0):
    u = np.random.default_rng(seed).normal(size=(n, 3))
    return off + r * (u / np.linalg.norm(u, axis=1)[:, None])


def _exact_vertex(P, q):
    """The exact circumcentre of sites ``q`` (4 indices) as Fractions, or None (flat)."""
    a = [Fraction(float(c)) for c in P[q[0]]]
    A = [[Fraction(float(P[j][k])) - a[k] for k in range(3)] for j in q[1:]]
    b = [sum(x * x for x in r) / 2 for r in A]

    def det(M):
        return (
            M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1])
            - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0])
            + M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0])
        )

    D = det(A)
    if D == 0:
        return None
    out = []
    for k in range(3):
        M = [row[:] for row in A]
        for r in range(3):
            M[r][k] = b[r]
        out.append(a[k] + det(M) / D)
    return out


def test_exact_point_is_right_to_a_few_ulps_of_itself():
    # 8 float points on the unit sphere: every quadruple's centre lies within ~1e-15 of the
    # origin, where the float solve p0 + y (sites of size 1) keeps none of its digits
    P = _sphere(8, 8)
    W = np.zeros(8)
    WP = np.zeros((0, 4))
    buf = scratch()
    x = np.zeros(3)
    for q in itertools.combinations(range(8), 4):
        e = _exact_vertex(P, q)
        assert exact_point(q[0], q[1], q[2], q[3], P, W, WP, 8, buf, x) == (e is not None)
        if e is None:
            continue
        for k in range(3):
            err = abs(Fraction(float(x[k])) - e[k])
            assert err <= 4 * 2.0**-52 * abs(e[k]), (q, k, float(e[k]), x[k])


def test_exact_point_with_walls_and_weights():
    # a power vertex with one wall row, checked against the float solve where it is exact
    P = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    W = np.array([0.0, 0.25, -0.25])
    WP = np.array([[0.0, 0.0, 1.0, 0.5]])  # z <= 0.5
    x = np.zeros(3)
    assert exact_point(0, 1, 2, 3, P, W, WP, 3, scratch(), x)
    # 2 x . (p_k - p_0) = |p_k|^2 + w_0 - w_k: x = (1 - 0.25) / 2, y = (1 + 0.25) / 2
    assert x.tolist() == [0.375, 0.625, 0.5]


def _exact_nearest(S, q):
    d2 = [sum((Fraction(float(q[k])) - Fraction(float(s[k]))) ** 2 for k in range(3)) for s in S]
    m = min(d2)
    return min(i for i in range(len(S)) if d2[i] == m)


@pytest.mark.parametrize("n", [20, 200])  # the full scan and the k-d tree path
def test_locate_far_queries_no_overflow(n):
    # queries at 1e200 squared to inf: every site was a near tie, with an overflow warning
    g = np.random.default_rng(1)
    S = g.random((n, 3))
    d = vf.voronoi3d(S)
    Q = np.array(
        [[1e200, 0.5, 0.5], [-1e200, 1e200, 0.0], [1e308, 1e308, 1e308], [1e-300, 0.0, 0.7]]
    )
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = d.locate(Q)
    assert got.tolist() == [_exact_nearest(S, q) for q in Q]


def test_locate_far_queries_weighted():
    g = np.random.default_rng(2)
    S = g.random((30, 3))
    W = 0.01 * g.random(30)
    d = vf.voronoi3d(S, weights=W)
    q = np.array([1e250, -3e249, 0.5])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = d.locate(q)
    d2 = [
        sum((Fraction(float(q[k])) - Fraction(float(s[k]))) ** 2 for k in range(3))
        - Fraction(float(w))
        for s, w in zip(S, W, strict=True)
    ]
    assert got == min(range(30), key=lambda i: (d2[i], i))
