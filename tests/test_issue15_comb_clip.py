"""Issue 15: cells cut by the boundary segments near them (``kernels.polyclip``).

Above ``PIECE_SMALL`` vertices a cell that meets the domain's boundary is clipped by the
segments in the grid buckets over its box instead of a GEOS overlay per cell. Checked
against independent references: shapely's intersection of the rectangle diagram's cells
with the domain (the same region), valid cells tiling the domain, every site in the domain
inside its own cell, and the kernel's crossing against GEOS's on random segments, bit for
bit (the overlay's crossings, which neighbouring cells share).
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from shapely import affinity

from voroforge.kernels.polyclip import DONE, geos_intersection

from catalogue import comb_outline, saw_outline, zigzag_outline
from validate import clipped_like_shapely


def _domains():
    comb = comb_outline(120)
    return {
        "comb": comb,
        "comb_reversed": comb.reverse(),
        "comb_far": affinity.translate(comb, 1e13, 3e12),
        "comb_rotated": affinity.rotate(comb, 33, origin=(0, 0)),
        "comb_holes": shapely.Polygon(
            comb.exterior.coords,
            [shapely.box(i + 0.2, 300, i + 0.4, 700).exterior.coords for i in range(120)],
        ),
        "saw": saw_outline(300),
        "zigzag": zigzag_outline(2000),
        "multi": shapely.MultiPolygon(
            [comb_outline(60), affinity.translate(comb_outline(60).reverse(), 0, 1100)]
        ),
    }


@pytest.mark.parametrize("name", list(_domains()))
def test_cells_are_the_box_cells_cut(name, clip_statuses):
    geom = _domains()[name]
    x0, y0, x1, y1 = geom.bounds
    rng = np.random.default_rng(len(name))
    p = rng.random((500, 2)) * [x1 - x0, y1 - y0] + [x0, y0]
    clipped_like_shapely(p, geom)
    status = np.concatenate(clip_statuses)
    # the kernel clipped most cells
    assert (status == DONE).mean() > {"zigzag": 0.02, "comb_far": 0.3}.get(name, 0.5)


def test_crossings_are_geos(monkeypatch):
    rng = np.random.default_rng(3)
    for scale, shift in ((1.0, 0.0), (1e-9, 0.0), (1e9, 0.0), (1.0, 4e12)):
        s = rng.random((400, 4, 2)) * scale + shift
        a, b = shapely.linestrings(s[:, :2]), shapely.linestrings(s[:, 2:])
        ref = shapely.intersection(a, b)
        hit = np.flatnonzero(shapely.get_type_id(ref) == 0)
        assert len(hit) > 50
        for k in hit:
            got = geos_intersection(*s[k].ravel())
            assert got == tuple(shapely.get_coordinates(ref[k])[0]), (scale, k)
