"""Issue 15: polygon domains clipped by the exact-predicate clip, not GEOS's overlay.

``kernels.polyclip`` used to leave to the overlay every cell whose edge lies on a side of
the domain's bounding box where the boundary runs along or touches it (a comb's top and
bottom rows, a zigzag's top row) and every cell holding a ring of the domain wholly
(a hole, an island). The boundary along the box's sides is now pushed out of the box by an
infinitesimal (the domain inside the box is the same), and rings wholly inside a cell are
the cell's holes or parts. Checked against independent references: shapely's intersection
of the rectangle diagram's cells with the domain, valid cells that tile the domain, sites in
their cells, every crossing one point in both cells that share it, the three algorithms'
cells equal.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from shapely import affinity

import voroforge as vf
from voroforge.kernels.polyclip import DONE, NONE

from catalogue import comb_outline, holed_square, zigzag_outline
from validate import clipped_like_shapely


def _islands(k):
    """A holed square and, inside every other hole, an island (a MultiPolygon part)."""
    holed = holed_square(k)
    isles = [
        shapely.Polygon(affinity.scale(shapely.Polygon(r), 0.4, 0.4).exterior)
        for r in list(holed.interiors)[::2]
    ]
    return shapely.MultiPolygon([holed, *isles])


def _domains():
    comb = comb_outline(80)
    return {
        "comb": (comb, 300),
        "comb_far": (affinity.translate(comb, 1e13, 3e12), 300),
        "comb_1e6": (affinity.translate(comb, 1e6, -1e6), 300),
        "zigzag": (zigzag_outline(4001), 150),
        "holed": (holed_square(14), 400),
        "islands": (_islands(10), 120),
        "multi": (
            shapely.MultiPolygon(
                [comb_outline(60), affinity.translate(comb_outline(60).reverse(), 0, 1100)]
            ),
            400,
        ),
    }


def _shared_points_agree(cells, tol):
    """Every vertex of a cell that lies on another cell's boundary is one of its vertices."""
    xy, idx = shapely.get_coordinates(cells, return_index=True)
    tree = shapely.STRtree(cells)
    pts = shapely.points(xy)
    hit_pt, hit_cell = tree.query(pts, predicate="dwithin", distance=tol)
    other = hit_cell != idx[hit_pt]
    hit_pt, hit_cell = hit_pt[other], hit_cell[other]
    have = {(int(c), tuple(p)) for c, p in zip(idx, xy.tolist(), strict=True)}
    for k, c in zip(hit_pt, hit_cell, strict=True):
        if (int(c), tuple(xy[k].tolist())) in have:
            continue
        # a vertex may lie inside the other cell's edge (a domain vertex on a Voronoi
        # edge is a vertex of one cell only when the other turns there): it must be on it
        if shapely.distance(shapely.boundary(cells[c]), pts[k]) > tol:
            return False
    return True


@pytest.mark.parametrize("name", list(_domains()))
def test_cells_against_shapely(name, clip_statuses):
    geom, n = _domains()[name]
    x0, y0, x1, y1 = geom.bounds
    rng = np.random.default_rng(len(name))
    p = rng.random((n, 2)) * [x1 - x0, y1 - y0] + [x0, y0]
    cut = clipped_like_shapely(p, geom)
    # no two cells overlap
    assert shapely.area(shapely.union_all(cut)) == pytest.approx(geom.area, rel=1e-12)
    ulp = np.spacing(max(abs(x0), abs(y0), abs(x1), abs(y1)))
    assert _shared_points_agree(cut, 4 * ulp)
    status = np.concatenate(clip_statuses)
    # at most half the cells of the comb at 1e13 (teeth ~100 ulps wide) are left to the
    # overlay, none elsewhere
    assert (status > NONE).sum() <= {"comb_far": len(status) // 2}.get(name, 0)


def test_box_rows_and_holes_stay_in_the_kernel(clip_statuses):
    """The comb's top and bottom rows and cells holding a hole or an island: all clipped here."""
    for geom in (comb_outline(40), _islands(6), zigzag_outline(1001)):
        x0, y0, x1, y1 = geom.bounds
        p = np.random.default_rng(7).random((80, 2)) * [x1 - x0, y1 - y0] + [x0, y0]
        vf.voronoi(p, geom)
    status = np.concatenate(clip_statuses)
    assert len(status) and (status <= NONE).all() and (status == DONE).sum() > 40


def test_samples_in_nearest_cell():
    geom = _islands(8)
    x0, y0, x1, y1 = geom.bounds
    rng = np.random.default_rng(11)
    p = rng.random((90, 2)) * [x1 - x0, y1 - y0] + [x0, y0]
    cut = vf.voronoi(p, geom).cells
    q = rng.random((4000, 2)) * [x1 - x0, y1 - y0] + [x0, y0]
    q = q[shapely.contains_xy(geom, q[:, 0], q[:, 1])]
    d2 = ((q[:, None, :] - p[None, :, :]) ** 2).sum(axis=2)
    near = np.argmin(d2, axis=1)
    srt = np.sort(d2, axis=1)
    clear = srt[:, 1] - srt[:, 0] > 1e-9  # (points on a bisector: either cell)
    assert shapely.intersects_xy(cut[near[clear]], q[clear, 0], q[clear, 1]).all()


@pytest.mark.parametrize("name", ["comb", "islands"])
def test_algorithms_agree(name):
    geom, n = _domains()[name]
    x0, y0, x1, y1 = geom.bounds
    p = np.random.default_rng(3).random((n // 2, 2)) * [x1 - x0, y1 - y0] + [x0, y0]
    got = [
        shapely.normalize(vf.voronoi(p, geom, algorithm=a).cells)
        for a in ("delaunay", "fortune", "halfplane")
    ]
    scale = (x1 - x0) * (y1 - y0) * 1e-13
    for other in got[1:]:
        assert np.all(shapely.area(shapely.symmetric_difference(got[0], other)) <= scale)
