"""Surface Morph, panels (planarity, planarize, openings, solids) and unrolled cut sheets."""

from __future__ import annotations

import ezdxf
import numpy as np
import pytest
import shapely

from voroforge import surface
from voroforge.design.compute import compute
from voroforge.design.designfile import load

TAU = 2 * np.pi


@pytest.fixture(scope="module")
def design_result():
    design, base = load(
        {
            "boundary": {"shape": "rectangle", "width": TAU * 100, "height": 300},
            "seeds": {"method": "poisson", "radius": 60},
            "attractors": [{"type": "point", "points": [[100, 150]], "radius": 400}],
            "cells": {"web": {"near": 6, "far": 20}},
        }
    )
    return compute(design, base)


@pytest.fixture(scope="module")
def sphere_panels():
    vd = surface.voronoi(surface.sphere(2.0, subdivisions=3), 40, relax=10)
    return vd.panels()


@pytest.fixture(scope="module")
def saddle_panels():
    S = surface.saddle(4.0, 4.0, 0.8, resolution=24)
    vd = surface.voronoi(S, 40, relax=15)
    return vd.panels()


def test_morph_on_a_cylinder_is_isometric_and_on_the_surface(design_result):
    S = surface.cylinder(100.0, 300.0)
    panels = surface.morph(design_result, S, what="cells")
    r = np.linalg.norm(panels.vertices[:, :2], axis=1)
    assert np.abs(r - 100.0).max() < 1e-9
    assert panels.vertices[:, 2].min() >= -1e-9 and panels.vertices[:, 2].max() <= 300 + 1e-9
    # areas on the surface equal the UV areas times 2 pi r h: the design's own areas here
    design_areas = [
        shapely.intersection(design_result.raw[i], design_result.domain).area for i in panels.ids
    ]
    np.testing.assert_allclose(panels.areas(), design_areas, rtol=1e-12)
    # the panels with their openings cut: area = cell - opening
    with_holes = surface.morph(design_result, S, what="panels")
    assert with_holes.areas().sum() == pytest.approx(design_result.frame.area, rel=1e-9)
    assert any(len(r) > 1 for r in with_holes.rings)


@pytest.mark.parametrize(
    "S, check",
    [
        (surface.sphere_patch(2.0), lambda p: np.linalg.norm(p, axis=1) - 2.0),
        (
            surface.saddle(4.0, 2.0, 0.5),
            lambda p: p[:, 2] - 0.5 * ((p[:, 0] / 2) ** 2 - (p[:, 1] / 1) ** 2),
        ),
        (
            surface.torus(1.0, 0.4),
            lambda p: np.hypot(np.hypot(p[:, 0], p[:, 1]) - 1, p[:, 2]) - 0.4,
        ),
    ],
    ids=["sphere", "saddle", "torus"],
)
def test_morphed_vertices_lie_on_the_analytic_surface(S, check):
    geoms = [shapely.Point(0.5, 0.5).buffer(0.3), shapely.box(0.05, 0.05, 0.2, 0.9)]
    panels = surface.morph(geoms, S, bounds=(0, 0, 1, 1))
    assert np.abs(check(panels.vertices)).max() < 1e-9
    assert list(panels.ids) == [0, 1]


def test_morph_rejects_bad_input():
    S = surface.cylinder(1, 1)
    with pytest.raises(ValueError, match="what"):
        surface.morph([shapely.box(0, 0, 1, 1)], S, what="walls")
    with pytest.raises(ValueError, match="outside"):
        surface.morph([shapely.box(0, 0, 2, 1)], S, bounds=(0, 0, 1, 1))
    with pytest.raises(ValueError, match="UV map"):
        surface.morph([shapely.box(0, 0, 1, 1)], surface.sphere(1.0, subdivisions=1))
    with pytest.raises(ValueError, match="shapely"):
        surface.morph(["box"], S)


def test_planarity_of_flat_and_bent_panels():
    flat = surface.Panels(
        np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float),
        [[np.arange(4)]],
        np.array([7]),
    )
    ab, rel = flat.planarity()
    assert ab[0] == 0 and rel[0] == 0
    bent = surface.Panels(
        np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0.1], [0, 1, 0]], float),
        [[np.arange(4)]],
        np.array([7]),
    )
    ab, rel = bent.planarity()
    assert 0.025 <= ab[0] <= 0.0251  # a twisted quad: about d / 4 at each corner
    assert rel[0] == pytest.approx(ab[0] / np.sqrt(1.01), rel=1e-12)


def test_planarize_reaches_the_tolerance_or_flags_and_flags_negative_curvature(saddle_panels):
    tol = 0.0005  # 0.5 mm at a 4 m span
    before = saddle_panels.planarity().absolute.max()
    out = saddle_panels.planarize(tol)
    plan = out.planarity().absolute
    rep = out.report
    assert before > 10 * tol
    assert set(np.flatnonzero(plan > tol)) == set(rep.not_planar)
    assert rep.ok and plan.max() <= tol
    # a saddle curves negatively everywhere: every panel is flagged
    assert len(rep.negative_curvature) == len(out)
    assert rep.surface_distance < 0.1  # near the surface
    # shared corners stay shared: the same vertex count
    assert len(out.vertices) == len(saddle_panels.vertices)
    # border panels: their mesh-border runs left out, and no panel crosses itself or turns over
    assert rep.dropped > 0 and len(rep.invalid) == 0
    assert (
        sum(len(r[0]) for r in out.rings)
        == sum(len(r[0]) for r in saddle_panels.rings) - rep.dropped
    )
    dome = surface.voronoi(surface.sphere_patch(2.0, polar=(0, 1.0)), 30, relax=10).panels()
    assert len(dome.planarize(0.001).report.negative_curvature) == 0


def test_unroll_keeps_edge_lengths_labels_and_does_not_overlap(sphere_panels, tmp_path):
    panels = sphere_panels.planarize(0.0005).openings(0.5)
    sheets = panels.unroll(sheet=(3.0, 1.5))
    assert sheets.count >= 1
    assert sorted(p.label for p in sheets.parts) == sorted(str(i) for i in panels.ids)
    for part in sheets.parts:
        flat = part.rings[0]
        d2 = np.linalg.norm(np.roll(flat, -1, axis=0) - flat, axis=1)
        d3 = panels.edge_lengths(part.panel)[0]
        assert np.abs(d2 - d3).max() <= 1e-9 * d3.max()
        assert part.polygon.is_valid and len(part.polygon.interiors) == 1
        assert part.polygon.contains(shapely.Point(part.label_at))
        xmin, ymin, xmax, ymax = part.polygon.bounds
        assert xmin >= 0 and ymin >= 0 and xmax <= 3.0 and ymax <= 1.5
    for k in range(sheets.count):
        polys = [p.polygon for p in sheets.sheet(k)]
        tree = shapely.STRtree(polys)
        a, b = tree.query(polys, predicate="intersects")
        assert (a == b).all()
    dxf = sheets.write_dxf(tmp_path / "sheet.dxf", units="m")
    doc = ezdxf.readfile(dxf)
    texts = [e.dxf.text for e in doc.modelspace().query("TEXT")]
    assert sorted(texts) == sorted(str(i) for i in panels.ids)
    assert len(doc.modelspace().query("LWPOLYLINE")) == 2 * len(panels)
    svg = sheets.write_svg(tmp_path / "sheet.svg", units="m").read_text()
    assert svg.count("<path") == 2 * len(panels) and svg.count("<text") == len(panels)


def test_unroll_of_a_morphed_curved_panel_keeps_its_boundary_lengths():
    S = surface.sphere_patch(1.0, polar=(0.3, 1.2), azimuth=(0, 1.5))
    panels = surface.morph([shapely.Point(0.5, 0.5).buffer(0.4)], S, bounds=(0, 0, 1, 1))
    sheets = panels.unroll()
    flat = sheets.parts[0].rings[0]
    d2 = np.linalg.norm(np.roll(flat, -1, axis=0) - flat, axis=1)
    np.testing.assert_allclose(d2, panels.edge_lengths(0)[0], rtol=1e-9)


def test_unroll_of_bent_border_panels_keeps_lengths_and_does_not_overlap(saddle_panels):
    sheets = saddle_panels.unroll()
    assert sheets.count == 1
    boxes = [shapely.box(*p.polygon.bounds) for p in sheets.parts]
    tree = shapely.STRtree(boxes)
    a, b = tree.query(boxes, predicate="intersects")
    assert (a == b).all()
    for part in sheets.parts:
        d2 = np.linalg.norm(np.roll(part.rings[0], -1, axis=0) - part.rings[0], axis=1)
        np.testing.assert_allclose(d2, saddle_panels.edge_lengths(part.panel)[0], rtol=1e-9)


def test_solids_are_watertight_with_the_right_volume(sphere_panels):
    planar = sphere_panels.planarize(0.0002)
    t = 0.03
    solids = planar.thicken(t)
    assert all(s.is_volume for s in solids)
    vol = np.array([s.volume for s in solids])
    np.testing.assert_allclose(vol, planar.areas() * t, rtol=2e-3)
    frames = planar.frame(0.04)
    assert all(f.is_volume for f in frames)
    assert all(f.volume < s.volume * 0.04 / t for f, s in zip(frames, solids, strict=True))
    graded = planar.openings((0.7, 0.2), attractors=[[0, 0, 2.0]], radius=3.0)
    holes = -graded.areas() + planar.areas()
    top = np.linalg.norm(graded.centroids() - [0, 0, 2.0], axis=1)
    assert np.corrcoef(top, holes / planar.areas())[0, 1] < -0.8  # bigger near the attractor
    assert all(s.is_volume for s in graded.thicken(t))
    cyl = surface.morph(
        [shapely.box(0.1, 0.1, 0.3, 0.4)], surface.cylinder(1, 1), bounds=(0, 0, 1, 1)
    )
    (shell,) = cyl.thicken(0.01)
    assert shell.is_volume
    # outward: a shell between r = 1 and 1.01
    assert np.hypot(shell.vertices[:, 0], shell.vertices[:, 1]).max() == pytest.approx(1.01)


def test_outline_faults_find_bow_ties_and_turned_panels_and_planarize_warns():
    square = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)
    bow = square[[0, 1, 3, 2]]  # the same corners in crossing order
    V = np.concatenate([square, bow + [3, 0, 0], square + [6, 0, 0]])
    rings = [[np.arange(4)], [np.arange(4, 8)], [np.arange(8, 12)]]
    P = surface.Panels(V, rings, np.array([10, 11, 12]))
    crossed, flipped = P.outline_faults()
    assert list(crossed) == [1] and len(flipped) == 0
    # against normals that say the third should face down: turned over
    ref = np.array([[0, 0, 1], [0, 0, 1], [0, 0, -1]], float)
    crossed, flipped = P.outline_faults(ref)
    assert list(crossed) == [1] and list(flipped) == [2]
    # a hole outside its panel is no valid polygon either
    holed = surface.Panels(
        np.concatenate([square, square * 0.2 + [2, 2, 0]]),
        [[np.arange(4), np.arange(4, 8)]],
        np.array([5]),
    )
    assert list(holed.outline_faults()[0]) == [0]
    with pytest.warns(surface.PlanarizeWarning, match=r"panel ids \[11\]"):
        out = P.planarize(1e-6)
    assert list(out.report.self_intersecting) == [1] and not out.report.ok
    assert list(out.report.invalid) == [1]


def test_panels_that_cross_themselves_are_refused_by_thicken_and_frame():
    # a bow tie (a corner cell of a creased mesh planarized) cannot be capped on its own
    # corners: thicken used to crash in numpy, with an opening it returned an open solid
    square = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)
    bow = square[[0, 1, 3, 2]]
    V = np.concatenate([square, bow + [3, 0, 0]])
    P = surface.Panels(V, [[np.arange(4)], [np.arange(4, 8)]], np.array([10, 11]))
    for make in (
        lambda: P.thicken(0.1),
        lambda: P.openings(0.5).thicken(0.1),
        lambda: P.frame(0.05),
    ):
        with pytest.raises(ValueError, match=r"1 of 2 panels \(cells 11\) cross themselves"):
            make()
    # the valid panel alone still makes its closed solid, with the right volume
    ok = surface.Panels(square.copy(), [[np.arange(4)]], np.array([10]))
    (solid,) = ok.thicken(0.1)
    assert solid.is_watertight and solid.is_volume
    assert solid.volume == pytest.approx(0.1)
    (holed,) = ok.openings(0.5).thicken(0.1)
    assert holed.is_watertight and holed.volume == pytest.approx(0.1 * 0.75)
