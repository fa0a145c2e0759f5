"""The half-plane cell kernel on its own, against brute force and the default algorithm.

``halfplane_cells`` is called directly (not through ``vf.voronoi``): cells equal the
brute-force cells, every vertex is equidistant from its owners, cells tile the box, owners
are symmetric, near-duplicate and collinear sites keep all of that, and every vertex has
the bits the Delaunay-dual cells give it (one vertex-naming rule, ``kernels/vertex``).
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

import voroforge as vf
from voroforge.kernels.cells import cells_from_triangulation
from voroforge.kernels.delaunay import triangulate_sorted
from voroforge.kernels.halfplane import halfplane_cells

from catalogue import CATALOGUE
from reference import brute_voronoi

BOX = (-0.25, -0.25, 1.25, 1.25)


def _cells(pts, box=BOX):
    """Half-plane cells as (rings without the closing vertex, owners) per site."""
    coords, offsets, owner, hard = halfplane_cells(
        np.ascontiguousarray(pts[:, 0]), np.ascontiguousarray(pts[:, 1]), np.array(box)
    )
    assert not hard.any()
    n = len(pts)
    assert offsets.shape == (n + 1,) and offsets[0] == 0 and offsets[-1] == len(coords)
    rings, owners = [], []
    for i in range(n):
        a, b = offsets[i], offsets[i + 1]
        if b > a:
            assert np.array_equal(coords[a], coords[b - 1]) and owner[b - 1] == -2
            rings.append(coords[a : b - 1])
            owners.append(owner[a : b - 1])
        else:
            rings.append(np.zeros((0, 2)))
            owners.append(np.zeros(0, np.int64))
    return rings, owners


def _default_cells(pts, box=BOX):
    """The default algorithm's cells straight from its kernels, in input order."""
    xs = np.ascontiguousarray(pts[:, 0])
    ys = np.ascontiguousarray(pts[:, 1])
    order, sx, sy, tri, he, _, ok = triangulate_sorted(xs, ys)
    assert ok
    coords, lengths, owner = cells_from_triangulation(
        np.ascontiguousarray(sx),
        np.ascontiguousarray(sy),
        tri,
        he,
        np.array(box),
        order,
        order.copy(),
    )
    return [coords[lengths[i] : lengths[i + 1]][:-1] for i in range(len(pts))]


def _shoelace(ring):
    x, y = ring[:, 0], ring[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def _check_cells(pts, box=BOX):
    """Tiling, orientation, symmetric owners and equidistant vertices."""
    rings, owners = _cells(pts, box)
    n = len(pts)
    area = (box[2] - box[0]) * (box[3] - box[1])
    total = 0.0
    nbrs = [set() for _ in range(n)]
    scale = max(1.0, float(np.abs(pts).max()), float(np.abs(np.array(box)).max()))
    for i, (ring, own) in enumerate(zip(rings, owners, strict=True)):
        if len(ring) == 0:
            continue
        assert len(ring) >= 3
        assert len(np.unique(ring, axis=0)) == len(ring), "a vertex repeated"
        a = _shoelace(ring)
        assert a > 0.0, "rings are counter-clockwise"
        total += a
        assert np.all(ring[:, 0] >= box[0]) and np.all(ring[:, 0] <= box[2])
        assert np.all(ring[:, 1] >= box[1]) and np.all(ring[:, 1] <= box[3])
        assert np.all(own >= -1)
        m = len(ring)
        for v in range(m):
            j = int(own[v])
            if j >= 0:
                nbrs[i].add(j)
                # the edge lies on the bisector of i and j
                for p in (ring[v], ring[(v + 1) % m]):
                    di = np.hypot(*(p - pts[i]))
                    dj = np.hypot(*(p - pts[j]))
                    assert abs(di - dj) <= 1e-9 * scale
            # a vertex between two site edges is equidistant from its three owners
            k = int(own[v - 1])
            if j >= 0 and k >= 0:
                d = [np.hypot(*(ring[v] - pts[s])) for s in (i, j, k)]
                assert max(d) - min(d) <= 1e-9 * scale
    assert abs(total - area) <= 1e-9 * area, "cells tile the box"
    for i in range(n):
        for j in nbrs[i]:
            assert i in nbrs[j], f"{i} faces {j} but not the other way round"
    return rings, owners


@pytest.mark.parametrize("n", [1, 2, 3, 5, 12, 40, 200])
def test_cells_equal_brute_force(n):
    pts = np.random.default_rng(n).random((n, 2))
    rings, _ = _check_cells(pts)
    want = brute_voronoi(pts, shapely.box(*BOX))
    for i in range(n):
        got = shapely.Polygon(rings[i])
        assert got.is_valid
        assert got.symmetric_difference(want[i]).area <= 1e-12


def test_single_site_is_the_box():
    rings, owners = _cells(np.array([[0.3, 0.4]]))
    assert set(map(tuple, rings[0].tolist())) == {
        (BOX[0], BOX[1]),
        (BOX[2], BOX[1]),
        (BOX[2], BOX[3]),
        (BOX[0], BOX[3]),
    }
    assert np.all(owners[0] == -1)


def test_sites_outside_the_box():
    rng = np.random.default_rng(2)
    pts = rng.random((60, 2)) * 3.0 - 1.0  # many sites outside the box
    rings, _ = _check_cells(pts)
    want = brute_voronoi(pts, shapely.box(*BOX))
    for i in range(len(pts)):
        got = shapely.Polygon(rings[i]) if len(rings[i]) else shapely.Polygon()
        assert got.symmetric_difference(want[i]).area <= 1e-12


@pytest.mark.parametrize("ulps", [1, 2, 4])
def test_near_duplicate_sites(ulps):
    """Sites 1-4 ulps from others: owners symmetric. A site's edge that meets the box where
    its near-duplicate is nearer was kept by the float cut in place of the duplicate's
    (their bisectors coincide in floats); the settling now gives that end to the duplicate."""
    rng = np.random.default_rng(ulps)
    pts = rng.random((50, 2))
    near = pts[:5].copy()
    for _ in range(ulps):
        near = np.nextafter(near, near + 1.0)
    _check_cells(np.vstack([pts, near]))


def test_collinear_sites():
    t = np.linspace(0.0, 1.0, 30)
    _check_cells(np.column_stack((t, np.full(30, 0.5))))  # horizontal
    _check_cells(np.column_stack((np.full(30, 0.5), t)))  # vertical
    _check_cells(np.column_stack((t, t)))  # diagonal


def test_grid_is_cocircular_without_zero_length_edges():
    g = np.stack(np.meshgrid(np.arange(8.0), np.arange(8.0)), -1).reshape(-1, 2) / 7
    rings, _ = _check_cells(g)
    assert all(len(r) == 4 for r in rings), "every cell of a grid is a rectangle"


@given(
    st.lists(st.tuples(st.integers(0, 6), st.integers(0, 6)), min_size=1, max_size=25, unique=True)
)
@settings(max_examples=40, deadline=None)
def test_small_integer_inputs(cells):
    """Small integer lattices: many cocircular and collinear sites."""
    pts = np.array(cells, dtype=float) / 6.0
    _check_cells(pts)


def _vertex_bits(rings):
    return [set(r.tobytes() for r in ring) for ring in rings]


@pytest.mark.parametrize("kind", ["random", "grid", "hex"])
def test_vertices_bit_identical_to_default_algorithm(kind):
    """One vertex rule: the half-plane cells' vertices are the default cells', bit for bit."""
    rng = np.random.default_rng(11)
    if kind == "random":
        pts = rng.random((500, 2))
    elif kind == "grid":
        pts = np.stack(np.meshgrid(np.arange(12.0), np.arange(12.0)), -1).reshape(-1, 2) / 11
    else:
        i, j = np.meshgrid(np.arange(10.0), np.arange(10.0))
        pts = np.column_stack(((i + 0.5 * (j % 2)).ravel() / 10, (j * np.sqrt(0.75)).ravel() / 10))
    rings, _ = _cells(pts)
    ref = _default_cells(pts)
    assert _vertex_bits(rings) == _vertex_bits(ref)


def test_sites_on_one_circle_are_hard_by_their_settling():
    """Float sites on a circle: every cell's centre vertex has all sites on its circle to
    rounding, and naming it would try thousands of exact centres. The settling's own work
    count (not the search's, which visits only the n sites) makes such a cell hard."""
    t = np.arange(150) * (2.0 * np.pi / 150)
    *_, hard = halfplane_cells(np.cos(t), np.sin(t), np.array([-1.2, -1.2, 1.2, 1.2]))
    assert hard.sum() >= 140  # (150 sites: too few for the sample that sends all to the dual)


@pytest.mark.parametrize("name", ["float_circle_64_small_off", "float_circle_100_far"])
def test_spliced_cells_share_their_seams_with_the_dual(name):
    """Hard cells come from the dual; their neighbours whose shared edge the two
    constructions named differently come from it too, so the cells are the default's."""
    pts, boundary = CATALOGUE[name]
    ref = vf.voronoi(pts, boundary)
    got = vf.voronoi(pts, boundary, algorithm="halfplane")
    for a, b in zip(ref.cells, got.cells, strict=True):
        assert set(map(tuple, shapely.get_coordinates(a).tolist())) == set(
            map(tuple, shapely.get_coordinates(b).tolist())
        )
