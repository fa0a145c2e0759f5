"""3D describe() at offsets where an ulp is coarser than 1e-9 of a cell, and 3D periodic
duplicates across the wrap (independent check, 2026-12-04)."""

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


def test_periodic_3d_duplicates_across_the_wrap():
    # a site on the upper face is the lower face's site on the torus (independent check F3:
    # volumes [0.5, 0.5, 0.5] summed to 1.5)
    box = (0, 0, 0, 1, 1, 1)
    for p, dup in (
        ([[0, 0.3, 0.3], [1, 0.3, 0.3], [0.5, 0.5, 0.5]], [-1, 0, -1]),
        ([[1, 0.3, 0.3], [0, 0.3, 0.3]], [-1, 0]),
        ([[0, 0, 0], [1, 1, 1], [1, 0, 1], [0.5, 0.5, 0.5]], [-1, 0, 0, -1]),
    ):
        d = vf.voronoi3d(np.array(p, dtype=float), box, periodic=True)
        assert d.duplicate_of.tolist() == dup
        assert d.volumes.sum() == pytest.approx(1.0, rel=1e-12)
