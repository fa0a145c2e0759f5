"""The lost-side screen of the half-plane cells and of the cut cells (issue 15).

``kernels.sidegap.restore_sides`` puts back box sides a float cut lost between two
parallel bisectors (sites exactly on one line); it is asked of every half-plane cell.
Its callers now screen each ring first with ``may_have_parallel`` (inlined, a dot product
and orient2d's float filter, no call and no exact code), and call it only where some pair
of consecutive neighbours may lie on one line with the site, on opposite sides. The screen
must never skip a ring that ``restore_sides`` would change: checked here on strips of
sites an ulp apart on a line (where it must say yes), rings of random sites (where it says
no, and ``restore_sides`` agrees), and near-collinear triples either side of exact
collinearity (Fractions decide). ``side_path`` hands its crossings to
``restore_side_vertices``: they are the canonical crossings (``vertex.box_crossing``).
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np

from test_issue15_polygon_domains import _ulps_from
from voroforge.kernels.sidegap import may_have_parallel, restore_sides, side_path
from voroforge.kernels.vertex import box_crossing


def _collinear_between(i, a, b, xs, ys):
    """Exact (Fractions): ``i`` strictly between ``a`` and ``b`` on one line."""
    p = [(Fraction(xs[k]), Fraction(ys[k])) for k in (a, i, b)]
    (ax, ay), (ix, iy), (bx, by) = p
    if (bx - ax) * (iy - ay) - (by - ay) * (ix - ax) != 0:
        return False
    return (ax - ix) * (bx - ix) + (ay - iy) * (by - iy) < 0


def _check(i, lab, xs, ys, box):
    """The screen's answer against restore_sides' and the exact pairs of ``lab``."""
    m = len(lab)
    exact = any(
        lab[u - 1] >= 0
        and lab[u] >= 0
        and lab[u - 1] != i
        and lab[u] != i
        and lab[u - 1] != lab[u]
        and _collinear_between(i, lab[u - 1], lab[u], xs, ys)
        for u in range(m)
    )
    lab_arr = np.zeros(m + 8, np.int64)
    lab_arr[:m] = lab
    sure = np.ones(m + 8)
    screen = may_have_parallel(i, lab_arr, m, xs, ys)
    if exact:
        assert screen, (i, lab)
    if not screen:
        assert restore_sides(i, lab_arr, sure, m, xs, ys, box) == m
        assert lab_arr[:m].tolist() == list(lab)
    return screen, exact


def test_screen_never_skips_a_strip():
    """Sites an ulp apart on lines in 7 directions at offsets 0 .. 1e15: every middle site's
    ring with its two line neighbours (both orders, with sides between) is screened in,
    and restore_sides then puts the sides back."""
    hits = 0
    for off in (0.0, 5e5, 1e15):
        scale = 64.0 if off >= 1e15 else 1.0
        b = np.array([off, off, off + 10.0 * scale, off + 10.0 * scale])
        for step in ((1, -1), (-1, 1), (1, 1), (1, 0), (0, 1), (2, -1), (1, 3)):
            pts = _ulps_from((off + 2.25 * scale, off + 3.7 * scale), step, 5)
            xs = np.ascontiguousarray(pts[:, 0])
            ys = np.ascontiguousarray(pts[:, 1])
            for lab in ([1, -1, 3], [3, -3, 1], [1, 3], [-2, 1, -4, 3]):
                screen, exact = _check(2, lab, xs, ys, b)
                hits += exact
    assert hits >= 40


def test_screen_says_no_on_ordinary_rings():
    """Random sites (uniform, a grid, a circle): consecutive Delaunay-like rings are
    screened out nearly always, never where Fractions find a collinear pair."""
    g = np.random.default_rng(3)
    box = np.array([0.0, 0.0, 1.0, 1.0])
    said = 0
    total = 0
    for kind in ("uniform", "grid", "circle"):
        if kind == "uniform":
            pts = g.random((60, 2))
        elif kind == "grid":
            k = np.arange(8) / 8.0 + 1.0 / 16.0
            pts = np.column_stack([a.ravel() for a in np.meshgrid(k, k)])
        else:
            t = np.arange(60) * (2 * np.pi / 60)
            pts = 0.5 + 0.4 * np.column_stack((np.cos(t), np.sin(t)))
        xs = np.ascontiguousarray(pts[:, 0])
        ys = np.ascontiguousarray(pts[:, 1])
        n = len(xs)
        for i in range(n):
            d = np.hypot(xs - xs[i], ys - ys[i])
            d[i] = np.inf
            near = np.argsort(d)[:6]
            ang = np.arctan2(ys[near] - ys[i], xs[near] - xs[i])
            lab = [int(j) for j in near[np.argsort(ang)]]
            screen, exact = _check(i, lab, xs, ys, box)
            said += screen
            total += 1
    # a grid's opposite neighbours are exactly collinear: screened in (and restore_sides
    # leaves them: they are not consecutive in these rings unless the ring is a strip)
    assert total == 184 and said < total // 2, said


def test_screen_on_near_collinear_triples():
    """A site moved 0, 1 or 2 ulps off the line of its two neighbours, on opposite sides
    and on one side, at offsets 0.3 .. 4e6: the screen says yes wherever Fractions find the
    three collinear with the site between."""
    box = np.array([-1e7, -1e7, 1e7, 1e7])
    for off in (0.3, 7.0, 5e5, 4e6):
        for d in ((1.0, 0.0), (1.0, 1.0), (1.0, -3.0), (0.6, 0.8)):
            a = np.array([off, off])
            i = a + np.array(d) * 2.0**-20 * max(1.0, off)
            b = a + np.array(d) * 2.0**-19 * max(1.0, off)
            for k in range(3):
                ii = i.copy()
                ii[1] = np.nextafter(ii[1], np.inf) if k == 1 else ii[1]
                ii[0] = np.nextafter(np.nextafter(ii[0], -np.inf), -np.inf) if k == 2 else ii[0]
                for pts in ((a, ii, b), (b, ii, a), (a, b, ii)):
                    xs = np.ascontiguousarray([p[0] for p in pts])
                    ys = np.ascontiguousarray([p[1] for p in pts])
                    _check(1, [0, 2], xs, ys, box)
                    _check(1, [2, -1, 0], xs, ys, box)


def test_side_path_gives_the_canonical_crossings():
    """Five sites an ulp apart on the diagonal (1, -1): the crossings side_path returns
    are box_crossing's for both edges, on the sides it names."""
    pts = _ulps_from((2.25, 3.7), (1, -1), 5)
    xs = np.ascontiguousarray(pts[:, 0])
    ys = np.ascontiguousarray(pts[:, 1])
    box = np.array([0.0, 0.0, 10.0, 10.0])
    for a, b in ((1, 3), (3, 1)):
        first, count, xa, ya, xb, yb = side_path(2, a, b, xs, ys, box)
        assert count >= 1
        last = first
        for _ in range(count - 1):
            last = last - 1 if last > -4 else -1
        assert (xa, ya) == tuple(box_crossing(2, a, xs, ys, first, box))
        assert (xb, yb) == tuple(box_crossing(2, b, xs, ys, last, box))
