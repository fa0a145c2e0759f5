"""vf.delaunay3d: exact Delaunay tetrahedra, checked against exact rationals and scipy/Qhull."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from scipy.spatial import ConvexHull, Delaunay

import voroforge as vf
from reference3d import dyadic_ints


def _det3(m):
    return (
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    )


def _orient(a, b, c, d):
    """det[b - a, c - a, d - a] in rationals."""
    return _det3([[b[k] - a[k] for k in range(3)] for b in (b, c, d)])


def _insphere(a, b, c, d, e):
    """> 0 when e lies strictly inside the sphere through a, b, c, d (right-handed), exact."""
    rows = []
    for p in (a, b, c, d):
        v = [p[k] - e[k] for k in range(3)]
        rows.append(v + [v[0] ** 2 + v[1] ** 2 + v[2] ** 2])
    # 4x4 determinant by expansion along the last column
    det = 0
    for i in range(4):
        minor = [rows[j][:3] for j in range(4) if j != i]
        det += (-1) ** (i + 3) * rows[i][3] * _det3(minor)
    return -det


def _check(P, t, exact=True):
    """Invariants: right-handed tetrahedra, faces shared by two (hull faces by one, and they
    are the hull triangles listed, outward), neighbours symmetric, the hull's volume, every
    distinct point a vertex, and (exact) no point strictly inside any circumsphere."""
    S = t.simplices
    assert S.shape[1] == 4 and len(S) > 0
    span = float(np.ptp(P, axis=0).max())
    assert (t.volumes >= -1e-12 * span**3).all()  # float; > 0 exactly: below
    distinct = np.flatnonzero(t.duplicate_of < 0)
    assert set(np.unique(S)) == set(distinct.tolist())
    faces = {}
    for s in S:
        for f in itertools.combinations(sorted(s.tolist()), 3):
            faces[f] = faces.get(f, 0) + 1
    assert max(faces.values()) <= 2  # a face in at most two (one tetrahedron: one)
    once = {f for f, c in faces.items() if c == 1}
    assert once == {tuple(sorted(h)) for h in t.convex_hull.tolist()}
    if not exact:
        c = P[distinct].mean(axis=0)
        for h in t.convex_hull:
            a, b, cc = P[h]
            assert np.dot(np.cross(b - a, cc - a), a - c) > 0  # counter-clockwise from outside
    for i in range(len(S)):
        for j in range(4):
            k = t.neighbors[i, j]
            if k >= 0:
                assert i in t.neighbors[k]
                assert len(set(S[i]) & set(S[k])) == 3 and S[i, j] not in S[k]
    hull = ConvexHull(P[distinct] - P[distinct[0]]).volume  # Qhull is off far out
    assert abs(t.volumes.sum() - hull) <= 1e-12 * hull
    if exact:
        # the points' rationals times one power of two, as ints (the signs of orient and
        # insphere, homogeneous polynomials, are the rationals'; ints are ~30x faster)
        (F,) = dyadic_ints(P)
        for h in t.convex_hull.tolist():  # outward: no point beyond, some inside
            sides = [_orient(*(F[i] for i in h), F[e]) for e in distinct.tolist()]
            assert max(sides) == 0 and min(sides) < 0
        for s in S.tolist():
            a, b, c, d = (F[i] for i in s)
            assert _orient(a, b, c, d) > 0
            for e in distinct.tolist():
                if e not in s:
                    assert _insphere(a, b, c, d, F[e]) <= 0, (s, e)


def _grid(k):
    return np.array(list(itertools.product(range(k), repeat=3)), float)


def _sphere(n, seed):
    p = np.random.default_rng(seed).normal(size=(n, 3))
    return p / np.linalg.norm(p, axis=1)[:, None]


def _integer_sphere(r2):
    r = int(np.sqrt(r2)) + 1
    return np.array(
        [p for p in itertools.product(range(-r, r + 1), repeat=3) if sum(x * x for x in p) == r2],
        float,
    )


CASES = {
    "uniform": lambda: np.random.default_rng(1).random((60, 3)),
    "cubic grid": lambda: _grid(3),
    "cubic grid far": lambda: _grid(3) + [5e5, 4e6, 100.0],
    "cubic grid 1e-9": lambda: _grid(3) * 1e-9,
    "cubic grid 1e9": lambda: _grid(3) * 1e9,
    "bcc": lambda: np.vstack([_grid(3), _grid(2) + 0.5]),
    "fcc": lambda: np.array(
        [p for p in itertools.product(range(4), repeat=3) if sum(p) % 2 == 0], float
    ),
    "sphere": lambda: _sphere(40, 2),
    "sphere and centre": lambda: np.vstack([_sphere(40, 3), [0.0, 0.0, 0.0]]),
    "integer sphere": lambda: _integer_sphere(25),
    "integer sphere and centre": lambda: np.vstack([_integer_sphere(9), [0.0, 0.0, 0.0]]),
    "duplicates": lambda: np.vstack([_grid(3), _grid(3)[::4], [[-0.0, 0.0, 0.0]]]),
    "square pyramid": lambda: np.array(
        [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [0.5, 0.5, 1.0]]
    ),
    "two coplanar layers": lambda: np.vstack(
        [
            np.c_[np.random.default_rng(4).random((12, 2)), np.zeros(12)],
            np.c_[np.random.default_rng(5).random((12, 2)), np.ones(12)],
        ]
    ),  # fmt: skip
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_catalogue_exact(name):
    P = CASES[name]()
    _check(P, vf.delaunay3d(P))


@pytest.mark.parametrize("name", ["cubic grid", "bcc", "integer sphere and centre", "fcc"])
def test_independent_of_insertion_order(name):
    # ties are broken by the points' indices, not by the order they are inserted in: the
    # kernel fed the same points in other orders gives the same tetrahedra
    from voroforge.kernels.delaunay3d import INF, triangulate

    P = CASES[name]()

    def tets(order):
        T, _, ok = triangulate(np.ascontiguousarray(P), order)
        assert ok
        return {frozenset(t) for t in T.tolist() if INF not in t}

    base = tets(np.arange(len(P), dtype=np.int64))
    assert base == {frozenset(s) for s in vf.delaunay3d(P).simplices.tolist()}
    for seed in range(4):
        order = np.random.default_rng(seed).permutation(len(P)).astype(np.int64)
        assert tets(order) == base


def test_same_as_qhull_in_general_position():
    P = np.random.default_rng(7).random((3000, 3))
    t = vf.delaunay3d(P)
    ours = {frozenset(s) for s in t.simplices.tolist()}
    theirs = {frozenset(s) for s in Delaunay(P).simplices.tolist()}
    assert ours == theirs
    _check(P, t, exact=False)


def test_cubes_cut_alike_far_out():
    # an exactly representable lattice far out: the same tetrahedra as at the origin
    g = _grid(4)
    a = vf.delaunay3d(g).simplices
    b = vf.delaunay3d(g + [2.0**40, -(2.0**41), 2.0**39]).simplices
    assert np.array_equal(a, b)


@pytest.mark.parametrize(
    "P",
    [np.zeros((0, 3)), np.zeros((3, 3)), np.eye(3), np.c_[np.arange(6.0), np.zeros((6, 2))],
     np.c_[np.random.default_rng(0).random((9, 2)), np.full(9, 3.0)]],
    ids=["none", "one point thrice", "three", "collinear", "coplanar"],
)  # fmt: skip
def test_no_volume_gives_no_tetrahedra(P):
    t = vf.delaunay3d(P)
    assert t.simplices.shape == (0, 4) and t.convex_hull.shape == (0, 3)


@pytest.mark.parametrize(
    "bad, match",
    [(np.array([[0.0, 0.0, np.nan]]), "finite|NaN"), (np.zeros((4, 2)), "shape|3")],
)
def test_bad_input_is_named(bad, match):
    with pytest.raises(ValueError, match=match):
        vf.delaunay3d(bad)


def test_input_not_mutated():
    P = np.random.default_rng(3).random((30, 3))
    keep = P.copy()
    vf.delaunay3d(P)
    assert np.array_equal(P, keep)


def test_volumes_of_slivers_are_positive_and_exactly_rounded():
    # checker8: points on cones (k cos a, k sin a, k) give slivers whose float determinant
    # read -1.5e-16 where the exact volume is +1e-33; unsure ones are computed in rationals
    from fractions import Fraction

    P = np.array(
        [(k * np.cos(a), k * np.sin(a), k) for a in np.arange(12) * np.pi / 6 for k in range(1, 7)]
    )
    t = vf.delaunay3d(P)
    vol = t.volumes
    assert (vol > 0).all()
    slivers = 0
    Q = [[Fraction(float(x)) for x in row] for row in P]
    for s, v in zip(t.simplices.tolist(), vol.tolist(), strict=True):
        a, b, c, d = (Q[i] for i in s)
        u, w, z = ([q[i] - a[i] for i in range(3)] for q in (b, c, d))
        exact = (
            u[0] * (w[1] * z[2] - w[2] * z[1])
            - u[1] * (w[0] * z[2] - w[2] * z[0])
            + u[2] * (w[0] * z[1] - w[1] * z[0])
        ) / 6
        if exact < Fraction(1, 10**20):  # a sliver: as exact as one rounding allows
            assert v == pytest.approx(float(exact), rel=1e-15)
            slivers += 1
        else:  # float, relative to the first vertex: to the rounding of coordinates ~6
            assert v == pytest.approx(float(exact), abs=1e-13)
    assert slivers > 0  # the input makes them (else the test shows nothing)
