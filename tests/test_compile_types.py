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


def test_hull_path_face_table_has_the_box_builders_types():
    # a big Convex's cells (engine.hull3d) are built with build3d's argument types and carry
    # its index types, so the cell builder and the face-table kernels (diagram3d's faces,
    # neighbours, caller's order) compile once for both paths
    from scipy.spatial import ConvexHull

    from voroforge.engine.diagram3d import _unique_faces

    rng = np.random.default_rng(2)
    hull = _sphere(rng, 300)
    s = (rng.random((200, 3)) - 0.5) * 0.8
    box = vf.voronoi3d(s, (-1, -1, -1, 1, 1, 1))
    built = set(build_cells.signatures)
    big = vf.voronoi3d(s, vf.Convex(points=hull))
    assert set(build_cells.signatures) == built  # hull3d's second pass: build3d's types
    for name in ("_cell_faces", "_flabel", "_roff", "_ring", "_voff", "_vid"):
        assert getattr(big, name).dtype == getattr(box, name).dtype, name
    assert len(box.faces) > 0
    seen = set(_unique_faces.signatures)
    assert len(big.faces) > 0
    assert set(_unique_faces.signatures) == seen
    # the cells tile the hull (scipy's volume) and each face has two sides or a wall
    assert np.isclose(big.volumes.sum(), ConvexHull(hull).volume, rtol=1e-9)
    cells = big.faces.cells
    assert (cells[:, 0] >= 0).all() and ((cells[:, 1] > cells[:, 0]) | (cells[:, 1] < 0)).all()


def test_sites_inside_frozen_points_compiles_no_second_inside_mesh():
    # a read-only array is another numba type: frozen sites (a Diagram3D's) are copied
    from scipy.spatial import ConvexHull, Delaunay

    from voroforge.engine.mesh3d import as_mesh_container, sites_inside
    from voroforge.kernels.inside3d import inside_mesh

    rng = np.random.default_rng(3)
    hull = _sphere(rng, 60)
    ch = ConvexHull(hull)
    tri = ch.simplices.copy()  # a closed convex mesh, each triangle turned outward
    a, b, c = (hull[tri[:, k]] for k in range(3))
    inward = np.einsum("ij,ij->i", np.cross(b - a, c - a), ch.equations[:, :3]) < 0
    tri[inward] = tri[inward][:, ::-1]
    mesh = as_mesh_container((hull, tri))[0]
    q = (rng.random((500, 3)) - 0.5) * 2.2
    got = sites_inside(mesh, q)
    seen = set(inside_mesh.signatures)
    frozen = q.copy()
    frozen.flags.writeable = False
    assert np.array_equal(sites_inside(mesh, frozen), got)
    assert set(inside_mesh.signatures) == seen
    assert np.array_equal(got, Delaunay(hull).find_simplex(q) >= 0)  # convex: scipy's test
