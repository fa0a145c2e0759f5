"""``lloyd`` on a domain wider than float64 holds (checker16 F2's lloyd case).

``vf.lloyd([[1.7e308, 0], [0, 0]])`` said "points contains NaN coordinates" (none given):
the domain's size overflowed, so it was not relaxed in a scaled frame. The reference is the
same problem scaled down by an exact power of two (no overflow there), scaled back.
"""

from __future__ import annotations

import numpy as np

import voroforge as vf


def test_a_box_wider_than_float64_relaxes_as_its_scaled_copy():
    rng = np.random.default_rng(7)
    box = np.array([-1.7e308, -1e308, 1.7e308, 1e308])  # xmax - xmin overflows
    pts = rng.uniform(-0.9, 0.9, (12, 2)) * [1.7e308, 1e308]
    got = vf.lloyd(pts, tuple(box), iterations=4)
    k = 1000
    ref = vf.lloyd(np.ldexp(pts, -k), tuple(np.ldexp(box, -k)), iterations=4)
    assert np.isfinite(got.points).all()
    np.testing.assert_allclose(np.ldexp(got.points, -k), ref.points, rtol=1e-9, atol=0)
    assert not np.array_equal(got.points, pts)  # it moved


def test_default_box_of_far_apart_sites_relaxes():
    pts = np.array([[1.7e308, 0.0], [0.0, 0.0], [0.0, 5e307]])
    r = vf.lloyd(pts, iterations=2)
    assert np.isfinite(r.points).all() and not np.array_equal(r.points, pts)
    # two sites on a line: both move towards the quarter points of the padded box
    r = vf.lloyd([[1.7e308, 0.0], [0.0, 0.0]], iterations=1)
    assert np.isfinite(r.points).all()
    assert r.points[0, 0] < 1.7e308 and r.points[1, 0] > 0.0
