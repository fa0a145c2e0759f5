"""Sites spanning more than float64 can pad: the default box, ``describe`` and the raster.

Sites past +-9e307 on both sides (or 1.7e308 from the others) made the padded box's sides
or extent overflow: a cell with infinite vertices (invalid, area NaN), ``vf.voronoi`` never
returning, ``describe`` failing in scipy, the raster's NaN error (checker16 F2). The box is
now clamped to the largest double, so the cells are valid polygons; areas past the largest
double are inf (overflow of the true value, not an error).
"""

from __future__ import annotations

import warnings
from fractions import Fraction

import numpy as np
import pytest
import shapely

import voroforge as vf
from voroforge.engine.domain import padded_bounds

TOP = float(np.finfo(np.float64).max)

HUGE = {
    "one site at 1.7e308": [[1.7e308, 0.0], [0.0, 0.0], [0.0, 1.0]],
    "extent overflows": [[9e307, 0.0], [-9e307, 0.0], [0.0, 1.0]],
    "diagonal +-1e308": [[1e308, 1e308], [-1e308, -1e308]],
    "at the largest double": [[TOP, 0.0], [-TOP, 0.0]],
}


def _nearest(q, P):
    keys = [
        (sum((Fraction(float(a)) - Fraction(float(b))) ** 2 for a, b in zip(q, p, strict=True)), i)
        for i, p in enumerate(P)
    ]
    return min(keys)[1]


@pytest.mark.parametrize("name", sorted(HUGE))
def test_default_box_of_huge_sites(name):
    P = np.array(HUGE[name])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        # rounding 1.0 next to 1.7e308 (README) merges two sites: said, not an error
        warnings.filterwarnings("ignore", "1 distinct sites are used as one", RuntimeWarning)
        d = vf.voronoi(P)
        box = d.bounds
        assert all(np.isfinite(box))
        assert box[0] <= P[:, 0].min() and box[2] >= P[:, 0].max()
        assert box[1] <= P[:, 1].min() and box[3] >= P[:, 1].max()
        live = np.flatnonzero(d.duplicate_of < 0)
        assert all(shapely.is_valid(d.cells[i]) and not d.cells[i].is_empty for i in live)
        for i in live:  # every cell holds its site, and its vertices are finite
            assert np.isfinite(shapely.get_coordinates(d.cells[i])).all()
            assert d.cells[i].intersects(shapely.Point(P[i]))
        r = d.describe()
        assert r.euler_ok and r.convex_ok
        raster = vf.rasterize(P, (4, 4))
    # the raster's labels are the exact nearest sites of the pixel centres (in a frame scaled
    # by a power of two, where the centres are exact)
    x0, y0, x1, y1 = (np.ldexp(v, -64) for v in box)
    live_pts = P[live]
    for row in range(4):
        for col in range(4):
            q = (
                x0 + (col + 0.5) * ((x1 - x0) / 4),
                y1 - (row + 0.5) * ((y1 - y0) / 4),  # (row 0 at the top)
            )
            want = live[_nearest(q, np.ldexp(live_pts, -64))]
            got = raster.labels[row, col]
            assert got == want or d.duplicate_of[got] == want


def test_ordinary_extents_pad_as_before():
    rng = np.random.default_rng(7)
    for scale in (1e-300, 1e-9, 1.0, 1e9, 1e300):
        P = rng.random((20, 2)) * scale - scale / 3
        lo, hi = P.min(0), P.max(0)
        size = hi - lo
        want = (lo[0] - 0.1 * size[0], lo[1] - 0.1 * size[1], hi[0] + 0.1 * size[0])
        assert padded_bounds(P)[:3] == want
