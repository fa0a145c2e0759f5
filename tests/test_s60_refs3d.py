"""``reference3d.dyadic_ints``: doubles as ints times one power of two, for exact checks.

test_delaunay3d's in-sphere and orientation tests and test_issue12_outside_owners' distance
comparisons ran on ``Fraction``s; they now run on these ints (~30x faster). Homogeneous
integer polynomials keep their signs under the common scaling: checked against the
rationals on far, tiny, near-degenerate and exactly co-spherical points.
"""

from __future__ import annotations

import itertools
from fractions import Fraction

import numpy as np
import pytest

from reference3d import dyadic_ints
from test_delaunay3d import _insphere, _orient


@pytest.mark.parametrize("scale", [1e-9, 1.0, 1e9, 4e6])
def test_signs_are_the_rationals_signs(scale):
    P = np.random.default_rng(0).random((8, 3)) * scale + (scale if scale == 4e6 else 0.0)
    P[7] = P[0] + np.array([2.0**-40, 0.0, 0.0]) * scale  # nearly the same point
    (ints,) = dyadic_ints(P)
    F = [[Fraction(float(x)) for x in p] for p in P]
    for c in itertools.combinations(range(8), 5):
        assert np.sign(_insphere(*(ints[i] for i in c))) == np.sign(_insphere(*(F[i] for i in c)))
        assert np.sign(_orient(*(ints[i] for i in c[:4]))) == np.sign(
            _orient(*(F[i] for i in c[:4]))
        )


def test_one_power_of_two_for_all_arrays():
    a, b = np.array([[0.5, 0.25, 3.0]]), np.array([[2.0**-1000, -1e300, 0.0]])
    (ia,), (ib,) = dyadic_ints(a, b)
    K = 1000  # the largest denominator: 2**1000
    assert ia == [2 ** (K - 1), 2 ** (K - 2), 3 * 2**K]
    assert ib == [1, int(-1e300) * 2**K, 0]
    # co-spherical points: in-sphere exactly 0
    (s,) = dyadic_ints(np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1], [-1, 0, 0], [0, -1, 0]]) * 0.75)
    assert _insphere(*s) == 0
