"""The batched exact incircle of reference.py (used by validate.check_empty_circumcircles).

``exact_incircle_signs`` computes :func:`reference.exact_incircle`'s determinant in Python
integers over one common power of two, for many (triangle, point) pairs at once. These
tests check that it gives the Fraction version's sign on every pair: clear cases, exact
ties (sign 0), float circles (ties only to rounding), and doubles from subnormal to huge
in one input (the common denominator spans the whole exponent range).
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from reference import (
    dyadic_integers,
    exact_circumcentre,
    exact_circumcentres,
    exact_incircle,
    exact_incircle_signs,
)
from validate import check_empty_circumcircles


def _pairs(n_pts, n_tri, m, seed):
    rng = np.random.default_rng(seed)
    T = np.array([rng.choice(n_pts, 3, replace=False) for _ in range(n_tri)], dtype=np.int64)
    ti = rng.integers(0, n_tri, m)
    pi = rng.integers(0, n_pts, m)
    return T, ti, pi


def _circle(n, r, off):
    t = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
    return np.column_stack((np.cos(t), np.sin(t))) * r + off


def _inputs():
    rng = np.random.default_rng(0)
    grid = np.array([(x, y) for x in range(-3, 4) for y in range(-3, 4)], dtype=float)
    mixed = rng.random((40, 2)) * 10.0 ** rng.integers(-300, 300, (40, 2))
    mixed[:4] = [[5e-324, 0.0], [-5e-324, 1e-310], [1e300, -1e300], [2.0**-1074, 2.0**1023]]
    return {
        "random": rng.random((30, 2)),
        "integer_grid": grid,  # many exactly co-circular quadruples
        "float_circle": _circle(40, 1.0, 0.0),
        "float_circle_far": _circle(40, 2.0, [1e4, 1e4]),
        "mixed_exponents": mixed,
    }


@pytest.mark.parametrize("name", list(_inputs()))
def test_signs_are_the_fraction_signs(name):
    pts = _inputs()[name]
    T, ti, pi = _pairs(len(pts), 60, 600, 1)
    got = exact_incircle_signs(pts, T, ti, pi)
    want = [exact_incircle(*pts[T[t]], pts[k]) for t, k in zip(ti, pi, strict=True)]
    assert got.tolist() == want
    assert {-1, 1} <= set(got.tolist())
    if name == "integer_grid":
        assert (got == 0).any()  # exact ties, told apart from both sides


@pytest.mark.parametrize("name", list(_inputs()))
def test_circumcentres_are_the_fraction_centres(name):
    pts = _inputs()[name]
    pts = np.ldexp(pts, -int(np.frexp(np.abs(pts).max())[1]))  # as validate scales them
    T, _, _ = _pairs(len(pts), 200, 0, 2)
    T = T[[not _collinear(pts[t]) for t in T]]
    got = exact_circumcentres(pts, T)
    want = np.array([exact_circumcentre(*pts[t]) for t in T])
    assert got.shape == (len(T), 2) and len(T) > 100
    assert np.array_equal(got, want)  # the same doubles (both round the exact value once)
    with pytest.raises(ZeroDivisionError):  # exactly collinear, as exact_circumcentre
        exact_circumcentres([[0.0, 0.0], [1.0, 1.0], [3.0, 3.0]], [[0, 1, 2]])


def _collinear(p):
    (ax, ay), (bx, by), (cx, cy) = (tuple(map(Fraction, q)) for q in p.tolist())
    return (bx - ax) * (cy - ay) == (by - ay) * (cx - ax)


def test_dyadic_integers_are_exact():
    v = np.array([[0.1, -3.5], [5e-324, 1e300], [0.0, -0.0]])
    K, s = dyadic_integers(v)
    assert K.shape == v.shape and s & (s - 1) == 0  # a power of two
    assert all(int(k) / s == x for k, x in zip(K.ravel(), v.ravel(), strict=True))


def test_empty_circle_check_still_finds_a_point_inside():
    # a square's two triangulations: the point of the other diagonal is on the circle
    # (accepted); pulled in by one ulp it is inside (named)
    pts = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    T = np.array([[0, 1, 2], [0, 2, 3]], dtype=np.int64)
    check_empty_circumcircles(pts, T, np.arange(4))
    pts[3, 0] = np.nextafter(0.0, 1.0)
    with pytest.raises(AssertionError, match=r"inside circumcircles.*\(0, 3\)"):
        check_empty_circumcircles(pts, T, np.arange(4))
    assert len(exact_incircle_signs(pts, T, np.zeros(0, int), np.zeros(0, int))) == 0
