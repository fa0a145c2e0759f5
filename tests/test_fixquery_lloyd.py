"""Lloyd on domains of extreme aspect ratio: every site moves to its cell's centroid.

A 1.6e308 x 1.2 box, scaled to unit size, had an area of ~2**-1024: every cell's mass was
subnormal and no site moved. And ``tol`` was a fraction of the long side, so on a
1.6e8 x 1.2 strip any move across it passed the test at once. The reference centroid is
shapely's, of the same cells scaled per axis to unit size (a centroid commutes with an
axis scaling) and scaled back.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely

import voroforge as vf
from voroforge.engine.domain import make_domain
from voroforge.engine.lloyd import size_exponent


def _reference_step(P, box):
    W, H = box[2] - box[0], box[3] - box[1]
    if not np.isfinite(W):
        W = 2.0 * (box[2] / 2 - box[0] / 2)
    d = vf.voronoi(P, box)
    out = []
    for cell in d.cells:
        xy = shapely.get_coordinates(cell)
        c = shapely.polygons(xy / np.array([W, H])).centroid
        out.append((c.x * W, c.y * H))
    return np.array(out), np.array([W, H])


@pytest.mark.parametrize("W", [1.6e8, 1e100, 1.6e308])
def test_one_step_is_the_centroid_of_each_cell(W):
    rng = np.random.default_rng(0)
    H = 1.2
    P = np.c_[(rng.random(12) - 0.5) * W * 0.9, rng.random(12) * H * 0.9]
    box = (-W / 2, 0.0, W / 2, H)
    r = vf.lloyd(P, box, iterations=1)
    ref, sides = _reference_step(P, box)
    assert np.all(np.abs(r.points - ref) <= 1e-12 * sides)
    assert (r.points[:, 1] != P[:, 1]).all()


def test_the_issue_three_sites_relax_as_at_unit_scale():
    """The same three sites at 1.6e8 and 1.6e308: the same points, scaled (dyadic moves)."""
    a = vf.lloyd([[7e7, 0], [-7e7, 0], [0, 1]], (-8e7, -0.1, 8e7, 1.1), iterations=3)
    b = vf.lloyd([[7e307, 0], [-7e307, 0], [0, 1]], (-8e307, -0.1, 8e307, 1.1), iterations=3)
    assert np.allclose(b.points[:, 0] / 1e300, a.points[:, 0], rtol=1e-14, atol=0)
    assert np.allclose(b.points[:, 1], a.points[:, 1], rtol=1e-14, atol=0)
    assert np.allclose(a.points, [[53593750.0, 0.5], [-53593750.0, 0.5], [0.0, 0.5]], rtol=1e-14)


def test_size_exponent_is_a_fixed_point():
    for box in [(0, 0, 1.6e308, 1.2), (0, 0, 1.0, 1e-300), (0, 0, 1e-300, 1.0), (0, 0, 1e80, 1e70)]:
        k = size_exponent(make_domain(box, None))
        assert size_exponent(make_domain(tuple(np.ldexp(box, k)), None)) == 0


@pytest.mark.parametrize("method", ["lloyd", "lbfgs"])
def test_tol_holds_on_both_axes_of_a_thin_strip(method):
    """A strip 1.6e8 x 1.2: tol=1e-3 stops only once the short axis has converged too."""
    rng = np.random.default_rng(1)
    W, H = 1.6e8, 1.2
    P = np.c_[(rng.random(8) - 0.5) * W * 0.9, rng.random(8) * H * 0.9]
    box = (-W / 2, 0.0, W / 2, H)
    r = vf.lloyd(P, box, iterations=200, tol=1e-3, method=method)
    assert r.iterations > 1
    # at the end every site is within 1e-2 of the strip's height of its cell's centroid
    ref, sides = _reference_step(r.points, box)
    assert np.all(np.abs(r.points - ref) <= 1e-2 * sides)
    # on a square the test is the old one: no site moved farther than tol times the side
    s = vf.lloyd(P / np.array([W, H]), (-0.5, 0, 0.5, 1), iterations=200, tol=1e-3)
    assert s.iterations < 200 and s.shift[-1] <= 1e-3 and (s.shift[:-1] > 1e-3).all()
