"""The raster's Delaunay walk: exact labels where sites crowd, at the cost of a triangulation.

Inside a circle of sites every pixel's nearest distance reaches across the whole bucket grid,
so the tile search scanned every bucket for each small tile (10,000 sites on a circle at
1024^2: 9.7 s, slanted line 24 s). Crowded sites are now labelled by walking the Delaunay
graph from a neighbouring pixel's site and filling rectangles whose four corners prove one
unique nearest site (``kernels.raster.walk_tiles``); pixels within rounding of a tie are
brute-forced (``fix_pixels``). Labels and distances must equal a brute-force argmin with
ties to the lowest index, for ``exact`` and ``jfa``.
"""

from __future__ import annotations

import numpy as np
import pytest

import voroforge as vf
from test_issue15_jfa import arrangement, brute
from voroforge.engine.raster import _delaunay_neighbors, _walks, pixel_centers
from voroforge.kernels.raster import walk_tiles

BOX = (0.0, 0.0, 1.0, 1.0)


def crowded(kind: str) -> np.ndarray:
    g = np.random.default_rng(3)
    if kind == "circle_with_centre":
        return np.vstack((arrangement("circle", 700), [[0.5, 0.5]]))
    if kind == "clusters":
        return np.clip(g.random((4, 2))[g.integers(0, 4, 900)] + g.normal(0, 0.01, (900, 2)), 0, 1)
    if kind == "outside_and_duplicates":
        p = np.vstack((arrangement("circle", 400), g.random((30, 2)) * 3 - 1))
        return p[np.r_[np.arange(len(p)), np.arange(0, len(p), 7)]]
    return arrangement(kind, 800)


KINDS = (
    "circle",
    "circle_with_centre",
    "two_circles",
    "slanted_line",
    "line",
    "clusters",
    "outside_and_duplicates",
)


def brute_any(p, shape, bounds):
    """``brute`` with duplicates: labels are the lowest index of each distinct site."""
    _, first, inverse = np.unique(p, axis=0, return_index=True, return_inverse=True)
    keep = np.sort(first)
    lab, d1, _ = brute(p[keep], shape, bounds)
    return keep[lab], d1


@pytest.mark.parametrize("shape", [(64, 64), (45, 71)])
@pytest.mark.parametrize("kind", KINDS)
def test_walk_equals_brute_force(kind, shape):
    p = crowded(kind)
    assert _walks(np.unique(p, axis=0), BOX, shape, "euclidean", False)  # the walk decides
    lab, d1 = brute_any(p, shape, BOX)
    for method in ("exact", "jfa"):
        r = vf.rasterize(p, shape, BOX, method=method)
        np.testing.assert_array_equal(r.labels, lab, err_msg=method)
        np.testing.assert_array_equal(r.distance, d1, err_msg=method)


@pytest.mark.parametrize(
    "offset, scale", [((0.0, 0.0), 1.0), ((5e5, 4e6), 1e-3), ((-3e12, 7e11), 1.0), ((0, 0), 1e-9)]
)
def test_walk_moved_and_scaled(offset, scale):
    p = arrangement("circle", 500) * scale + offset
    bounds = tuple(np.array(BOX) * scale + np.r_[offset, offset])
    shape = (50, 40)
    lab, d1 = brute_any(p, shape, bounds)
    r = vf.rasterize(p, shape, bounds)
    np.testing.assert_array_equal(r.labels, lab)
    np.testing.assert_array_equal(r.distance, d1)


def test_centre_of_a_float_circle():
    """The pixel at the centre of 2,000 sites on a circle: every site is within rounding of it.

    It has more candidates than the first buffer holds; numba's parallel loop lost buffers
    reassigned in a branch, so the tile search (and the walk's fallback) returned the nearest
    of the first 192 (site 1413 at key 0.20249999999999996 instead of 235 at ...9990).
    """
    p = arrangement("circle", 2000)
    shape = (97, 61)
    lab, d1 = brute_any(p, shape, BOX)
    for method in ("exact", "jfa"):
        r = vf.rasterize(p, shape, BOX, method=method)
        np.testing.assert_array_equal(r.labels, lab, err_msg=method)
    # the same pixel through the tile search (uniform-looking sites around it)
    q = np.vstack((p, np.random.default_rng(0).random((20000, 2)) * 0.1 + 2.0))
    assert not _walks(q, BOX, shape, "euclidean", False)
    lab2, _ = brute_any(q, shape, BOX)
    np.testing.assert_array_equal(vf.rasterize(q, shape, BOX).labels, lab2)


def test_ties_are_left_to_the_brute_force():
    """A pixel centre equidistant from two sites is not decided by the walk; lowest index wins."""
    xs = np.array([1.0, 0.0, 0.5])
    ys = np.array([0.5, 0.5, 2.0])
    px, py = pixel_centers(BOX, (1, 1))  # (0.5, 0.5): sites 0 and 1 tie
    nptr, nidx = _delaunay_neighbors(np.column_stack((xs, ys)))
    lab, d1, hard = walk_tiles(
        xs, ys, px, py, nptr, nidx, np.array([1, 1]), np.zeros((0, 0), np.int32)
    )
    assert hard[0, 0]
    r = vf.rasterize(np.column_stack((xs, ys)), (1, 1), BOX)
    assert r.labels[0, 0] == 0 and r.distance[0, 0] == 0.5


def test_uniform_sites_keep_the_tile_search():
    p = np.random.default_rng(1).random((2000, 2))
    assert not _walks(p, BOX, (256, 256), "euclidean", False)
    assert not _walks(arrangement("circle", 800), BOX, (256, 256), "euclidean", True)  # F2
    assert not _walks(arrangement("circle", 800), BOX, (256, 256), "manhattan", False)
    assert not _walks(
        arrangement("circle", 800), BOX, (16, 16), "euclidean", False
    )  # < 1 px a site
