"""Issue 12: cells of hundreds of faces (sites on a helix) and sites on one circle.

A helix's cells are slabs whose bisectors are nearly parallel: two thirds of their vertices
are named by ill-conditioned quadruples and solved exactly (``predicates3d.vertex_offset``:
~0.4 us in double-double where its bound decides, expansions of a few us otherwise), once
by each cell at the vertex and again when a cell past its slots is built alone.
``vertex_offset`` now keeps its results in its scratch, keyed by the query; these tests
check that a hit gives the solve's bits (and a miss on other arrays), that the offsets are
right against rationals, and the cells against voro++.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

import voroforge as vf
from reference3d import VOROPP, brute_volumes, voropp_volumes
from voroforge.kernels.predicates3d import _vertex_offset, scratch, vertex_offset

BOX = (0.0, 0.0, 0.0, 1.0, 1.0, 1.0)
WP = np.array(
    [[1, 0, 0, 1.0], [-1, 0, 0, 0], [0, 1, 0, 1], [0, -1, 0, 0], [0, 0, 1, 1], [0, 0, -1, 0]]
)


def _helix(n, turns=10, r=0.3):
    a = np.linspace(0, 2 * np.pi * turns, n)
    return np.c_[0.5 + r * np.cos(a), 0.5 + r * np.sin(a), np.linspace(0.05, 0.95, n)]


def _circle(n, r=0.4):
    a = 2 * np.pi * np.arange(n) / n
    return np.c_[0.5 + r * np.cos(a), 0.5 + r * np.sin(a), np.full(n, 0.5)]


def _queries(P, rng, m):
    """Site/owner quadruples near each other (consecutive helix sites: ill-conditioned)."""
    n = len(P)
    out = []
    for _ in range(m):
        a = int(rng.integers(n - 60))
        ks = a + 1 + rng.choice(59, 3, replace=False)
        if rng.random() < 0.3:  # a wall among the owners
            ks[2] = n + int(rng.integers(6))
        out.append((a, *(int(k) for k in ks)))
    return out


def _exact_offset(P, a, ks, c):
    """The vertex of ``a``'s owners ``ks`` less ``c``, in rationals (None: no one point)."""
    n = len(P)
    rows, rhs = [], []
    pa = [Fraction(float(v)) for v in P[a]]
    for k in ks:
        if k < n:
            r = [Fraction(float(v)) - pa[q] for q, v in enumerate(P[k])]
            rows.append(r)
            rhs.append(sum(x * x for x in r) / 2)  # r . (x - p_a) = |r|^2 / 2
        else:
            w = WP[k - n]
            r = [Fraction(float(v)) for v in w[:3]]
            rows.append(r)
            rhs.append(Fraction(float(w[3])) - sum(r[q] * pa[q] for q in range(3)))
    det = (
        rows[0][0] * (rows[1][1] * rows[2][2] - rows[1][2] * rows[2][1])
        - rows[0][1] * (rows[1][0] * rows[2][2] - rows[1][2] * rows[2][0])
        + rows[0][2] * (rows[1][0] * rows[2][1] - rows[1][1] * rows[2][0])
    )
    if det == 0:
        return None
    y = []
    for q in range(3):
        m = [list(r) for r in rows]
        for t in range(3):
            m[t][q] = rhs[t]
        dq = (
            m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
        )
        y.append(dq / det + pa[q] - Fraction(float(c[q])))
    return y


def test_vertex_offset_cache_gives_the_solves_bits():
    rng = np.random.default_rng(12)
    P = _helix(400)
    W = np.zeros(len(P))
    ns = len(P)
    shared = scratch()  # every query twice on one scratch: the second is a hit
    hits = 0
    for a, k0, k1, k2 in _queries(P, rng, 150):
        for c in (P[a], P[a] + rng.normal(size=3) * 1e-3, np.zeros(3)):
            want = np.full(3, 7.0)
            ok = _vertex_offset(a, k0, k1, k2, P, W, WP, ns, scratch(), *c, want)
            for _ in range(2):
                got = np.full(3, 7.0)  # a False leaves x as it was, hit or not
                assert vertex_offset(a, k0, k1, k2, P, W, WP, ns, shared, *c, got) == ok
                assert got.tobytes() == want.tobytes()
            hits += 1
            exact = _exact_offset(P, a, (k0, k1, k2), c)
            assert ok == (exact is not None)
            if ok:  # right to a few ulps of itself (rationals)
                for q in range(3):
                    assert abs(Fraction(float(got[q])) - exact[q]) <= 16 * 2.0**-52 * abs(exact[q])
    assert hits == 450
    # the same query on other sites (same scratch, other array): solved again, not hit
    Q = P.copy()
    Q[:, 0] += 2.0**-20
    for a, k0, k1, k2 in _queries(P, rng, 40):
        want = np.zeros(3)
        got = np.zeros(3)
        ok = _vertex_offset(a, k0, k1, k2, Q, W, WP, ns, scratch(), *Q[a], want)
        vertex_offset(a, k0, k1, k2, P, W, WP, ns, shared, *P[a], np.zeros(3))
        assert vertex_offset(a, k0, k1, k2, Q, W, WP, ns, shared, *Q[a], got) == ok
        assert got.tobytes() == want.tobytes()


def _check(d, P):
    """Positive volumes that tile the box, and neighbours from both sides."""
    assert (d.volumes > 0).all()
    assert abs(d.volumes.sum() - 1.0) <= 1e-12
    indptr, nb = d.neighbors
    pairs = {(i, int(j)) for i in range(len(P)) for j in nb[indptr[i] : indptr[i + 1]] if j >= 0}
    assert all((j, i) in pairs for i, j in pairs), "neighbours not symmetric"


@pytest.mark.parametrize("make", [_helix, _circle], ids=["helix", "circle"])
def test_helix_and_circle_cells(make):
    P = make(300)
    d = vf.voronoi3d(P, BOX)
    _check(d, P)
    faces = np.diff(d.neighbors[0])
    assert faces.mean() > (50 if make is _helix else 3.5)
    # Qhull's cells (scipy, half-spaces of every site) for every thirtieth cell
    some = list(range(0, len(P), 30))
    ref = brute_volumes(P, WP, cells=some)
    assert np.allclose(d.volumes[some], ref, rtol=1e-7, atol=1e-12)
    if VOROPP:
        v = voropp_volumes(P, BOX)
        # voro++ prints 6 significant digits
        assert np.allclose(d.volumes, v, rtol=2e-5, atol=1e-9)


def test_flat_sites_get_a_grid_in_their_plane():
    # sites on one plane had a degenerate z extent, buckets of side ~1e-3 and a 630 x 630 x 1
    # grid for 500 sites: every cell reaching the circle's axis walked 400,000 buckets
    from voroforge.engine.build3d import PER_BUCKET
    from voroforge.engine.sitegrid3d import grid3d_shape

    for P in (_circle(500), np.c_[np.random.default_rng(1).random((500, 2)), np.full(500, 0.5)]):
        g = grid3d_shape(P, PER_BUCKET)
        counts = g[6:9]
        assert counts[2] == 1 and counts.prod() <= 2 * len(P) / PER_BUCKET + 2 * counts[:2].sum()
        assert counts.prod() >= 0.5 * len(P) / PER_BUCKET
        d = vf.voronoi3d(P, BOX)
        _check(d, P)
    U = np.random.default_rng(2).random((2000, 3))  # a full box: the cube grid as before
    g = grid3d_shape(U, PER_BUCKET)
    side = (np.prod(np.ptp(U, axis=0)) / (len(U) / PER_BUCKET)) ** (1 / 3)
    assert (g[6:9] == np.maximum(np.floor(np.ptp(U, axis=0) / side), 1)).all()
