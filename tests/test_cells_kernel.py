"""Delaunay-dual cells (kernels/cells) and power cells (kernels/power) on the kernels directly."""

from __future__ import annotations

import numpy as np
import shapely

import voroforge as vf
from voroforge.kernels.cells import cells_from_triangulation
from voroforge.kernels.delaunay import triangulate_sorted
from voroforge.kernels.power import power_cells
from voroforge.kernels.vertex import sorted_triple

BOX = np.array([-0.5, -0.5, 1.5, 1.5])


def _kernel_cells(pts, box=BOX):
    """Cells straight from the kernels, in input order: (rings, owners) per site."""
    xs = np.ascontiguousarray(pts[:, 0])
    ys = np.ascontiguousarray(pts[:, 1])
    order, sx, sy, tri, he, _, ok = triangulate_sorted(xs, ys)
    assert ok
    n = len(pts)
    # the arrays exactly as the engine passes them (strided views of the triangulation's
    # sorted sites): a contiguous copy would compile every kernel below a second time
    coords, lengths, owner = cells_from_triangulation(sx, sy, tri, he, box, order, order.copy())
    rings = [coords[lengths[i] : lengths[i + 1]][:-1] for i in range(n)]
    owners = [owner[lengths[i] : lengths[i + 1]][:-1] for i in range(n)]
    return rings, owners


def _brute_force_cell(pts, i, box=BOX):
    cell = shapely.box(*box)
    for j in range(len(pts)):
        if j == i:
            continue
        d = pts[j] - pts[i]
        m = 0.5 * (pts[i] + pts[j])
        t = np.array([-d[1], d[0]]) * 1e3
        half = shapely.Polygon([m + t, m - t, m - t - 1e3 * d, m + t - 1e3 * d])
        cell = cell.intersection(half)
    return cell


def test_cells_against_brute_force():
    rng = np.random.default_rng(0)
    for n in (3, 5, 12, 40):
        pts = rng.random((n, 2))
        rings, _ = _kernel_cells(pts)
        for i in range(n):
            want = _brute_force_cell(pts, i)
            got = shapely.Polygon(rings[i])
            assert got.is_valid
            assert got.symmetric_difference(want).area <= 1e-12


def _named_vertices(rings, owners):
    """Map vertex name (sorted owner triple) -> set of coordinate bits, over all cells."""
    names = {}
    for i, (ring, own) in enumerate(zip(rings, owners, strict=True)):
        m = len(ring)
        for v in range(m):
            a, b = own[v - 1], own[v]
            if a >= 0 and b >= 0 and a != b:
                key = tuple(sorted((i, int(a), int(b))))
                names.setdefault(key, set()).add(ring[v].tobytes())
    return names


def test_shared_vertices_are_bit_identical_between_neighbours():
    rng = np.random.default_rng(1)
    pts = rng.random((400, 2))
    rings, owners = _kernel_cells(pts, np.array([0.0, 0.0, 1.0, 1.0]))
    names = _named_vertices(rings, owners)
    assert len(names) > 500
    assert all(len(bits) == 1 for bits in names.values())
    # and so are the cocircular vertices of a grid
    g = np.stack(np.meshgrid(np.arange(6.0), np.arange(6.0)), -1).reshape(-1, 2) / 5
    rings, owners = _kernel_cells(g, np.array([-0.1, -0.1, 1.1, 1.1]))
    xy = np.concatenate([r for r in rings if len(r)])
    inner = xy[(xy > 0).all(1) & (xy < 1).all(1)]
    assert len(np.unique(inner, axis=0)) == 25  # one vertex per grid square, no near twins


def test_triangulation_circumcenters_are_the_voronoi_vertices_bit_for_bit():
    rng = np.random.default_rng(2)
    ring = [(5, 0), (4, 3), (3, 4), (0, 5), (-3, 4), (-4, 3), (-5, 0), (-4, -3), (-3, -4)]
    ring += [(0, -5), (3, -4), (4, -3)]
    # exactly cocircular sites (a grid of step 1/8, integer points on one circle): the
    # triangles of a circle share its canonical vertex. Sites only within rounding of a
    # circle (a grid of step 0.1) are merged by the cells but keep their own centres in
    # the triangulation (each exact to its conditioning).
    for pts in (
        rng.random((300, 2)),
        np.stack(np.meshgrid(np.arange(7.0), np.arange(5.0)), -1).reshape(-1, 2) * 0.125,
        np.array(ring, dtype=float),
    ):
        tri = vf.delaunay(pts)
        cc = tri.circumcenters
        lo = cc.min(0) - 1.0
        hi = cc.max(0) + 1.0
        d = vf.voronoi(pts, (lo[0], lo[1], hi[0], hi[1]))
        verts = {p.tobytes() for p in shapely.get_coordinates(d.cells)}
        assert all(c.tobytes() in verts for c in cc)


def test_power_cells_with_equal_weights_are_the_voronoi_cells_bit_for_bit():
    rng = np.random.default_rng(3)
    n = 60
    pts = rng.random((n, 2))
    rings, _ = _kernel_cells(pts, np.array([0.0, 0.0, 1.0, 1.0]))
    xs = np.ascontiguousarray(pts[:, 0])
    ys = np.ascontiguousarray(pts[:, 1])
    indptr = np.arange(0, n * (n - 1) + 1, n - 1, dtype=np.int64)
    indices = np.array([j for i in range(n) for j in range(n) if j != i], dtype=np.int64)
    for w in (0.0, 2.5):
        coords, lengths, _ = power_cells(
            xs, ys, np.full(n, w), indptr, indices, np.array([0.0, 0.0, 1.0, 1.0]), np.ones(n, bool)
        )
        for i in range(n):
            ring = coords[lengths[i] : lengths[i + 1]][:-1]
            assert {p.tobytes() for p in ring} == {p.tobytes() for p in rings[i]}


def test_power_cells_share_vertices_bit_for_bit():
    rng = np.random.default_rng(4)
    n = 200
    pts = rng.random((n, 2))
    w = rng.random(n) * 0.002
    xs = np.ascontiguousarray(pts[:, 0])
    ys = np.ascontiguousarray(pts[:, 1])
    indptr = np.arange(0, n * (n - 1) + 1, n - 1, dtype=np.int64)
    indices = np.array([j for i in range(n) for j in range(n) if j != i], dtype=np.int64)
    coords, lengths, owner = power_cells(
        xs, ys, w, indptr, indices, np.array([0.0, 0.0, 1.0, 1.0]), np.ones(n, bool)
    )
    rings = [coords[lengths[i] : lengths[i + 1]][:-1] for i in range(n)]
    owners = [owner[lengths[i] : lengths[i + 1]][:-1] for i in range(n)]
    names = _named_vertices(rings, owners)
    assert len(names) > 200
    assert all(len(bits) == 1 for bits in names.values())
    # a name is computed in canonical order: any order of the owners gives the same triple
    assert sorted_triple(2, 0, 1, xs, ys) == sorted_triple(1, 2, 0, xs, ys)
