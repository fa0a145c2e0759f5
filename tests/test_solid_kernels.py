"""The hull lattice's building blocks against brute force: box pairs, convex separation,
bit-exact row lookup; and the 3D preview renderer's depth order and culling."""

from __future__ import annotations

import numpy as np
import pytest

trimesh = pytest.importorskip("trimesh")

from voroforge.solid.hulls import _find_rows  # noqa: E402
from voroforge.solid.kernels import box_pairs, separated  # noqa: E402


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
