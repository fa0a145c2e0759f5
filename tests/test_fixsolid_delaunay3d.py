"""Tetrahedralization.volumes at extreme scales: inf past float64's range, never NaN
(checker20 F6), against scaling by powers of two (exact) and rationals."""

import dataclasses
from fractions import Fraction

import numpy as np
import pytest

import voroforge as vf


def _exact_volume(q):
    a, b, c, d = ([Fraction(float(x)) for x in row] for row in q)
    u, v, w = ([r[i] - a[i] for i in range(3)] for r in (b, c, d))
    det = (
        u[0] * (v[1] * w[2] - v[2] * w[1])
        - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0])
    )
    return det / 6


@pytest.mark.parametrize("k", [300, 340, 400, 498, 600, 1000])
def test_volumes_scale_by_powers_of_two(k):
    P = np.random.default_rng(0).random((50, 3))
    base = vf.delaunay3d(P)
    t = vf.delaunay3d(np.ldexp(P, k))
    assert np.array_equal(t.simplices, base.simplices)
    v = t.volumes
    assert not np.isnan(v).any()
    with np.errstate(over="ignore"):
        assert np.array_equal(v, np.ldexp(base.volumes, 3 * k))


@pytest.mark.parametrize("seed", range(4))
def test_finite_volume_whose_products_overflow(seed):
    # edges ~2^520 nearly parallel: the cross product's terms overflow, the volume does not
    rng = np.random.default_rng(seed)
    L = 2.0**520
    u = np.array([1.0, 1.0, 0.0]) + rng.random(3) * 1e-3
    v = u + np.array([0.0, 2.0**-40, 0.0]) * (1 + rng.random())
    q = np.array([[0.0, 0.0, 0.0], u * L, v * L, [0.0, 0.0, 2.0**-10 * (1 + rng.random())]])
    # delaunay3d's own tolerance for such a sliver is not the point: volumes of this tet
    t = dataclasses.replace(
        vf.delaunay3d(np.eye(4, 3)), points=q, simplices=np.array([[0, 1, 2, 3]])
    )
    (vol,) = t.volumes
    # the same tetrahedron scaled by 2^-521 (exact) has finite products: same float volume
    (small,) = dataclasses.replace(t, points=np.ldexp(q, -521)).volumes
    assert vol == np.ldexp(small, 3 * 521)
    exact = _exact_volume(q)
    # a sliver: float rounding ~ eps * (terms' magnitudes / volume) ~ eps * 2^41
    assert np.isfinite(vol) and exact > 0
    assert abs(Fraction(vol) - exact) <= 1e-3 * exact
