"""Issue 15: polygon domains far out, and shared edges, cut by the exact-predicate clip.

Far out a boundary line passes through cells' vertices (a comb at 7e14: its teeth and the
cells' vertices on one grid of 0.125), and the boundary runs along cells' edges (two sites
at one ordinate on either side of a tooth's side). Every sign is now exact: a crossing at
a cell's vertex is that vertex, a boundary along a cell's edge is pushed out of the cell by
an infinitesimal (as on the box's sides), and no cell of these goes to GEOS's overlay. The
diagram's shared edges are cut by the same crossings, so their ends are the clipped cells'
vertices bit for bit. Checked against shapely's intersection of the rectangle diagram's
cells with the domain, and against the cells' own shared boundaries.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from shapely import affinity

import voroforge as vf
from voroforge.engine import polyclip
from voroforge.kernels.edgeclip import HARD as EDGE_HARD
from voroforge.kernels.polyclip import DONE, NONE, box_sides, bucket_segments, clip_cells

from catalogue import comb_outline, holed_square, saw_outline
from validate import edges_are_the_cells

ALGORITHMS = ("delaunay", "fortune", "halfplane")


def _sites(geom, n, seed):
    x0, y0, x1, y1 = geom.bounds
    return np.random.default_rng(seed).random((n, 2)) * [x1 - x0, y1 - y0] + [x0, y0]


def _check_cells(geom, p, cells, algorithm):
    """Equal to shapely's intersection of the same algorithm's rectangle cells and the domain.

    (Far out the algorithms' rectangle cells may differ by ulps: 7e14, half-plane.)
    """
    x0, y0, x1, y1 = geom.bounds
    box = vf.voronoi(p, (x0, y0, x1, y1), algorithm=algorithm).cells
    ref = shapely.intersection(box, geom)
    scale = (x1 - x0) * (y1 - y0) * 1e-12
    assert np.all(shapely.area(shapely.symmetric_difference(cells, ref)) <= scale)
    assert np.all(shapely.is_valid(cells))
    # (far out a shoelace sum is only good to the coordinates' ulps times the perimeter)
    ulp = np.spacing(np.abs(np.asarray(geom.bounds)).max())
    slack = max(1e-9 * geom.area, 8 * ulp * geom.length)
    assert abs(shapely.area(cells).sum() - geom.area) <= slack
    inside = shapely.contains_xy(geom, p[:, 0], p[:, 1])
    assert shapely.intersects_xy(cells[inside], p[inside, 0], p[inside, 1]).all()


@pytest.mark.parametrize("algorithm", ALGORITHMS)
@pytest.mark.parametrize("offset", [1e13, 7e14])
def test_comb_far_out_in_the_kernel(algorithm, offset, clip_statuses, edge_statuses):
    """A comb far out: no cell and no edge left to the overlay, all equal to shapely's."""
    geom = affinity.translate(comb_outline(80), offset, offset / 3)
    p = _sites(geom, 120, 5)
    d = vf.voronoi(p, geom, algorithm=algorithm)
    _check_cells(geom, p, d.cells, algorithm)
    edges_are_the_cells(d, 1000.0)
    status = np.concatenate(clip_statuses)
    edges = np.concatenate(edge_statuses)
    # (at 7e14, ulps of 0.125 against teeth 0.375 wide, a crossing may round onto a vertex
    # of the domain: that cell takes the overlay)
    most = 0 if offset < 1e14 else len(status) // 50
    assert len(status) and (status > NONE).sum() <= most
    assert len(edges) and (edges == EDGE_HARD).sum() <= most


@pytest.mark.parametrize("algorithm", ALGORITHMS)
def test_sloped_and_holed_edges_are_the_cells(algorithm, clip_statuses, edge_statuses):
    """Sloped boundaries (a saw, turned holes, far out too): edges end at the cells' vertices."""
    for geom in (
        saw_outline(150),
        affinity.translate(saw_outline(150), 3e12, 1e12),
        holed_square(9),
        affinity.translate(holed_square(9), -5e11, 2e12),
    ):
        p = _sites(geom, 120, 9)
        d = vf.voronoi(p, geom, algorithm=algorithm)
        _check_cells(geom, p, d.cells, algorithm)
        edges_are_the_cells(d, max(np.ptp(np.asarray(geom.bounds).reshape(2, 2), axis=0)))
    status = np.concatenate(clip_statuses)
    assert (status <= NONE).all() and (status == DONE).sum() > 100
    assert (np.concatenate(edge_statuses) < EDGE_HARD).all()


def _clip(ring, domain):
    """One convex ring (counter-clockwise, closed) clipped by the kernel: status, polygon."""
    ring = np.asarray(ring, dtype=np.float64)
    seg, nxt = polyclip._segments(domain)
    x0, y0 = domain.bounds[:2]
    grid = np.array([x0, y0, 8.0, 4.0, 4.0])
    boff, bids = bucket_segments(seg, x0, y0, 8.0, 4, 4)
    box = np.asarray(domain.bounds, dtype=np.float64)
    off = np.array([0, len(ring)], dtype=np.int64)
    sides = box_sides(seg, nxt, box)
    status, xy, r_off, _, _ = clip_cells(ring, off, seg, nxt, boff, bids, grid, box, sides)
    parts = [shapely.Polygon(xy[r_off[k] : r_off[k + 1]]) for k in range(len(r_off) - 1)]
    return int(status[0]), shapely.union_all(parts) if parts else shapely.Polygon(ring)


def test_crossing_at_a_vertex_is_the_vertex():
    """A boundary line through a cell's vertex crosses it there, bit for bit; one along a
    cell's edge leaves the cell whole (exact signs: the overlay was asked before)."""
    far = 2.0**44  # (ulp 2**-8: the coordinates below are exact, the crossings are not)
    xy = [(0, 0), (16, 0), (16, 16), (4, 16), (4, 1), (2, 1), (2, 16), (0, 16)]
    notch = shapely.Polygon([(far + x, far + y) for x, y in xy])
    cell = [(far + x, far + y) for x, y in [(1, 3), (4, 2), (6, 4), (3, 6)]]
    status, got = _clip(cell + cell[:1], notch)
    assert status == DONE
    assert (far + 4, far + 2) in set(map(tuple, shapely.get_coordinates(got).tolist()))
    want = shapely.intersection(shapely.Polygon(cell), notch)
    assert shapely.get_num_geometries(got) == 2 and shapely.is_valid(got)
    assert shapely.area(shapely.symmetric_difference(got, want)) <= 1e-12 * shapely.area(want)
    # the notch's side x = far + 4 along the cell's edge from (4, 5) to (4, 2)
    cell = [(far + x, far + y) for x, y in [(7, 3), (6, 6), (4, 5), (4, 2)]]
    status, got = _clip(cell + cell[:1], notch)
    assert status == NONE  # (no segment enters it: the engine keeps it whole, or drops it)
    assert shapely.contains_xy(notch, far + 7, far + 3)
