"""The half-plane cell's exact finishing is compiled once, not retyped in the cell loop (s59).

numba's ``inline="always"`` inlines a function's IR at its call site, where it is typed and
lowered again with its caller: :func:`.halfplane_finish.finish_cell` (with the settling it
inlines in turn) made ``halfplane._cells`` the costliest single compile of the 2D suite.
It is a plain compiled function now (one call per cell); these tests keep it so, and check
that the cells it finishes did not move.
"""

from __future__ import annotations

import numpy as np

import voroforge as vf
from voroforge.kernels import halfplane_finish


def test_finish_cell_is_a_call_not_inlined_into_the_cell_loop():
    assert halfplane_finish.finish_cell.targetoptions.get("inline", "never") != "always"


def test_halfplane_cells_match_the_dual_on_grid_and_random_sites():
    # a grid (every vertex cocircular: the exact settling's rounds) and random sites
    grid = np.stack(np.meshgrid(np.arange(7.0), np.arange(5.0)), -1).reshape(-1, 2)
    rnd = np.random.default_rng(5).random((300, 2))
    for pts in (grid, rnd):
        ref = vf.voronoi(pts)
        d = vf.voronoi(pts, algorithm="halfplane")
        assert np.allclose(d.areas, ref.areas, rtol=0.0, atol=1e-12)
        assert np.allclose(d.centroids, ref.centroids, rtol=0.0, atol=1e-12)
