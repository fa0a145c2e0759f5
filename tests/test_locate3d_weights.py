"""``Diagram3D.locate`` with weights: the power-nearest site, exact ties to the lowest index.

Checked against a brute force in rationals over every site, on inputs with many exact power
ties (integer sites and weights, half-integer queries), weights far larger than the box, and
on the 3-torus. Weighted queries go through a KD-tree of lifted sites (a fourth coordinate
``sqrt(max w - w)``); these inputs have more than 64 sites so they take it.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

import voroforge as vf


def _power_nearest(q, P, w, live, period=None):
    best = None
    for i in live:
        t = Fraction(0)
        for a in range(3):
            dl = Fraction(float(q[a])) - Fraction(float(P[i, a]))
            if period is not None:
                dl %= period[a]
                dl = min(dl, period[a] - dl)
            t += dl * dl
        key = (t - Fraction(float(w[i])), int(i))
        best = key if best is None or key < best else best
    return best[1]


def _check(d, P, w, Q, period=None):
    got = d.locate(Q)
    live = np.flatnonzero(np.asarray(d.duplicate_of) < 0)
    want = [_power_nearest(q, P, w, live, period) for q in Q]
    assert got.tolist() == want


@pytest.mark.parametrize("offset", [0.0, 5e5])
def test_integer_lattice_with_integer_weights_ties_to_the_lowest_index(offset):
    rng = np.random.default_rng(3)
    g = np.arange(5.0)
    P = np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3) + offset
    w = rng.integers(0, 3, len(P)).astype(float)
    d = vf.voronoi3d(
        P, (offset - 1, offset - 1, offset - 1, offset + 5, offset + 5, offset + 5), weights=w
    )
    # half-integer queries: on cell faces, edges and corners where several sites tie exactly
    Q = rng.integers(-1, 10, (150, 3)) / 2.0 + offset
    _check(d, P, w, Q)


def test_weights_far_larger_than_the_box_and_empty_cells():
    rng = np.random.default_rng(4)
    P = rng.random((300, 3))
    w = 1e9 + rng.random(300) * 0.05  # all close to 1e9: the lift's rounding is ~1e-7 of it
    w[:5] += 2.0  # five heavy sites empty most others
    d = vf.voronoi3d(P, (0, 0, 0, 1, 1, 1), weights=w)
    Q = rng.random((200, 3))
    _check(d, P, w, Q)
    assert set(d.locate(Q).tolist()) <= set(np.flatnonzero(d.volumes > 0).tolist())


def test_equal_weights_locate_as_no_weights():
    rng = np.random.default_rng(5)
    P = rng.random((200, 3))
    Q = np.vstack((rng.random((200, 3)), P[:20]))
    plain = vf.voronoi3d(P, (0, 0, 0, 1, 1, 1)).locate(Q)
    equal = vf.voronoi3d(P, (0, 0, 0, 1, 1, 1), weights=np.full(200, 7.0)).locate(Q)
    assert plain.tolist() == equal.tolist()


def test_weighted_on_the_torus():
    rng = np.random.default_rng(6)
    g = np.arange(4.0) / 4
    P = np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3) + 0.125
    P = np.vstack((P, rng.random((40, 3))))
    w = rng.integers(0, 3, len(P)) / 64.0
    d = vf.voronoi3d(P, (0, 0, 0, 1, 1, 1), weights=w, periodic=True)
    # queries in and outside the box (wrapped), on the lattice's exact power ties
    Q = np.vstack((rng.integers(-8, 16, (120, 3)) / 8.0, rng.random((60, 3)) * 3 - 1))
    _check(d, P, w, Q, period=(Fraction(1), Fraction(1), Fraction(1)))
