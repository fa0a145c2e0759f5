"""Fixes of the eighth independent check's findings (lead): rasters at 1e308, messages."""

from __future__ import annotations

import numpy as np
import pytest

import voroforge as vf


@pytest.mark.parametrize("method", ["exact", "jfa"])
@pytest.mark.parametrize("e", [1000, 1020, -1000])
def test_rasters_near_float64s_limits_are_the_unit_raster_scaled(method, e):
    # bounds (0, 0, 1e308, 1e308) gave inf distances; (-1e308, ..., 1e308) raised numpy's
    # "cannot convert float NaN to integer" (the box's width overflowed)
    pts = np.random.default_rng(0).random((50, 2))
    s = 2.0**e
    for box in ((0, 0, 1, 1), (-1, -1, 1, 1)):
        ref = vf.rasterize(pts, (16, 16), box, method=method, f2=True)
        r = vf.rasterize(pts * s, (16, 16), tuple(np.array(box) * s), method=method, f2=True)
        assert np.array_equal(r.labels, ref.labels)
        assert np.array_equal(r.distance, np.ldexp(ref.distance, e))
        assert np.array_equal(r.f2, np.ldexp(ref.f2, e))
        assert r.bounds == tuple(float(v) * s for v in box)
