"""The vertex rule (kernels/vertex) tested on the kernel directly."""

from __future__ import annotations

import itertools
from fractions import Fraction

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from voroforge.kernels.vertex import (
    box_crossing,
    canonical_triple,
    canonical_vertex,
    canonical_vertex4,
    center,
    circumcenter,
    power_box_crossing,
    power_vertex,
    voronoi_vertex,
)

coord = st.floats(-1e3, 1e3, allow_nan=False, allow_infinity=False)


def _exact_power_center(p, w):
    """Exact power centre of three weighted points (Cramer's rule in Fractions)."""
    (ax, ay), (bx, by), (cx, cy) = [(Fraction(x), Fraction(y)) for x, y in p]
    wa, wb, wc = (Fraction(v) for v in w)
    # 2 (b - a).x = |b|^2 - |a|^2 - (wb - wa), same for c
    a11, a12 = 2 * (bx - ax), 2 * (by - ay)
    a21, a22 = 2 * (cx - ax), 2 * (cy - ay)
    r1 = bx * bx + by * by - ax * ax - ay * ay - (wb - wa)
    r2 = cx * cx + cy * cy - ax * ax - ay * ay - (wc - wa)
    det = a11 * a22 - a12 * a21
    return (r1 * a22 - r2 * a12) / det, (a11 * r2 - a21 * r1) / det


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(coord, coord), min_size=3, max_size=3, unique=True))
def test_vertex_bits_do_not_depend_on_argument_order(pts):
    xs = np.array([p[0] for p in pts])
    ys = np.array([p[1] for p in pts])
    ws = np.array([0.5, -2.0, 3.0])
    vor = {voronoi_vertex(a, b, c, xs, ys) for a, b, c in itertools.permutations(range(3))}
    pw = {power_vertex(a, b, c, xs, ys, ws) for a, b, c in itertools.permutations(range(3))}
    assert len(vor) == 1 or all(np.isnan(v).any() for v in vor)
    assert len(pw) == 1 or all(np.isnan(v).any() for v in pw)


def _bits(v):
    return np.array(v, dtype=np.float64).view(np.int64).tolist()


def _canonical_center(a, b, c, xs, ys, ws):
    """The rule's definition: :func:`center` on the owners sorted by (x, y, index).

    With equal weights, a centre whose rounding bound exceeds ``VERTEX_REFINE_RTOL`` of its
    magnitude is the exact expansions' (a sliver's), when that is finite.
    """
    from voroforge.config import VERTEX_REFINE_RTOL
    from voroforge.kernels.expansion import exact_circumcenter
    from voroforge.kernels.vertex import center_error

    a, b, c = sorted((a, b, c), key=lambda i: (xs[i], ys[i], i))
    args = (xs[a], ys[a], ws[a], xs[b], ys[b], ws[b], xs[c], ys[c], ws[c])
    x, y = center(*args)
    if ws[a] == ws[b] == ws[c] and center_error(*args) > VERTEX_REFINE_RTOL * (abs(x) + abs(y)):
        rx, ry = exact_circumcenter(xs[a], ys[a], xs[b], ys[b], xs[c], ys[c])
        if np.isfinite(rx) and np.isfinite(ry):
            return rx, ry
    return x, y


def _triples_catalogue():
    """Triples where an order-dependent shortcut would show: ties, zeros, slivers, extremes."""
    rng = np.random.default_rng(11)
    out = [rng.random((3, 2)) for _ in range(300)]
    out += [rng.integers(-3, 4, size=(3, 2)).astype(float) for _ in range(400)]  # ties
    out += [
        np.array([[0.0, 0.0], [1.0, 0.0], [0.5, np.sqrt(3) / 2]]),  # near equilateral
        np.array([[-0.0, 0.0], [-1.0, 2.0], [1.0, 2.0]]),  # centre on x = -0.0
        np.array([[0.0, -0.0], [2.0, -1.0], [2.0, 1.0]]),  # centre on y = -0.0
        np.array([[-0.0, -0.0], [-1.0, 1.0], [1.0, 1.0]]),  # right angle at -0.0
        np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]),  # right isosceles
        np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 1e-300]]),  # flat: huge centre
        np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]),  # collinear
        np.array([[1.0, 1.0], [1.0, 1.0], [3.0, 0.0]]),  # repeated site
        np.array([[1e300, 0.0], [-1e300, 0.0], [0.0, 1e300]]),  # overflow
        np.array([[1e-300, 0.0], [0.0, 1e-300], [-1e-300, 0.0]]),  # underflow
    ]
    for _ in range(200):  # slivers and near-collinear triples (the orient2d fallback)
        a = rng.random(2)
        d = rng.normal(size=2)
        h = 10.0 ** -rng.integers(6, 17)
        out.append(np.array([a, a + d, a + 0.5 * d + h * np.array([-d[1], d[0]])]))
    return out


def test_vertex_bits_are_those_of_the_sorted_owners_in_every_order():
    # the shortcut that skips the sort must give the rule's bits exactly, sign of zero too
    for p in _triples_catalogue():
        xs, ys = p[:, 0].copy(), p[:, 1].copy()
        zero = np.zeros(3)
        ws = np.array([0.25, -1.0, 2.0])
        ref = _bits(_canonical_center(0, 1, 2, xs, ys, zero))
        pref = _bits(_canonical_center(0, 1, 2, xs, ys, ws))
        for a, b, c in itertools.permutations(range(3)):
            assert _bits(voronoi_vertex(a, b, c, xs, ys)) == ref, p
            assert _bits(power_vertex(a, b, c, xs, ys, zero)) == ref, p
            assert _bits(power_vertex(a, b, c, xs, ys, ws)) == pref, p


def test_zero_or_equal_weights_give_the_circumcentre_bits():
    rng = np.random.default_rng(1)
    for p in rng.normal(size=(500, 6)) * 10.0 ** rng.integers(-5, 6, size=(500, 1)):
        ax, ay, bx, by, cx, cy = p
        c0 = circumcenter(ax, ay, bx, by, cx, cy)
        w = float(rng.normal()) * 1e3
        assert center(ax, ay, 0.0, bx, by, 0.0, cx, cy, 0.0) == c0
        assert center(ax, ay, w, bx, by, w, cx, cy, w) == c0


def test_circumcentre_against_exact_fractions():
    rng = np.random.default_rng(2)
    for p in rng.random((300, 3, 2)):
        xs, ys = p[:, 0].copy(), p[:, 1].copy()
        ex, ey = _exact_power_center(p, (0, 0, 0))
        x, y = voronoi_vertex(0, 1, 2, xs, ys)
        r = float(abs(ex - Fraction(p[0, 0])) + abs(ey - Fraction(p[0, 1])))
        assert abs(Fraction(x) - ex) + abs(Fraction(y) - ey) <= 1e-13 * (r + 1.0)


def test_near_degenerate_triples_keep_their_precision():
    rng = np.random.default_rng(3)
    for _ in range(200):
        # slivers: a tiny edge, or a third point almost on the line of the other two
        a = rng.random(2)
        d = rng.normal(size=2)
        h = 10.0 ** -rng.integers(4, 9)
        if rng.random() < 0.5:
            p = np.array([a, a + d, a + 0.5 * d + h * np.array([-d[1], d[0]])])
        else:
            p = np.array([a, a + h * d, a + rng.normal(size=2)])
        xs, ys = p[:, 0].copy(), p[:, 1].copy()
        ex, ey = _exact_power_center(p, (0, 0, 0))
        x, y = voronoi_vertex(0, 1, 2, xs, ys)
        r = float(abs(ex - Fraction(p[0, 0])) + abs(ey - Fraction(p[0, 1])))
        longest = max(np.hypot(*(p[i] - p[j])) for i, j in ((0, 1), (1, 2), (2, 0)))
        # a careful centre is off by a few ulps of the radius times the conditioning r / L
        assert abs(Fraction(x) - ex) + abs(Fraction(y) - ey) <= 8 * 2.0**-52 * r * max(
            1.0, r / longest
        )


def test_power_centre_against_exact_fractions():
    rng = np.random.default_rng(4)
    for _ in range(300):
        p = rng.random((3, 2))
        w = rng.random(3) * 0.1
        ex, ey = _exact_power_center(p, w)
        x, y = power_vertex(0, 1, 2, p[:, 0].copy(), p[:, 1].copy(), w)
        scale = float(abs(ex) + abs(ey)) + 1.0
        assert abs(Fraction(x) - ex) + abs(Fraction(y) - ey) <= 1e-12 * scale


def test_box_crossing_is_canonical_and_equal_weights_match():
    rng = np.random.default_rng(5)
    box = np.array([-1.0, -1.0, 2.0, 2.0])
    for _ in range(200):
        xs, ys = rng.random(2), rng.random(2)
        ws = np.full(2, float(rng.normal()))
        for side in (-1, -2, -3, -4):
            c = box_crossing(0, 1, xs, ys, side, box)
            assert c == box_crossing(1, 0, xs, ys, side, box)
            assert c == power_box_crossing(0, 1, xs, ys, ws, side, box)
            assert c == power_box_crossing(1, 0, xs, ys, ws, side, box)
            # on the bisector
            d0 = (c[0] - xs[0]) ** 2 + (c[1] - ys[0]) ** 2
            d1 = (c[0] - xs[1]) ** 2 + (c[1] - ys[1]) ** 2
            assert abs(d0 - d1) <= 1e-9 * (d0 + d1)


def test_power_box_crossing_is_on_the_power_bisector():
    xs = np.array([0.0, 1.0])
    ys = np.array([0.0, 0.0])
    ws = np.array([0.25, 0.0])  # |x|^2 - 1/4 = |x - 1|^2  ->  x = 5/8
    box = np.array([-1.0, -1.0, 2.0, 2.0])
    assert power_box_crossing(0, 1, xs, ys, ws, -2, box) == (0.625, -1.0)
    assert power_box_crossing(1, 0, xs, ys, ws, -4, box) == (0.625, 2.0)


def test_canonical_triple_of_cocircular_sites_is_the_same_from_every_order():
    # eight sites on the unit circle: every triple names the centre (to rounding)
    t = np.arange(8) * np.pi / 4
    xs, ys = np.cos(t), np.sin(t)
    rng = np.random.default_rng(6)
    for _ in range(20):
        sub = rng.permutation(8)[: rng.integers(4, 9)].astype(np.int64)
        vx, vy = voronoi_vertex(sub[0], sub[1], sub[2], xs, ys)
        s = sub[0]
        name = canonical_triple(sub.copy(), len(sub), vx, vy, xs[s], ys[s], xs, ys)
        assert name[0] >= 0
        # another order of the same sites, with repeats, another reference vertex and site
        other = np.concatenate((rng.permutation(sub), sub[:2]))
        wx, wy = voronoi_vertex(sub[-1], sub[-2], sub[-3], xs, ys)
        s2 = sub[-1]
        assert canonical_triple(other, len(other), wx, wy, xs[s2], ys[s2], xs, ys) == name
        v = canonical_vertex(sub.copy(), len(sub), vx, vy, xs[s], ys[s], xs, ys)
        assert v == voronoi_vertex(*name, xs, ys)


def test_canonical_triple_skips_ill_conditioned_triples():
    # sites 0 and 1 a few ulps apart on a circle: no name may hold both
    xs = np.array([1.0, np.nextafter(1.0, 2.0), 0.0, -1.0])
    ys = np.array([0.0, 0.0, 1.0, 0.0])
    on = np.array([0, 1, 2, 3], dtype=np.int64)
    a, b, c = canonical_triple(on, 4, 0.0, 0.0, 1.0, 0.0, xs, ys)
    assert a >= 0
    assert not {0, 1} <= {a, b, c}
    none = canonical_triple(np.array([0, 1], dtype=np.int64), 2, 0.0, 0.0, 1.0, 0.0, xs, ys)
    assert none == (-1, -1, -1)


def test_canonical_vertex4_is_canonical_vertex_bit_for_bit():
    # squares of a float grid (their triples' centres differ by ulps), four sites on the
    # unit circle, and a square with two sites a few ulps apart (ill-conditioned triples)
    k = 316  # benchmarks' grid(1e5): about half its squares' triples differ in bits
    axis = (np.arange(k) + 0.5) / k
    gx, gy = (g.ravel() for g in np.meshgrid(axis, axis))
    quads = [(gx, gy, [i, i + 1, i + k, i + k + 1]) for i in (0, 8, 17, 40, 1000, 5003, 20000)]
    t = np.array([0.1, 1.7, 2.9, 4.4])
    quads.append((np.cos(t), np.sin(t), [0, 1, 2, 3]))
    xs = np.array([1.0, np.nextafter(1.0, 2.0), 0.0, -1.0])
    quads.append((xs, np.array([0.0, 0.0, 1.0, 0.0]), [0, 1, 2, 3]))
    for xs, ys, q in quads:
        for p0, p1, p2, p3 in itertools.permutations(q):
            vx, vy = voronoi_vertex(p1, p2, p3, xs, ys)
            c1 = voronoi_vertex(p0, p2, p3, xs, ys)
            c2 = voronoi_vertex(p0, p1, p3, xs, ys)
            on = np.array([p0, p1, p2, p3], dtype=np.int64)
            want = canonical_vertex(on, 4, vx, vy, xs[p3], ys[p3], xs, ys)
            got = canonical_vertex4(p0, p1, p2, p3, vx, vy, *c1, *c2, xs, ys)
            assert _bits(got) == _bits(want)
