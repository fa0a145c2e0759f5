"""Strip cells of a float circle far out keep their site, and leave no hole (issue 15, s56).

1025 sites on a circle of radius 1e-7 at (5e5, 4e6): sites 7 x-ulps apart whose shared edge
has ends 2.9 y-ulps apart (151.56 and 154.44) were merged by the rounding-bound rule, the
merged point put one site outside its ring (a thin wedge out to the box's side), and that
ring was emptied. Its gap stayed open (a wedge of ~68,500 units^2 in no cell: sample points
whose nearest site is clear lay in no cell), because a sliver between two other cells, whose
shared edge ends an ulp apart on the box's side, joined the gap's boundary. Now the gap's
boundary goes round that sliver (``restore._despiked``) and is the site's ring, and the
merged point is split where floats hold two (``restore.split_lost``), so the ring holds its
site. Checked against exact nearest sites in the circle's integer frame (no engine code).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import shapely

import voroforge as vf

from reference import holds_exactly

CENTRE = (5e5, 4e6)
UNIT = 2.0**-34  # an x-ulp at 5e5; a y-ulp at 4e6 is 8 units
R = 1e-7


def _circle(n, phase):
    t = np.arange(n) * (2.0 * np.pi / n) + phase
    return np.column_stack((R * np.cos(t), R * np.sin(t))) + CENTRE


def _local(xy):
    out = (np.asarray(xy, dtype=np.float64) - CENTRE) / UNIT
    assert (out == np.round(out)).all()  # exact: every float here is on the unit grid
    return out


def _diagram(n, phase, algorithm="delaunay"):
    pts = _circle(n, phase)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return pts, vf.voronoi(pts, None, algorithm=algorithm)


@pytest.mark.parametrize(("phase", "strip"), [(0.2, 351), (0.05, 888), (0.85, 245)])
def test_strip_cell_holds_its_site_and_leaves_no_hole(phase, strip):
    pts, d = _diagram(1025, phase)
    p = _local(pts)
    cells = np.asarray(d.cells, dtype=object)
    nonempty = np.array([c is not None and not c.is_empty for c in cells])
    assert shapely.is_valid(cells[nonempty]).all()
    assert d.describe().euler_ok
    # the strip's own ring holds its site (exact test in the integer frame)
    ring = _local(shapely.get_coordinates(cells[strip]))
    assert len(ring) >= 4 and holds_exactly(ring, p[strip])
    # float points around the strip (its wedge reaches ~850 x-units and ~100 y-ulps out):
    # each lies in some cell, and in its nearest site's cell where that is clear (by 4
    # y-ulps from every bisector of the nearest site, exact squared distances)
    g = np.random.default_rng(1)
    out = p[strip] - p.mean(axis=0)  # the wedge runs out from the circle's centre
    t = g.uniform(0.0, 850.0, 3000)[:, None] * out / np.abs(out).max()
    q = np.round(p[strip] + t + g.uniform(-60.0, 60.0, t.shape) * (1.0, 8.0))
    q[:, 1] = 8.0 * np.round(q[:, 1] / 8.0)  # floats: y on the y-ulp grid
    d2 = ((q[:, None, :] - p[None]) ** 2).sum(-1)  # exact: integers below 2**53
    near = d2.argmin(axis=1)
    gap = np.sqrt(((p[None, :, :] - p[near][:, None, :]) ** 2).sum(-1))
    gap[np.arange(len(q)), near] = 1.0
    margin = (d2 - d2[np.arange(len(q)), near][:, None]) / (2.0 * gap)
    margin[np.arange(len(q)), near] = np.inf
    clear = margin.min(axis=1) >= 32.0
    world = shapely.points(q * UNIT + CENTRE)
    box = d.boundary
    inbox = shapely.intersects(box, world)
    covered = np.zeros(len(q), dtype=bool)
    for i in np.unique(near):
        for j in {int(i), *range(max(0, i - 12), min(len(p), i + 13))}:
            if nonempty[j]:
                covered |= shapely.intersects(cells[j], world)
    assert covered[inbox].all(), q[inbox & ~covered][:3]
    mine = np.array(
        [nonempty[k] and shapely.intersects(cells[k], w) for k, w in zip(near, world, strict=True)]
    )
    assert (inbox & clear).sum() > 100
    assert mine[inbox & clear].all(), q[inbox & clear & ~mine][:3]


def test_box_covered_where_strip_was_emptied():
    """The box's area minus the cells' union: the ~68,500 units^2 wedge is gone."""
    pts, d = _diagram(1025, 0.2)
    cells = [c for c in d.cells if c is not None and not c.is_empty]
    loc = [shapely.transform(c, lambda a: (a - CENTRE) / UNIT) for c in cells]
    x0, y0, x1, y1 = d.boundary.bounds
    box = shapely.box(
        (x0 - CENTRE[0]) / UNIT,
        (y0 - CENTRE[1]) / UNIT,
        (x1 - CENTRE[0]) / UNIT,
        (y1 - CENTRE[1]) / UNIT,
    )
    hole = shapely.difference(box, shapely.union_all(loc))
    assert hole.area < 1.0  # units^2 (of a box of ~1.7e7)


@pytest.mark.parametrize("algorithm", ["fortune", "halfplane"])
def test_every_algorithm_gives_the_strip(algorithm):
    _, a = _diagram(1025, 0.2)
    _, b = _diagram(1025, 0.2, algorithm)
    for x, y in zip(a.cells, b.cells, strict=True):
        assert shapely.equals_exact(x, y, 0.0) or (x.is_empty and y.is_empty)
    assert a.unresolved.tolist() == b.unresolved.tolist()
