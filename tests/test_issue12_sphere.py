"""Issue 12: points on a sphere without its centre (every cell reaches the centre).

Float points on a sphere are co-spherical only to rounding: every bisector passes within
an ulp of the centre, where each cell has a cluster of exact vertices, so the float filter
decides none of them and each candidate was tested exactly against each (quadratic time:
1,000 points took 52 s). ``predicates3d.offset_side`` decides them on the vertex's exact
offset from its float point; these tests check that it agrees with the exact predicate,
that it decides the sphere's planes, and the cells' invariants.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import voroforge as vf
from reference3d import VOROPP, voropp_cells
from test_issue12_exact3d import _check_cells
from voroforge.kernels.expansion import two_diff
from voroforge.kernels.predicates3d import (
    bisector_side,
    frame_lift,
    frame_offset,
    frame_side,
    offset_side,
    scratch,
    vertex_offset,
)


def _fib(n):
    i = np.arange(n) + 0.5
    phi = np.arccos(1 - 2 * i / n)
    th = np.pi * (1 + 5**0.5) * i
    return np.c_[np.cos(th) * np.sin(phi), np.sin(th) * np.sin(phi), np.cos(phi)]


def _rnd(n, seed=0):
    x = np.random.default_rng(seed).normal(size=(n, 3))
    return x / np.linalg.norm(x, axis=1)[:, None]


def _box(S, pad=0.5):
    lo = S.min(0) - pad * np.ptp(S, 0).max()
    hi = S.max(0) + pad * np.ptp(S, 0).max()
    return tuple(lo) + tuple(hi)


@pytest.mark.parametrize(
    ("r", "off", "weights"),
    [(1.0, 0.0, False), (1e-3, 1e4, False), (1.0, 0.0, True), (3.0, -2.5, False)],
)
def test_offset_side_agrees_with_the_exact_side(r, off, weights):
    # vertices near the centre, named by three random other sites (their exact circumcentre
    # with i), against every other site: offset_side is the exact side or 0 (unsure)
    rng = np.random.default_rng(1)
    P = _rnd(60, 2) * r + off
    W = rng.random(60) * 1e-3 * r * r if weights else np.zeros(60)
    WP = np.zeros((0, 4))
    rows = np.zeros((2, 4, 4))
    buf = scratch()
    d = np.zeros(3)
    E = np.zeros(6)
    decided = tried = framed = 0
    for _ in range(40):
        i, k0, k1, k2 = (int(x) for x in rng.choice(60, 4, replace=False))
        # the float centre, or a point near it
        c = np.full(3, float(off)) + rng.normal(size=3) * r * 1e-15 * rng.integers(0, 2)
        if not vertex_offset(i, k0, k1, k2, P, W, WP, 60, buf, c[0], c[1], c[2], d):
            continue
        for j in range(60):
            if j in (i, k0, k1, k2):
                continue
            want = bisector_side(i, k0, k1, k2, j, P, W, WP, 60, rows, buf)
            got = offset_side(i, j, c[0], c[1], c[2], d[0], d[1], d[2], P, W)
            assert got in (0, want), (i, k0, k1, k2, j, got, want)
            decided += got != 0
            tried += 1
            # the same in a frame o near the vertex (the cell's first solved vertex)
            o = c + rng.normal(size=3) * r * 1e-15 * rng.integers(0, 2)
            frame_offset(c[0], c[1], c[2], d[0], d[1], d[2], o[0], o[1], o[2], E)
            K, kerr = frame_lift(i, j, o[0], o[1], o[2], P, W)
            (rh0, rl0), (rh1, rl1), (rh2, rl2) = (two_diff(P[j, q], P[i, q]) for q in range(3))
            got = frame_side(E, rh0, rh1, rh2, rl0, rl1, rl2, K, kerr)
            assert got in (0, want), (i, k0, k1, k2, j, got, want, "frame")
            framed += got != 0
    # the point of it: near the centre it decides (almost) all of them
    assert tried > 1000 and decided >= 0.99 * tried, (decided, tried)
    assert framed >= 0.9 * tried, (framed, tried)


def test_offset_side_refuses_what_it_cannot_tell():
    # exactly co-spherical integer sites (a cube's corners): the centre is on every
    # bisector, and offset_side must say 0, never a side
    P = np.array([[x, y, z] for x in (-1.0, 1.0) for y in (-1.0, 1.0) for z in (-1.0, 1.0)])
    W = np.zeros(8)
    WP = np.zeros((0, 4))
    buf = scratch()
    d = np.zeros(3)
    assert vertex_offset(0, 1, 2, 4, P, W, WP, 8, buf, 0.0, 0.0, 0.0, d)
    assert (d == 0).all()
    E = np.zeros(6)
    frame_offset(0.0, 0.0, 0.0, d[0], d[1], d[2], 0.0, 0.0, 0.0, E)
    for j in (3, 5, 6, 7):
        assert offset_side(0, j, 0.0, 0.0, 0.0, d[0], d[1], d[2], P, W) == 0
        K, kerr = frame_lift(0, j, 0.0, 0.0, 0.0, P, W)
        assert K == 0.0
        r = P[j] - P[0]
        assert frame_side(E, r[0], r[1], r[2], 0.0, 0.0, 0.0, K, kerr) == 0
    # and a point an ulp off the centre is decided, on the right side
    e = np.spacing(1.0)
    assert offset_side(0, 7, e, e, e, 0.0, 0.0, 0.0, P, W) == 1  # toward site 7 (1, 1, 1)
    assert offset_side(0, 7, -e, -e, -e, 0.0, 0.0, 0.0, P, W) == -1


def _sites(kind, n):
    if kind == "fibonacci":
        return _fib(n)
    if kind == "random":
        return _rnd(n)
    if kind == "hemisphere":
        p = _rnd(2 * n, 3)
        return p[p[:, 2] >= 0][:n]
    if kind == "interior":  # a sphere plus 10% uniform points inside its cube
        return np.r_[_rnd(n, 4), np.random.default_rng(5).random((n // 10, 3)) * 1.2 - 0.6]
    if kind == "small_far":  # radius 1e-3 at 1e4
        return _rnd(n, 6) * 1e-3 + 1e4
    raise ValueError(kind)


@pytest.mark.parametrize("kind", ["fibonacci", "random", "hemisphere", "interior", "small_far"])
def test_sphere_cells_are_valid(kind):
    S = _sites(kind, 150)
    box = _box(S)
    d = vf.voronoi3d(S, box)
    _check_cells(d, box)
    # every cell reaches the centre (all but the interior points' cells)
    if kind in ("fibonacci", "random"):
        assert (d.volumes > 0).all()


@pytest.mark.parametrize("kind", ["fibonacci", "random"])
def test_sphere_default_container(kind):
    S = _sites(kind, 200)
    d = vf.voronoi3d(S)
    assert d.unmatched_vertices == 0
    r = d.describe()
    assert r["euler_ok"] and r["convex"], r
    vol = d.container_volume
    assert abs(d.volumes.sum() - vol) <= 1e-12 * vol


@pytest.mark.parametrize("centre", [False, True])
def test_sphere_3000_with_and_without_centre(centre):
    # 3,000 points on a sphere, alone (every cell reaches the centre, where every bisector
    # passes within an ulp) or with the centre as a site (its cell has 3,000 faces and 6,000
    # vertices: its retry with big slots zeroed an owner table of 17 GB at 4,000 points)
    S = _rnd(3000, 7)
    if centre:
        S = np.r_[S, [[0.0, 0.0, 0.0]]]
    box = (-2.0, -2.0, -2.0, 2.0, 2.0, 2.0)
    d = vf.voronoi3d(S, box)
    assert d.unmatched_vertices == 0
    assert (d.volumes > 0).all()
    _check_cells(d, box)
    if centre:  # the centre's cell meets every other
        indptr, nbr = d.neighbors
        assert set(nbr[indptr[3000] : indptr[3001]].tolist()) == set(range(3000))


@pytest.mark.skipif(VOROPP is None, reason="voro++ CLI not installed")
@pytest.mark.parametrize("centre", [False, True])
def test_sphere_against_voropp(centre):
    S = _rnd(400, 8)
    if centre:
        S = np.r_[S, [[0.0, 0.0, 0.0]]]
    box = (-2.0, -2.0, -2.0, 2.0, 2.0, 2.0)
    d = vf.voronoi3d(S, box)
    vol, _ = voropp_cells(S, box)
    np.testing.assert_allclose(d.volumes, vol, rtol=2e-5, atol=1e-9)  # voro++ prints 6 digits


# ---- extreme scales: volumes are reported in the caller's units -------------------------


def _extreme(off, span, how):
    S = off + (np.random.default_rng(2).random((30, 3)) - 0.5) * span
    box = tuple(S.min(0) - 0.1 * np.ptp(S, 0)) + tuple(S.max(0) + 0.1 * np.ptp(S, 0))
    if how == "default":
        return vf.voronoi3d(S)
    return vf.voronoi3d(S, box, periodic=how == "periodic")


@pytest.mark.parametrize(("off", "span"), [(1e200, 1e199), (1e-200, 1e-201), (0.0, 1e300)])
@pytest.mark.parametrize("how", ["default", "box", "periodic"])
def test_extreme_scales_raise_naming_the_limit(off, span, how):
    # at 1e200 +- 1e199 the box volume overflowed (warnings, then inf volumes); at 1e-200
    # every cell measured 0: volumes outside 1e-270..1e300 are refused, naming the range
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(ValueError, match=r"outside 1e-270\.\.1e\+300.*scale the points"):
            _extreme(off, span, how)


@pytest.mark.parametrize(("off", "span"), [(0.0, 1e-70), (3e66, 1e67)])
@pytest.mark.parametrize("how", ["default", "box", "periodic"])
def test_extreme_scales_inside_the_range_work(off, span, how):
    # refused before the areas and volumes were computed in a power-of-two frame
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        d = _extreme(off, span, how)
    assert np.isfinite(d.volumes).all() and (d.volumes > 0).all()
    vol = d.container_volume
    assert abs(d.volumes.sum() - vol) <= 1e-12 * vol
    assert d.describe()["euler_ok"]


@pytest.mark.parametrize("k", [-215, -150, 150, 210])
@pytest.mark.parametrize("how", ["default", "box", "weights"])
def test_power_of_two_scales_inside_the_limit(k, how):
    # a power of two scales exactly: the same cells, volumes times 2**(3k), no warnings
    g = np.random.default_rng(3)
    S = g.random((40, 3))
    box = (0.0, 0.0, 0.0, 1.0, 1.0, 1.0) if how == "box" else None
    w = g.random(40) * 1e-3 if how == "weights" else None
    unit = vf.voronoi3d(S, box, weights=w)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        big = vf.voronoi3d(
            np.ldexp(S, k),
            None if box is None else tuple(np.ldexp(box, k)),
            weights=None if w is None else np.ldexp(w, 2 * k),
        )
        assert np.isfinite(big.face_areas).all()
        assert big.describe()["euler_ok"]
    assert (big.volumes == np.ldexp(unit.volumes, 3 * k)).all()
    assert (big.vertices == np.ldexp(unit.vertices, k)).all()
