"""The hull lattice's building blocks against brute force: box pairs, convex separation,
bit-exact row lookup; the 3D preview renderer's depth order and culling; the solid
preview's z-buffer and cut; Taubin smoothing against trimesh's."""

from __future__ import annotations

import numpy as np
import pytest

trimesh = pytest.importorskip("trimesh")

from voroforge.solid.hulls import _find_rows  # noqa: E402
from voroforge.solid.kernels import box_pairs, separated, taubin  # noqa: E402


def _brute_pairs(lo, hi):
    ov = ((lo[:, None] <= hi[None]) & (lo[None] <= hi[:, None])).all(axis=2)
    i, j = np.nonzero(np.triu(ov, 1))
    return np.stack([i, j], axis=1)


@pytest.mark.parametrize("case", ["random", "touching", "points", "same", "one", "skewed"])
def test_box_pairs_are_the_brute_force_pairs(case):
    rng = np.random.default_rng(5)
    if case == "random":
        c = rng.random((400, 3)) * 50
        e = rng.random((400, 3)) * rng.choice([0.1, 1, 6], (400, 1))
        lo, hi = c - e, c + e
    elif case == "touching":  # closed boxes: sharing a face or a corner counts
        g = np.stack(np.meshgrid(*[np.arange(5.0)] * 3, indexing="ij"), -1).reshape(-1, 3)
        lo, hi = g, g + 1.0
    elif case == "points":  # zero-size boxes, some repeated
        lo = np.round(rng.random((200, 3)) * 4)
        hi = lo.copy()
    elif case == "same":
        lo, hi = np.zeros((30, 3)), np.ones((30, 3))
    elif case == "one":
        lo, hi = np.zeros((1, 3)), np.ones((1, 3))
    else:  # long thin boxes along x and tiny ones: the grid's buckets are uneven
        c = rng.random((300, 3)) * 20
        e = np.where(rng.random((300, 1)) < 0.2, [[15.0, 0.1, 0.1]], [[0.05, 0.05, 0.05]])
        lo, hi = c - e, c + e
    got = box_pairs(lo, hi)
    assert got.dtype == np.int64
    np.testing.assert_array_equal(got, _brute_pairs(lo, hi).reshape(-1, 2))


def _cube(centre, size):
    v = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float) - 0.5
    v = v * size + centre
    n = np.vstack([np.eye(3), -np.eye(3)])
    off = -(n @ centre) - 0.5 * size
    return v, np.column_stack([n, off])


def test_separated_is_the_facet_test():
    rng = np.random.default_rng(2)
    polys = [_cube(rng.random(3) * 6, 0.5 + rng.random()) for _ in range(60)]
    vp = np.concatenate([[0], np.cumsum([len(v) for v, _ in polys])])
    qp = np.concatenate([[0], np.cumsum([len(q) for _, q in polys])])
    V = np.vstack([v for v, _ in polys])
    Q = np.vstack([q for _, q in polys])
    x, y = (a.ravel() for a in np.meshgrid(np.arange(60), np.arange(60)))
    margin = 0.01
    got = separated(vp, V, qp, Q, x, y, margin)
    want = [
        bool(((polys[a][0] @ polys[b][1][:, :3].T + polys[b][1][:, 3]) > margin).all(0).any())
        for a, b in zip(x, y, strict=True)
    ]
    assert got.tolist() == want
    assert not got[x == y].any()  # nothing is apart from itself
    # axis-aligned cubes: the facet test is exact (apart beyond the margin along an axis)
    c = np.array([p[0].mean(0) for p in polys])
    s = np.array([p[0].max(0) - p[0].min(0) for p in polys])[:, 0]
    gap = (np.abs(c[x] - c[y]) - 0.5 * (s[x] + s[y])[:, None]).max(axis=1)
    assert (got == (gap > margin)).all()


def test_find_rows_is_bit_exact_and_first():
    rng = np.random.default_rng(0)
    table = rng.random((500, 3))
    table[100] = table[7]  # a repeated row: the first one is reported
    table[200] = [0.0, 1.0, 2.0]
    rows = np.vstack([table[[7, 3, 499]], [[-0.0, 1.0, 2.0]], table[5] + [0, 0, 1e-16]])
    got = _find_rows(table, rows)
    assert got.tolist() == [7, 3, 499, -1, -1]  # -0.0 and a last-bit change are other rows
    assert _find_rows(np.zeros((0, 3)), rows).tolist() == [-1] * 5


def test_find_rows_survives_hash_collisions(monkeypatch):
    # every row hashing alike: the lookup must still find the first exact match (a collision
    # taken for a miss once made joints of 3,000 cells fail their ring check)
    from voroforge.solid import hulls

    rng = np.random.default_rng(1)
    table = rng.random((50, 3))
    table[30] = table[4]
    rows = np.vstack([table[[4, 49, 0]], [[2.0, 2.0, 2.0]]])
    want = _find_rows(table, rows).tolist()
    assert want == [4, 49, 0, -1]
    monkeypatch.setattr(hulls, "_row_hash", lambda a: np.zeros(len(a), dtype=np.uint64))
    assert hulls._find_rows(table, rows).tolist() == want


def test_preview_paints_near_over_far_and_culls_back_faces(tmp_path):
    from PIL import Image

    from voroforge.io.render3d import render

    near = trimesh.creation.box((1, 1, 1))
    far = trimesh.creation.box((3, 3, 3))
    far.apply_translation([0, 5, 0])  # behind the near box for a camera looking along +y
    red, blue = (255, 0, 0), (0, 0, 255)
    out = render([far, near], tmp_path / "a.png", size=(80, 80), view=(0, 0),
                 colors=[blue, red], edges=False)  # fmt: skip
    px = np.asarray(Image.open(out).convert("RGB")).astype(int)
    centre = px[40, 40]
    assert centre[0] > 100 and centre[2] < 60  # the near (red) box covers the far one
    corner = px[40, 8]
    assert corner[2] > 100 and corner[0] < 60  # the far box shows beside it
    # the same triangles given as rings give the same picture
    rings = [(m.vertices, [list(f) for f in m.faces]) for m in (far, near)]
    out2 = render(rings, tmp_path / "b.png", size=(80, 80), view=(0, 0),
                  colors=[blue, red], edges=False)  # fmt: skip
    assert (np.asarray(Image.open(out2)) == np.asarray(Image.open(out))).all()
    # one triangle across the view: drawn facing the camera (normal -y), culled facing away
    tri = np.array([[-1.0, 0, -1], [0, 0, 1], [1.0, 0, -1]])
    for faces, seen in (([[0, 2, 1]], True), ([[0, 1, 2]], False)):
        out3 = render([(tri, faces)], tmp_path / "c.png", size=(40, 40), view=(0, 0), edges=False)
        px = np.asarray(Image.open(out3).convert("RGB"))
        assert (px != 255).any() == seen


def _pixels(path):
    from PIL import Image

    with Image.open(path) as im:
        return np.asarray(im.convert("RGB")).astype(np.int64)


def test_solid_preview_is_the_painter_s_picture_of_a_box(tmp_path):
    # on a convex solid the painter's algorithm is exact: the z-buffer must draw the same
    # picture (same framing, shading and colour), up to the edges' antialiasing
    from voroforge.io.render3d import render
    from voroforge.solid.render import preview

    box = trimesh.creation.box((10.0, 6.0, 4.0))
    box.apply_transform(trimesh.transformations.rotation_matrix(0.3, (1, 2, 3)))
    for view in [(35.0, 25.0), (-55.0, 30.0)]:
        a = render([box], tmp_path / "a.png", size=(200, 160), view=view, edges=False,
                   colors=[(196, 205, 214)])  # fmt: skip
        b = preview(box, tmp_path / "b.png", size=200, view=view, cut=False)
        pa, pb = _pixels(a), _pixels(b)
        assert pa.shape == pb.shape
        diff = np.abs(pa - pb).max(axis=2)
        assert (pb != 255).any(axis=2).mean() > 0.2  # the box fills the frame
        assert (diff > 8).mean() < 0.02  # only along the edges
        assert np.median(diff[(pb != 255).any(axis=2)]) == 0


def test_solid_preview_cut_shows_caps_and_voids(tmp_path):
    # cut open, a solid shows its cross-section as a flat cap facing the camera; a hollow
    # one shows a ring of cap around its void's far walls
    from voroforge.io.render3d import view_rotation
    from voroforge.solid.render import preview

    view = (35.0, 25.0)
    light = np.array([-0.4, -0.8, 0.6]) / np.linalg.norm([-0.4, -0.8, 0.6])  # io.render3d's
    shade = 0.35 + 0.65 * max(0.0, -view_rotation(view)[1] @ light)  # a face towards the camera
    cap = np.minimum(255.0, np.array([196.0, 205.0, 214.0]) * shade + 20.0).astype(np.int64)
    outer = trimesh.creation.box((10.0, 10.0, 10.0))
    inner = trimesh.creation.box((7.0, 7.0, 7.0))
    inner.invert()
    hollow = trimesh.Trimesh(
        np.vstack([outer.vertices, inner.vertices]),
        np.vstack([outer.faces, inner.faces + len(outer.vertices)]),
        process=False,
    )
    frac = {}
    for name, m, cut in [("whole", outer, False), ("solid", outer, True), ("hollow", hollow, True)]:
        px = _pixels(preview(m, tmp_path / f"{name}.png", size=200, view=view, cut=cut))
        shape = (px != 255).any(axis=2)
        is_cap = (np.abs(px - cap).max(axis=2) <= 1) & shape
        frac[name] = is_cap.sum() / shape.sum()
        if name == "hollow":
            # the void: pixels inside the cap's ring that are neither cap nor background
            rows = np.flatnonzero(is_cap.any(axis=1))
            mid = px[rows[len(rows) // 2]]
            inside = np.flatnonzero(np.abs(mid - cap).max(axis=1) <= 1)
            span = mid[inside.min() : inside.max()]
            assert (np.abs(span - cap).max(axis=1) > 8).sum() > 20
    assert frac["whole"] == 0
    assert frac["solid"] > 0.5  # the square's section, seen face on, covers most of it
    assert 0.1 < frac["hollow"] < 0.8 * frac["solid"]


@pytest.mark.parametrize("iterations", [1, 6, 11])
def test_taubin_is_trimesh_s_filter(iterations):
    rng = np.random.default_rng(iterations)
    m = trimesh.creation.icosphere(3)
    m.vertices = m.vertices + rng.normal(0.0, 0.02, m.vertices.shape)
    want = m.copy()
    trimesh.smoothing.filter_taubin(want, iterations=iterations)
    got = taubin(m.vertices, m.faces, iterations)
    assert np.abs(got - want.vertices).max() < 1e-13
    assert np.abs(got - m.vertices).max() > 1e-3  # it did move them
    assert not np.shares_memory(got, m.vertices)


@pytest.mark.parametrize("n_seeds", [2, 3, 90])
def test_two_nearest_is_the_kd_tree_s_answer(n_seeds):
    from scipy.spatial import cKDTree

    from voroforge.solid.kernels import two_nearest

    rng = np.random.default_rng(n_seeds)
    seeds = rng.normal(0.0, 10.0, (n_seeds, 3))
    pts = np.vstack([rng.normal(0.0, 12.0, (5000, 3)), seeds[:2], seeds[:1] + 1e-9])
    d1, d2 = two_nearest(pts, seeds)
    dd, _ = cKDTree(seeds).query(pts, k=2)
    assert np.allclose(d1, dd[:, 0], rtol=1e-15, atol=0) and np.allclose(d2, dd[:, 1], rtol=1e-15)
    assert d1[-3] == 0.0 and (d2 >= d1).all()
    with pytest.raises(ValueError, match="two seeds"):
        two_nearest(pts, seeds[:1])


@pytest.mark.parametrize("rims", ["circle", "tilted", "one point"])
def test_shell_rim_scans_in_height_windows_are_the_kd_tree_s(rims):
    # min(f_web, d - rim), each run of points scanning only the boundary points within its
    # heights' reach: the KD-tree's nearest distance, bit for bit
    from scipy.spatial import cKDTree

    from voroforge.solid.shell import _with_rim

    rng = np.random.default_rng(3)
    t = rng.uniform(0, 6.3, 400)
    bpts = np.column_stack([np.cos(t), np.sin(t), 0 * t]) * 30
    if rims == "tilted":  # heights all along the range, and a second rim higher up
        bpts[:, 2] = 0.5 * bpts[:, 0]
        bpts = np.vstack([bpts, bpts[:150] * [0.5, 0.5, 0.1] + [0, 0, 35]])
    elif rims == "one point":
        bpts = bpts[:1]
    xyz = rng.uniform(-40, 40, (12000, 3))
    f_web = rng.uniform(-6.0, 15.0, len(xyz))
    want = np.minimum(f_web, cKDTree(bpts).query(xyz)[0] - 4.0)
    got = _with_rim(f_web, xyz, bpts, 4.0)
    assert np.array_equal(got, want)
    assert (got < f_web).mean() > 1e-3 and (got == f_web).mean() > 0.5  # both cases occur


def test_revolve_and_even_samples_are_trimesh_s():
    # the shell's surface without trimesh: the same vertices, faces, open edges and samples
    from voroforge.solid.surfaces import boundary_edges, revolve, sample_even

    prof = np.array([[38, 0], [46, 15], [52, 35], [54, 55], [44, 95], [34, 110]], float)
    for sections, count, seed in ((96, 90, 2), (13, 40, 0), (96, 600, 1)):  # 600: KD pairs
        m, b = trimesh.creation.revolve(prof, sections=sections), revolve(prof, sections)
        assert np.array_equal(b.vertices, m.vertices) and np.array_equal(b.faces, m.faces)
        e, n = np.unique(np.sort(m.edges, axis=1), axis=0, return_counts=True)
        assert np.array_equal(boundary_edges(b.faces), e[n == 1])
        want = trimesh.sample.sample_surface_even(m, count, seed=seed)[0]
        assert np.array_equal(sample_even(b, count, seed=seed), want)
    # a profile ending on the axis closes there: one rim, no zero-area triangles
    dome = revolve(dome_prof := [[0, 10], [6, 8], [9, 0]], 24)
    assert len(dome.faces) == len(trimesh.creation.revolve(dome_prof, sections=24).faces)
    assert len(boundary_edges(dome.faces)) == 24
    # a closed profile: a closed surface (trimesh merges its seam too), the same samples
    ring = [[10, 0], [12, 2], [14, 0], [12, -2], [10, 0]]
    torus, want = revolve(ring, 24), trimesh.creation.revolve(ring, sections=24)
    assert len(boundary_edges(torus.faces)) == 0 and len(torus.faces) == len(want.faces)
    wanted = trimesh.sample.sample_surface_even(want, 30, seed=1)[0]
    assert np.array_equal(sample_even(torus, 30, seed=1), wanted)


def test_near_classes_are_scipys_components():
    # strut_graph's node merge: the components of cKDTree.query_pairs(tol), as
    # connected_components numbers them (by lowest member), chains and clusters included
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree

    from voroforge.solid.kernels import near_classes

    rng = np.random.default_rng(2)
    for n, tol in ((1, 0.1), (60, 1e-9), (200, 0.02), (200, 0.3)):
        p = np.round(rng.uniform(0, 1, (n, 3)) * 6) / 6 + rng.normal(0, 4e-3, (n, 3))
        pairs = cKDTree(p).query_pairs(tol, output_type="ndarray")
        g = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
        assert np.array_equal(near_classes(p, tol), connected_components(g, directed=False)[1])
