"""checker14 F6 (surface Voronoi with sites far from a small surface) and F7 (the Fortune
tracer at extreme scales), against independent references."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from voroforge import surface


def _clip(poly, a, b):
    """Keep the part of polygon ``poly`` where ``a . x <= b`` (exact rationals)."""
    out = []
    for k, p in enumerate(poly):
        q = poly[(k + 1) % len(poly)]
        fp = sum(x * y for x, y in zip(a, p, strict=True)) - b
        fq = sum(x * y for x, y in zip(a, q, strict=True)) - b
        if fp <= 0:
            out.append(p)
        if (fp < 0 < fq) or (fq < 0 < fp):
            t = fp / (fp - fq)
            out.append(tuple(x + t * (y - x) for x, y in zip(p, q, strict=True)))
    return out


def _area(poly):
    if len(poly) < 3:
        return 0.0
    p = np.array([[float(c) for c in v] for v in poly])
    s = sum(np.cross(p[i] - p[0], p[i + 1] - p[0]) for i in range(1, len(p) - 1))
    return 0.5 * float(np.linalg.norm(s))


def _rvd(V, F, S):
    """Restricted cell areas: every triangle clipped by every bisector (after checker14's
    rvd.py), the bisectors in exact rationals."""
    S = [tuple(Fraction(float(c)) for c in s) for s in S]
    areas = np.zeros(len(S))
    for f in F:
        tri = [tuple(Fraction(float(c)) for c in V[w]) for w in f]
        for i, si in enumerate(S):
            poly = tri
            for j, sj in enumerate(S):
                if j == i:
                    continue
                a = tuple(2 * (y - x) for x, y in zip(si, sj, strict=True))
                b = sum(y * y for y in sj) - sum(x * x for x in si)
                poly = _clip(poly, a, b)
                if len(poly) < 3:
                    break
            areas[i] += _area(poly)
    return areas


@pytest.mark.parametrize("D", [10.0, 1e4, 1e6, 1e8, 1e11])
def test_far_sites_match_reference(D):
    T = surface.torus(1.0, 0.4, resolution=(24, 10))
    s = np.array([[1.0, 0.3, 0.1], [-0.2, 1.0, 0.0], [-1.0, 0.1, -0.2]]) * D
    vd = surface.voronoi(T, s)
    ref = _rvd(T.vertices, T.faces, s)
    assert abs(vd.areas.sum() / T.area - 1.0) < 1e-9
    assert np.abs(vd.areas - ref).max() < 1e-9 * T.area
    assert vd.sample_check(1000) == 1.0


def test_sample_check_sees_wrong_owner():
    """The diagnostic is exact: a site far away owning a piece it does not is reported."""
    T = surface.torus(1.0, 0.4, resolution=(24, 10))
    s = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]]) * 1e9
    vd = surface.voronoi(T, s)
    assert vd.sample_check(500) == 1.0
    vd.piece_cell[:] = vd.piece_cell[::-1]
    assert vd.sample_check(500) < 1.0


@pytest.mark.parametrize("scale", [1.0, 1e-300, 1e-200, 1e-110, 1e110, 1e160, 1e250, 1e300])
def test_fortune_trace_scale_free(scale):
    """checker14 F7: the tracer's edges equal vf.voronoi's at every scale."""
    import voroforge as vf
    from voroforge.explain.fortune import trace

    pts = np.random.default_rng(0).random((30, 2)) * scale
    t = trace(pts)
    ours = {tuple(p) for p in t.edges().pairs.tolist()}
    d = vf.voronoi(pts, t.bounds).edges
    P = np.sort(np.asarray(d.pairs), 1)
    ref = {tuple(p) for p in P[P[:, 1] >= 0].tolist()}
    assert ours == ref
    # states scale back exactly: the sweep positions and circle events follow the sites
    ys = [s.y for s in t.states if s.kind == "site"]
    assert sorted(ys, reverse=True) == ys
    assert set(ys) <= set(pts[:, 1].tolist())
    for s in t.states:
        for e in s.pending:
            r = [np.hypot(*(np.asarray(e.centre) - pts[i])) for i in e.sites]
            assert max(r) - min(r) <= 1e-9 * max(r)
            assert e.y == pytest.approx(e.centre[1] - e.radius, rel=1e-9, abs=1e-9 * scale)


def test_fortune_trace_refuses_unsweepable_spread():
    from voroforge.explain.fortune import trace

    with pytest.raises(ValueError, match="span more than"):
        trace([[1e300, 0.0], [5e-324, 1.0], [0.0, -1e300]])


def test_fortune_trace_cocircular_many():
    """checker14 F12: 1200 sites on a circle (was cubic: 800 took 24 s). Each site's cell
    is a wedge sharing rays with its two neighbours on the circle."""
    from voroforge.explain.fortune import trace

    n = 1200
    th = 2 * np.pi * np.arange(n) / n
    t = trace(np.column_stack([np.cos(th), np.sin(th)]))
    pairs = {tuple(p) for p in t.edges().pairs.tolist()}
    assert pairs == {tuple(sorted((i, (i + 1) % n))) for i in range(n)}
    for s in t.states[:: n // 7]:
        for e in s.pending:  # a pending event's middle arc is on the beach line
            assert e.sites[1] in s.arcs


def test_too_far_sites_refused():
    T = surface.torus(1.0, 0.4, resolution=(24, 10))
    with pytest.raises(ValueError, match="times the surface's size"):
        surface.voronoi(T, np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]) * 1e13)
