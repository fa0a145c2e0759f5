"""3D describe() at offsets where an ulp is coarser than 1e-9 of a cell (independent check)."""

from __future__ import annotations

import numpy as np
import pytest

import voroforge as vf


@pytest.mark.parametrize("seed", range(4))
def test_convexity_is_judged_at_the_coordinates_resolution(seed):
    # cells 4 wide at 7e13 (ulp 0.0078): rounding dents a third of an ulp deep were reported
    # as non-convex against 1e-9 of the cell's size
    off = 7e13
    p = off + np.random.default_rng(seed).random((3, 3)) * 4
    r = vf.voronoi3d(p, (off, off, off, off + 4, off + 4, off + 4)).describe()
    assert r["convex"] and r["euler_ok"], r
