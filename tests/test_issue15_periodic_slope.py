"""Issue 15, periodic sites on a sloped line far out: wrapped cells that folded once rounded.

Far out (a 3 x 2 box at 4e12, an ulp 2**-11) the periodic diagram is built in a frame where
every copy is exact and its cells are moved back, one rounding per coordinate. Two vertices
of a cell a fraction of an ulp apart (a tiny edge) rounded to neighbouring floats in the
wrong order, and the wrapped cell crossed itself (500 sites on the line y = 0.3 x + 0.1).
The later point of such a pair now takes the earlier one's value, in every cell that has it,
so the tiny edge rounds away and the cells still tile the box. A cell narrower than an ulp
whose long sides cross once rounded stays a documented flag: its site is unresolved, and it
keeps the part its ring winds round the right way.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import shapely

import voroforge as vf
from test_issue15_periodic import _check_torus

from reference import exact_cell

OFF = 4e12
BOX = (OFF, OFF, OFF + 3.0, OFF + 2.0)
ULP = 2.0**-11  # of 4e12


def _sloped(slope: float, c: float, seed: int, n: int = 500):
    x = np.random.default_rng(seed).random(n) * 3.0
    return np.column_stack((OFF + x, OFF + np.mod(slope * x + c, 2.0)))


def test_sloped_line_at_4e12_unwrapped_cells_tile_the_torus():
    _check_torus(_sloped(0.3, 0.1, 0), BOX, "delaunay", False, samples=300, describe=False)


def test_sloped_line_at_4e12_wrapped_cells_valid_and_tiling():
    p = _sloped(0.3, 0.1, 0)
    d = vf.voronoi(p, BOX, periodic=True, wrap=True)
    cells = d.cells
    assert shapely.is_valid(cells).all()
    # the box's area exactly: the cells meet vertex to vertex (their shoelace sums cancel)
    assert d.areas.sum() == 6.0
    indptr, idx = d.neighbors
    pairs = {(i, int(j)) for i in range(len(p)) for j in idx[indptr[i] : indptr[i + 1]]}
    assert all((j, i) in pairs for i, j in pairs)
    # sample points clear of ties lie in the cell of their nearest periodic image (the
    # differences in the box's frame, exact)
    lo = np.array(BOX[:2])
    s = p - lo
    q = np.random.default_rng(1).random((300, 2)) * [3.0, 2.0]
    shifts = np.array([(a, b) for a in (-1, 0, 1) for b in (-1, 0, 1)], dtype=float) * [3, 2]
    d2 = (((q[:, None, None] - (s[None, :, None] + shifts[None, None])) ** 2).sum(3)).min(2)
    order = np.argsort(d2, axis=1)
    first = np.sqrt(np.take_along_axis(d2, order[:, :1], axis=1)[:, 0])
    second = np.sqrt(np.take_along_axis(d2, order[:, 1:2], axis=1)[:, 0])
    lost = set(np.asarray(d.unresolved).tolist())
    local = shapely.transform(cells, lambda xy: xy - lo)
    for k in np.flatnonzero(second - first > 1e3 * ULP):
        if order[k, 0] not in lost:
            assert local[order[k, 0]].covers(shapely.Point(q[k])), k


def test_the_folded_cell_against_the_exact_torus_cell():
    p = _sloped(0.3, 0.1, 0)
    d = vf.voronoi(p, BOX, periodic=True, wrap=True)
    cells = d.cells
    assert shapely.is_valid(cells).all()
    # site 327's cell lies inside the box (it folded on a vertex pair 0.05 x 0.13 ulps apart)
    i = 327
    local = p - np.array(BOX[:2])  # exact (Sterbenz)
    s = local[i]
    # every site's 9 images: the cell lies within half a period of its site on each axis,
    # so a site that cuts it is within one and a half periods
    near = [q + (a * 3.0, b * 2.0) for q in local for a in (-1, 0, 1) for b in (-1, 0, 1)]
    pts = np.array([s, *[q for q in near if (q != s).any()]])
    ring = exact_cell(pts, 0, (s[0] - 1.5, s[1] - 1.0, s[0] + 1.5, s[1] + 1.0))
    exact = shapely.Polygon([(float(a), float(b)) for a, b in ring])
    ours = shapely.transform(cells[i], lambda xy: xy - np.array(BOX[:2]))
    assert shapely.hausdorff_distance(ours, exact) <= 1.0 * ULP
    area = sum(
        a0 * b1 - a1 * b0 for (a0, b0), (a1, b1) in zip(ring, ring[1:] + ring[:1], strict=True)
    ) / Fraction(2)
    assert abs(d.areas[i] - float(area)) <= 0.5 * ULP * exact.length


@pytest.mark.parametrize(("slope", "c", "seed"), [(2 / 3, 0.0, 2), (1.3, 0.05, 0)])
def test_cells_narrower_than_an_ulp_that_fold_are_flagged(slope, c, seed):
    p = _sloped(slope, c, seed)
    d = vf.voronoi(p, BOX, periodic=True, wrap=True)
    assert shapely.is_valid(d.cells).all()
    flagged = np.asarray(d.unresolved)
    assert 1 <= len(flagged) <= 2
    # what a flagged cell keeps or leaves is fractions of an ulp across its length
    assert abs(d.areas.sum() - 6.0) <= 1e-5
    assert (np.asarray(d.areas)[flagged] < 0.02).all()
