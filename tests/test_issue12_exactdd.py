"""Issue 12: the exact vertex solve rounded correctly, and its double-double stage.

``predicates3d.vertex_offset`` puts coordinate ``q`` of a vertex less a point ``c`` at
``-RN(D4_q) / (2 RN(D3))``: each exact determinant rounded to its nearest double
(``vertexdd3d.nearest``), then one division, so the value depends on the exact
determinants alone. ``vertexdd3d.vertex_dd`` evaluates them in double-double with a proven
bound and answers only where the nearest doubles are proven: the same bits as the
expansions (``predicates3d.vertex_exact``) by construction, at a fraction of their cost
(a helix's many-faced cells solve millions of ill-conditioned vertices). Checked here
against rationals: the rounding of expansions (ties and near-ties), the exact stage's
values, the double-double stage against the exact one on random and near-degenerate
queries, and helix/three-line diagrams.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

import voroforge as vf
from catalogue3d import helix, three_lines
from reference3d import brute_volumes
from test_issue12_exact3d import _check_cells
from voroforge.kernels.expansion import grow
from voroforge.kernels.predicates3d import scratch, vertex_exact, vertex_offset
from voroforge.kernels.vertexdd3d import nearest, vertex_dd

BOX = (0.0, 0.0, 0.0, 1.0, 1.0, 1.0)
WP = np.array(
    [[-1, 0, 0, 0], [1, 0, 0, 1.0], [0, -1, 0, 0], [0, 1, 0, 1], [0, 0, -1, 0], [0, 0, 1, 1]]
)


def _expansion(values):
    e = np.zeros(len(values) + 1)
    n = 0
    for v in values:
        n = grow(e, n, float(v))
    return e, n


def test_nearest_rounds_expansions_correctly():
    rng = np.random.default_rng(3)
    tmp = np.zeros(64)
    cases = []
    for _ in range(400):  # sums of doubles over a few dozen binades
        k = int(rng.integers(1, 8))
        cases.append(rng.normal(size=k) * 2.0 ** rng.integers(-80, 5, k))
    for _ in range(400):  # a double and its half-ulp (a tie) plus or minus a little
        h = float(rng.normal() * 2.0 ** rng.integers(-10, 10))
        if rng.random() < 0.3:
            h = float(np.copysign(2.0 ** rng.integers(-10, 10), h))  # a binade's edge
        u = float(np.spacing(abs(h)))
        if rng.random() < 0.5:
            u = abs(h) - float(np.nextafter(abs(h), 0.0))  # the half-ulp below
        tiny = float(rng.choice([0.0, 1.0, -1.0])) * u * 2.0 ** -float(rng.integers(1, 60))
        cases.append([h, float(rng.choice([1.0, -1.0])) * u / 2, tiny])
    for vals in cases:
        e, n = _expansion(vals)
        want = float(sum((Fraction(float(v)) for v in vals), Fraction(0)))
        got = nearest(e, n, tmp)
        assert got == want, (vals, got, want)


def _row(key, a, P, W, walls, ns):
    if key < ns:
        r = [Fraction(float(P[key, c])) - Fraction(float(P[a, c])) for c in range(3)]
        return r + [sum(x * x for x in r) + Fraction(float(W[a])) - Fraction(float(W[key]))]
    w = walls[key - ns]
    n = [Fraction(float(v)) for v in w[:3]]
    o = [Fraction(float(v)) for v in w[4:7]] if len(w) > 4 else [Fraction(0)] * 3
    pa = [Fraction(float(v)) for v in P[a]]
    return n + [2 * Fraction(float(w[3])) - 2 * sum(n[c] * (pa[c] - o[c]) for c in range(3))]


def _det3(m):
    return (
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    )


def _want(a, ks, P, W, walls, ns, c):
    """``-RN(D4_q) / (2 RN(D3))`` from rationals (``float(Fraction)`` rounds to nearest)."""
    rows = [_row(k, a, P, W, walls, ns) for k in ks]
    d3 = _det3([r[:3] for r in rows])
    if d3 == 0:
        return None
    out = []
    for q in range(3):
        mq = _det3([[r[j] for j in range(4) if j != q] for r in rows])
        d4 = (-1) ** (q + 1) * mq + 2 * (Fraction(float(c[q])) - Fraction(float(P[a, q]))) * d3
        out.append(-float(d4) / (2.0 * float(d3)))
    return out


def _queries(rng, ns, m, span, walls):
    out = []
    for _ in range(m):
        a = int(rng.integers(ns - span - 1))
        ks = sorted(a + 1 + rng.choice(span, 3, replace=False))
        if rng.random() < 0.25:
            ks[2] = ns + int(rng.integers(walls))
        out.append((a, *(int(k) for k in ks)))
    return out


def _cases(rng):
    """Helix, three lines, weights, a Convex-like wall about an origin; near-degenerate."""
    out = []
    P = helix(600)
    out.append((P, np.zeros(len(P)), WP, 12))
    P = three_lines(600)
    out.append((P, rng.random(len(P)) * 1e-3, WP, 60))
    far = np.c_[WP, np.tile([0.5, 0.5, 0.5], (6, 1))]  # (n, d, o) rows
    far[:, 3] = 0.5
    P = helix(300) + rng.normal(size=(300, 3)) * 2.0**-50  # a few ulps off the curve
    out.append((P, np.zeros(len(P)), far, 8))
    P = np.repeat(rng.random((100, 3)), 3, axis=0)
    P[1::3, 0] = np.nextafter(P[1::3, 0], 2.0)  # twins an ulp apart: nearly parallel planes
    P[2::3, 1] = np.nextafter(P[2::3, 1], -1.0)
    out.append((P, np.zeros(len(P)), WP, 9))
    return out


def test_exact_stage_against_rationals():
    rng = np.random.default_rng(7)
    buf = scratch()
    for P, W, walls, span in _cases(rng):
        ns = len(P)
        for a, *ks in _queries(rng, ns, 20, span, len(walls)):
            for c in (P[a], np.zeros(3), P[a] + rng.normal(size=3) * 1e-3):
                got = np.full(3, 7.0)
                ok = vertex_exact(a, *ks, P, W, walls, ns, buf, *c, got)
                want = _want(a, ks, P, W, walls, ns, c)
                assert ok == (want is not None)
                if ok:
                    assert got.tolist() == want, (a, ks, c)


def test_double_double_stage_gives_the_exact_bits():
    rng = np.random.default_rng(11)
    buf = scratch()
    R = np.zeros(63)
    decided = total = 0
    helix_decided = 0
    for t, (P, W, walls, span) in enumerate(_cases(rng)):
        ns = len(P)
        for a, *ks in _queries(rng, ns, 400, span, len(walls)):
            want = np.full(3, 7.0)
            ok = vertex_exact(a, *ks, P, W, walls, ns, buf, *P[a], want)
            c = P[a]
            if rng.random() < 0.3 and ok:  # at the vertex itself: offsets of an ulp
                c = P[a] + want
                ok = vertex_exact(a, *ks, P, W, walls, ns, buf, *c, want)
            got = np.full(3, 5.0)
            if vertex_dd(a, *ks, P, W, walls, ns, *c, R, got):
                assert ok and got.tobytes() == want.tobytes(), (t, a, ks)
                decided += 1
                helix_decided += t == 0
            total += 1
            # the cached entry point gives the same bits however it solved
            x = np.full(3, 7.0)
            assert vertex_offset(a, *ks, P, W, walls, ns, buf, *c, x) == ok
            if ok:
                assert x.tobytes() == want.tobytes()
    assert helix_decided > 200  # of ~280 helix queries at the site (the stage's point)
    assert decided > total // 4


@pytest.mark.parametrize(("make", "n"), [(helix, 300), (three_lines, 150)], ids=["helix", "lines3"])
def test_many_faced_cells(make, n):
    P = make(n)
    d = vf.voronoi3d(P, BOX)
    _check_cells(d, BOX)
    some = list(range(0, n, 37))
    assert np.allclose(d.volumes[some], brute_volumes(P, WP, cells=some), rtol=1e-7, atol=1e-12)
