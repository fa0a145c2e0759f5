"""Issue 12: many-faced cells after the cut stopped finding the radius after every cut.

``cellcut3d._cut_batch`` keeps a bound on the cell's squared radius after a graph cut (the
one before, padded) and finds the radius itself only where the band test or the batch's end
needs it. The cells must still be the exact ones: a helix (cells of ~100 faces) and three
orthogonal lines, sampled cells against rational cells (``reference3d_exact``), all the
volumes summing to the box, and the neighbours symmetric.
"""

from __future__ import annotations

import pytest

import voroforge as vf
from catalogue3d import helix, three_lines
from reference3d_exact import exact_power_cell

BOX = (0.0, 0.0, 0.0, 1.0, 1.0, 1.0)


@pytest.mark.parametrize(
    "points, cells",
    [(helix(240), (0, 117, 239)), (three_lines(240), (3, 95, 170))],
    ids=["helix", "lines3"],
)
def test_many_faced_cells_exact(points, cells):
    d = vf.voronoi3d(points, BOX)
    assert abs(d.volumes.sum() - 1.0) <= 1e-12
    ptr, nb = d.neighbors
    pairs = {(i, int(j)) for i in range(len(points)) for j in nb[ptr[i] : ptr[i + 1]]}
    assert all((j, i) in pairs for i, j in pairs if j >= 0)
    for i in cells:
        ex = exact_power_cell(points, i, BOX)
        want = {int(j) for lab in ex.neighbour_sets() for j in lab if j >= 0}
        got = {int(j) for j in nb[ptr[i] : ptr[i + 1]] if j >= 0}
        assert got == want, i
        assert abs(d.volumes[i] - float(ex.volume)) <= 1e-12 * max(1.0, float(ex.volume))
        assert max(len(want), 1) >= 8
