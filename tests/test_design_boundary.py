"""Boundaries: primitives, validation, and the SVG / DXF / GeoJSON readers against exact areas."""

from __future__ import annotations

import json
import math

import ezdxf
import numpy as np
import pytest
import shapely

from voroforge.design import boundary as bd

TOL = 0.01


def _svg(tmp_path, body: str, *, attrs: str = 'viewBox="0 0 200 100"') -> str:
    path = tmp_path / "shape.svg"
    path.write_text(f'<svg xmlns="http://www.w3.org/2000/svg" {attrs}>{body}</svg>')
    return path


# ----------------------------------------------------------------------------- primitives


def test_rectangle_and_circle():
    r = bd.rectangle(600, 400, origin=(10, 20))
    assert r.bounds == (10.0, 20.0, 610.0, 420.0)
    assert r.area == 240000.0
    c = bd.circle(50, center=(1, 2), segments=64)
    assert len(c.exterior.coords) == 65
    assert c.area == pytest.approx(0.5 * 64 * 50**2 * math.sin(2 * math.pi / 64))
    assert np.allclose(np.hypot(*(np.asarray(c.exterior.coords) - (1, 2)).T), 50)


def test_polygon_with_holes_is_oriented_and_validated():
    p = bd.polygon([(0, 0), (0, 10), (10, 10), (10, 0)], holes=[[(2, 2), (4, 2), (4, 4)]])
    assert p.exterior.is_ccw and not p.interiors[0].is_ccw
    assert p.area == pytest.approx(100 - 2)
    with pytest.raises(ValueError, match="Self-intersection"):
        bd.polygon([(0, 0), (10, 10), (10, 0), (0, 10)])
    with pytest.raises(ValueError, match="at least 3"):
        bd.polygon([(0, 0), (1, 1)])
    with pytest.raises(ValueError, match="NaN"):
        bd.polygon([(0, 0), (1, np.nan), (1, 0)])


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: bd.rectangle(-1, 2), "width must be > 0"),
        (lambda: bd.rectangle(1, float("inf")), "height must be finite"),
        (lambda: bd.rectangle(1, 1, origin=(0,)), "origin"),
        (lambda: bd.circle(0), "radius must be > 0"),
        (lambda: bd.circle(1, segments=2), "segments"),
        (lambda: bd.union(), "at least one"),
        (lambda: bd.union(shapely.Point(0, 0)), "Polygon or MultiPolygon"),
        (lambda: bd.load("outline.stl"), "unsupported boundary file type"),
        (lambda: bd.from_svg("does-not-exist.svg"), "no such file"),
    ],
)
def test_bad_input_raises_clear_value_error(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_union_merges_overlaps_and_keeps_separate_parts():
    u = bd.union(bd.rectangle(10, 10), bd.rectangle(10, 10, origin=(5, 0)))
    assert u.area == pytest.approx(150)
    m = bd.union(bd.rectangle(1, 1), bd.rectangle(1, 1, origin=(5, 5)))
    assert m.geom_type == "MultiPolygon" and m.area == pytest.approx(2)


def test_even_odd_nesting():
    squares = [bd.rectangle(s, s, origin=(-s / 2, -s / 2)).exterior.coords for s in (8, 6, 4, 2)]
    g = bd.even_odd(squares)
    assert g.area == pytest.approx((64 - 36) + (16 - 4))
    assert not g.contains(shapely.Point(0, 0)) and g.contains(shapely.Point(1.5, 0))


# ----------------------------------------------------------------------------- SVG


def test_svg_path_all_commands_areas(tmp_path):
    # rectangle by absolute and relative lines, H/V, with a circular hole by two arcs
    body = '<path d="M10 10 H190 V90 h-180 z M100,30 a20 20 0 1 0 0 40 A20,20 0 1,0 100,30 Z"/>'
    g = bd.from_svg(_svg(tmp_path, body), tolerance=TOL)
    exact = 180 * 80 - math.pi * 20**2
    assert g.area == pytest.approx(exact, abs=2 * math.pi * 20 * TOL + 1e-9)
    assert len(g.interiors) == 1
    # y flipped within the viewBox: the drawing keeps its position, upright
    assert g.bounds == pytest.approx((10, 10, 190, 90))


def test_svg_cubic_and_quadratic_curves(tmp_path):
    # a circle of radius 50 from four cubic Béziers (kappa), drawn with C, c and S;
    # a parabola segment closed by a line (area 2/3 of the bounding triangle... exactly 4/3 w h)
    k = 0.5522847498 * 50
    d = (
        f"M150 50 C150 {50 + k} {100 + k} 100 100 100 c{-k} 0 -50 {-50 + k} -50 -50 "
        f"S{100 - k} 0 100 0 S150 {50 - k} 150 50 Z"
    )
    g = bd.from_svg(_svg(tmp_path, f'<path d="{d}"/>'), tolerance=1e-3)
    assert g.area == pytest.approx(math.pi * 50**2, rel=1e-3)  # kappa circle error ~2.7e-4
    # quadratic: y = x^2 style arch from (0,0) to (100,0), control (50,100): area 2/3*100*50
    q = bd.from_svg(_svg(tmp_path, '<path d="M0 0 Q50 100 100 0 Z"/>'), tolerance=1e-3)
    assert q.area == pytest.approx(2 / 3 * 100 * 50, abs=0.2)
    t = bd.from_svg(_svg(tmp_path, '<path d="M0 0 q50 100 100 0 t100 0 z"/>'), tolerance=1e-3)
    # T reflects the control point: second arch mirrored below; areas cancel to the sum
    assert t.area == pytest.approx(2 * (2 / 3 * 100 * 50), abs=0.5)


def test_svg_shapes_transforms_and_units(tmp_path):
    body = (
        '<g transform="translate(100 0)"><rect x="10" y="10" width="40" height="20"/></g>'
        '<circle cx="30" cy="50" r="10"/>'
        '<polygon points="0,0 20,0 0,20" transform="scale(2)"/>'
        '<rect x="150" y="60" width="40" height="30" rx="5"/>'
        "<defs><rect width='999' height='999'/></defs>"
    )
    g = bd.from_svg(
        _svg(tmp_path, body, attrs='width="400mm" height="200mm" viewBox="0 0 200 100"'),
        tolerance=1e-3,
    )
    s2 = 4.0  # 2 mm per user unit, areas times 4
    exact = (40 * 20 + math.pi * 100 + 0.5 * 40 * 40 + (40 * 30 - (4 - math.pi) * 25)) * s2
    assert g.area == pytest.approx(exact, rel=1e-4)
    assert g.bounds[2] == pytest.approx(2 * 190)


def test_svg_bad_path_data(tmp_path):
    with pytest.raises(ValueError, match="shape.svg"):
        bd.from_svg(_svg(tmp_path, '<path d="M 0 0 L 10 x"/>'))
    with pytest.raises(ValueError, match="no closed shapes"):
        bd.from_svg(_svg(tmp_path, '<line x1="0" y1="0" x2="1" y2="1"/>'))


def test_path_rings_arc_flattening_tolerance():
    # half-circle arc of radius 100: every flattened vertex on the circle, chords within tol
    (ring,) = bd.path_rings("M0 0 A100 100 0 0 1 200 0 Z", tolerance=0.05)
    r = np.hypot(ring[:, 0] - 100, ring[:, 1])
    arc = ring[1:]
    assert np.allclose(r[1:], 100)
    mids = (arc[1:] + arc[:-1]) / 2
    sag = 100 - np.hypot(mids[:, 0] - 100, mids[:, 1])
    assert sag.max() <= 0.05 + 1e-12


# ----------------------------------------------------------------------------- DXF


def test_dxf_bulges_circles_and_nesting(tmp_path):
    doc = ezdxf.new("R2000")
    msp = doc.modelspace()
    # stadium: 100 x 40 with semicircular ends (bulge 1 = half circle)
    msp.add_lwpolyline(
        [(0, 0, 0, 0, 0), (100, 0, 0, 0, 1), (100, 40, 0, 0, 0), (0, 40, 0, 0, 1)],
        format="xyseb",
        close=True,
    )
    msp.add_circle((50, 20), radius=10)  # hole
    msp.add_circle((50, 20), radius=5)  # island inside the hole
    # a 2D POLYLINE square with a quarter-circle bulge side elsewhere
    msp.add_polyline2d([(300, 0), (340, 0), (340, 40), (300, 40)], close=True)
    path = tmp_path / "part.dxf"
    doc.saveas(path)
    g = bd.from_dxf(path, tolerance=1e-3)
    stadium = 100 * 40 + math.pi * 20**2
    exact = stadium - math.pi * 100 + math.pi * 25 + 1600
    # inscribed chords lose at most tol x arc length of area
    arcs = 2 * math.pi * 20 + 2 * math.pi * 10 + 2 * math.pi * 5
    assert g.area == pytest.approx(exact, abs=arcs * 1e-3)
    assert g.area != pytest.approx(exact, abs=1e-9)  # curves really are polylines
    assert g.geom_type == "MultiPolygon" and len(g.geoms) == 3
    # bounds include the arcs' extreme points
    assert g.bounds == pytest.approx((-20, 0, 340, 40), abs=1e-6)


def test_dxf_negative_bulge_and_loose_lines(tmp_path):
    doc = ezdxf.new("R2000")
    msp = doc.modelspace()
    # square 40 x 40 with a semicircular notch (bulge -1 bites inwards on the top side)
    msp.add_lwpolyline([(0, 0, 0), (40, 0, 0), (40, 40, -1), (0, 40, 0)], format="xyb", close=True)
    # a triangle drawn from loose LINEs on another layer
    for a, b in [((100, 0), (140, 0)), ((140, 0), (100, 30)), ((100, 30), (100, 0))]:
        msp.add_line(a, b, dxfattribs={"layer": "LOOSE"})
    path = tmp_path / "loose.dxf"
    doc.saveas(path)
    g = bd.from_dxf(path, tolerance=1e-3)
    assert g.area == pytest.approx(1600 - math.pi * 200 + 600, abs=math.pi * 20 * 1e-3)
    assert g.area > 1600 - math.pi * 200 + 600  # the notch polyline lies inside the arc
    only = bd.from_dxf(path, layers=["LOOSE"])
    assert only.area == pytest.approx(600)
    with pytest.raises(ValueError, match="no closed outlines"):
        bd.from_dxf(path, layers=["LOOSE"], loose=False)


def test_dxf_ellipse_and_closed_spline(tmp_path):
    doc = ezdxf.new("R2000")
    msp = doc.modelspace()
    msp.add_ellipse((0, 0), major_axis=(30, 0), ratio=0.5)  # full ellipse 30 x 15
    ring = [(200 + 40 * math.cos(t), 40 * math.sin(t)) for t in np.linspace(0, 2 * np.pi, 13)[:-1]]
    spline = msp.add_spline(fit_points=[*ring, ring[0]])
    spline.closed = True
    path = tmp_path / "curves.dxf"
    doc.saveas(path)
    g = bd.from_dxf(path, tolerance=1e-3)
    ellipse, spline = sorted(g.geoms, key=lambda p: p.centroid.x)
    assert ellipse.area == pytest.approx(math.pi * 30 * 15, rel=1e-4)
    # a spline through 12 points of a circle of radius 40 is that circle to within 0.5%
    assert spline.area == pytest.approx(math.pi * 40**2, rel=5e-3)
    assert spline.centroid.distance(shapely.Point(200, 0)) < 0.2  # not periodic at the seam


def test_dxf_units_to_mm(tmp_path):
    doc = ezdxf.new("R2000")
    doc.header["$INSUNITS"] = 1  # inches
    doc.modelspace().add_lwpolyline([(0, 0), (2, 0), (2, 1), (0, 1)], close=True)
    path = tmp_path / "inch.dxf"
    doc.saveas(path)
    assert bd.from_dxf(path, to_mm=True).bounds == pytest.approx((0, 0, 50.8, 25.4))
    assert bd.from_dxf(path).area == pytest.approx(2.0)


def test_dxf_unreadable(tmp_path):
    path = tmp_path / "junk.dxf"
    path.write_text("this is not a dxf")
    with pytest.raises(ValueError, match="junk.dxf"):
        bd.from_dxf(path)


def test_geojson_and_load_dispatch(tmp_path):
    poly = bd.polygon([(0, 0), (10, 0), (10, 10), (0, 10)], holes=[[(2, 2), (3, 2), (3, 3)]])
    path = tmp_path / "b.geojson"
    path.write_text(json.dumps({"type": "Feature", "geometry": shapely.geometry.mapping(poly)}))
    g = bd.load(path)
    assert g.area == pytest.approx(poly.area)
    svg = _svg(tmp_path, '<rect x="0" y="0" width="5" height="5"/>')
    assert bd.load(svg).area == pytest.approx(25)
    with pytest.raises(ValueError, match="no options"):
        bd.load(path, tolerance=0.1)


def test_path_syntax_corners():
    # implicit lineto after a relative moveto, compact numbers and arc flags
    (sq,) = bd.path_rings("m10 10 20 0 0 20-20 0z")
    assert shapely.Polygon(sq).area == pytest.approx(400)
    (arc,) = bd.path_rings("M0 0a25,25 0 1,0 50,0z", tolerance=1e-3)
    (compact,) = bd.path_rings("M0 0a25 25 0 1050 0z", tolerance=1e-3)
    assert np.array_equal(arc, compact)
    assert shapely.Polygon(arc).area == pytest.approx(math.pi * 625 / 2, rel=1e-4)
    (dots,) = bd.path_rings("M0,0L1.5.5.5-1z")  # "1.5.5" is 1.5 then .5
    assert dots.tolist() == [[0, 0], [1.5, 0.5], [0.5, -1]]
    with pytest.raises(ValueError, match="arc flag"):
        bd.path_rings("M0 0 A 5 5 0 2 0 10 0")
    with pytest.raises(ValueError, match="start with a command"):
        bd.path_rings("10 10")


def test_path_lines_keep_open_paths_open():
    lines = bd.path_lines("M0 0 L10 0 L10 10 M20 0 h5 v5 z")
    assert [ln.tolist() for ln in lines] == [
        [[0, 0], [10, 0], [10, 10]],
        [[20, 0], [25, 0], [25, 5], [20, 0]],
    ]


def test_curves_from_svg_drive_a_curve_attractor(tmp_path):
    from voroforge.design.attractors import CurveAttractor

    body = (
        '<path d="M0 50 C50 0 150 100 200 50"/>'
        '<line x1="0" y1="90" x2="200" y2="90"/>'
        '<polyline points="0,10 100,10 100,0"/>'
        '<circle cx="100" cy="50" r="5"/>'
    )
    curves = bd.curves_from_svg(_svg(tmp_path, body), tolerance=1e-3)
    assert curves.geom_type == "MultiLineString" and len(curves.geoms) == 4
    # flipped inside the 100-high viewBox: the line y=90 becomes y=10
    assert shapely.Point(50, 10).distance(curves) == pytest.approx(0, abs=1e-9)
    assert curves.geoms[3].length == pytest.approx(2 * math.pi * 5, rel=1e-4)
    a = CurveAttractor(curves, radius=5.0, falloff="linear")
    assert a(np.array([[50.0, 10.0], [50.0, 12.5]])) == pytest.approx([1.0, 0.5])
