"""seeds.method = "curves": cell edges that trace curves (the leaf-venation example)."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest
import shapely

import voroforge as vf
from voroforge.design.build import build
from voroforge.design.compute import compute
from voroforge.design.designfile import DesignError, load
from voroforge.design.populate import along_curves, crossing_edges

ROOT = Path(__file__).resolve().parents[1]


def test_pairs_put_the_edges_on_a_straight_curve():
    box = (0.0, 0.0, 100.0, 50.0)
    pts = along_curves(box, [[(0, 25), (100, 25)]], 10.0, radius=9.0, seed=3)
    d = vf.voronoi(pts, box)
    on = [c for c in d.edges.coords if np.abs(c[:, 1] - 25.0).max() < 1e-9]
    assert sum(float(np.hypot(*(c[1] - c[0]))) for c in on) == pytest.approx(100.0)
    # the fill keeps its distance: no site nearer the line than the pairs
    assert np.abs(pts[:, 1] - 25.0).min() == pytest.approx(5.0)
    traced = crossing_edges(d, [[(0, 25), (100, 25)]])
    assert traced.length == pytest.approx(100.0) and len(traced.geoms) == 1


def test_curved_and_branching_curves_are_traced_as_one_network():
    leaf = shapely.Point(0, 0).buffer(60.0)
    arc = np.column_stack((np.linspace(-55, 55, 60), 8 * np.sin(np.linspace(-1.5, 1.5, 60))))
    branch = np.array([[0.0, 0.0], [20.0, 25.0], [30.0, 45.0]])
    curves = [arc, branch]
    pts = along_curves(leaf, curves, 5.0, radius=6.0, seed=1)
    assert shapely.contains_xy(leaf, pts[:, 0], pts[:, 1]).all()
    # no site in another curve's band (so the junction does not pull either curve away)
    for k, c in enumerate(curves):
        other = shapely.LineString(curves[1 - k])
        near = shapely.distance(shapely.LineString(c), shapely.points(pts)) < 2.5 - 1e-9
        assert (shapely.distance(other, shapely.points(pts[near])) >= 2.5 - 1e-9).all()
    traced = crossing_edges(vf.voronoi(pts, leaf), curves)
    # one connected network that follows both curves closely
    assert shapely.buffer(traced, 1e-6).geom_type == "Polygon"
    for c in curves:
        probe = shapely.line_interpolate_point(
            shapely.LineString(c), np.linspace(0.05, 0.95, 40), normalized=True
        )
        assert (shapely.distance(traced, probe) < 1.5).mean() >= 0.9
    assert traced.hausdorff_distance(shapely.MultiLineString(curves)) < 6.0


def test_bad_curves_are_refused():
    with pytest.raises(ValueError, match="spacing"):
        along_curves((0, 0, 1, 1), [[(0, 0), (1, 1)]], 0.0)
    with pytest.raises(ValueError, match="polyline"):
        along_curves((0, 0, 1, 1), [[(0, 0)]], 0.1)
    with pytest.raises(ValueError, match="positive length"):
        along_curves((0, 0, 1, 1), [[(0.5, 0.5), (0.5, 0.5)]], 0.1)
    with pytest.raises(ValueError, match="finite"):
        along_curves((0, 0, 1, 1), [[(0, 0), (np.nan, 1)]], 0.1)


BASE = """
[boundary]
width = 100
height = 60
[seeds]
method = "curves"
spacing = 6
radius = 7
"""


@pytest.mark.parametrize(
    "extra, key, words",
    [
        ("", "seeds.curves", "exactly one of"),
        ('curves = [[[0, 30], [100, 30]]]\npath = "M 0 0 L 1 1"\n', "seeds.curves", "exactly one"),
        (
            'path = "M 0 30 L 100 30"\n[recursion]\ndepth = 1\n'
            "probability = { near = 1, far = 0 }\n",
            "recursion.probability",
            "attractors",
        ),
        (
            'path = "M 0 30 L 100 30"\n[recursion]\ndepth = 1\nprobability = 1.5\n',
            "recursion.probability",
            "between 0 and 1",
        ),
    ],
)
def test_design_errors_name_the_key(tmp_path, extra, key, words):
    f = tmp_path / "d.toml"
    f.write_text(BASE + extra)
    with pytest.raises(DesignError) as info:
        design, base = load(f)
        compute(design, base)
    assert any(i.key == key and words in i.message for i in info.value.issues), info.value


def test_graded_probability_subdivides_every_cell_near_the_attractor(tmp_path):
    f = tmp_path / "d.toml"
    f.write_text(
        BASE.replace('method = "curves"', 'method = "poisson"').replace("radius = 7", "radius = 9")
        + "[[attractors]]\ntype = 'point'\npoints = [[0, 30]]\nradius = 40\nfalloff = 'linear'\n"
        + "[recursion]\ndepth = 1\ncount = 3\nprobability = { near = 1, far = 0 }\n"
    )
    design, base = load(f)
    r = compute(design, base)
    top = r.extra["levels"][0]
    split = set(r.extra["levels"][1].parent.tolist())
    at = shapely.get_coordinates(shapely.point_on_surface(np.asarray(top.cells, dtype=object)))
    dist = np.hypot(at[:, 0], at[:, 1] - 30)
    assert all(i in split for i in np.flatnonzero(dist < 2.0))  # field ~1: always
    assert not any(i in split for i in np.flatnonzero(dist > 40.0))  # field 0: never
    assert 0 < len(split) < len(top)


def test_leaf_example_traces_its_midrib_and_veins():
    path = ROOT / "examples" / "leaf-venation.toml"
    design, base = load(path)
    r = compute(design, base)
    traced = r.extra["curve_edges"]
    subpaths = tomllib.loads(path.read_text())["seeds"]["path"].strip().splitlines()
    from voroforge.io.readers.svg import path_lines

    leaf = r.boundary
    for sub in subpaths:  # midrib and each secondary: traced over >= 85 % of the length
        (vein,) = path_lines(sub)
        line = shapely.intersection(shapely.LineString(vein), leaf)
        probe = shapely.line_interpolate_point(line, np.linspace(0.03, 0.97, 60), normalized=True)
        assert (shapely.distance(traced, probe) < 2.0).mean() >= 0.85, sub
    # the traced veins are cell edges: every piece lies on the drawn edges
    assert shapely.buffer(r.edges, 1e-6).contains(traced)
    assert r.level.max() == 1 and (r.level == 1).sum() > len(r.extra["levels"][0])


def test_curves_from_an_svg_file_and_inline_polylines_agree(tmp_path):
    # a designer's SVG (y down, mm) and the same line given inline (y up) trace the same edges
    (tmp_path / "veins.svg").write_text(
        '<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="60mm" '
        'viewBox="0 0 100 60"><path d="M 0 20 L 100 40" fill="none" stroke="black"/></svg>'
    )
    head = '[boundary]\nwidth = 100\nheight = 60\n[seeds]\nmethod = "curves"\nspacing = 6\n'
    traced = []
    for extra in ('file = "veins.svg"\n', "curves = [[[0, 40], [100, 20]]]\n"):
        f = tmp_path / "d.toml"
        f.write_text(head + extra + "radius = 7\n[output]\nlayers = { ENGRAVE = 'curves' }\n")
        design, base = load(f)
        traced.append(compute(design, base).extra["curve_edges"])
    line = shapely.LineString([(0, 40), (100, 20)])
    for t in traced:
        assert t.length == pytest.approx(line.length, rel=1e-6)
        assert t.hausdorff_distance(line) < 1e-6
    assert traced[0].equals_exact(traced[1], 1e-6)
    out = build(tmp_path / "d.toml", tmp_path / "out")  # the curves product as a layer
    assert "ENGRAVE" in out[0].read_text()


@pytest.mark.parametrize("curve", [[[0, 0], [200, 0]], [[0, 300], [200, 300]]])
def test_a_curve_no_cell_edge_can_trace_builds(tmp_path, curve):
    # checker25 F4: a curve along the outline or outside it left no crossing edge and
    # `voroforge build` ended in a TypeError traceback from shapely
    d = vf.voronoi(np.random.default_rng(0).random((30, 2)) * [200, 120], (0, 0, 200, 120))
    traced = crossing_edges(d, [curve])
    assert traced.geom_type == "MultiLineString" and traced.is_empty
    spec = {
        "boundary": {"shape": "rectangle", "width": 200, "height": 120},
        "seeds": {"method": "curves", "curves": [curve], "spacing": 8, "radius": 20},
    }
    written = build(spec, tmp_path / "o")
    assert written and all(p.exists() for p in written)
