"""voroforge.solid: lattices, foams, shells, slabs and print checks (watertight, exact volumes)."""

from __future__ import annotations

import math
import threading
import warnings

import numpy as np
import pytest
import shapely

trimesh = pytest.importorskip("trimesh")
pytest.importorskip("manifold3d")
pytest.importorskip("skimage")

import voroforge as vf  # noqa: E402
from reference_solid import box_cells, hull_volume, segment_distance, winding_numbers  # noqa: E402
from voroforge import config, solid  # noqa: E402
from voroforge.io import mesh as mio  # noqa: E402
from voroforge.solid import implicit  # noqa: E402
from voroforge.solid.booleans import manifold_status  # noqa: E402
from voroforge.solid.hulls import ring_area  # noqa: E402


def _solid_ok(m):
    assert m.is_volume
    assert manifold_status(m) == "NoError"


# --- lattice: the hull route, exact ------------------------------------------------------


def test_single_strut_volume_is_analytic():
    r, L, k = 0.5, 10.0, 8
    m = solid.lattice((np.array([[0, 0, 0], [L, 0, 0.0]]), [[0, 1]]), radius=r, nodes="hull")
    _solid_ok(m)
    d = config.SOLID_RING_MIN * r  # a lone end: the ring sits at the minimum distance
    area = ring_area(k) * r * r
    expected = area * (L - 2 * d) + 2 * area * d / 3  # prism + two cones to the node points
    assert abs(m.volume - expected) <= 1e-9 * expected


def test_cube_cell_struts_analytic_and_nodes_independent():
    L, r, k = 10.0, 0.5, 8
    m = solid.lattice(trimesh.creation.box((L, L, L)), radius=r)
    _solid_ok(m)
    parts = m.metadata["parts"]
    assert parts["method"] == "hull" and parts["merged"] == 0
    assert len(m.metadata["struts"]["a"]) == 12
    # right angles: cot(45 deg) = 1, ring at SAFETY * r from each corner
    d = max(config.SOLID_RING_SAFETY, config.SOLID_RING_MIN) * r
    struts = 12 * ring_area(k) * r * r * (L - 2 * d)
    assert abs(parts["strut_volume"] - struts) <= 1e-9 * struts
    # each corner blob is convex: its hull volume from Delaunay tetrahedra (no facets)
    v = np.asarray(m.vertices)
    corner = v[np.linalg.norm(v - [L / 2, L / 2, L / 2], axis=1) < d + 1.5 * r]
    blob = hull_volume(corner)
    assert abs(m.volume - (struts + 8 * blob)) <= 1e-6 * m.volume
    assert abs(m.volume - (parts["hull_volume"] + parts["strut_volume"])) <= 1e-9 * m.volume


@pytest.mark.parametrize("nodes", ["sphere", "hull"])
def test_bcc_cells_hull_route(nodes):
    g = np.mgrid[0:3, 0:3, 0:3].reshape(3, -1).T * 10.0 + 5.0
    pts = np.vstack([g, g[(g < 25).all(axis=1)] + 5.0])
    cells = box_cells(pts, (0, 0, 0, 30, 30, 30))
    m = solid.lattice(cells, radius=0.4, nodes=nodes)
    _solid_ok(m)
    p = m.metadata["parts"]
    assert abs(m.volume - (p["hull_volume"] + p["strut_volume"])) <= 1e-9 * m.volume


def test_graded_radius_is_frustums():
    f = solid.fields.point([[5, 5, 5]], radius=30.0, falloff="linear")
    m = solid.lattice(trimesh.creation.box((10, 10, 10)), radius=(0.3, 0.9), field=f)
    _solid_ok(m)
    s = m.metadata["struts"]
    r = np.concatenate([s["ra"], s["rb"]])
    assert r.min() < r.max()  # graded
    assert (s["ra"] != s["rb"]).any()  # frustums
    p = m.metadata["parts"]
    assert abs(m.volume - (p["hull_volume"] + p["strut_volume"])) <= 1e-9 * m.volume


@pytest.mark.parametrize("nodes", ["sphere", "hull"])
def test_random_cells_hull_route_with_joints(nodes):
    # random cells have struts too short for two rings: their nodes share a joint (a
    # manifold3d union of the node hulls and the short struts), the rest stays exact
    rng = np.random.default_rng(3)
    cells = box_cells(rng.random((25, 3)) * 20, (0, 0, 0, 20, 20, 20))
    r = 0.6
    m = solid.lattice(cells, radius=r, nodes=nodes)
    _solid_ok(m)
    p = m.metadata["parts"]
    assert p["method"] == "hull" and p["joints"] > 0 and p["merged"] > 0
    assert abs(m.volume - (p["hull_volume"] + p["strut_volume"])) <= 1e-9 * m.volume
    if nodes == "hull":
        return
    # no overlapping parts (winding number 2 where a self-intersecting mesh doubles up) and no
    # missing material (every point within 0.6 r of a strut axis is inside); the points
    # cluster at the nodes of joints, where pieces meet
    s = m.metadata["struts"]
    a, b = s["a"], s["b"]
    short = np.linalg.norm(b - a, axis=1) < 3 * r
    centres = np.vstack([a[short], b[short]])
    pts = centres[rng.integers(0, len(centres), 300)] + rng.normal(0, r, (300, 3))
    t = rng.random((150, 1))
    k = rng.integers(0, len(a), 150)
    pts = np.vstack([pts, a[k] + t * (b[k] - a[k]) + rng.normal(0, 0.7 * r, (150, 3))])
    w = winding_numbers(m.vertices, m.faces, pts, chunk=16)
    assert np.abs(w - np.round(w)).max() < 1e-6
    assert set(np.round(w).astype(int).tolist()) <= {0, 1}
    assert (np.round(w)[segment_distance(pts, a, b) < 0.6 * r] == 1).all()


def test_joint_pockets_are_filled_and_checks_stay_clean():
    # overlapping convex parts of a joint can enclose a pocket a fraction of a strut across:
    # filled (its volume added back), so the print check lists no trapped void
    import voroforge as vf

    pts = np.random.default_rng(2).random((60, 3)) * 30
    cells = vf.voronoi3d(pts, (0, 0, 0, 30, 30, 30))
    r = 0.06 * 30 / 60 ** (1 / 3)
    m = solid.lattice(cells, radius=r)
    _solid_ok(m)
    p = m.metadata["parts"]
    assert p["method"] == "hull" and p["pockets"] >= 1
    assert 0 < p["pocket_volume"] < p["pockets"] * (2 * r) ** 3
    assert abs(m.volume - (p["hull_volume"] + p["strut_volume"])) <= 1e-9 * m.volume
    assert "trapped_void" not in solid.check(m, max_overhang=None).by_kind()


def test_random_cells_implicit_route_agrees():
    # the implicit route's plain union of round struts and spherical nodes on the same cells:
    # the two constructions' volumes are close (octagonal struts hold 90% of a circle's area,
    # node hulls fill a little between struts)
    rng = np.random.default_rng(3)
    cells = box_cells(rng.random((25, 3)) * 20, (0, 0, 0, 20, 20, 20))
    hull = solid.lattice(cells, radius=0.6)
    imp = solid.lattice(cells, radius=0.6, route="implicit", voxel=0.3, smoothing=0)
    _solid_ok(imp)
    assert imp.metadata["parts"]["method"] == "implicit"
    assert len(imp.metadata["struts"]["a"]) == len(hull.metadata["struts"]["a"])
    assert 0.85 < hull.volume / imp.volume < 1.15


# --- lattice: the implicit route ---------------------------------------------------------


def test_capsule_volume_close_to_analytic():
    r, L = 1.0, 8.0
    m = solid.lattice(
        (np.array([[0, 0, 0], [L, 0, 0.0]]), [[0, 1]]),
        radius=r,
        nodes="smooth",
        smoothing=0,
        voxel=0.15,
    )
    _solid_ok(m)
    exact = math.pi * r * r * L + 4 / 3 * math.pi * r**3
    assert abs(m.volume - exact) / exact < 0.015


def test_slabs_stitch_exactly(monkeypatch):
    box = trimesh.creation.box((6, 6, 6))
    one = solid.lattice(box, radius=0.6, nodes="smooth", smoothing=0, voxel=0.25)
    monkeypatch.setattr(implicit, "_SLAB", 7)  # many slabs: every seam must close
    many = solid.lattice(box, radius=0.6, nodes="smooth", smoothing=0, voxel=0.25)
    _solid_ok(many)
    # same triangles; vertices differ only by marching cubes' float32 rounding of positions
    assert len(one.faces) == len(many.faces)
    assert abs(one.volume - many.volume) <= 1e-6 * one.volume


def test_slabs_are_sampled_ahead_in_order_and_errors_reach_the_caller(monkeypatch):
    monkeypatch.setattr(implicit, "_SLAB", 5)
    monkeypatch.setattr(implicit, "THREADS", True)  # whatever the machine's load
    seen = []

    def ball(shape, origin, krange):
        seen.append((krange, threading.current_thread().name))
        ijk = np.indices(shape).reshape(3, -1).T
        p = origin + 0.5 * ijk
        return (np.linalg.norm(p - 2.0, axis=1) - 1.5).reshape(shape).astype(np.float32)

    m = implicit.march(ball, (0, 0, 0), (4, 4, 4), 0.5, bare=True)
    ks = [k for k, _ in seen]  # in order, each slab starting where the last one ends
    assert (
        len(ks) == 3
        and ks[0][0] == 0
        and all(a[1] == b[0] for a, b in zip(ks, ks[1:], strict=False))
    )
    assert [t for _, t in seen] == ["MainThread"] + ["voroforge-slab"] * 2
    assert m.trimesh().is_volume  # the seams closed
    assert abs(implicit.signed_volume(m) / (4 / 3 * np.pi * 1.5**3) - 1) < 0.1  # coarse

    def broken(shape, origin, krange):
        if krange[0] > 0:
            raise ValueError(f"no field at {krange}")
        return ball(shape, origin, krange)

    with pytest.raises(ValueError, match=r"no field at \(5, 10\)"):
        implicit.march(broken, (0, 0, 0), (4, 4, 4), 0.5, bare=True)
    # without a spare core, every slab on the caller's thread: the same mesh
    monkeypatch.setattr(implicit, "THREADS", False)
    seen.clear()
    one = implicit.march(ball, (0, 0, 0), (4, 4, 4), 0.5, bare=True)
    assert [t for _, t in seen] == ["MainThread"] * 3
    assert np.array_equal(one.vertices, m.vertices) and np.array_equal(one.faces, m.faces)


def test_container_trim_and_skin(monkeypatch):
    rng = np.random.default_rng(5)
    cells = box_cells(rng.random((12, 3)) * 20, (0, 0, 0, 20, 20, 20))
    c = trimesh.creation.icosphere(2, radius=8.0)
    c.apply_translation([10, 10, 10])
    reaching = implicit._reaching
    kept = []
    monkeypatch.setattr(implicit, "_reaching", lambda *a: kept.append(reaching(*a)) or kept[-1])
    m = solid.lattice(cells, radius=0.6, container=c, skin=1.0, voxel=0.4, smoothing=0)
    _solid_ok(m)
    # inside the container's bounds; skin volume about area * thickness
    assert (m.bounds[0] >= c.bounds[0] - 0.5).all() and (m.bounds[1] <= c.bounds[1] + 0.5).all()
    assert m.volume > 0.6 * c.area * 1.0
    # struts left out where they cannot change the trimmed field (outside the container, and
    # with a skin in its outer half too): the same mesh as with every strut evaluated
    trim = solid.lattice(cells, radius=0.6, container=c, route="implicit", voxel=0.4, smoothing=0)
    left_out = [int((~k).sum()) for k in kept]  # one slab each
    assert len(left_out) == 2 and left_out[0] > left_out[1] > 0
    # the container's field started ahead on a second thread (a design build's, while its
    # cells relax): the lattice takes those blocks, the same mesh
    bare, block, threads = implicit.Bare(c.vertices, c.faces), implicit._ContainerField.block, []

    def counted(self, *a):
        threads.append(threading.current_thread().name)
        return block(self, *a)

    monkeypatch.setattr(implicit._ContainerField, "block", counted)
    monkeypatch.setattr(implicit, "THREADS", True)  # whatever the machine's load
    implicit.prefetch_container(bare, 1.0, 0.4)
    ahead = solid.lattice(cells, radius=0.6, container=bare, skin=1.0, voxel=0.4, smoothing=0)
    assert threads and set(threads) == {"voroforge-container"} and bare._ahead is None
    assert np.array_equal(ahead.vertices, m.vertices) and np.array_equal(ahead.faces, m.faces)
    monkeypatch.setattr(implicit, "_reaching", lambda c, below, o, h, a, *r: np.ones(len(a), bool))
    for skin, got in ((1.0, m), (0.0, trim)):
        route = "auto" if skin else "implicit"
        every = solid.lattice(
            cells, radius=0.6, container=c, skin=skin, route=route, voxel=0.4, smoothing=0
        )
        assert np.array_equal(got.vertices, every.vertices) and np.array_equal(
            got.faces, every.faces
        )


@pytest.mark.parametrize("skin", [0.0, 2.0])
def test_struts_left_out_do_not_change_the_trimmed_field(monkeypatch, skin):
    # the field itself, every sample: 600 short struts strewn over a sphere's box, so that
    # some lie wholly in each zone (outside, in the skin's outer and inner half, deeper)
    rng = np.random.default_rng(7)
    a = rng.uniform(0, 10, (600, 3))
    struts = {"a": a, "b": a + rng.normal(0, 0.3, (600, 3)), "ra": np.full(600, 0.2)}
    struts["rb"] = struts["ra"] + rng.uniform(0, 0.1, 600)
    c = trimesh.creation.icosphere(2, radius=4.0)
    c.apply_translation([5, 5, 5])
    fields = []

    def field(evaluate, lo, hi, h, **kw):  # the block march would sample first, whole
        n = np.ceil((np.asarray(hi) - lo) / h).astype(int) + 1
        fields.append(evaluate(tuple(int(k) for k in n), np.asarray(lo, float), (0, n[2] - 1)))
        return fields[-1]

    monkeypatch.setattr(implicit, "march", field)
    reaching = implicit._reaching
    monkeypatch.setattr(implicit, "_reaching", lambda c, below, o, h, a, *r: np.ones(len(a), bool))
    implicit.capsules_mesh(struts, voxel=0.15, container=c, skin=skin, smooth=0.0)  # every strut
    kept = []
    monkeypatch.setattr(implicit, "_reaching", lambda *a: kept.append(reaching(*a)) or kept[-1])
    implicit.capsules_mesh(struts, voxel=0.15, container=c, skin=skin, smooth=0.0)
    assert 50 < int((~kept[0]).sum()) < 550
    assert np.array_equal(fields[0], fields[1]) and (fields[0] < 0).any()


# --- foam ----------------------------------------------------------------------------------


def test_foam_single_and_two_cells_analytic():
    m = solid.foam([trimesh.creation.box((1, 1, 1))], wall=0.2)
    _solid_ok(m)
    assert abs(m.volume - (1 - 0.8**3)) <= 1e-9
    a = trimesh.creation.box((1, 1, 1))
    b = a.copy()
    b.apply_translation([1, 0, 0])
    m2 = solid.foam([a, b], wall=0.2)
    assert m2.is_volume
    assert abs(m2.volume - (2 - 2 * 0.8**3)) <= 1e-9


def test_foam_random_is_container_minus_bubbles():
    rng = np.random.default_rng(0)
    cells = box_cells(rng.random((30, 3)) * 10, (0, 0, 0, 10, 10, 10))
    m = solid.foam(cells, wall=0.5)
    _solid_ok(m)
    bubbles = solid.foam.__globals__["bubbles"](cells, 0.5)
    inner = sum(b.volume for b, _, _ in bubbles if b is not None)
    assert abs(m.volume - (1000.0 - inner)) <= 1e-9 * 1000.0
    rep = solid.check(m, max_overhang=None)
    assert rep.by_kind()["trapped_void"] == sum(b is not None for b, _, _ in bubbles)


@pytest.mark.parametrize("scale", [1e-9, 1e-6, 1e6])
def test_foam_keeps_every_bubble_at_any_scale(scale):
    # trimesh's face normals are zero below an absolute area: a foam 1e-6 across lost 21 of
    # 30 bubbles (its volume came out negative), at 1e-7 all of them
    rng = np.random.default_rng(1)
    p = rng.random((30, 3))
    one = solid.foam(vf.voronoi3d(p, (0, 0, 0, 1, 1, 1)), wall=0.02)
    cells = vf.voronoi3d(p * scale, (0, 0, 0, scale, scale, scale))
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no "walls fill k cells"
        m = solid.foam(cells, wall=0.02 * scale)
    assert m.is_watertight
    assert (m.metadata["pores"]["size"] > 0).all()
    assert len(m.metadata["pores"]["size"]) == 30
    assert abs(m.volume / scale**3 - one.volume) <= 1e-9 * one.volume


def test_foam_walls_thicker_than_cells_are_reported():
    # a wall of 100 in cells ~4 wide fills every cell: a solid block, which check() must not
    # call fine (it said "ok" with min_pore=3: no pore was recorded)
    rng = np.random.default_rng(7)
    cells = box_cells(rng.random((10, 3)) * 30, (0, 0, 0, 30, 30, 30))
    with pytest.warns(UserWarning, match="fill 10 of 10 cells"):
        m = solid.foam(cells, wall=100.0)
    assert abs(m.volume - 27000.0) <= 1e-6
    assert (m.metadata["pores"]["size"] == 0.0).all()
    rep = solid.check(m, min_pore=3.0, max_overhang=None)
    assert rep.by_kind()["small_pore"] == 10 and not rep.ok
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no cell filled: no warning
        m = solid.foam(cells, wall=0.5)
    assert (m.metadata["pores"]["size"] > 0).all()


# --- shell and extrude ---------------------------------------------------------------------


def test_shell_with_openings():
    surf = trimesh.creation.cylinder(radius=10.0, height=12.0, sections=48)
    keep = surf.face_normals[:, 2] ** 2 < 0.5  # the open tube: no caps
    tube = trimesh.Trimesh(surf.vertices, surf.faces[keep], process=True)
    m = solid.shell(tube, thickness=1.0, openings=12, web=1.5, voxel=0.4, smoothing=2)
    _solid_ok(m)
    plain = 2 * math.pi * 10.0 * 12.0 * 1.0
    assert 0.2 * plain < m.volume < 0.95 * plain  # openings removed material
    assert len(m.metadata["pores"]["size"]) == 12


def test_shell_of_an_unwelded_surface_is_the_welded_one():
    # every triangle with its own three vertices (as STL gives them): every edge was "open",
    # the rim covered the whole surface and no opening was cut (the plain shell's volume)
    surf = trimesh.creation.cylinder(radius=10.0, height=12.0, sections=48)
    keep = surf.face_normals[:, 2] ** 2 < 0.5
    tube = trimesh.Trimesh(surf.vertices, surf.faces[keep], process=True)
    loose = trimesh.Trimesh(
        tube.vertices[tube.faces].reshape(-1, 3),
        np.arange(3 * len(tube.faces)).reshape(-1, 3),
        process=False,
    )
    args = dict(thickness=1.0, openings=12, web=1.5, voxel=0.4, smoothing=2)
    a, b = solid.shell(tube, **args), solid.shell(loose, **args)
    _solid_ok(b)
    assert b.volume < 0.95 * 2 * math.pi * 10.0 * 12.0
    assert b.volume == pytest.approx(a.volume, rel=1e-9)


def test_extrude_analytic_and_relief():
    frame = shapely.box(0, 0, 10, 10).difference(shapely.box(2, 2, 8, 8))
    m = solid.extrude(frame, 3.0)
    _solid_ok(m)
    assert abs(m.volume - 192.0) <= 1e-9 * 192.0
    m2 = solid.extrude(frame, 3.0, relief=lambda xy: 0.1 * xy[:, 0])
    _solid_ok(m2)
    # the top is linear in x: volume = integral of (3 + x / 10) over the frame
    cx = frame.centroid.x
    assert abs(m2.volume - frame.area * (3.0 + 0.1 * cx)) <= 1e-9 * m2.volume
    two = solid.extrude(shapely.MultiPolygon([shapely.box(0, 0, 1, 1), shapely.box(3, 0, 4, 1)]), 1)
    assert two.is_volume and abs(two.volume - 2.0) < 1e-12
    assert solid.check(two, max_overhang=None).by_kind() == {"floating_part": 1}


def test_extrude_relief_follows_sharp_and_touching_outlines():
    # a 20-spike star (spike angle about 6 degrees), a hole touching the outline at a point
    # (inside one of its edges) and two holes touching each other at a vertex
    ang = np.linspace(0, 2 * np.pi, 41)[:-1]
    r = np.where(np.arange(40) % 2, 1.0, 10.0)
    star = shapely.Polygon(np.c_[r * np.cos(ang), r * np.sin(ang)])
    touch = shapely.Polygon(
        [(0, 0), (4, 0), (4, 4), (0, 4)], [[(0, 2), (2, 1), (2, 3)]]
    )  # valid: the hole meets the outline at (0, 2)
    pair = shapely.Polygon(
        [(0, 0), (4, 0), (4, 4), (0, 4)], [[(1, 1), (2, 2), (1, 3)], [(2, 2), (3, 1), (3, 3)]]
    )
    assert touch.is_valid and pair.is_valid
    for g in (star, touch, pair):
        _solid_ok(solid.extrude(g, 1.0))
        assert abs(solid.extrude(g, 1.0).volume - g.area) <= 1e-12 * g.area
        m = solid.extrude(g, 1.0, relief=lambda xy: 0.05 * xy[:, 1])
        _solid_ok(m)
        # the top is linear in y: the volume is exact only if the top tiles the outline
        assert abs(m.volume - g.area * (1.0 + 0.05 * g.centroid.y)) <= 1e-9 * m.volume
        assert len(m.faces) > 200  # the relief is followed by a fine top, not the bare outline


def test_extrude_takes_a_design_results_frame():
    from types import SimpleNamespace

    rng = np.random.default_rng(2)
    holes = [shapely.Point(p).buffer(1.5) for p in rng.random((6, 2)) * 30 + 5]
    frame = shapely.box(0, 0, 40, 40).difference(shapely.union_all(holes))
    m = solid.extrude(SimpleNamespace(frame=frame), 2.5)  # what design.compute returns
    _solid_ok(m)
    assert abs(m.volume - 2.5 * frame.area) <= 1e-9 * m.volume


# --- checks --------------------------------------------------------------------------------


def test_check_thin_strut_located():
    f = solid.fields.point([[5, 5, 5]], radius=4.0, falloff="linear")
    m = solid.lattice(trimesh.creation.box((10, 10, 10)), radius=(0.8, 0.2), field=f)
    rep = solid.check(m, min_strut=1.0, max_overhang=None)
    thin = [v for v in rep.violations if v.kind == "thin_strut"]
    assert len(thin) == 3  # the three struts at the (5, 5, 5) corner
    for v in thin:
        assert np.linalg.norm(np.array(v.location) - 5) <= 5.0 + 1e-9
        assert v.value < 1.0 and v.limit == 1.0


def test_check_small_pore_and_trapped_void_located():
    big = trimesh.creation.box((1, 1, 1))
    small = trimesh.creation.box((0.3, 1, 1))
    small.apply_translation([0.65, 0, 0])
    m = solid.foam([big, small], wall=0.1)
    rep = solid.check(m, min_pore=0.25, max_overhang=None)
    pores = [v for v in rep.violations if v.kind == "small_pore"]
    assert len(pores) == 1 and abs(pores[0].location[0] - 0.65) < 1e-9
    assert abs(pores[0].value - 0.2) < 1e-9
    voids = [v for v in rep.violations if v.kind == "trapped_void"]
    assert len(voids) == 2
    assert sorted(round(v.location[0], 9) for v in voids) == [0.0, 0.65]


def test_check_clean_and_overhang():
    rep = solid.check(trimesh.creation.box((1, 1, 1)))
    assert rep.ok and rep.stats["bodies"] == 1  # the bottom lies on the bed
    t = trimesh.creation.box((1, 1, 1))
    t.apply_transform(trimesh.transformations.rotation_matrix(0.3, [1, 0, 0]))
    rep = solid.check(t, max_overhang=45)
    assert rep.by_kind().get("overhang", 0) >= 1
    assert all(v.value > 45 for v in rep.violations)


def test_check_reports_pinches_that_files_would_weld(tmp_path):
    """Two squares touching at a corner, extruded: watertight in memory, but the STL's
    welded edge has four faces (found by an independent check)."""
    m = solid.extrude(shapely.MultiPolygon([shapely.box(0, 0, 1, 1), shapely.box(1, 1, 2, 2)]), 1)
    assert m.is_watertight
    rep = solid.check(m, max_overhang=None)
    pinches = [v for v in rep.violations if v.kind == "pinch"]
    assert sorted(v.location for v in pinches) == [(1.0, 1.0, 0.0), (1.0, 1.0, 1.0)]
    assert rep.stats["pinches"] == 2 and all(v.value == 2 for v in pinches)
    path = tmp_path / "pinch.stl"
    m.export(path)
    assert not trimesh.load(path).is_watertight  # what the check warns about
    parts = shapely.MultiPolygon([shapely.box(0, 0, 1, 1), shapely.box(2, 2, 3, 3)])
    apart = solid.extrude(parts, 1)
    assert "pinch" not in solid.check(apart, max_overhang=None).by_kind()


# --- files ---------------------------------------------------------------------------------


@pytest.mark.parametrize("ext", [".3mf", ".stl", ".obj", ".ply", ".glb", ".3dm"])
def test_solids_round_trip(tmp_path, ext):
    meshes = {
        "lattice": solid.lattice(trimesh.creation.box((10, 10, 10)), radius=0.5),
        "foam": solid.foam([trimesh.creation.box((1, 1, 1))], wall=0.2),
        "slab": solid.extrude(shapely.box(0, 0, 4, 3).difference(shapely.box(1, 1, 2, 2)), 1.0),
    }
    for name, m in meshes.items():
        back = mio.read(mio.write(m, tmp_path / f"{name}{ext}"))
        assert back.is_volume, name
        exp = m.volume
        if ext in (".stl", ".glb"):
            exp = trimesh.Trimesh(m.vertices.astype(np.float32).astype(float), m.faces).volume
        assert abs(back.volume - exp) <= 1e-9 * abs(exp), name


# --- fields and bad input ------------------------------------------------------------------


def test_fields():
    xyz = np.array([[0.0, 0, 0], [5, 0, 0], [0, 0, 20]])
    assert solid.fields.point([[0, 0, 0]], radius=10, falloff="linear")(xyz).tolist() == [
        1.0,
        0.5,
        0.0,
    ]
    c = solid.fields.curve(np.array([[0, 0, 0], [0, 0, 10.0]]), radius=10, falloff="linear")
    assert np.allclose(c(xyz), [1.0, 0.5, 0.0])
    p = solid.fields.plane((0, 0, 0), (0, 0, 2), radius=40, falloff="linear")
    assert np.allclose(p(xyz), [1, 1, 0.5])
    m = solid.fields.mesh(trimesh.creation.box((2, 2, 2)), radius=4, falloff="linear")
    assert np.allclose(m(np.array([[0, 0, 0], [3, 0, 0]])), [0.75, 0.5])
    both = solid.fields.combine([c, p], mode="min")
    assert np.allclose(both(xyz), [1, 0.5, 0.0])
    assert np.allclose(p.remap(2, 4)(xyz), [4, 4, 3])
    # a tilted plane: the distance along its unit normal (by columns, not BLAS: the same to
    # rounding)
    q = np.random.default_rng(1).normal(0, 30, (500, 3))
    tilt = solid.fields.plane((1, -2, 3), (1, 2, -2), radius=50, falloff="linear")
    want = 1 - np.minimum(np.abs((q - [1, -2, 3]) @ (np.array([1, 2, -2]) / 3)) / 50, 1)
    assert np.allclose(tilt(q), want, rtol=0, atol=1e-14)


def test_bad_input():
    box = trimesh.creation.box((1, 1, 1))
    with pytest.raises(ValueError, match="radius"):
        solid.lattice(box, radius=-1)
    with pytest.raises(ValueError, match="nodes"):
        solid.lattice(box, nodes="cubes")
    with pytest.raises(ValueError, match="route"):
        solid.lattice(box, route="voxels")
    with pytest.raises(ValueError, match="route='hull' cannot"):
        solid.lattice(box, nodes="smooth", route="hull")
    with pytest.raises(ValueError, match="skin needs a container"):
        solid.lattice(box, radius=0.1, skin=1.0)
    with pytest.raises(ValueError, match="NaN"):
        solid.lattice((np.array([[0, 0, 0], [np.nan, 0, 0]]), [[0, 1]]))
    with pytest.raises(ValueError, match="edges index"):
        solid.lattice((np.zeros((2, 3)), [[0, 5]]))
    with pytest.raises(ValueError, match="expected"):
        solid.lattice("cells")
    with pytest.raises(ValueError, match="thickness"):
        solid.extrude(shapely.box(0, 0, 1, 1), 0)
    with pytest.raises(ValueError, match="wall"):
        solid.foam([box], wall=-2)
    with pytest.raises(ValueError, match="check"):
        solid.check("mesh")
    nodes = np.array([[0, 0, 0], [1, 0, 0.0]])
    keep = nodes.copy()
    solid.lattice((nodes, [[0, 1]]), radius=0.1)
    assert (nodes == keep).all()  # never mutates the input


def _torus_cells():
    """30 cells in a torus (R 20, r 8): those at its inner side are cut non-convex."""
    import voroforge as vf

    rng = np.random.default_rng(4)
    tor = trimesh.creation.torus(major_radius=20, minor_radius=8)
    X = rng.uniform(-28, 28, (2, 4000, 3))[1]  # (checker20's second draw)
    P = X[(np.hypot(X[:, 0], X[:, 1]) - 20) ** 2 + X[:, 2] ** 2 < 7.5**2][:30]
    return vf.voronoi3d(P, tor), tor


def test_foam_keeps_the_bubbles_of_cells_a_torus_cuts():
    # checker20 F3: a cut cell's mesh fans a ring with three collinear vertices into a
    # triangle of ~1e-15 area; its zero normal became the plane 0 <= -wall/2 and three of
    # 30 roomy cells lost their bubbles ("walls fill 3 of 30 cells")
    from scipy.optimize import linprog

    from voroforge.solid.foam import bubbles
    from voroforge.solid.graph import cell_meshes

    d, tor = _torus_cells()
    got = bubbles(cell_meshes(d), 1.0)
    for i, (mesh, _, rad) in enumerate(got):
        # reference: the largest ball inside the cell's own face planes (Newell normals of
        # its rings) moved in by half the wall
        cell = d.cell(i)
        V = np.asarray(cell.vertices)
        rows = []
        for ring in cell.faces:
            q = V[np.asarray(ring)]
            n = np.cross(q, np.roll(q, -1, axis=0)).sum(0)
            if np.linalg.norm(n) > 1e-9 * np.ptp(V, axis=0).max() ** 2:
                n /= np.linalg.norm(n)
                rows.append([*n, n @ q.mean(0) - 0.5])
        A = np.asarray(rows)
        lp = linprog(
            [0, 0, 0, -1],
            A_ub=np.c_[A[:, :3], np.ones(len(A))],
            b_ub=A[:, 3],
            bounds=[(None, None)] * 3 + [(0, None)],
        )
        assert lp.success and lp.x[3] > 0.1, i
        assert mesh is not None, i
        assert rad == pytest.approx(lp.x[3], rel=1e-6), i
    # foam() itself refuses cells the torus cut into non-convex pieces (checker28 F7: their
    # plane-by-plane bubbles were up to 5x too small), naming one
    with pytest.raises(ValueError, match="foam: cell .* is not convex"):
        solid.foam(d, wall=1.0, container=tor)


def test_non_convex_cells_are_not_hulled_silently(tmp_path):
    # checker20 F9/F10: subdivide took each torus-cut cell's hull (leaves 12% over the torus,
    # outside it), and foam(d)'s default container, the cells' hull, filled the torus's hole
    from voroforge.design.build import build
    from voroforge.design.designfile import DesignError
    from voroforge.solid.cells import subdivide

    d, tor = _torus_cells()
    with pytest.raises(ValueError, match="not convex"):
        subdivide(d, 4)
    # checker28 F7: a bubble is its cell shrunk plane by plane, so a torus-cut cell's bubble
    # was far too small (walls up to 4x thicker): refused, with or without the container
    for container in (None, tor):
        with pytest.raises(ValueError, match="foam: cell .* is not convex"):
            solid.foam(d, wall=1.0, container=container)
    box = trimesh.creation.box((10, 10, 10))
    apart = box.copy()
    apart.apply_translation((20, 0, 0))
    with pytest.warns(UserWarning, match="convex hull"):  # convex cells short of their hull
        solid.foam([box, apart], wall=1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        solid.foam([box], wall=2.0)  # cells that fill their hull: no warning
    tor.export(tmp_path / "torus.stl")
    (tmp_path / "f.toml").write_text(
        '[solid]\nkind = "foam"\ncontainer = "torus.stl"\ncells = 12\nseed = 3\n'
        'wall = 1.0\nsubdivide = 1\nsubdivide_count = 4\nformats = ["3mf"]\n'
    )
    with pytest.raises(DesignError, match="non-convex"):
        build(tmp_path / "f.toml", tmp_path / "out")
