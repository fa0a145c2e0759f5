"""Cell moments (areas, centroids, CVT energy) against exact rational shoelace sums."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

import voroforge as vf

from reference import exact_polygon_moments

HOLED = shapely.box(0, 0, 1, 1).difference(shapely.Point(0.5, 0.5).buffer(0.25, quad_segs=6))
TWO_PARTS = shapely.MultiPolygon([shapely.box(0, 0, 0.45, 1), shapely.box(0.55, 0, 1, 1)])


@pytest.mark.parametrize("offset", [0.0, 5e5, 4e6])
@pytest.mark.parametrize("domain", [HOLED, TWO_PARTS], ids=["holed", "two_parts"])
def test_areas_and_centroids_are_the_exact_ones_rounded(domain, offset):
    # far from the origin too: the kernel sums relative to each cell's first vertex
    rng = np.random.default_rng(3)
    pts = rng.random((25, 2)) + offset
    dom = shapely.affinity.translate(domain, offset, offset)
    d = vf.voronoi(pts, dom)
    for i, cell in enumerate(d.cells):
        if cell.is_empty:
            assert d.areas[i] == 0 and np.isnan(d.centroids[i]).all()
            continue
        origin = shapely.get_coordinates(cell)[0]
        area, mx, my, _ = exact_polygon_moments(cell, origin)
        assert d.areas[i] == pytest.approx(float(area), rel=1e-13, abs=0)
        want = origin + [float(mx / area), float(my / area)]
        # the centroid is relative to a nearby vertex: its error scales with the cell's size
        size = np.sqrt(float(area))
        assert np.abs(d.centroids[i] - want).max() <= 1e-13 * size + 2 * np.spacing(offset)


@pytest.mark.parametrize("domain", [HOLED, TWO_PARTS], ids=["holed", "two_parts"])
def test_lloyd_energy_is_the_exact_second_moment(domain):
    rng = np.random.default_rng(4)
    pts = rng.random((30, 2))
    pts = pts[shapely.contains_xy(domain, pts[:, 0], pts[:, 1])]
    r = vf.lloyd(pts, domain, iterations=1)
    d0 = vf.voronoi(pts, domain)
    # energy[0]: the start's sum over cells of ∫ |x - z_i|^2, each about its own site
    want = sum(
        float(exact_polygon_moments(c, p)[3])
        for c, p in zip(d0.cells, pts, strict=True)
        if not c.is_empty
    )
    assert r.energy[0] == pytest.approx(want, rel=1e-12)
    # energy[1]: the same sum for the moved sites and the returned diagram
    want = sum(
        float(exact_polygon_moments(c, p)[3])
        for c, p in zip(r.diagram.cells, r.points, strict=True)
        if not c.is_empty
    )
    assert r.energy[1] == pytest.approx(want, rel=1e-12)
    assert r.energy[1] < r.energy[0]


def test_power_cells_have_exact_moments_too():
    rng = np.random.default_rng(5)
    pts = rng.random((20, 2))
    d = vf.power(pts, rng.random(20) * 0.01, HOLED)
    areas = [float(exact_polygon_moments(c)[0]) if not c.is_empty else 0.0 for c in d.cells]
    assert np.allclose(d.areas, areas, rtol=1e-12, atol=1e-15)
    assert sum(areas) == pytest.approx(HOLED.area, rel=1e-12)
