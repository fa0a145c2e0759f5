"""3D cells in closed-mesh containers: torus (genus 1), L-bracket, a block with a through-hole."""

from __future__ import annotations

import numpy as np
import pytest

import voroforge as vf

trimesh = pytest.importorskip("trimesh")
pytest.importorskip("manifold3d")


def _box(lo, hi):
    m = trimesh.creation.box(extents=np.subtract(hi, lo))
    m.apply_translation(np.add(lo, hi) / 2)
    return m


def _bool(a, b, op):
    import manifold3d as m3

    def man(m):
        return m3.Manifold(
            m3.Mesh(
                vert_properties=np.asarray(m.vertices, np.float32),
                tri_verts=np.asarray(m.faces, np.uint32),
            )
        )

    r = {"union": man(a) + man(b), "minus": man(a) - man(b)}[op].to_mesh()
    return trimesh.Trimesh(
        np.asarray(r.vert_properties)[:, :3], np.asarray(r.tri_verts), process=False
    )


def _torus():
    return trimesh.creation.torus(
        major_radius=1.0, minor_radius=0.4, major_sections=24, minor_sections=12
    )


def _lbracket():
    return _bool(_box((0, 0, 0), (2, 0.5, 1)), _box((0, 0, 0), (0.5, 2, 1)), "union")


def _holed():
    cyl = trimesh.creation.cylinder(radius=0.3, height=3.0, sections=24)
    return _bool(_box((-1, -1, -0.5), (1, 1, 0.5)), cyl, "minus")


def _cavity():
    # a spherical hollow cut out of a box's corner: the surface is concave from the inside
    ball = trimesh.creation.icosphere(subdivisions=2, radius=0.9)
    ball.apply_translation([2, 2, 2])
    return _bool(_box((0, 0, 0), (2, 2, 2)), ball, "minus")


def _check_mesh_diagram(d, mesh, pts):
    vol = abs(mesh.volume)
    assert abs(d.volumes.sum() - vol) <= 1e-9 * vol
    assert d.container == "mesh" and d.cut_cells is not None
    box = vf.voronoi3d(pts, tuple(np.r_[mesh.bounds[0] - 0.1, mesh.bounds[1] + 0.1]))
    cf, lab, farea, roff, ring = d.cell_face_table()
    for i in range(len(d)):
        if d.volumes[i] == 0:
            continue
        if not d.cut_cells[i]:  # untouched: the same convex cell as without the container
            np.testing.assert_allclose(d.volumes[i], box.volumes[i], rtol=1e-12)
            assert d.pieces[i] == 1
            assert (lab[cf[i] : cf[i + 1]] >= 0).all()
        else:
            assert d.volumes[i] <= box.volumes[i] * (1 + 1e-9)
            m = d.to_trimesh(i)
            assert m.is_watertight
            np.testing.assert_allclose(m.volume, d.volumes[i], rtol=1e-9)
    # every wall triangle names a container triangle; areas of wall faces add to the surface
    wall = lab < 0
    assert (-1 - lab[wall] < len(mesh.faces)).all()
    np.testing.assert_allclose(np.linalg.norm(farea[wall], axis=1).sum(), mesh.area, rtol=1e-9)
    # sample points inside the mesh: the nearest site's cell is the one that holds them
    rng = np.random.default_rng(0)
    q = rng.uniform(mesh.bounds[0], mesh.bounds[1], (400, 3))
    from voroforge.engine.mesh3d import as_mesh_container, sites_inside

    mc, _ = as_mesh_container(mesh)
    q = q[sites_inside(mc, q)]
    near = ((q[:, None] - pts[None]) ** 2).sum(-1).argmin(1)
    assert (d.volumes[near] > 0).all()
    assert d.describe()["cut_cells"] == int(d.cut_cells.sum())


@pytest.mark.parametrize("make", [_torus, _lbracket, _holed], ids=["torus", "lbracket", "holed"])
def test_mesh_containers(make):
    mesh = make()
    rng = np.random.default_rng(1)
    lo, hi = mesh.bounds
    from voroforge.engine.mesh3d import as_mesh_container, sites_inside

    q = rng.uniform(lo, hi, (3000, 3))
    ins = sites_inside(as_mesh_container(mesh)[0], q)
    pts = np.vstack([q[ins][:250], q[~ins][:15]])  # some sites outside own parts too
    d = vf.voronoi3d(pts, mesh)
    _check_mesh_diagram(d, mesh, pts)
    assert d.cut_cells.sum() > 0 and (d.volumes[~d.cut_cells] > 0).any()
    # the same container as (vertices, faces) and as a file
    e = vf.voronoi3d(pts, (mesh.vertices, mesh.faces))
    np.testing.assert_allclose(e.volumes, d.volumes, rtol=1e-12, atol=1e-15)


def test_mesh_file_and_split_cells(tmp_path):
    # a C shape: a site in the slot owns parts of both prongs
    c = _bool(_box((0, 0, 0), (3, 3, 1)), _box((1, 1, -1), (4, 2, 2)), "minus")
    path = tmp_path / "c.stl"
    c.export(path)
    pts = np.array(
        [[0.5, 0.5, 0.5], [0.5, 2.5, 0.5], [2.5, 1.5, 0.5], [1.5, 0.5, 0.5], [1.5, 2.5, 0.5]]
    )
    d = vf.voronoi3d(pts, str(path))
    assert abs(d.volumes.sum() - abs(c.volume)) <= 1e-9 * abs(c.volume)
    assert d.pieces[2] == 2  # the slot site: a piece in each prong
    assert (d.pieces[[0, 1, 3, 4]] == 1).all()


def test_cell_faces_on_the_container_surface_are_walls():
    # sites mirrored across the cube's sides: bisector planes lie in the container's faces,
    # where the boolean keeps the cells' faces; they are walls (the outer sites' cells are
    # empty), so the wall areas add up to the surface and no cell names an empty neighbour
    mesh = _box((0, 0, 0), (1, 1, 1))
    g = np.arange(-0.25, 1.3, 0.5)
    pts = np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3)
    d = vf.voronoi3d(pts, mesh)
    _check_mesh_diagram(d, mesh, pts)
    np.testing.assert_allclose(d.volumes[d.volumes > 0], 0.125, rtol=1e-12)
    indptr, indices = d.neighbors
    assert (d.volumes[indices] > 0).all()
    assert (np.diff(indptr)[d.volumes > 0] == 3).all()  # each octant cube: three inner faces


def test_bad_meshes():
    m = _torus()
    with pytest.raises(ValueError, match="open"):
        vf.voronoi3d([[1, 0, 0]], (m.vertices, m.faces[:-1]))
    f = np.vstack([m.faces, m.faces[:1]])
    with pytest.raises(ValueError, match="non-manifold|oriented"):
        vf.voronoi3d([[1, 0, 0]], (m.vertices, f))
    with pytest.raises(ValueError, match="none of the sites"):
        vf.voronoi3d([[0, 0, 0]], m)  # the hole of the torus
    with pytest.raises(ValueError, match="not found"):
        vf.voronoi3d([[1, 0, 0]], "/nonexistent/mesh.stl")
    with pytest.raises(ValueError, match="container must be"):
        vf.voronoi3d([[1, 0, 0]], object())


def test_container_parts_wholly_inside_a_cell():
    # three separate bodies: a slab, a cube floating inside one cell alone and another in a
    # cell that also reaches the slab. Cells are cut in batches of cells that do not touch;
    # a part of the container that touches no face of its cell cannot be told apart in a
    # batch, so that batch is halved until it can (the island sites come first, so they
    # share their batches with slab cells)
    slab = _box((0, 0, 0), (4, 4, 1))
    alone = _box((1.4, 1.4, 1.9), (1.6, 1.6, 2.1))
    shared = _box((2.4, 2.4, 1.6), (2.6, 2.6, 1.8))
    mesh = trimesh.util.concatenate([slab, alone, shared])
    g = np.arange(0.25, 4.0, 0.5)
    pts = np.array([[1.5, 1.5, 2.0], [2.5, 2.5, 1.25]] + [[x, y, 0.5] for x in g for y in g])
    d = vf.voronoi3d(pts, mesh)
    _check_mesh_diagram(d, mesh, pts)
    np.testing.assert_allclose(d.volumes[0], 0.008, rtol=1e-9)
    assert d.pieces[0] == 1 and d.pieces[1] == 2
    assert d.cut_cells[:2].all()
    assert len(d.to_trimesh(1).split(only_watertight=False)) == 2


def _point_triangle_distance(p, tri):
    """Reference: distance from points ``p`` (one per triangle) to triangles ``tri (m, 3, 3)``."""

    def seg(p, a, b):
        ab = b - a
        t = np.clip(((p - a) * ab).sum(1) / np.maximum((ab * ab).sum(1), 1e-300), 0.0, 1.0)
        return np.linalg.norm(p - (a + t[:, None] * ab), axis=1)

    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    n = np.cross(b - a, c - a)
    nn = np.maximum((n * n).sum(1), 1e-300)
    h = ((p - a) * n).sum(1) / nn
    q = p - h[:, None] * n
    inside = np.ones(len(tri), bool)
    for u, v in ((a, b), (b, c), (c, a)):
        inside &= (np.cross(v - u, q - u) * n).sum(1) >= 0
    d = np.minimum(np.minimum(seg(p, a, b), seg(p, b, c)), seg(p, c, a))
    return np.where(inside, np.abs(h) * np.sqrt(nn), d)


def test_touching_cells_against_references():
    # the cells the cut skips must lie on one side of the surface (all their vertices agree),
    # and every cell called touching has a triangle within its farthest vertex from its site
    from voroforge.engine.mesh3d import _touching, as_mesh_container, sites_inside

    mesh = _torus()
    mc, t = as_mesh_container(mesh)
    pts = np.random.default_rng(3).uniform(mesh.bounds[0], mesh.bounds[1], (300, 3))
    d = vf.voronoi3d(pts, tuple(np.r_[t.bounds[0], t.bounds[1]]))
    cf, lab, farea, roff, ring = d.cell_face_table()
    # writeable, as cut_by_mesh hands them on (numba types the flag: a read-only array
    # compiled touching_cells and its callees once more for this test)
    V, farea = np.array(d.vertices), np.array(farea)
    tri = mc.vertices[mc.faces]
    live = np.diff(cf) > 0
    touch = _touching(cf, roff, ring, V, farea, live, tri, 1e-9)
    assert 0 < touch.sum() < live.sum()
    for i in np.flatnonzero(live):
        vs = np.unique(ring[roff[cf[i]] : roff[cf[i + 1]]])
        side = sites_inside(mc, V[vs])
        if not touch[i]:
            assert side.all() or not side.any()
        else:
            reach = np.linalg.norm(V[vs] - pts[i], axis=1).max()
            dist = _point_triangle_distance(np.repeat(pts[i : i + 1], len(tri), 0), tri)
            assert dist.min() <= reach * (1 + 1e-9)


def test_batches_share_no_vertex():
    # the greedy colouring (first fit, in order) against the plain set version
    from voroforge.engine.mesh3d import _apart

    pts = np.random.default_rng(4).random((200, 3))
    d = vf.voronoi3d(pts, (0, 0, 0, 1, 1, 1))
    cf, _, _, roff, ring = d.cell_face_table()
    cells = np.arange(0, 200, 2)
    got = _apart(cells, cf, roff, ring, len(d.vertices))
    batches, used = [], []
    for i in cells:
        vs = set(ring[roff[cf[i]] : roff[cf[i + 1]]].tolist())
        for b, u in zip(batches, used, strict=True):
            if u.isdisjoint(vs):
                b.append(i)
                u |= vs
                break
        else:
            batches.append([i])
            used.append(vs)
    assert [b.tolist() for b in got] == batches


@pytest.mark.parametrize("make", [_torus, _holed], ids=["torus", "holed"])
def test_cells_that_cannot_reach_the_mesh_are_not_built(make, monkeypatch):
    # sites outside whose cells cannot meet the surface are skipped (reaching_sites); the
    # result is the same as building every cell, and no skipped site owns any volume
    import voroforge.engine.mesh3d as m3d

    mesh = make()
    mc, _ = m3d.as_mesh_container(mesh)
    lo, hi = mesh.bounds
    pts = np.random.default_rng(7).uniform(lo - 0.5, hi + 0.5, (1500, 3))
    reach = m3d.reaching_sites(mc, pts, m3d.sites_inside(mc, pts))
    d = vf.voronoi3d(pts, mesh)
    monkeypatch.setattr(m3d, "reaching_sites", lambda mesh, pts, inside: np.ones(len(pts), bool))
    full = vf.voronoi3d(pts, mesh)
    assert 0 < reach.sum() < len(pts)
    assert (full.volumes[~reach] == 0).all()
    np.testing.assert_array_equal(d.volumes, full.volumes)
    np.testing.assert_array_equal(d.pieces, full.pieces)
    np.testing.assert_array_equal(d.cut_cells, full.cut_cells)
    a, b = d.cell_face_table(), full.cell_face_table()
    for x, y in zip(a, b, strict=True):
        np.testing.assert_array_equal(x, y)
    assert d.unmatched_vertices == 0


def _wall_areas(d):
    """``{(cell, label): area}`` of a diagram's faces, summed per cell and label."""
    cf, lab, farea, _, _ = d.cell_face_table()
    own = np.repeat(np.arange(len(d)), np.diff(cf))
    out: dict = {}
    for c, la, a in zip(own, lab, np.linalg.norm(farea, axis=1), strict=True):
        out[(int(c), int(la))] = out.get((int(c), int(la)), 0.0) + a
    return out


@pytest.mark.parametrize(
    "make", [_torus, _lbracket, _holed, _cavity], ids=["torus", "lbracket", "holed", "cavity"]
)
def test_convex_cuts_against_manifold(make, monkeypatch):
    # cells that the surface meets are cut by our kernel (kernels/meshcut3d.convex_cells:
    # by the triangles' planes, split into convex parts at reflex edges and saddles);
    # manifold3d's boolean gives the same volumes (to the rounding of its absolute
    # coordinates), pieces and walls
    import voroforge.engine.mesh3d as m3d

    mesh = make()
    lo, hi = mesh.bounds
    pts = np.random.default_rng(11).uniform(lo - 0.2, hi + 0.2, (800, 3))
    calls = []
    real = m3d._convex_part

    def spy(todo, *args):
        got = real(todo, *args)
        calls.append(0 if got is None else len(got[0][1]))
        return got

    monkeypatch.setattr(m3d, "_convex_part", spy)
    d = vf.voronoi3d(pts, mesh)
    monkeypatch.setattr(m3d, "_convex_part", lambda *a: None)
    ref = vf.voronoi3d(pts, mesh)
    assert 0 < calls[0] < d.cut_cells.sum() + 1
    scale = np.median(ref.volumes[ref.volumes > 0])
    np.testing.assert_allclose(d.volumes, ref.volumes, rtol=1e-9, atol=1e-11 * scale)
    np.testing.assert_array_equal(d.pieces, ref.pieces)
    np.testing.assert_array_equal(d.cut_cells, ref.cut_cells)
    a, b = _wall_areas(d), _wall_areas(ref)
    big = {k for k, v in b.items() if v > 1e-9 * mesh.area}
    assert big <= set(a) and {k for k, v in a.items() if v > 1e-9 * mesh.area} <= set(b)
    for k in big:
        assert abs(a[k] - b[k]) <= 1e-8 * mesh.area
    for i in np.flatnonzero(d.cut_cells)[:60]:
        assert d.to_trimesh(i).is_watertight


def test_mesh_container_far_from_the_origin():
    # a UTM-like offset: the same cells, translated (the convex cuts' tolerances follow the
    # mesh's size, above the rounding of coordinates near 4e6)
    mesh = _torus()
    lo, hi = mesh.bounds
    pts = np.random.default_rng(12).uniform(lo, hi, (400, 3))
    shift = np.array([500000.0, 4000000.0, 100.0])
    d = vf.voronoi3d(pts, mesh)
    far = mesh.copy()
    far.apply_translation(shift)
    e = vf.voronoi3d(pts + shift, far)
    assert abs(e.volumes.sum() - abs(mesh.volume)) <= 1e-9 * abs(mesh.volume)
    np.testing.assert_allclose(e.volumes, d.volumes, rtol=1e-6, atol=1e-9 * abs(mesh.volume))
    np.testing.assert_array_equal(e.pieces, d.pieces)


def test_same_cells_on_one_thread_and_two():
    # the convex cuts run in slices on threads (from 256 cells a thread), each slice's cells
    # writing their rows one after another, and the touch test walks the cells in space
    # order: one thread and two must give the same cells, bit for bit
    import numba

    if numba.config.NUMBA_NUM_THREADS < 2:
        pytest.skip("needs two numba threads")
    mesh = _torus()
    lo, hi = mesh.bounds
    pts = np.random.default_rng(5).uniform(lo, hi, (6000, 3))
    before = numba.get_num_threads()
    try:
        numba.set_num_threads(1)
        one = vf.voronoi3d(pts, mesh)
        numba.set_num_threads(2)
        two = vf.voronoi3d(pts, mesh)
    finally:
        numba.set_num_threads(before)
    assert one.cut_cells.sum() >= 512  # two threads of slices
    np.testing.assert_array_equal(one.volumes, two.volumes)
    np.testing.assert_array_equal(one.centroids, two.centroids)
    np.testing.assert_array_equal(one.vertices, two.vertices)
    np.testing.assert_array_equal(one.pieces, two.pieces)
    for a, b in zip(one.cell_face_table(), two.cell_face_table(), strict=True):
        np.testing.assert_array_equal(a, b)
    assert abs(one.volumes.sum() - abs(mesh.volume)) <= 1e-9 * abs(mesh.volume)
