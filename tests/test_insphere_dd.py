"""insphere's double-double stage (kernels/insphere_dd) against fractions.

Points rounded onto a sphere are cospherical to ~1 ulp: the float filter cannot tell their
insphere sign, and every test of their Delaunay triangulation went to the expansions
(~12 us each). The double-double stage between them must never give a sign that the exact
determinant does not have, must decide nearly all of these, and must leave exact zeros
(integer points of one sphere) to the expansions.
"""

from __future__ import annotations

from fractions import Fraction as Q

import numpy as np
import pytest

from test_predicates3d import _det
from voroforge.kernels.insphere_dd import insphere_dd
from voroforge.kernels.predicates3d import insphere


def _insphere_ref(p5):
    e = [Q(v) for v in p5[4]]
    rows = []
    for p in p5[:4]:
        r = [Q(float(p[k])) - e[k] for k in range(3)]
        rows.append(r + [sum(x * x for x in r)])
    d = _det(rows)
    return (d > 0) - (d < 0)


def _rounded_sphere(rng, n, scale, centre):
    v = rng.normal(size=(n, 3))
    return v / np.linalg.norm(v, axis=1)[:, None] * scale + np.asarray(centre)


@pytest.mark.parametrize(
    "scale, centre",
    [
        (1.0, (0.0, 0.0, 0.0)),
        (1e-9, (0.0, 0.0, 0.0)),
        (1e9, (0.0, 0.0, 0.0)),
        (1.0, (0.5, 1e-3, 3.0)),  # mixed magnitudes: differences with tails
        (1e-6, (123.456, 0.0, -1e-5)),
        (1e3, (5e5, 4e6, 100.0)),  # UTM-like offset
    ],
)
def test_dd_signs_are_exact_on_rounded_spheres(scale, centre):
    rng = np.random.default_rng(17)
    S = _rounded_sphere(rng, 400, scale, centre)
    decided = 0
    for t in range(150):
        p5 = np.ascontiguousarray(S[rng.choice(len(S), 5, replace=False)])
        if t % 2:  # the query moved by a few ulps off the rounded sphere
            p5[4] += rng.integers(-3, 4, 3) * np.spacing(p5[4])
        want = _insphere_ref(p5)
        got = insphere_dd(p5)
        assert got == 0.0 or np.sign(got) == want, (t, p5)
        decided += got != 0.0
        assert np.sign(insphere(p5)) == want
    # the float filter decides none of these; the stage must decide nearly all
    assert decided >= 140


def test_dd_leaves_exact_zeros_to_the_expansions():
    # integer points of one sphere (x^2 + y^2 + z^2 = 693^2, scaled by 2^-9: exact)
    r = 693
    quads = [(1, 2, 2, 3), (2, 3, 6, 7), (1, 4, 8, 9), (4, 4, 7, 9), (2, 6, 9, 11), (6, 6, 7, 11)]
    rng = np.random.default_rng(3)
    zeros = 0
    for _ in range(60):
        pts = []
        for _ in range(5):
            a, b, c, q = quads[rng.integers(len(quads))]
            v = np.array([a, b, c], float)[rng.permutation(3)] * rng.choice([-1, 1], 3)
            pts.append(v * (r // q) / 512.0)
        p5 = np.ascontiguousarray(pts)
        want = _insphere_ref(p5)
        got = insphere_dd(p5)
        assert got == 0.0 or np.sign(got) == want
        if want == 0:
            zeros += 1
            assert got == 0.0 and insphere(p5) == 0.0
    assert zeros >= 50


def test_dd_agrees_with_the_expansions_in_bulk():
    # many more cases than fractions allow: against the exact stage (itself checked
    # against fractions in test_predicates3d), on a rounded sphere's quintuples
    from numba import njit

    from voroforge.kernels.predicates3d import _put_diff, _put_lift, exact_dets, scratch

    @njit
    def both(Q5, out):
        buf = scratch()
        EL = np.zeros((4, 3), np.int64)
        TL = np.zeros(4, np.int64)
        for t in range(Q5.shape[0]):
            for k in range(4):
                for c in range(3):
                    _put_diff(buf, EL, k, c, Q5[t, k, c], Q5[t, 4, c])
                _put_lift(buf, EL, TL, k, 0.0, 0.0)
            out[t, 0] = insphere_dd(Q5[t])
            out[t, 1] = exact_dets(buf, EL, TL, np.bool_(True))[1]

    rng = np.random.default_rng(8)
    S = _rounded_sphere(rng, 20000, 1.0, (0.0, 0.0, 0.0))
    Q5 = np.ascontiguousarray(S[rng.integers(0, len(S), (20000, 5))])
    out = np.zeros((len(Q5), 2))
    both(Q5, out)
    dec = out[:, 0] != 0.0
    assert (out[dec, 0] == out[dec, 1]).all()
    assert dec.mean() > 0.99
