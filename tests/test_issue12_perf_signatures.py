"""Issue 12: the 3D cell builder compiles once for the grid's cells, the lists' and the hull's.

``kernels.cells3d.build_cells`` took ``big`` and ``star`` as None or as arrays, and numba
compiled the kernel once for each form it met (the grid's ``(None, None)``, the Delaunay
lists' ``(big, star)``, a big vertex's or a big hull's ``(big, None)``): ~9 s each on a cold
cache. None now stands for empty arrays of the lists' types, so one compile serves all.
"""

from __future__ import annotations

import numpy as np

import voroforge as vf
from voroforge.engine import lists3d
from voroforge.kernels.cells3d import build_cells


def test_grid_and_list_cells_share_one_compile(monkeypatch):
    rng = np.random.default_rng(12)
    p = rng.random((300, 3))
    box = (0, 0, 0, 1, 1, 1)
    grid = vf.voronoi3d(p, box)
    seen = set(build_cells.signatures)
    # no compile of the kernel takes None for big, star or gone (another numba type each)
    assert all(str(t) != "none" for sig in seen for t in sig[26:29])
    monkeypatch.setattr(lists3d, "FORCE", True)  # every cell from its Delaunay list
    listed = vf.voronoi3d(p, box)
    assert set(build_cells.signatures) == seen
    # the same cells either way (volumes to rounding; vertex order may differ)
    assert np.allclose(listed.volumes, grid.volumes, rtol=1e-12, atol=0)
    for a, b in zip(listed.neighbors, grid.neighbors, strict=True):
        assert np.array_equal(a, b)
    assert np.isclose(grid.volumes.sum(), 1.0, rtol=1e-12)
