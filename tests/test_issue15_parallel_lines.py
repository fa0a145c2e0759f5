"""Points along a few parallel lines (issue 15, checker12 F14): the sweep's quadratic flips.

The circle sweep reaches such points one line after another: every point of a later line
takes over the fan of edges its predecessor held to the earlier line, so the sweep made
``~n / 30`` flips a point on three lines (1,324 a point at 48,000 points against 4.4 for
uniform ones; 4.3 s against 0.07 s), and a periodic diagram of sites on one line (whose
images are such lines) took minutes. The sweep now gives up past a flip budget and inserts
the points in a biased randomised order after the convex hull (``_triangulate_brio``):
the same triangulation wherever it is unique, and a Delaunay one (exact incircle)
everywhere. Three lines of integer points made the sweep's hull walk quadratic instead
(~n / 150 steps a point); the walk's steps count against the same budget.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from scipy.spatial import ConvexHull, Delaunay

import voroforge as vf
from voroforge.kernels import delaunay as kd
from voroforge.kernels.cocircular import canonical_flips

from reference import brute_voronoi, exact_incircle, exact_orient, exact_twice_area


def _lines(n, k, *, seed=0, angle=0.0, offset=0.0, integer=False):
    rng = np.random.default_rng(seed)
    m = n // k
    parts = []
    for j in range(k):
        x = np.arange(m, dtype=float) if integer else rng.random(m)
        parts.append(np.column_stack([x, np.full(m, float(j))]))
    p = np.vstack(parts)
    if angle:
        c, s = np.cos(angle), np.sin(angle)
        p = p @ np.array([[c, s], [-s, c]])
    return p + offset


def _crossing(n, seed=0):
    rng = np.random.default_rng(seed)
    a = 2.0 * rng.random(n // 2) - 1.0
    b = 2.0 * rng.random(n // 2) - 1.0
    return np.vstack([np.column_stack([a, 0.3 * a]), np.column_stack([b, 1e-3 - 2.0 * b])])


CASES = {
    "2_lines": lambda n: _lines(n, 2),
    "3_lines": lambda n: _lines(n, 3),
    "5_lines": lambda n: _lines(n, 5),
    "10_lines": lambda n: _lines(n, 10),
    "3_lines_at_0.3_rad": lambda n: _lines(n, 3, angle=0.3),
    "3_lines_at_1e6": lambda n: _lines(n, 3, offset=1e6),
    "2_crossing_lines": _crossing,
    "uniform": lambda n: np.random.default_rng(0).random((n, 2)),
}
#: Qhull's joggled answer is not the exact one on rounded or far lines
SCIPY_EXACT = {"2_lines", "3_lines", "5_lines", "10_lines", "2_crossing_lines", "uniform"}


def _brio(p):
    """The fallback forced, on the sweep's order; returns its result and its flips."""
    order, sx, sy = kd.triangulate_sorted(p[:, 0].copy(), p[:, 1].copy())[:3]
    return kd._triangulate_brio(sx, sy, order)


def _triangle_set(order, tri):
    t = np.sort(np.asarray(order)[tri].reshape(-1, 3), axis=1)
    return set(map(tuple, t.tolist()))


def _check_exact(order, sx, sy, tri, he, p):
    """Halfedge twins, CCW triangles, locally Delaunay edges (exact) and the hull's area."""
    pts = np.column_stack([sx, sy])
    e = np.flatnonzero(he >= 0)
    assert np.array_equal(he[he[e]], e)
    nxt = 3 * (e // 3) + (e % 3 + 1) % 3
    assert np.array_equal(tri[he[e]], tri[nxt])
    for t in tri.reshape(-1, 3):
        assert exact_orient(pts[t[0]], pts[t[1]], pts[t[2]]) > 0
    for a in e[he[e] > e]:
        b = he[a]
        q = [tri[a], tri[3 * (a // 3) + (a % 3 + 1) % 3], tri[3 * (a // 3) + (a % 3 + 2) % 3]]
        d = tri[3 * (b // 3) + (b % 3 + 2) % 3]
        assert exact_incircle(*(pts[i] for i in q), pts[d]) <= 0
    # the triangles tile the convex hull (Qhull's, to its rounding)
    total = sum(exact_twice_area(pts, t) for t in tri.reshape(-1, 3))
    assert abs(float(total) / 2 - ConvexHull(p).volume) <= 1e-12 * ConvexHull(p).volume


@pytest.mark.parametrize("name", sorted(CASES))
def test_fallback_is_the_sweeps_delaunay(name):
    """Forced on 600 points: the same triangles as the unlimited sweep (exact) and scipy's."""
    p = CASES[name](600)
    (order, sx, sy, tri, he, hull, ok), flips = _brio(p)
    assert ok
    full = kd.triangulate_sorted(p[:, 0].copy(), p[:, 1].copy(), max_flips=-1)
    assert _triangle_set(order, tri) == _triangle_set(full[0], full[3])
    if name in SCIPY_EXACT:
        assert _triangle_set(order, tri) == _triangle_set(np.arange(len(p)), Delaunay(p).simplices)
    hull_in = order[hull]
    assert sorted(hull_in.tolist()) == sorted(full[0][full[5]].tolist())
    assert flips <= 4 * len(p)


@pytest.mark.parametrize("name", ["3_lines", "2_crossing_lines", "3_lines_at_0.3_rad"])
def test_fallback_is_exactly_delaunay(name):
    p = CASES[name](150)
    (order, sx, sy, tri, he, _, _), _ = _brio(p)
    _check_exact(order, sx, sy, tri, he, p)


def test_integer_lines_with_ties():
    """Squares of a lattice of 3 x 40 points: every diagonal is a tie. Both builders give a
    Delaunay triangulation (exact), the same one once ties go to the lower diagonal."""
    p = _lines(120, 3, integer=True)
    (order, sx, sy, tri, he, _, _), _ = _brio(p)
    _check_exact(order, sx, sy, tri, he, p)
    full = kd.triangulate_sorted(p[:, 0].copy(), p[:, 1].copy(), max_flips=-1)
    sets = []
    for o, x, y, t, h in ((order, sx, sy, tri, he), full[:5]):
        t = t.copy()
        h = h.copy()
        canonical_flips(np.ascontiguousarray(x), np.ascontiguousarray(y), t, h, np.arange(len(t)))
        sets.append(_triangle_set(o, t))
    assert sets[0] == sets[1]


def test_default_gives_up_on_three_lines():
    """3 x 2,000 points: the sweep passes its flip budget (it would make ~60 flips a point),
    the fallback makes fewer than 4 a point, and vf.delaunay's triangles are scipy's."""
    p = _lines(6000, 3)
    xs, ys = p[:, 0].copy(), p[:, 1].copy()
    order, sx, sy = kd.triangulate_sorted(xs, ys, max_flips=-1)[:3]
    budget = kd.FLIP_BUDGET_PER_POINT * len(p) + kd.FLIP_BUDGET_BASE
    assert kd._sweep(sx, sy, budget)[-1] > budget
    assert kd._triangulate_brio(sx, sy, order)[1] < 4 * len(p)
    tri = vf.delaunay(p)
    assert _triangle_set(np.arange(len(p)), tri.triangles) == _triangle_set(
        np.arange(len(p)), Delaunay(p).simplices
    )
    outer = np.flatnonzero(p[:, 1] != 1.0)  # every point of the two outer lines
    assert set(outer.tolist()) <= set(tri.hull.tolist())
    assert sorted(tri.hull.tolist()) == sorted(
        order[kd.triangulate_sorted(xs, ys, max_flips=-1)[5]].tolist()
    )
    hp = p[tri.hull]
    u = np.roll(hp, -1, 0) - hp
    v = np.roll(u, -1, 0)
    turn = u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]
    assert (turn >= 0).all()


def test_voronoi_through_the_fallback(monkeypatch):
    """With no flip budget, the default Voronoi of 3 x 40 points on lines (through the
    fallback) has the half-plane intersection's cells."""
    monkeypatch.setattr(kd, "FLIP_BUDGET_PER_POINT", 0)
    monkeypatch.setattr(kd, "FLIP_BUDGET_BASE", 0)
    p = _lines(120, 3, seed=3)
    order, sx, sy = kd.triangulate_sorted(p[:, 0].copy(), p[:, 1].copy(), max_flips=-1)[:3]
    assert kd._sweep(sx, sy, 0)[-1] > 0  # so the default gave up
    d = vf.voronoi(p, (-0.5, -0.5, 1.5, 2.5))
    ref = brute_voronoi(p, shapely.box(-0.5, -0.5, 1.5, 2.5))
    np.testing.assert_allclose(d.areas, [c.area for c in ref], rtol=1e-9, atol=1e-12)


def test_integer_lines_hull_walk_gives_up():
    """3 x 6,667 integer points: the sweep's hull walk (Delaunator's forward walk from the
    angle hash) went round long collinear hull runs, ~n / 150 steps a point (107 s at 1e6
    points); it now gives up past the budget too. The result is checked exactly in integers."""
    p = _lines(20001, 3, integer=True)
    xs, ys = p[:, 0].copy(), p[:, 1].copy()
    order, sx, sy = kd.triangulate_sorted(xs, ys, max_flips=-1)[:3]
    budget = kd.FLIP_BUDGET_PER_POINT * len(p) + kd.FLIP_BUDGET_BASE
    assert kd._sweep(sx, sy, budget)[-1] > budget
    tri = vf.delaunay(p)
    q = p.astype(np.int64)
    t = tri.triangles
    a, b, c = q[t[:, 0]], q[t[:, 1]], q[t[:, 2]]
    assert ((b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0] > 0).all()
    e = np.flatnonzero(tri.halfedges > np.arange(len(tri.halfedges)))
    f = tri.halfedges[e]
    flat = t.ravel()
    pa, pb = q[flat[e]], q[flat[3 * (e // 3) + (e % 3 + 1) % 3]]
    pc, pd = q[flat[3 * (e // 3) + (e % 3 + 2) % 3]], q[flat[3 * (f // 3) + (f % 3 + 2) % 3]]
    u, v, w = pa - pd, pb - pd, pc - pd
    lift = [(r * r).sum(axis=1) for r in (u, v, w)]
    det = (
        lift[0] * (v[:, 0] * w[:, 1] - w[:, 0] * v[:, 1])
        + lift[1] * (w[:, 0] * u[:, 1] - u[:, 0] * w[:, 1])
        + lift[2] * (u[:, 0] * v[:, 1] - v[:, 0] * u[:, 1])
    )
    assert (det <= 0).all()  # every edge locally Delaunay: the triangulation is Delaunay
    assert len(t) == 2 * len(p) - 2 - len(tri.hull)
