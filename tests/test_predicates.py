"""The robust predicates agree in sign with exact rational arithmetic."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from voroforge.kernels.predicates import incircle, incircle_fast, orient2d

from reference import exact_incircle, exact_orient


def _sgn(v: float) -> int:
    return int(v > 0) - int(v < 0)  # int(): numpy bools do not subtract (JIT off)


def _check_orient(cases) -> None:
    bad = []
    for a, b, c in cases:
        got = _sgn(orient2d(*map(float, (*a, *b, *c))))
        want = exact_orient(a, b, c)
        if got != want:
            bad.append((a.tolist(), b.tolist(), c.tolist(), got, want))
    assert not bad, f"{len(bad)} orient2d sign errors, e.g. {bad[:3]}"


def _check_incircle(cases) -> None:
    bad = []
    for a, b, c, d in cases:
        if exact_orient(a, b, c) < 0:
            b, c = c, b
        got = _sgn(incircle(*map(float, (*a, *b, *c, *d))))
        want = exact_incircle(a, b, c, d)
        if got != want:
            bad.append((a.tolist(), b.tolist(), c.tolist(), d.tolist(), got, want))
    assert not bad, f"{len(bad)} incircle sign errors, e.g. {bad[:3]}"


def _ulp_nudge(p: np.ndarray, rng: np.random.Generator, k: int = 3) -> np.ndarray:
    """Move each coordinate of ``p`` by up to ``k`` ulps."""
    steps = rng.integers(-k, k + 1, size=p.shape)
    out = p.copy()
    for idx in np.ndindex(p.shape):
        for _ in range(abs(int(steps[idx]))):
            out[idx] = np.nextafter(out[idx], np.inf if steps[idx] > 0 else -np.inf)
    return out


def _near_collinear(n: int, seed: int, offset: float = 0.0):
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        a, b = rng.random((2, 2)) * max(10.0, offset) + offset
        t = rng.uniform(-2, 3)
        c = a + t * (b - a)  # rounded: usually a few ulps off the line
        out.append((a, b, _ulp_nudge(c, rng)))
    return out


def _near_cocircular(n: int, seed: int, offset: float = 0.0):
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        centre = rng.random(2) * 10 + offset
        r = rng.uniform(0.1, 5) * max(1.0, offset / 10)
        ang = np.sort(rng.uniform(0, 2 * np.pi, 4))
        p = centre + r * np.column_stack((np.cos(ang), np.sin(ang)))
        out.append((p[0], p[1], p[2], _ulp_nudge(p[3], rng)))
    return out


def test_orient_random():
    rng = np.random.default_rng(1)
    _check_orient(rng.uniform(-5, 5, size=(1000, 3, 2)))


def test_incircle_random():
    rng = np.random.default_rng(2)
    _check_incircle(rng.uniform(-5, 5, size=(1000, 4, 2)))


@pytest.mark.parametrize("offset", [0.0, 500000.0, 4000000.0], ids=["origin", "500k", "4M"])
def test_orient_near_collinear(offset):
    _check_orient(_near_collinear(600, 3, offset))


@pytest.mark.parametrize("offset", [0.0, 500000.0, 4000000.0], ids=["origin", "500k", "4M"])
def test_incircle_near_cocircular(offset):
    _check_incircle(_near_cocircular(600, 4, offset))


def test_orient_ulp_lattice():
    """Shewchuk's classic: c on a tiny lattice around the line through (12, 12) and (24, 24)."""
    ulp = 2.0**-53
    cases = []
    for i in range(48):
        for j in range(48):
            c = np.array([0.5 + i * ulp, 0.5 + j * ulp])
            cases.append((c, np.array([12.0, 12.0]), np.array([24.0, 24.0])))
    _check_orient(cases)


def test_incircle_ulp_lattice():
    """d on a tiny lattice around a point of the unit circle through three exact points."""
    a, b, c = np.array([1.0, 0.0]), np.array([0.0, 1.0]), np.array([-1.0, 0.0])
    base = np.array([0.6, -0.8])  # 0.6 and 0.8 are not exact in binary: near, not on
    cases = []
    for i in range(-20, 20):
        for j in range(-20, 20):
            d = base + np.array([i, j]) * 2.0**-52
            cases.append((a, b, c, d))
    _check_incircle(cases)


def test_integer_grid_exact_zeros():
    """Integer points: many exactly collinear / cocircular; zeros must come out as zeros."""
    pts = np.array([(x, y) for x in range(-3, 4) for y in range(-3, 4)], dtype=np.float64)
    rng = np.random.default_rng(5)
    tri = pts[rng.integers(0, len(pts), size=(1500, 3))]
    _check_orient(tri)
    quad = pts[rng.integers(0, len(pts), size=(1500, 4))]
    _check_incircle(quad)
    # a known exact zero of each
    assert orient2d(0.0, 0.0, 1.0, 1.0, 2.0, 2.0) == 0
    assert incircle(1.0, 0.0, 0.0, 1.0, -1.0, 0.0, 0.0, -1.0) == 0


def test_integer_grid_offset():
    """The same lattice at 500000/4000000: exact arithmetic, so the same signs."""
    pts = np.array([(x, y) for x in range(-3, 4) for y in range(-3, 4)], dtype=np.float64)
    rng = np.random.default_rng(6)
    off = np.array([500000.0, 4000000.0])
    _check_orient(pts[rng.integers(0, len(pts), size=(800, 3))] + off)
    _check_incircle(pts[rng.integers(0, len(pts), size=(800, 4))] + off)


def test_symmetries():
    rng = np.random.default_rng(7)
    for a, b, c, d in _near_cocircular(200, 8):
        o = _sgn(orient2d(*a, *b, *c))
        assert _sgn(orient2d(*b, *a, *c)) == -o
        assert _sgn(orient2d(*b, *c, *a)) == o
        if exact_orient(a, b, c) < 0:
            b, c = c, b
        s = _sgn(incircle(*a, *b, *c, *d))
        assert _sgn(incircle(*b, *c, *a, *d)) == s
        assert _sgn(incircle(*a, *c, *b, *d)) == -s
    del rng


# The predicates are exact when nothing underflows: coordinates are 0 or at least 2**-188
# in magnitude (and below 2**200). ``engine.inputs.working_frame`` puts every input there.
coord = st.floats(min_value=-1e6, max_value=1e6, allow_nan=False, allow_infinity=False).map(
    lambda v: v if abs(v) >= 2.0**-188 else 0.0
)
point = st.tuples(coord, coord).map(lambda p: np.array(p, dtype=np.float64))
small_int = st.integers(-4, 4).map(float)
lattice_point = st.tuples(small_int, small_int).map(lambda p: np.array(p))


@given(st.tuples(point, point, point))
def test_orient_hypothesis(abc):
    _check_orient([abc])


@given(st.tuples(point, point, point, point))
def test_incircle_hypothesis(abcd):
    _check_incircle([abcd])


@given(
    st.tuples(lattice_point, lattice_point, lattice_point, lattice_point),
    st.sampled_from([0.0, 0.5, 500000.0, 1e-3]),
)
def test_lattice_hypothesis(abcd, offset):
    a, b, c, d = (p + offset for p in abcd)
    _check_orient([(a, b, c)])
    _check_incircle([(a, b, c, d)])


def _tailed_near_cocircular(n: int, seed: int) -> np.ndarray:
    """``(n, 8)`` nearly cocircular quadruples whose differences to ``d`` are mostly inexact.

    Points of circles around (near) the origin, corners of grids with spacing ``2 / m``
    straddling zero, and Pythagorean integer points moved by a non-exact shift; ``d`` moved
    by a few ulps; scales ``2**-40 .. 2**40``. These reach incircle's adaptive stages
    (the rounded-difference determinant, its first-order tail correction, the exact one).
    """
    rng = np.random.default_rng(seed)
    k = n // 3
    scale = 2.0 ** rng.integers(-40, 41, (k, 1))
    centre = rng.uniform(-1, 1, (k, 2)) * rng.choice([0.0, 0.3, 1.0], (k, 1))
    radius = rng.uniform(0.05, 3.0, (k, 1))
    ang = rng.uniform(0, 2 * np.pi, (k, 4))
    circ = np.zeros((k, 8))
    circ[:, 0::2] = (centre[:, :1] + radius * np.cos(ang)) * scale
    circ[:, 1::2] = (centre[:, 1:] + radius * np.sin(ang)) * scale
    m = rng.choice([6, 10, 14, 632], (k, 1))
    i, j = rng.integers(-3, 3, (2, k, 1))
    x0, x1, y0, y1 = (2 * i + 1) / m, (2 * i + 3) / m, (2 * j + 1) / m, (2 * j + 3) / m
    grid = np.hstack((x0, y0, x1, y0, x1, y1, x0, y1)) * 2.0 ** rng.integers(-40, 41, (k, 1))
    pts = np.array([(5, 0), (0, 5), (-5, 0), (0, -5), (3, 4), (-3, 4), (3, -4), (-3, -4)])
    pts = np.vstack((pts, pts[4:, ::-1]))
    pick = np.array([rng.choice(len(pts), 4, replace=False) for _ in range(n - 2 * k)])
    shift = rng.choice([0.1, 1 / 3, 0.7], (n - 2 * k, 1, 2))
    pyth = ((pts[pick] + shift) * 2.0 ** rng.integers(-40, 41, (n - 2 * k, 1, 1))).reshape(-1, 8)
    circ[:, 6:] = _ulp_nudge(circ[:, 6:], rng, 10)
    grid[:, 6:] = _ulp_nudge(grid[:, 6:], rng, 1)  # often not at all: exactly cocircular
    pyth[:, 6:] = _ulp_nudge(pyth[:, 6:], rng, 10)
    return np.vstack((circ, grid, pyth))


def test_incircle_adaptive_stages():
    """Inexact differences: the stages between the float filter and the exact determinant."""
    cases = _tailed_near_cocircular(4000, 11)
    undecided = 0
    for q in cases:
        a, b, c, d = q[0:2], q[2:4], q[4:6], q[6:8]
        diffs = [(a[0], d[0]), (a[1], d[1]), (b[0], d[0]), (b[1], d[1]), (c[0], d[0]), (c[1], d[1])]
        tails = any(Fraction(float(u - v)) != Fraction(u) - Fraction(v) for u, v in diffs)
        undecided += bool(tails and np.isnan(incircle_fast(*map(float, q))))
    # the cases exercise the adaptive stages, not only the float filter
    assert undecided > len(cases) // 3
    _check_incircle([(q[0:2], q[2:4], q[4:6], q[6:8]) for q in cases])
    # the raw determinant's sign (no reordering to counter-clockwise) agrees too
    for q in cases[:300]:
        assert _sgn(incircle(*map(float, q))) == exact_incircle(q[0:2], q[2:4], q[4:6], q[6:8])


def test_parabola_gap_sign_is_exact():
    """``parabola_gap``'s sign against rationals, for ``sx`` a few ulps from the two
    parabolas' crossing (where the float filter cannot decide and the expansion stage
    answers), with sites close together or far apart, at several magnitudes."""
    from voroforge.kernels.fortune import _breakpoint
    from voroforge.kernels.predicates import parabola_gap

    rng = np.random.default_rng(12)
    exact_stage = 0
    for k in range(3000):
        scale = 10.0 ** rng.integers(-3, 4)
        spread = scale * (1e-14 if k % 2 else 1.0)
        px, py, qx, qy = scale * rng.normal() + spread * rng.normal(size=4)
        sweep = max(py, qy) + abs(rng.normal()) * spread
        if sweep <= max(py, qy) or py == qy:
            continue
        sx = _breakpoint(px, py, qx, qy, sweep)
        for _ in range(int(rng.integers(0, 4))):
            sx = np.nextafter(sx, rng.choice((-np.inf, np.inf)))
        args = tuple(float(v) for v in (sx, px, py, qx, qy, sweep))
        fx = [Fraction(v) for v in args]
        hp, hq = fx[5] - fx[2], fx[5] - fx[4]
        f = hp * ((fx[0] - fx[3]) ** 2 + hq**2) - hq * ((fx[0] - fx[1]) ** 2 + hp**2)
        assert _sgn(parabola_gap(*args)) == (f > 0) - (f < 0), args
        u, v, h, g = args[0] - args[1], args[0] - args[3], args[5] - args[2], args[5] - args[4]
        t1, t2 = h * (v * v + g * g), g * (u * u + h * h)
        exact_stage += abs(t1 - t2) < 8.0 * 2.0**-53 * (t1 + t2)
    assert exact_stage > 300  # the expansion stage was exercised
