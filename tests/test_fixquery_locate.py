"""``locate`` at many-way ties: the compiled exact comparison against rationals.

Near ties (float distances within rounding of the nearest) are decided by
``kernels.nearest_exact.nearest_of``: a float filter, a double-double filter, then
expansions. Every answer here is checked against a brute force over every site in
``Fraction`` (lowest index on exact ties), on inputs built to tie: sites on a circle or a
sphere around the query, integer lattices with queries on their Voronoi vertices, at offsets
of 1e15, at scales 2**+-600, with weights.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

import voroforge as vf
from voroforge.engine import locate3d
from voroforge.kernels.nearest_exact import nearest_of


def _brute(q, P, w=None, live=None):
    """Lowest index of the exactly nearest site by ``|q - p|^2 - w`` (rationals)."""
    best = None
    for i in range(len(P)) if live is None else live:
        t = sum(
            (Fraction(float(a)) - Fraction(float(b))) ** 2 for a, b in zip(q, P[i], strict=True)
        )
        key = (t - (0 if w is None else Fraction(float(w[i]))), int(i))
        best = key if best is None or key < best else best
    return best[1]


def _circle(n, radius=1.0, centre=(0.0, 0.0)):
    t = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
    return np.c_[np.cos(t), np.sin(t)] * radius + np.asarray(centre)


@pytest.mark.parametrize(
    ("scale", "off"), [(1.0, 0.0), (2.0**-600, 0.0), (2.0**600, 0.0), (1.0, 1e15), (3.0, -7.25)]
)
def test_circle_of_1000_sites_around_the_query(scale, off):
    P = _circle(1000) * scale + off
    rng = np.random.default_rng(1)
    Q = np.vstack([[off, off], off + rng.normal(0.0, 1e-17 * scale, (4, 2))])
    Q = np.vstack([Q, [[off + scale * 1e-9, off]]])
    want = [_brute(q, P) for q in Q]
    assert vf.locate(P, Q).tolist() == want
    # a diagram's locate takes the same path through its own (cached) locator
    d = vf.voronoi(P[:200], (off - 2 * scale, off - 2 * scale, off + 2 * scale, off + 2 * scale))
    assert d.locate(Q).tolist() == [_brute(q, P[:200]) for q in Q]


@pytest.mark.parametrize(
    ("scale", "off"), [(1.0, 0.0), (1.0, 1e15), (2.0**-600, 0.0), (2.0**600, 0.0)]
)
def test_queries_on_the_voronoi_vertices_of_a_lattice(scale, off):
    g = np.arange(-6.0, 7.0)
    P = (np.stack(np.meshgrid(g, g), -1).reshape(-1, 2) * scale) + off
    rng = np.random.default_rng(2)
    # vertices (4-way ties), edge midpoints (2-way), sites, and the exact centre
    Q = rng.integers(-12, 13, (60, 2)) / 2.0 * scale + off
    want = [_brute(q, P) for q in Q]
    assert vf.locate(P, Q).tolist() == want
    # reversed order: the lowest index is another site
    assert vf.locate(P[::-1], Q).tolist() == [_brute(q, P[::-1]) for q in Q]


def test_power_locate_with_integer_weights_on_a_lattice():
    g = np.arange(0.0, 8.0)
    P = np.stack(np.meshgrid(g, g), -1).reshape(-1, 2)
    rng = np.random.default_rng(3)
    w = rng.integers(0, 3, len(P)).astype(float) * 0.25
    d = vf.power(P, w, (-1, -1, 8, 8))
    Q = rng.integers(-2, 17, (120, 2)) / 2.0
    live = np.flatnonzero(np.asarray(d.duplicate_of) < 0)
    assert d.locate(Q).tolist() == [_brute(q, P, w, live) for q in Q]


def test_power_locate_circle_of_sites_with_equal_and_offset_weights():
    P = _circle(400, 1.0, (1e6, -1e6))
    w = np.where(np.arange(400) % 2 == 0, 0.5, 0.25)  # two power radii: many ties per group
    d = vf.power(P, w, (1e6 - 2, -1e6 - 2, 1e6 + 2, -1e6 + 2))
    rng = np.random.default_rng(4)
    Q = np.vstack([[1e6, -1e6], [1e6, -1e6] + rng.normal(0.0, 1e-10, (3, 2))])
    live = np.flatnonzero(np.asarray(d.duplicate_of) < 0)
    assert d.locate(Q).tolist() == [_brute(q, P, w, live) for q in Q]


def _sphere(n):
    i = np.arange(n) + 0.5
    phi = np.arccos(1.0 - 2.0 * i / n)
    t = np.pi * (1.0 + 5.0**0.5) * i
    return np.c_[np.cos(t) * np.sin(phi), np.sin(t) * np.sin(phi), np.cos(phi)]


@pytest.mark.parametrize("off", [0.0, 1e15])
def test_3d_sphere_of_sites_and_weighted_lattice(off):
    P = _sphere(300) + off
    d = vf.voronoi3d(P, (off - 2,) * 3 + (off + 2,) * 3)
    rng = np.random.default_rng(5)
    Q = np.vstack([[off] * 3, off + rng.normal(0.0, 1e-17, (2, 3))])
    live = np.flatnonzero(np.asarray(d.duplicate_of) < 0)
    assert d.locate(Q).tolist() == [_brute(q, P, None, live) for q in Q]
    g = np.arange(4.0)
    L = np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3) + off
    w = rng.integers(0, 3, len(L)).astype(float)
    d = vf.voronoi3d(L, (off - 1,) * 3 + (off + 4,) * 3, weights=w)
    Q = rng.integers(-1, 8, (60, 3)) / 2.0 + off
    live = np.flatnonzero(np.asarray(d.duplicate_of) < 0)
    assert d.locate(Q).tolist() == [_brute(q, L, w, live) for q in Q]


def test_kernel_against_rationals_on_adversarial_candidate_sets():
    """Mirrored sets (exact ties), duplicates, 1e-17 offsets, scales 1e-300..1e300, weights."""
    rng = np.random.default_rng(6)
    decided = 0
    for trial in range(300):
        d = int(rng.integers(1, 4))
        base = rng.normal(size=d) * 10.0 ** float(rng.integers(-300, 300))
        r = 10.0 ** float(rng.integers(-20, 5)) * float(np.abs(base).max())
        if trial % 2:
            r = 10.0 ** float(rng.integers(-300, 300))
        k = int(rng.integers(2, 20))
        dirs = rng.normal(size=(k, d))
        S = base + r * dirs / np.linalg.norm(dirs, axis=1)[:, None]
        S[rng.random(k) < 0.2] = S[0]
        if trial % 3 == 0:
            S = np.vstack([S, 2.0 * base - S])
        w = None
        if trial % 4 == 1:
            with np.errstate(over="ignore", invalid="ignore"):
                top = r * r * 10.0 ** float(rng.integers(-20, 1))
                w = rng.choice([0.0, 1.0, -1.0], len(S)) * top
        if not np.isfinite(S).all() or (w is not None and not np.isfinite(w).all()):
            continue
        cand = rng.permutation(len(S)).astype(np.int64)
        for q in (base, base + r * 1e-17 * rng.normal(size=d)):
            want = _brute(q, S, w)
            # read-only sites and weights, as locate3d.nearest_exact passes them (numba
            # types the flag: writeable ones compiled nearest_of once more for this test)
            ro = [np.array(a) for a in (S, np.zeros(0) if w is None else w)]
            for a in ro:
                a.setflags(write=False)
            got = int(nearest_of(q, cand, *ro))
            assert got in (-1, want)
            decided += got >= 0
            assert locate3d.nearest_exact(q, cand, S, w) == want
    assert decided > 400  # the rational fallback is rare (offsets spanning > 900 binades)


def test_10000_way_tie_is_decided_without_rationals(monkeypatch):
    def fail(*args):
        raise AssertionError("decided in rationals")

    monkeypatch.setattr(locate3d, "_exact_key", fail)
    P = _circle(10000)
    Q = np.random.default_rng(7).normal(0.0, 1e-17, (3, 2))
    got = vf.locate(P, Q)
    monkeypatch.undo()
    assert got.tolist() == [_brute(q, P) for q in Q]
