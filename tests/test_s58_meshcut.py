"""The mesh cut's faster passes give the answers of the plain ones (lead s58, issue 12).

Each pass is checked against the obvious formula or a slower path: the power-of-two rows
against numpy's ``ldexp``/``frexp``, the ring renumbering against fancy indexing, the
touching test on a fine triangle grid (each triangle clipped in its first shared bucket
only) against one bucket holding every triangle, the ray test's box rejection against the
bare orientations on rays through vertices and edges, and the convex cut's gather (each
triangle looked at once per cell) on fine grids against one bucket (the same cells cut).
"""

from __future__ import annotations

import numpy as np
import pytest

import voroforge as vf
from voroforge.kernels.inside3d import inside_mesh, perturbed_side, yz_grid
from voroforge.kernels.meshclip3d import (
    face_points,
    map_runs,
    mark_runs,
    pow2_rows,
    touching_cells,
    tri_grid,
)

trimesh = pytest.importorskip("trimesh")


def _torus(major=24, minor=12):
    return trimesh.creation.torus(
        major_radius=1.0, minor_radius=0.4, major_sections=major, minor_sections=minor
    )


def test_pow2_rows_are_numpys_scaling_bit_for_bit():
    rng = np.random.default_rng(0)
    a = rng.normal(size=(400, 3)) * np.ldexp(1.0, rng.integers(-1070, 1020, (400, 1)))
    a[0] = 0.0
    a[1] = [-0.0, 0.0, 5e-324]  # a subnormal alone
    a[2] = [np.inf, 1.0, 2.0]
    a[3] = [np.nan, 1.0, 2.0]
    a[4] = [1e308, -1e308, 3.0]
    a[5] = [1e-310, 3e-300, -2e-320]  # scaled up past the subnormals
    a[6] = [0.75, 0.5, -0.999]  # already scaled: as it was
    with np.errstate(invalid="ignore"):
        want = np.ldexp(a, -np.frexp(np.abs(a).max(axis=1))[1][:, None])
    a.setflags(write=False)  # as the engine passes it: a diagram's frozen face table
    got = pow2_rows(a)
    assert got.tobytes() == want.tobytes()


def test_mark_and_map_runs_are_fancy_indexing():
    rng = np.random.default_rng(1)
    src = rng.integers(0, 50, 300).astype(np.int32)
    src.setflags(write=False)  # as the engine passes it: a diagram's frozen int32 rings
    s0 = np.array([0, 40, 100, 250])
    s1 = np.array([10, 40, 180, 300])
    used = np.zeros(50, bool)
    mark_runs(src, s0, s1, used)
    sel = np.concatenate([src[a:b] for a, b in zip(s0, s1, strict=True)])
    want = np.zeros(50, bool)
    want[sel] = True
    assert (used == want).all()
    remap = np.cumsum(used) - 1
    d0 = np.array([5, 20, 20, 120])  # an empty run writes nothing
    dst = np.full(200, -7, np.int64)
    map_runs(src, s0, s1, dst, d0, remap)
    ref = np.full(200, -7, np.int64)
    for a, b, d in zip(s0, s1, d0, strict=True):
        ref[d : d + b - a] = remap[src[a:b]]
    assert (dst == ref).all()


def _cells_and_triangles(n, seed, mesh=None):
    mesh = _torus() if mesh is None else mesh
    pts = np.random.default_rng(seed).uniform(mesh.bounds[0], mesh.bounds[1], (n, 3))
    lo, hi = mesh.bounds[0] - 0.05, mesh.bounds[1] + 0.05
    d = vf.voronoi3d(pts, tuple(np.r_[lo, hi]))
    cf, lab, farea, roff, ring = d.cell_face_table()
    # a writeable copy, as the engine passes (d.vertices is read-only: a read-only array
    # would compile the mesh kernels once more, ~17 s of the suite's CPU)
    V = np.array(d.vertices, dtype=np.float64, order="C")
    T = np.ascontiguousarray(np.asarray(mesh.vertices)[np.asarray(mesh.faces)], np.float64)
    return cf, lab, np.ascontiguousarray(farea), roff, ring, V, T


def _grid(T, tol, h):
    lo = T.min(axis=(0, 1)) - tol
    hi = T.max(axis=(0, 1)) + tol
    dims = np.maximum(1, np.ceil((hi - lo) / h)).astype(np.int64)
    start, items = tri_grid(T, lo, h, dims)
    return lo, h, dims, start, items


def test_touching_on_a_fine_grid_is_touching_on_one_bucket():
    # a triangle in many of a cell's buckets is clipped once, in the first: the same cells
    # as with every triangle in one bucket (where each is looked at once anyway)
    cf, lab, farea, roff, ring, V, T = _cells_and_triangles(400, 2)
    farea = np.array(farea)  # writeable, as the engine's cut_planes hands it on
    fpt = face_points(roff, ring, V)
    cells = np.flatnonzero(np.diff(cf) > 0)
    tol = 1e-9
    ext = float((T.max(axis=(0, 1)) - T.min(axis=(0, 1))).max())
    got = [
        touching_cells(cf, roff, ring, V, farea, fpt, cells, T, *_grid(T, tol, h), tol)
        for h in (2 * ext, ext / 40, ext / 97)
    ]
    assert 0 < got[0].sum() < len(cells)
    assert (got[1] == got[0]).all() and (got[2] == got[0]).all()


def _parity_reference(V, F, q):
    """Ray parity along +x with the orientations alone (no box rejection)."""
    out = np.zeros(len(q), bool)
    for k, (px, py, pz) in enumerate(q):
        par = 0
        for i0, i1, i2 in F:
            s = [
                perturbed_side(V[a, 1], V[a, 2], V[b, 1], V[b, 2], py, pz)
                for a, b in ((i0, i1), (i1, i2), (i2, i0))
            ]
            if 0 in s or not s[0] == s[1] == s[2]:
                continue
            u, w = V[i1] - V[i0], V[i2] - V[i0]
            nx = u[1] * w[2] - u[2] * w[1]
            if nx == 0.0:
                continue
            ny = u[2] * w[0] - u[0] * w[2]
            nz = u[0] * w[1] - u[1] * w[0]
            if V[i0, 0] - (ny * (py - V[i0, 1]) + nz * (pz - V[i0, 2])) / nx > px:
                par ^= 1
        out[k] = par == 1
    return out


def test_ray_box_rejection_keeps_the_parity_on_degenerate_rays():
    # rays through vertices and along edges' (y, z): the box test must reject only what
    # the perturbed orientations reject
    mesh = _torus()
    V = np.ascontiguousarray(mesh.vertices, np.float64)
    F = np.ascontiguousarray(mesh.faces, np.int64)
    rng = np.random.default_rng(3)
    pick = V[rng.integers(0, len(V), 60)]
    mid = 0.5 * (V[F[:30, 0]] + V[F[:30, 1]])
    q = np.concatenate([pick, mid, rng.uniform(mesh.bounds[0], mesh.bounds[1], (60, 3))])
    q[:, 0] = rng.uniform(-1.6, 1.6, len(q))
    g, start, items = yz_grid(V, F, 9)
    got = inside_mesh(np.ascontiguousarray(q), V, F, g, start, items)
    assert (got == _parity_reference(V, F, q)).all()


def test_convex_cut_gather_on_a_fine_grid_is_the_one_bucket_cut():
    from voroforge.engine.mesh3d import unit_normals
    from voroforge.kernels import meshcut3d as mc

    # 256 triangles: one bucket holding all stays below the gather's CC_SEEN
    cf, lab, farea, roff, ring, V, T = _cells_and_triangles(300, 4, _torus(16, 8))
    fpt = face_points(roff, ring, V)
    farea = pow2_rows(farea)
    tol = 1e-9
    ext = float((T.max(axis=(0, 1)) - T.min(axis=(0, 1))).max())
    g1 = _grid(T, tol, 2 * ext)
    cells = np.flatnonzero(
        touching_cells(cf, roff, ring, V, farea, fpt, np.arange(len(cf) - 1), T, *g1, tol)
    )
    tn, ok = unit_normals(T[:, 1] - T[:, 0], T[:, 2] - T[:, 0])
    to = np.where(ok, np.einsum("ij,ij->i", tn, T[:, 0]), np.nan)
    lab = np.asarray(lab, np.int64)

    def run(grid):
        k = len(cells)
        out = (
            np.zeros((k * mc.CC_OUT_V, 3)),
            np.zeros((k * mc.CC_OUT_F, 2), np.int64),
            np.zeros(k * mc.CC_OUT_R, np.int64),
            np.zeros((k, 3), np.int64),
            np.zeros(k),
            np.zeros((k, 3)),
            np.zeros(k, np.int64),
        )
        mc.convex_cells(cells, cf, roff, ring, V, lab, farea, fpt, T, tn, to, *grid, tol, *out)
        return out

    # the triangles come in another order (by bucket): the same cells cut, the same
    # volumes and centroids up to the rounding of the cuts' order
    one = run(g1)
    ok = one[3][:, 0] > 0
    assert ok.sum() > len(cells) // 2  # most cut here
    for h in (ext / 40, ext / 97):
        fine = run(_grid(T, tol, h))
        assert ((fine[3][:, 0] > 0) == ok).all()
        assert np.allclose(fine[4], one[4], rtol=1e-12, atol=0)
        assert np.allclose(fine[5][ok], one[5][ok], rtol=0, atol=1e-12)
        assert (fine[6] == one[6]).all()
