"""``RasterVoronoi.x``/``.y`` are the points sampled, at any scale (checker16 F3).

Bounds past ``2**±RASTER_FRAME_EXP`` are rastered in a power-of-two frame. The centres are
reported from that frame too: finite at bounds of ±1e308 (``xmax - xmin`` overflowed to inf),
and, where the pixel size is subnormal, the rounded points actually sampled (they were all 0
while the labels belonged to the unrounded centres). Checked against ``locate`` and against
a brute force in rationals at the reported centres.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

import voroforge as vf
from voroforge.engine.raster import pixel_centers

TINY = 5e-324


def _brute_labels(P, x, y):
    """Lowest index of the exactly nearest site of each ``(x[c], y[r])`` (rationals)."""
    F = [(Fraction(float(a)), Fraction(float(b))) for a, b in P]
    out = np.zeros((len(y), len(x)), dtype=np.int64)
    for r, yy in enumerate(y):
        for c, xx in enumerate(x):
            qx, qy = Fraction(float(xx)), Fraction(float(yy))
            out[r, c] = min(((qx - a) ** 2 + (qy - b) ** 2, i) for i, (a, b) in enumerate(F))[1]
    return out


def _located(P, r):
    X, Y = np.meshgrid(r.x, r.y)
    return vf.locate(P, np.c_[X.ravel(), Y.ravel()]).reshape(r.labels.shape)


@pytest.mark.parametrize("method", ["exact", "jfa"])
@pytest.mark.parametrize(
    ("P", "shape", "bounds"),
    [
        ([[0.0, 0.0], [TINY, 0.0]], (1, 8), (0.0, 0.0, 4 * TINY, TINY)),
        (
            [[0.0, 0.0], [3 * TINY, 2 * TINY], [TINY, 5 * TINY]],
            (5, 7),
            (0.0, 0.0, 6 * TINY, 6 * TINY),
        ),
        (
            [[2.0**-1060, 0.0], [0.0, 2.0**-1062]],
            (6, 6),
            (-(2.0**-1058), -(2.0**-1058), 2.0**-1058, 2.0**-1058),
        ),
        ([[1e307, 2e307], [-3e307, 5e306], [0.0, -1e308]], (4, 5), (-1e308, -1e308, 1e308, 1e308)),
        ([[1.7e308, 0.0], [-1.7e308, 1e308]], (3, 9), (-1.79e308, -1.79e308, 1.79e308, 1.79e308)),
    ],
)
def test_labels_are_those_of_the_reported_centres(P, shape, bounds, method):
    P = np.array(P)
    r = vf.rasterize(P, shape, bounds, method=method, f2=True)
    assert np.isfinite(r.x).all() and np.isfinite(r.y).all()
    assert np.all(np.diff(r.x) >= 0) and np.all(np.diff(r.y) <= 0)
    assert bounds[0] <= r.x.min() and r.x.max() <= bounds[2]
    assert bounds[1] <= r.y.min() and r.y.max() <= bounds[3]
    want = _brute_labels(P, r.x, r.y)
    assert r.labels.tolist() == want.tolist()
    assert _located(P, r).tolist() == want.tolist()
    # the distances are those of the reported centres (to the rounding of a square root)
    X, Y = np.meshgrid(r.x, r.y)
    e = int(np.frexp(max(abs(v) for v in bounds))[1])
    with np.errstate(over="ignore", under="ignore", invalid="ignore"):
        dx = np.ldexp(X, -e) - np.ldexp(P[want, 0], -e)
        dy = np.ldexp(Y, -e) - np.ldexp(P[want, 1], -e)
        d = np.ldexp(np.hypot(dx, dy), e)  # (inf past the largest double, as r.distance)
        # (a subnormal distance is rounded to a multiple of TINY)
        assert np.all((r.distance == d) | (np.abs(r.distance - d) <= 1e-15 * d + TINY))


def test_centres_at_huge_bounds_are_the_formula_scaled():
    """At ±1e308 the centres are those of the same bounds scaled by 2**-1024, scaled back."""
    b = (-1e308, -1e308, 1e308, 1e308)
    x, y = pixel_centers(b, (4, 4))
    xs, ys = pixel_centers(tuple(np.ldexp(b, -1024)), (4, 4))
    assert x.tolist() == np.ldexp(xs, 1024).tolist() == [-7.5e307, -2.5e307, 2.5e307, 7.5e307]
    assert y.tolist() == np.ldexp(ys, 1024).tolist()


@pytest.mark.parametrize("k", [-600, -100, 0, 100, 600])
def test_centres_scale_with_the_bounds(k):
    """Metamorphic: bounds scaled by 2**k give the centres scaled by 2**k (normal range)."""
    b = (0.1, -0.3, 0.7, 0.25)
    x, y = pixel_centers(b, (5, 11))
    xk, yk = pixel_centers(tuple(np.ldexp(b, k)), (5, 11))
    assert np.ldexp(x, k).tolist() == xk.tolist()
    assert np.ldexp(y, k).tolist() == yk.tolist()
    r = vf.rasterize([[0.2, 0.0], [0.5, -0.1]], (5, 11), b)
    assert r.x.tolist() == x.tolist() and r.y.tolist() == y.tolist()
