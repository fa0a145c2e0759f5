"""Recursive subdivision and relaxation: tiling of parents, depth, webs, reproducibility."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

import voroforge as vf
from voroforge.design import attractors as at
from voroforge.design import boundary as bd
from voroforge.design import cellops as co
from voroforge.design import populate as pop
from voroforge.design import recursive as rc
from voroforge.design import relax as rl

PANEL = shapely.difference(bd.rectangle(200, 100), bd.circle(15, center=(60, 50)))


def _check_tiling(levels):
    for k in range(1, len(levels)):
        child, par = levels[k], levels[k - 1]
        assert child.depth == k
        assert ((child.parent >= 0) & (child.parent < len(par))).all()
        # the children of each parent tile the parent's opening: areas sum, no overlap
        got = np.bincount(child.parent, weights=shapely.area(child.cells), minlength=len(par))
        has = np.bincount(child.parent, minlength=len(par)) > 0
        want = shapely.area(par.openings)
        assert got[has] == pytest.approx(want[has], rel=1e-9, abs=1e-9)
        for p in np.flatnonzero(has)[:10]:
            kids = child.cells[child.parent == p]
            union = shapely.union_all(kids)
            assert union.symmetric_difference(par.openings[p]).area < 1e-6 * union.area
            # each child lies in its parent cell, and its site in the parent's opening
            assert shapely.within(kids, shapely.buffer(par.cells[p], 1e-9)).all()
            sites = child.sites[child.parent == p]
            assert shapely.contains_xy(par.openings[p], sites[:, 0], sites[:, 1]).all()


@pytest.mark.parametrize("depth", [0, 1, 2])
def test_depth_and_tiling(depth):
    levels = rc.subdivide(PANEL, 10, depth=depth, count=4, seed=3, web=1.0)
    assert len(levels) == depth + 1
    assert [lv.depth for lv in levels] == list(range(depth + 1))
    assert len(levels[0]) == 10 and (levels[0].parent == -1).all()
    assert shapely.area(levels[0].cells).sum() == pytest.approx(PANEL.area)
    if depth:
        assert len(levels[1]) == 4 * int((~shapely.is_empty(levels[0].openings)).sum())
    _check_tiling(levels)


def test_webs_per_level_nest_and_frame():
    webs = [4.0, 2.0, 1.0]
    levels = rc.subdivide(PANEL, 8, depth=2, count=5, seed=1, web=webs)
    assert [lv.web for lv in levels] == webs
    for lv in levels:
        live = ~shapely.is_empty(lv.openings)
        # each opening keeps half the level's web from its cell's outline
        pts, owner = shapely.get_coordinates(lv.openings[live], return_index=True)
        dist = shapely.distance(shapely.boundary(lv.cells[live])[owner], shapely.points(pts))
        assert dist.min() >= lv.web / 2 * (1 - 1e-9)
    holes = rc.leaves(levels)
    # every subdivided cell is replaced by its children: leaf openings don't overlap
    assert shapely.area(shapely.union_all(holes)) == pytest.approx(shapely.area(holes).sum())
    assert len(holes) == len(levels[2]) - shapely.is_empty(levels[2].openings).sum()
    part = co.frame(PANEL, holes)
    assert part.area == pytest.approx(PANEL.area - shapely.area(holes).sum(), rel=1e-9)


def test_select_count_rules_and_reproducibility():
    big = lambda lv: co.by_area(lv.openings, min=800.0)  # noqa: E731
    field = at.PointAttractor([[150, 50]], radius=80.0)
    kw = dict(depth=2, seed=9, web=[2.0, 1.0, 0.5], select=big)
    a = rc.subdivide(
        PANEL, 12, count=[rc.count_by_area(1 / 150), rc.count_by_field(field, 2, 9)], **kw
    )
    b = rc.subdivide(
        PANEL, 12, count=[rc.count_by_area(1 / 150), rc.count_by_field(field, 2, 9)], **kw
    )
    for la, lb in zip(a, b, strict=True):
        assert np.array_equal(la.sites, lb.sites)
        assert np.array_equal(la.parent, lb.parent)
    chosen = np.flatnonzero(big(a[0]))
    assert set(np.unique(a[1].parent)) <= set(chosen)
    # count by area: children per parent follow the parent's opening area
    kids = np.bincount(a[1].parent, minlength=len(a[0]))
    want = np.round(shapely.area(a[0].openings) / 150).astype(int)
    assert np.array_equal(kids[chosen][want[chosen] > 1], want[chosen][want[chosen] > 1])
    _check_tiling(a)
    c = rc.subdivide(PANEL, 12, count=4, depth=1, seed=10)
    assert not np.array_equal(
        c[1].sites, rc.subdivide(PANEL, 12, count=4, depth=1, seed=9)[1].sites
    )


def test_zero_and_one_children():
    levels = rc.subdivide(PANEL, 6, depth=2, count=[1, 0], seed=2)
    assert len(levels[1]) == len(levels[0])
    assert shapely.equals(levels[1].cells, levels[0].openings).all()
    assert len(levels[2]) == 0
    assert len(rc.leaves(levels)) == len(levels[1])


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        (dict(depth=-1, count=3), "depth"),
        (dict(depth=1, count=-3), "count"),
        (dict(depth=2, count=[3]), r"one entry per level \(2\)"),
        (dict(depth=1, count=3, web=[1.0]), r"one entry per level \(2\)"),
        (dict(depth=1, count=3, web=-1.0), "web"),
        (dict(depth=1, count=3, select="big"), "select"),
        (dict(depth=1, count=3, select=lambda lv: np.ones(2, bool)), "boolean mask"),
        (dict(depth=1, count=lambda cell: 2.5), "count rule returned"),
    ],
)
def test_subdivide_bad_input(kwargs, match):
    with pytest.raises(ValueError, match=match):
        rc.subdivide(PANEL, 5, seed=0, **kwargs)


def test_children_clipped_to_a_sliver_parent():
    # four sites in a thin triangle: the engine once returned cells escaping the domain
    tri = shapely.Polygon([(199.5, 44.607428412228096), (162.86774354570446, 99.5), (199.5, 99.5)])
    sites = np.array(
        [
            [189.42102115, 67.73232358],
            [197.80013249, 62.26546853],
            [198.38206754, 72.20660227],
            [191.93206796, 68.44695967],
        ]
    )
    cells = rc._clipped(vf.voronoi(sites, tri), tri)
    assert shapely.area(cells).sum() == pytest.approx(tri.area, rel=1e-9)
    assert shapely.within(cells, shapely.buffer(tri, 1e-9)).all()
    ref = shapely.get_parts(shapely.voronoi_polygons(shapely.multipoints(sites), extend_to=tri))
    ref_areas = sorted(shapely.area(shapely.intersection(ref, tri)))
    assert sorted(shapely.area(cells)) == pytest.approx(ref_areas, rel=1e-9)


# ----------------------------------------------------------------------------- relax


def test_relax_evens_out_cells_and_matches_plain_lloyd():
    pts = pop.random(PANEL, 60, seed=4)
    before = vf.voronoi(pts, PANEL).areas
    out = rl.relax(pts, PANEL, iterations=15)
    after = vf.voronoi(out, PANEL).areas
    assert after.std() < 0.6 * before.std()
    assert shapely.contains_xy(PANEL, out[:, 0], out[:, 1]).all()
    # the engine path and the plain loop give the same Lloyd iterates
    assert np.allclose(out, rl._plain(pts.copy(), PANEL, 15, None), atol=1e-9)
    assert np.array_equal(rl.relax(pts, PANEL), pts) and rl.relax(pts, PANEL) is not pts


def test_relax_tolerance_converges():
    pts = pop.random(bd.rectangle(100, 100), 30, seed=1)
    out = rl.relax(pts, (0, 0, 100, 100), tol=0.02)
    c = vf.voronoi(out, (0, 0, 100, 100)).centroids
    shift = np.hypot(*(c - out).T).max()
    assert shift < 2 * 0.02  # the next Lloyd step would move no site much farther than tol
    assert np.hypot(*(c - pts).T).max() > 1.0  # it did move


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [(dict(iterations=-1), "iterations"), (dict(tol=-1.0), "tol"), (dict(density=3), "density")],
)
def test_relax_bad_input(kwargs, match):
    with pytest.raises(ValueError, match=match):
        rl.relax(np.zeros((3, 2)), PANEL, **kwargs)
    with pytest.raises(ValueError, match="shape"):
        rl.relax(np.zeros((3, 3)), PANEL, iterations=1)


# --- folded from test_qa_design.py: bugs found by using the design layer as designers
# and fabricators do


def test_subdivide_does_not_launch_the_parallel_area_kernel_per_cell(monkeypatch):
    # Recursion builds one small diagram per cell; Diagram.areas runs a numba parallel
    # kernel whose thread wake-up cost ~10 ms a call on a busy machine (a depth-3 design
    # took 15 s instead of 1 s). The tiling guard uses shapely's areas of the built cells.
    import voroforge.engine.diagram as engine
    from voroforge.design import recursive

    calls = []
    real = engine.area_centroid
    monkeypatch.setattr(engine, "area_centroid", lambda *a: calls.append(1) or real(*a))
    box = shapely.box(0, 0, 100, 60)
    levels = recursive.subdivide(box, 12, depth=2, count=3, seed=4, web=[2, 1, 0.5])
    assert len(calls) == 0
    # ... and the levels still tile: the leaves' cells cover each subdivided parent opening.
    top = levels[0]
    assert sum(c.area for c in top.cells) == pytest.approx(box.area, rel=1e-9)
    assert sum(c.area for c in levels[1].cells) == pytest.approx(
        sum(o.area for o in top.openings), rel=1e-9
    )
