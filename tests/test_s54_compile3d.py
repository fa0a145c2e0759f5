"""Issue 12: the 3D cell builder compiles its Delaunay-star path only where a star is read.

``kernels.cells3d.build_cells`` read cells off their Delaunay stars (``kernels.star3d``) in a
branch of its one compiled kernel, so every process that built a box's cells compiled the
star path too (~10 of the 3D warm-up's 189 CPU s). The stars are now read by a kernel of
their own (``cells3d._star_cells``), called only in list mode where a list is long enough;
the cut skips the cells it built. Checked here: no star pass for the grid's cells, a star
pass in list mode that builds cells, and the same diagram either way.
"""

from __future__ import annotations

import numpy as np

import voroforge as vf
from voroforge.engine import lists3d
from voroforge.kernels import cells3d


def test_star_pass_only_in_list_mode_and_same_cells(monkeypatch):
    built = []
    real = cells3d._star_cells

    def spy(*args):
        real(*args)
        built.append(int(args[-1].sum()))  # done: the cells read off their stars

    monkeypatch.setattr(cells3d, "_star_cells", spy)
    p = np.random.default_rng(12).random((300, 3))
    box = (0, 0, 0, 1, 1, 1)
    grid = vf.voronoi3d(p, box)
    assert built == []  # the grid's cells: the star kernel is not called, so not compiled
    monkeypatch.setattr(lists3d, "FORCE", True)
    monkeypatch.setattr(lists3d, "STAR_LEAST", 0)  # every interior cell from its star
    stars = vf.voronoi3d(p, box)
    assert built and sum(built) > 0
    assert np.allclose(stars.volumes, grid.volumes, rtol=1e-12, atol=0)
    for a, b in zip(stars.neighbors, grid.neighbors, strict=True):
        assert np.array_equal(a, b)
    assert np.isclose(stars.volumes.sum(), 1.0, rtol=1e-12)
