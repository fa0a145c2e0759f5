"""The kernels see the same numba types from call to call (one compile each, not two).

numba compiles a kernel once per argument type, and a read-only array is another type than
a writable one. ``Diagram3D`` froze its ``walls`` in place, and those were the container
template's own rows (``Template.absolute_walls``): the next ``voronoi3d`` on the same
:class:`Convex` passed the cell builder a read-only ``WP``, and every 3D cell kernel
(``cells3d.build_cells`` and its callees, ``hull3d``'s) compiled a second time: ~50 s of a
cold test suite, and a second compile in any cold process that reuses a Convex (Lloyd).
"""

from __future__ import annotations

import numpy as np

import voroforge as vf
from voroforge.kernels.cells3d import build_cells


def _sphere(rng, m):
    h = rng.normal(size=(m, 3))
    return h / np.linalg.norm(h, axis=1)[:, None]


def test_diagram_walls_are_frozen_copies_not_the_containers_rows():
    rng = np.random.default_rng(0)
    for c in (vf.Convex(points=_sphere(rng, 40)), vf.Convex(points=_sphere(rng, 300))):
        rows = c._template.WP
        before = rows.copy()
        d = vf.voronoi3d(rng.random((30, 3)) - 0.5, c)
        assert rows.flags.writeable  # the container's template is untouched
        assert np.array_equal(rows, before)
        assert not d.walls.flags.writeable
        assert not np.shares_memory(d.walls, rows)
        assert np.array_equal(d.walls, c._template.absolute_walls())


def test_a_second_diagram_in_the_same_convex_compiles_no_new_cell_builder():
    rng = np.random.default_rng(1)
    c = vf.Convex(points=_sphere(rng, 40))
    s = rng.random((30, 3)) - 0.5
    d0 = vf.voronoi3d(s, c)
    seen = set(build_cells.signatures)
    d1 = vf.voronoi3d(s, c)
    assert set(build_cells.signatures) == seen
    assert np.array_equal(d0.volumes, d1.volumes)
