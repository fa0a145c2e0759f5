"""The fast paths of the Delaunay-dual cells give the bits of the plain computations.

Issue 10's win-back replaced two whole passes of ``kernels/centers`` by cheaper ones:

- the centres' rounding bounds are computed with the centres, from one set-up
  (``vertex.voronoi_vertex_and_error``), instead of a second pass over the triangles;
- the fold rounds (``centers._unfold``) test only the Voronoi edges whose answer can have
  changed, instead of every edge every round.

Each is checked here against the plain version, bit for bit, on inputs where the merges
and folds actually happen (float circles, lattices, near-cocircular classes).
"""

from __future__ import annotations

import itertools
from fractions import Fraction

import numpy as np
import pytest

from voroforge.kernels import centers
from voroforge.kernels.delaunay import triangulate_sorted
from voroforge.kernels.predicates import incircle
from voroforge.kernels.vertex import (
    center_error,
    center_offset,
    voronoi_vertex,
    voronoi_vertex_and_error,
    voronoi_vertex_error,
)

from catalogue import CATALOGUE

#: ``_name_classes``' ``pick``: empty names every class
EVERY = np.zeros(0, dtype=np.uint8)


def _bits(*values):
    return np.array(values, dtype=np.float64).tobytes()


def _triples():
    """Site sets with ties of edge lengths, exact lattices far out, slivers, float circles."""
    rng = np.random.default_rng(3)
    out = []
    pts = rng.random((40, 2))
    out.append((pts, [tuple(rng.choice(40, 3, replace=False)) for _ in range(60)]))
    lat = np.array([(i, j) for i in range(4) for j in range(4)], dtype=np.float64)
    for off in (0.0, 5e13, 1e15):
        out.append((lat + off, list(itertools.combinations(range(16), 3))[::5]))
    t = np.arange(64) * (2.0 * np.pi / 64)
    circ = np.column_stack((np.cos(t), np.sin(t)))
    out.append((circ, list(itertools.combinations(range(64), 3))[::97]))
    sliver = np.array([[0.0, 0.0], [1.0, 1e-12], [2.0, 0.0], [1.0, 0.0], [0.5, 0.5]])
    out.append((sliver, list(itertools.combinations(range(5), 3))))
    return out


def test_vertex_and_error_are_the_separate_routines_bit_for_bit():
    n = 0
    for pts, trips in _triples():
        xs = np.ascontiguousarray(pts[:, 0])
        ys = np.ascontiguousarray(pts[:, 1])
        for trip in trips:
            for a, b, c in itertools.permutations(trip):
                x, y, err = voronoi_vertex_and_error(a, b, c, xs, ys)
                assert _bits(x, y) == _bits(*voronoi_vertex(a, b, c, xs, ys))
                assert _bits(err) == _bits(voronoi_vertex_error(a, b, c, xs, ys))
                n += 1
    assert n > 1000


def _exact_center(p):
    (ax, ay), (bx, by), (cx, cy) = [(Fraction(x), Fraction(y)) for x, y in p]
    d = 2 * ((bx - ax) * (cy - ay) - (by - ay) * (cx - ax))
    if d == 0:
        return None  # exactly collinear: no centre
    b2 = (bx - ax) ** 2 + (by - ay) ** 2
    c2 = (cx - ax) ** 2 + (cy - ay) ** 2
    ux = ((cy - ay) * b2 - (by - ay) * c2) / d
    uy = ((bx - ax) * c2 - (cx - ax) * b2) / d
    return ax + ux, ay + uy


def test_center_error_bounds_the_exact_centre():
    """The shared set-up keeps ``center_error`` a proven bound (exact centres, Fractions)."""
    rng = np.random.default_rng(4)
    checked = 0
    for scale, off in ((1.0, 0.0), (1e-6, 1e6), (1e3, -1e12)):
        for _ in range(200):
            p = rng.random((3, 2)) * scale + off
            args = (p[0, 0], p[0, 1], 0.0, p[1, 0], p[1, 1], 0.0, p[2, 0], p[2, 1], 0.0)
            ox, oy, ux, uy = center_offset(*args)
            err = center_error(*args)
            exact = _exact_center(p)
            if exact is None or not np.isfinite(err):
                continue  # no centre, or one floats cannot place (an infinite bound)
            dist = abs(Fraction(ox + ux) - exact[0]) + abs(Fraction(oy + uy) - exact[1])
            assert dist <= Fraction(err)
            checked += 1
    assert checked > 500


def _triangulation(pts):
    xs = np.ascontiguousarray(pts[:, 0])
    ys = np.ascontiguousarray(pts[:, 1])
    order, sx, sy, tri, he, _, ok = triangulate_sorted(xs, ys)
    assert ok
    return np.ascontiguousarray(sx), np.ascontiguousarray(sy), tri, he, order


def _plain_merge(sx, sy, tri, he, rank, box):
    """The cocircular merge with every fold round over every edge (the rule as stated)."""
    cx, cy, err, flag = centers.circumcenters(sx, sy, tri, he)
    t = len(cx)
    parent = np.arange(t)

    def find(a):
        while parent[a] != a:
            a = parent[a]
        return a

    def link(a, b):
        ra, rb = find(a), find(b)
        if ra == rb:
            return 0
        parent[max(ra, rb)] = min(ra, rb)
        return 1

    edges = [(e, int(he[e])) for e in range(len(tri)) if he[e] > e]
    merged = False
    for e, f in edges:
        q = [int(tri[e]), int(tri[e - e % 3 + (e + 1) % 3]), int(tri[e - e % 3 + (e + 2) % 3])]
        d = int(tri[f - f % 3 + (f + 2) % 3])
        close = centers._cc_close(sx, sy, tri, err, cx, cy, e // 3, f // 3)
        cocircular = flag[e] and incircle(*[v for s in (*q, d) for v in (sx[s], sy[s])]) == 0.0
        if close or cocircular:
            merged |= bool(link(e // 3, f // 3))
    changed = np.zeros(t, dtype=np.uint8)

    def rename():
        parent[:] = [find(k) for k in range(t)]
        centers._name_classes(sx, sy, tri, he, parent, cx, cy, rank, err, changed, False, EVERY)

    if merged:
        rename()
    rounds = 0
    while True:
        joins = sum(
            link(e // 3, f // 3)
            for e, f in edges
            if find(e // 3) != find(f // 3) and centers._folds(sx, sy, tri, e, f, cx, cy, box, err)
        )
        if joins == 0:
            return parent, cx, cy, rounds
        rounds += 1
        rename()


# (float circles at the origin no longer fold: their sliver centres are exact to ulps)
FOLDING = ["float_circle_64_small_off", "float_circle_128_tiny_off", "float_circles_concentric"]


@pytest.mark.parametrize("name", [*FOLDING, "lattice_offset_5e+13", "collinear_plus_one"])
def test_fold_rounds_on_changed_edges_only_equal_full_rounds(name):
    pts = CATALOGUE[name][0]
    sx, sy, tri, he, order = _triangulation(pts)
    lo = np.minimum(sx.min(), sy.min()) - 1.0
    hi = np.maximum(sx.max(), sy.max()) + 1.0
    box = np.array([lo, lo, hi, hi])
    rank = order.astype(np.int64)
    cx, cy, err, flag = centers.circumcenters(sx, sy, tri, he)
    cls, _ = centers.merge_cocircular(sx, sy, tri, he, cx, cy, err, flag, rank, box)
    # where an edge is short, merge_cocircular first flips exactly cocircular quads to one
    # triangulation (kernels.cocircular, in place): the plain rounds run on the one it ended
    parent, px, py, rounds = _plain_merge(sx, sy, tri, he, rank, box)
    assert np.array_equal(cls, parent)
    assert _bits(*cx, *cy) == _bits(*px, *py)
    if name in FOLDING:
        assert len(np.unique(cls)) < len(cls)  # the classes merged: the test is not idle


def test_some_input_needs_a_fold_round():
    """At least one of the inputs above exercises a fold merge (else the test proves little)."""
    total = 0
    for name in FOLDING:
        sx, sy, tri, he, order = _triangulation(CATALOGUE[name][0])
        box = np.array([-2.0, -2.0, 2.0, 2.0])
        total += _plain_merge(sx, sy, tri, he, order.astype(np.int64), box)[3]
    assert total > 0


def _pair_inputs():
    """Inputs whose cocircular classes are mostly two triangles (four sites on a circle)."""
    rng = np.random.default_rng(11)
    k = 24
    ax = (np.arange(k) + 0.5) / k
    grid = np.column_stack([a.ravel() for a in np.meshgrid(ax, ax)])
    yield grid
    yield grid[rng.permutation(len(grid))]  # names follow the input's numbering
    lattice = np.column_stack([a.ravel() for a in np.meshgrid(np.arange(12.0), np.arange(12.0))])
    yield lattice[rng.permutation(len(lattice))] + 5e13
    # rectangles of random sides: every 2x2 block is exactly cocircular
    xs = np.cumsum(rng.random(16) + 0.1)
    ys = np.cumsum(rng.random(16) + 0.1)
    yield np.column_stack([a.ravel() for a in np.meshgrid(xs, ys)])[rng.permutation(256)]
    for name in ("lattice_offset_5e+13", *FOLDING):
        yield CATALOGUE[name][0]


def _joined(sx, sy, tri, he, cx, cy, err, flag):
    """Classes after the exact merge and before any naming (compressed parents)."""
    box = np.array([-np.inf, -np.inf, np.inf, np.inf])
    fold = np.zeros(len(tri), dtype=np.uint8)
    near = np.zeros(len(cx), dtype=np.uint8)
    centers.flag_close(sx, sy, tri, he, cx, cy, flag, err, box, fold, near)
    parent = np.arange(len(cx))

    def find(a):
        while parent[a] != a:
            a = parent[a]
        return a

    for e in np.flatnonzero(flag):
        f = int(he[e])
        a, b, c, d = (int(v) for v in centers._quad(tri, e, f))
        close = centers._cc_close(sx, sy, tri, err, cx, cy, e // 3, f // 3)
        if close or incircle(sx[a], sy[a], sx[b], sy[b], sx[c], sy[c], sx[d], sy[d]) == 0.0:
            ra, rb = find(e // 3), find(f // 3)
            parent[max(ra, rb)] = min(ra, rb)
    parent[:] = [find(k) for k in range(len(cx))]
    return parent


def test_pair_classes_named_from_own_centres_equal_the_full_search():
    """``_name_pairs`` (the first naming: a class of two reuses a triangle's centre when
    its triple is the name) gives the bits and change marks of the full search."""
    kinds = {"root": 0, "other": 0, "neither": 0}
    for pts in _pair_inputs():
        sx, sy, tri, he, order = _triangulation(pts)
        rank = order.astype(np.int64)
        cx, cy, err, flag = centers.circumcenters(sx, sy, tri, he)
        parent = _joined(sx, sy, tri, he, cx, cy, err, flag)
        out = []
        for own in (True, False):
            ox, oy, changed = cx.copy(), cy.copy(), np.zeros(len(cx), dtype=np.uint8)
            centers._name_classes(sx, sy, tri, he, parent, ox, oy, rank, err, changed, own, EVERY)
            out.append(_bits(*ox, *oy) + changed.tobytes())
        assert out[0] == out[1]
        size = np.bincount(parent, minlength=len(parent))
        for r in np.flatnonzero(size == 2):
            u = int(np.flatnonzero(parent == r)[1])
            sites = set(tri[3 * r : 3 * r + 3]) | set(tri[3 * u : 3 * u + 3])
            first = set(sorted(sites, key=lambda v: rank[v])[:3])
            if first == set(tri[3 * r : 3 * r + 3]):
                kinds["root"] += 1
            elif first == set(tri[3 * u : 3 * u + 3]):
                kinds["other"] += 1
            else:
                kinds["neither"] += 1
    assert min(kinds.values()) > 50, kinds  # every branch of the short path is exercised
