"""Fabrication outputs and checks: DXF with true arcs, layered SVG, the fabrication report."""

import math
import re
import warnings
import xml.etree.ElementTree as ET

import ezdxf
import numpy as np
import pytest
import shapely
from ezdxf.math import bulge_to_arc
from hypothesis import given
from hypothesis import strategies as st

from voroforge import config
from voroforge.io.arcs import arc_runs, ring_bulges
from voroforge.io.dxf import write_dxf
from voroforge.io.svg import write_layers

SVG = "{http://www.w3.org/2000/svg}"
INKSCAPE = "{http://www.inkscape.org/namespaces/inkscape}"


def rounded_rect(w, h, r, quad_segs=8):
    """A w x h rectangle at the origin with corners rounded to radius r (shapely chords)."""
    return shapely.box(r, r, w - r, h - r).buffer(r, quad_segs=quad_segs)


def exact_rounded_rect_area(w, h, r):
    return w * h - (4.0 - math.pi) * r * r


def bulge_ring_area(points):
    """Exact area of a closed bulge polyline: shoelace of the vertices plus circular segments.

    A slow, obvious reference: every arc adds (or removes) the segment between its chord and
    the arc, R^2 / 2 * (theta - sin theta), with the sign of the bulge.
    """
    area = 0.0
    n = len(points)
    for i in range(n):
        x0, y0, b = points[i]
        x1, y1, _ = points[(i + 1) % n]
        area += 0.5 * (x0 * y1 - x1 * y0)
        if b:
            theta = 4.0 * math.atan(b)
            chord = math.hypot(x1 - x0, y1 - y0)
            radius = chord / (2.0 * math.sin(abs(theta) / 2.0))
            area += math.copysign(0.5 * radius**2 * (abs(theta) - math.sin(abs(theta))), theta)
    return abs(area)


def flatten_lwpolyline(e, step=0.0087):
    """Points of an LWPOLYLINE with its arcs sampled finely, via ezdxf's bulge_to_arc."""
    pts = list(e.get_points("xyb"))
    out = []
    for i, (x, y, b) in enumerate(pts):
        x1, y1, _ = pts[(i + 1) % len(pts)]
        out.append((x, y))
        if b:
            centre, a0, a1, radius = bulge_to_arc((x, y), (x1, y1), b)
            sweep = (a1 - a0) % (2 * math.pi)
            k = max(2, int(sweep / step))
            angles = a0 + sweep * np.arange(1, k) / k
            if b < 0:  # ezdxf reports the arc counter-clockwise from end to start
                angles = angles[::-1]
            out += [
                (centre.x + radius * math.cos(a), centre.y + radius * math.sin(a)) for a in angles
            ]
    return shapely.Polygon(out)


# --- arc detection ----------------------------------------------------------------------


def test_filleted_square_has_exactly_four_arcs(tmp_path):
    part = rounded_rect(40.0, 40.0, 2.0)
    out = write_dxf([part], tmp_path / "p.dxf")
    doc = ezdxf.readfile(out)
    entities = list(doc.modelspace())
    assert len(entities) == 1
    e = entities[0]
    assert e.dxftype() == "LWPOLYLINE" and e.closed and e.dxf.layer == "CUT"
    pts = list(e.get_points("xyb"))
    assert sum(1 for p in pts if p[2] != 0) == 4
    assert len(pts) == 8  # four straight sides and four arcs
    for p in pts:
        if p[2]:
            assert abs(4 * math.atan(p[2])) == pytest.approx(math.pi / 2, abs=1e-9)
    exact = exact_rounded_rect_area(40.0, 40.0, 2.0)
    assert bulge_ring_area(pts) == pytest.approx(exact, rel=1e-12)
    assert flatten_lwpolyline(e).area == pytest.approx(exact, rel=1e-5)
    # The chords shapely drew differ from the arcs by at most their sagitta area.
    sagitta_area = 4 * 8 * 0.5 * 4.0 * (math.pi / 16 - math.sin(math.pi / 16))
    assert exact - part.area == pytest.approx(sagitta_area, rel=1e-9)


def test_regular_polygons_stay_polygons():
    for sides in (3, 4, 6, 8):
        a = 2 * math.pi * np.arange(sides) / sides
        xy = np.column_stack((np.cos(a), np.sin(a))) * 10
        assert arc_runs(xy) == []
    # A circle (many equal chords) becomes two half arcs.
    circle = np.asarray(shapely.Point(5, 5).buffer(3, quad_segs=16).exterior.coords)[:-1]
    runs = arc_runs(circle)
    assert len(runs) == 2 and sum(c for _, c, _ in runs) == len(circle)
    assert sum(s for *_, s in runs) == pytest.approx(-2 * math.pi)  # shapely draws clockwise


def test_non_circular_equal_turn_run_is_not_an_arc():
    # An Archimedean-like spiral piece: equal turning but growing chords -> not an arc.
    t = np.linspace(0, 1.0, 12)
    spiral = np.column_stack(((5 + 3 * t) * np.cos(t), (5 + 3 * t) * np.sin(t)))
    ring = np.vstack((spiral, [[0.0, 0.0]]))
    assert all(c < 3 for _, c, _ in arc_runs(ring))
    bul = ring_bulges(ring)
    assert len(bul) == len(ring) and all(b == 0 for *_, b in bul)


@pytest.mark.parametrize("quad_segs", [4, 8, 16])
def test_fillets_with_holes_round_trip_area(tmp_path, quad_segs):
    outer = rounded_rect(100.0, 60.0, 5.0, quad_segs)
    hole = shapely.box(20, 20, 50, 40).buffer(3.0, quad_segs=quad_segs)
    part = outer.difference(hole)
    out = write_dxf(None, tmp_path / "h.dxf", layers={"cut": [part], "score": [hole.boundary]})
    doc = ezdxf.readfile(out)
    assert doc.header["$INSUNITS"] == 4
    assert doc.dxfversion >= "AC1015"
    closed = [e for e in doc.modelspace() if e.dxf.layer == "CUT"]
    assert all(e.dxftype() == "LWPOLYLINE" and e.closed for e in closed)
    assert len(closed) == 2
    arcs = [sum(1 for p in e.get_points("xyb") if p[2]) for e in closed]
    assert sorted(arcs) == [4, 4]
    areas = sorted(bulge_ring_area(list(e.get_points("xyb"))) for e in closed)
    exact_hole = 30 * 20 + 2 * 3 * (30 + 20) + math.pi * 9
    assert areas[0] == pytest.approx(exact_hole, rel=1e-12)
    assert areas[1] == pytest.approx(exact_rounded_rect_area(100, 60, 5), rel=1e-12)
    score = [e for e in doc.modelspace() if e.dxf.layer == "SCORE"]
    assert len(score) == 1 and not score[0].closed
    assert {layer.dxf.name for layer in doc.layers} >= {"CUT", "SCORE"}


def test_dxf_is_byte_identical_and_keeps_input(tmp_path):
    cells = [rounded_rect(10, 10, 1).buffer(0), shapely.box(20, 0, 30, 10)]
    before = [c.wkb for c in cells]
    a = write_dxf(cells, tmp_path / "a.dxf").read_bytes()
    b = write_dxf(cells, tmp_path / "b.dxf").read_bytes()
    assert a == b
    assert [c.wkb for c in cells] == before


def test_dxf_bad_arguments(tmp_path):
    with pytest.raises(ValueError, match="units"):
        write_dxf([shapely.box(0, 0, 1, 1)], tmp_path / "x.dxf", units="furlong")
    with pytest.raises(ValueError, match="R2000"):
        write_dxf([shapely.box(0, 0, 1, 1)], tmp_path / "x.dxf", version="R12")
    with pytest.raises(ValueError, match="layer"):
        write_dxf([shapely.box(0, 0, 1, 1)], tmp_path / "x.dxf", layer="a/b")
    with pytest.raises(ValueError, match="not a shapely geometry"):
        write_dxf([1.0], tmp_path / "x.dxf")


@given(
    w=st.floats(10, 500),
    h=st.floats(10, 500),
    frac=st.floats(0.02, 0.45),
    quad=st.integers(3, 24),
    x0=st.floats(-1e5, 1e5),
)
def test_rounded_rectangles_anywhere_give_four_exact_arcs(tmp_path_factory, w, h, frac, quad, x0):
    r = frac * min(w, h)
    part = shapely.affinity.translate(rounded_rect(w, h, r, quad), x0, -x0 / 3)
    xy = np.asarray(part.exterior.coords)[:-1]
    pts = ring_bulges(xy, tolerance=1e-6 * max(1.0, abs(x0)))
    assert sum(1 for p in pts if p[2]) == 4
    assert bulge_ring_area(pts) == pytest.approx(exact_rounded_rect_area(w, h, r), rel=1e-6)


# --- layered SVG ------------------------------------------------------------------------


def test_layered_svg_is_mm_with_one_closed_path_per_ring(tmp_path):
    part = rounded_rect(600.0, 400.0, 10.0).difference(shapely.box(100, 100, 200, 150))
    parts = [part, shapely.box(300, 200, 350, 250)]
    edges = shapely.MultiLineString([[(0, 0), (50, 50)], [(60, 60), (70, 10)]])
    out = write_layers(tmp_path / "l.svg", {"CUT": parts, "SCORE": [edges], "ENGRAVE": []})
    root = ET.parse(out).getroot()
    assert root.get("width") == "600mm" and root.get("height") == "400mm"
    assert [float(v) for v in root.get("viewBox").split()] == [0.0, -400.0, 600.0, 400.0]
    groups = {g.get("id"): g for g in root.iter(SVG + "g")}
    assert list(groups) == ["CUT", "SCORE", "ENGRAVE"]
    for g in groups.values():
        assert g.get(INKSCAPE + "groupmode") == "layer"
        assert float(g.get("stroke-width")) <= 0.01 and g.get("fill") == "none"
    cut = groups["CUT"].findall(SVG + "path")
    assert len(cut) == 3  # outer ring, hole, the separate box
    assert all(p.get("d").startswith("M") and p.get("d").endswith("Z") for p in cut)
    score = groups["SCORE"].findall(SVG + "path")
    assert len(score) == 2 and not any(p.get("d").endswith("Z") for p in score)
    # y is up: the hole at y in [100, 150] is drawn at -y.
    hole = [p.get("d") for p in cut if "100,-150" in p.get("d") or "200,-150" in p.get("d")]
    assert hole


def test_layered_svg_rejects_bad_options(tmp_path):
    with pytest.raises(ValueError, match="units"):
        write_layers(tmp_path / "x.svg", {"CUT": []}, units="parsec")
    with pytest.raises(ValueError, match="stroke_width"):
        write_layers(tmp_path / "x.svg", {"CUT": []}, stroke_width=0)


# --- fabrication check ------------------------------------------------------------------

from voroforge.design.fabrication import check, kerf  # noqa: E402


def slot_panel(web, *, fillet=0.0, width=10.0):
    """A 100 x 40 panel with two square-ish slots `web` apart and 5 mm from the edges."""
    a = shapely.box(5, 5, 5 + width, 35)
    b = shapely.box(5 + width + web, 5, 5 + 2 * width + web, 35)
    if fillet:
        a, b = (g.buffer(-fillet).buffer(fillet, quad_segs=8) for g in (a, b))
    return shapely.box(0, 0, 100, 40), [a, b]


def test_check_finds_thin_web_between_openings_at_the_right_place():
    outline, holes = slot_panel(1.5)
    report = check(openings=holes, boundary=outline, min_web=3.0)
    assert not report.ok
    (v,) = report.violations
    assert v.kind == "web" and v.items == (0, 1)
    assert v.value == pytest.approx(1.5) and v.limit == 3.0
    assert v.location[0] == pytest.approx(15.75) and 5 <= v.location[1] <= 35
    # The frame form gives the same answer.
    frame = outline.difference(shapely.union_all(holes))
    again = check(frame, min_web=3.0)
    assert [(w.kind, round(w.value, 9)) for w in again.violations] == [("web", 1.5)]
    assert "web" in report.table() and "1 violations" in report.table()


def test_check_passes_a_good_panel():
    outline, holes = slot_panel(4.0, fillet=2.5)
    report = check(
        openings=holes, boundary=outline, min_web=3.0, min_opening=5.0, min_inside_radius=2.0
    )
    assert report.ok, report.table()
    assert "no violations" in report.table()


def test_check_web_to_outline_and_overlap():
    outline = shapely.box(0, 0, 50, 50)
    near = shapely.box(1, 10, 20, 20)  # 1 mm from the left edge
    over = shapely.box(40, 40, 55, 45)  # sticks out of the panel
    report = check(openings=[near, over], boundary=outline, min_web=2.0)
    webs = sorted((v.value, v.items) for v in report.violations if v.kind == "web")
    assert webs == [(0.0, (1, -1)), (pytest.approx(1.0), (0, -1))]


def test_check_small_opening_by_inscribed_circle():
    outline = shapely.box(0, 0, 100, 100)
    thin = shapely.box(10, 10, 60, 12)  # long but only 2 mm wide
    big = shapely.Point(70, 70).buffer(10)
    report = check(openings=[thin, big], boundary=outline, min_opening=3.0)
    (v,) = report.violations
    assert v.kind == "opening" and v.items == (0,)
    assert v.value == pytest.approx(2.0, rel=1e-2)
    assert thin.buffer(1e-6).contains(shapely.Point(v.location))


def test_check_sharp_inside_corners_for_a_cnc_tool():
    outline, holes = slot_panel(6.0)  # sharp rectangular slots
    report = check(openings=holes, boundary=outline, min_inside_radius=3.0)
    corners = [v for v in report.violations if v.kind == "corner"]
    assert len(corners) == 8  # four corners per slot
    # the value is the corner's inside radius: a tool of radius t leaves t (sqrt 2 - 1) in a
    # sharp 90 degree corner, so the largest tool within corner_tolerance 0.02 reaches is
    tol = 0.02
    for v in corners:
        step = 3.0 / 2**config.FAB_CORNER_BISECTIONS  # the bisection's resolution
        assert tol / (math.sqrt(2) - 1) - step <= v.value <= tol / (math.sqrt(2) - 1)
        assert v.limit == 3.0 and 0 < v.severity <= 1
        assert (
            min(
                shapely.Point(v.location).distance(shapely.Point(c))
                for h in holes
                for c in h.exterior.coords
            )
            < 1e-9
        )
    # Fillets at least as large as the tool pass; smaller ones do not.
    _, rounded = slot_panel(6.0, fillet=3.0)
    assert check(openings=rounded, boundary=outline, min_inside_radius=3.0).ok
    _, small = slot_panel(6.0, fillet=1.0)
    bad = check(openings=small, boundary=outline, min_inside_radius=3.0).violations
    assert len(bad) == 8 and all(  # a 1 mm fillet: inside radius 1 (+ the tolerance's share)
        v.value == pytest.approx(1.0 + tol / (math.sqrt(2) - 1), rel=2e-2) for v in bad
    )


def test_check_notch_in_outline_is_a_corner():
    outline = shapely.box(0, 0, 60, 40).difference(shapely.box(20, 30, 40, 41))  # notch
    report = check(openings=[], boundary=outline, min_inside_radius=2.0)
    assert sum(v.kind == "corner" and v.items == (-1,) for v in report.violations) == 2


def test_check_finds_islands():
    outline = shapely.box(0, 0, 100, 100)
    ring = shapely.box(20, 20, 80, 80).difference(shapely.box(30, 30, 70, 70))  # a ring cut
    report = check(openings=[ring], boundary=outline)
    (v,) = report.violations
    assert v.kind == "island" and v.value == pytest.approx(1600.0)
    assert shapely.box(30, 30, 70, 70).contains(shapely.Point(v.location))


def test_report_overlays(tmp_path):
    outline, holes = slot_panel(1.0)
    report = check(openings=holes, boundary=outline, min_web=3.0, min_inside_radius=1.0)
    png = report.write_png(tmp_path / "r.png", size=200)
    svg = report.write_svg(tmp_path / "r.svg")
    from PIL import Image

    with Image.open(png) as img:
        px = np.asarray(img.convert("RGB")).reshape(-1, 3)
    assert ((px[:, 0] > 180) & (px[:, 1] < 80)).any()  # red markers drawn
    root = ET.parse(svg).getroot()
    counts = report.counts()
    for kind in ("web", "corner"):  # one layer per kind, one marker (3 strokes) per violation
        (layer,) = [g for g in root.iter(SVG + "g") if g.get("id") == kind.upper()]
        assert len(layer.findall(SVG + "path")) == 3 * counts[kind] > 0
        assert layer.get("vector-effect") == "non-scaling-stroke"
    (legend,) = [g for g in root.iter(SVG + "g") if g.get("id") == "LEGEND"]
    texts = [t.text for t in legend.iter(SVG + "text")]
    assert any("web" in t for t in texts) and any("corner" in t for t in texts)


def test_check_bad_arguments():
    with pytest.raises(ValueError, match="min_web"):
        check(shapely.box(0, 0, 1, 1), min_web=-1)
    with pytest.raises(ValueError, match="boundary"):
        check(openings=[shapely.box(0, 0, 1, 1)])
    with pytest.raises(ValueError, match="either"):
        check(shapely.box(0, 0, 1, 1), openings=[])


def test_kerf_grows_parts_and_shrinks_holes():
    outline, holes = slot_panel(5.0)
    frame = outline.difference(shapely.union_all(holes))
    cut = kerf(frame, 0.2)
    assert cut.exterior.bounds == pytest.approx((-0.1, -0.1, 100.1, 40.1))
    hole_boxes = sorted(shapely.Polygon(r).bounds for r in cut.interiors)
    assert hole_boxes[0] == pytest.approx((5.1, 5.1, 14.9, 34.9))
    shrunk = kerf(holes, 0.2, role="hole")
    assert shrunk[0].bounds == pytest.approx((5.1, 5.1, 14.9, 34.9))
    assert holes[0].bounds == (5.0, 5.0, 15.0, 35.0)  # input untouched
    assert kerf(frame, 0.0) is frame
    with pytest.raises(ValueError, match="kerf"):
        kerf(frame, -1)


# --- properties -------------------------------------------------------------------------


@given(gap=st.floats(0.1, 6.0), limit=st.floats(0.5, 5.0), height=st.floats(5.0, 30.0))
def test_web_violation_iff_gap_below_limit(gap, limit, height):
    outline = shapely.box(-50, -50, 100, 100)
    a = shapely.box(0, 0, 10, height)
    b = shapely.box(10 + gap, 0, 20 + gap, height)
    report = check(openings=[a, b], boundary=outline, min_web=limit)
    webs = [v for v in report.violations if v.kind == "web"]
    if gap < limit * (1 - config.FAB_LIMIT_RTOL) - 100 * config.FAB_LIMIT_COORD_RTOL:
        assert len(webs) == 1 and webs[0].value == pytest.approx(gap)
        assert 10 <= webs[0].location[0] <= 10 + gap
    else:
        assert not webs


@pytest.mark.parametrize("scale", [1e-6, 1e-3, 1.0, 1e3, 1e6])
@pytest.mark.parametrize("offset", [0.0, 5e5])
def test_web_and_opening_limits_are_relative_to_the_limit(scale, offset):
    # A web 0.01% under the limit is a violation at every scale (the slack was 1e-6 drawing
    # units: at 1e-3 it let such webs pass); a web exactly at the limit is not. (1e-4 of a
    # limit of 2e-6 at 5e5 is 2 ulps of the coordinates: below what the check can tell.)
    if scale * 1e-4 < 1e3 * np.spacing(offset):
        pytest.skip("the limit's 1e-4 is a few ulps of the coordinates")
    outline = shapely.box(offset - 50 * scale, -50 * scale, offset + 100 * scale, 100 * scale)
    limit = 2.0 * scale
    for gap, bad in ((limit * (1 - 1e-4), True), (limit, False), (limit * (1 + 1e-4), False)):
        a = shapely.box(offset, 0, offset + 10 * scale, 20 * scale)
        b = shapely.box(offset + 10 * scale + gap, 0, offset + 20 * scale + gap, 20 * scale)
        report = check(openings=[a, b], boundary=outline, min_web=limit)
        webs = [v for v in report.violations if v.kind == "web"]
        assert bool(webs) == bad, (scale, offset, gap)
        small = check(
            openings=[shapely.box(offset, 0, offset + gap, 50 * scale)],
            boundary=outline,
            min_opening=limit,
        )
        assert bool(small.violations) == bad, (scale, offset, gap)


@pytest.mark.parametrize("seed", [1, 2])
def test_filleted_voronoi_openings_round_trip_through_dxf(tmp_path, seed):
    import voroforge as vf
    from voroforge.design import cellops

    rng = np.random.default_rng(seed)
    d = vf.voronoi(rng.uniform(0, 200, (60, 2)), (0, 0, 200, 200))
    holes = cellops.fillet(cellops.inset(d.cells, 1.5), 2.0)
    holes = [h for h in holes if not h.is_empty]
    out = write_dxf(holes, tmp_path / "v.dxf")
    ents = list(ezdxf.readfile(out).modelspace())
    assert len(ents) == sum(len(shapely.get_parts(h)) for h in holes)
    arcs = 0
    parts = [p for hole in holes for p in shapely.get_parts(hole)]
    for e, h in zip(ents, parts, strict=True):
        pts = list(e.get_points("xyb"))
        arcs += sum(1 for p in pts if p[2])
        rebuilt = flatten_lwpolyline(e)
        # The arcs lie on the chords' circles: the outlines differ by at most a sagitta.
        assert shapely.hausdorff_distance(rebuilt.exterior, h.exterior) < 0.01
        assert bulge_ring_area(pts) == pytest.approx(h.area, rel=2e-3)
        assert len(pts) < len(h.exterior.coords) - 1  # arcs replaced runs of chords
    assert arcs >= 3 * len(ents)


def svg_path_area(d):
    """Area enclosed by an SVG path of M/L/A/Z (circular arcs), y flipped back up.

    A slow reference built from the SVG arc rules: the centre of an arc lies on the chord's
    perpendicular bisector, on the side that the large-arc and sweep flags choose.
    """
    import re

    tokens = re.findall(r"[MLAZ]|-?\d+(?:\.\d+)?(?:e-?\d+)?", d)
    pts, i, area, cur = [], 0, 0.0, None
    while i < len(tokens):
        t = tokens[i]
        if t in "ML":
            x, y = float(tokens[i + 1]), -float(tokens[i + 2])
            if cur is not None:
                area += 0.5 * (cur[0] * y - x * cur[1])
            cur = (x, y)
            pts.append(cur)
            i += 3
        elif t == "A":
            r = float(tokens[i + 1])
            large, sweep = int(tokens[i + 4]), int(tokens[i + 5])
            x, y = float(tokens[i + 6]), -float(tokens[i + 7])
            chord = math.hypot(x - cur[0], y - cur[1])
            theta = 2 * math.asin(min(1.0, chord / (2 * r)))
            if large:
                theta = 2 * math.pi - theta
            ccw = sweep == 0  # SVG's y points down: sweep 0 is counter-clockwise in data
            area += 0.5 * (cur[0] * y - x * cur[1])
            area += (1 if ccw else -1) * 0.5 * r * r * (theta - math.sin(theta))
            cur = (x, y)
            i += 8
        else:  # Z
            x, y = pts[0]
            area += 0.5 * (cur[0] * y - x * cur[1])
            i += 1
    return abs(area)


def test_layered_svg_writes_fillets_as_true_arcs(tmp_path):
    part = rounded_rect(120.0, 80.0, 6.0).difference(shapely.box(30, 20, 60, 50).buffer(4.0))
    out = write_layers(tmp_path / "a.svg", {"CUT": [part]})
    paths = [p.get("d") for p in ET.parse(out).getroot().iter(SVG + "path")]
    assert len(paths) == 2 and all(d.count("A") == 4 for d in paths)
    # (coordinates are written to about 1e-7 of the drawing's size, hence rel=1e-6)
    outer, hole = sorted(paths, key=svg_path_area, reverse=True)
    assert svg_path_area(outer) == pytest.approx(exact_rounded_rect_area(120, 80, 6), rel=1e-6)
    exact_hole = 30 * 30 + 4 * 4 * 30 + math.pi * 16
    assert svg_path_area(hole) == pytest.approx(exact_hole, rel=1e-6)
    plain = write_layers(tmp_path / "b.svg", {"CUT": [part]}, arcs=False)
    chords = [p.get("d") for p in ET.parse(plain).getroot().iter(SVG + "path")]
    assert all("A" not in d for d in chords)
    areas = sorted((svg_path_area(d) for d in chords), reverse=True)
    assert areas[0] == pytest.approx(shapely.Polygon(part.exterior).area, rel=1e-6)
    assert areas[1] == pytest.approx(shapely.Polygon(part.interiors[0]).area, rel=1e-6)


def test_inscribed_circles_match_known_shapes_and_the_polylabel_fallback(monkeypatch):
    from voroforge.design import fabrication

    shapes = [shapely.box(0, 0, 10, 4), shapely.Point(5, 5).buffer(3, quad_segs=64)]
    centres, radii = fabrication.inscribed_circles(shapes)
    assert radii == pytest.approx([2.0, 3.0], rel=2e-3)
    assert centres[1] == pytest.approx([5, 5], abs=0.02)
    monkeypatch.delattr(shapely, "maximum_inscribed_circle", raising=False)
    c2, r2 = fabrication.inscribed_circles(shapes)
    assert r2 == pytest.approx(radii, rel=5e-3)
    assert c2[1] == pytest.approx([5, 5], abs=0.05)


# --- folded from test_qa_design.py: bugs found by using the design layer as designers
# and fabricators do


def test_kerf_mitre_is_exact_and_validates_join():
    square = shapely.box(0, 0, 10, 10)
    grown = kerf(square, 0.4)
    assert grown.bounds == pytest.approx((-0.2, -0.2, 10.2, 10.2))
    # A part's straight edges move by exactly kerf / 2; sharp corners stay sharp.
    assert grown.area == pytest.approx(10.4**2)
    assert kerf(square, 0.4, join="round").area < grown.area
    disc = shapely.Point(0, 0).buffer(5, quad_segs=32)
    radii = np.hypot(*shapely.get_coordinates(kerf(disc, 1.0)).T)
    assert np.ptp(radii) < 1e-9  # all vertices on one circle: an arc for the DXF writer
    with pytest.raises(ValueError, match="join"):
        kerf(square, 0.4, join="bevel")


def test_periodic_tile_check_looks_across_the_seams():
    # A tileable pattern is cut as copies side by side: openings cut by the tile's edge are
    # not "0 mm from the outline" (29 false web violations on the lamp-tile example).
    from voroforge.design.build import check_design

    design = {
        "design": {"seed": 3},
        "boundary": {"width": 120, "height": 80},
        "seeds": {"method": "poisson", "radius": 18},
        "voronoi": {"periodic": True},
        "cells": {"web": 3},
        "fabrication": {"min_web": 2.5},
    }
    assert check_design(design).ok
    report = check_design(design, overrides={"fabrication.min_web": 3.5})
    webs = [v for v in report.violations if v.kind == "web"]
    # webs are 3 mm (or a little more, across a vertex), never the seams' false 0
    assert webs and all(3.0 - 1e-6 <= v.value < 3.5 for v in webs)
    assert all(0 <= v.location[0] < 120 and 0 <= v.location[1] < 80 for v in webs)
    # each neighbouring pair once: no two violations at the same spot
    spots = {(round(v.location[0], 6), round(v.location[1], 6)) for v in webs}
    assert len(spots) == len(webs)


def test_design_corner_tolerance_default_is_in_millimetres():
    # checker25 F1: the default 0.02 was drawing units, 20 mm in a design drawn in metres:
    # the same part had 442 corner violations in mm and none in m
    from voroforge.design.build import check_design
    from voroforge.design.designfile import load
    from voroforge.design.fabrication import design_corner_tolerance

    counts = {}
    for units, s in [("mm", 1.0), ("in", 1 / 25.4), ("m", 1e-3)]:
        spec = {
            "design": {"units": units, "seed": 3},
            "boundary": {
                "shape": "rectangle",
                "width": 200 * s,
                "height": 150 * s,
                "margin": 15 * s,
            },
            "seeds": {"method": "poisson", "radius": 38 * s},
            "cells": {"web": 3 * s},
            "fabrication": {"tool_radius": 1.0 * s},
        }
        design = load(spec)[0]
        assert np.isclose(design_corner_tolerance(design), 0.02 * s, rtol=1e-15)
        counts[units] = sum(v.kind == "corner" for v in check_design(spec).violations)
    assert counts["mm"] > 0
    assert max(counts.values()) - min(counts.values()) <= 0.1 * counts["mm"]
    given = load({**spec, "fabrication": {"tool_radius": 1e-3, "corner_tolerance": 0.5}})[0]
    assert design_corner_tolerance(given) == 0.5  # a value given is the design's units


def test_openings_narrower_than_the_kerf_are_named(tmp_path):
    # checker25 F5: a kerf wider than an opening dropped it from the SVG/DXF without a word
    from voroforge.design.build import DesignWarning, build

    spec = {
        "design": {"name": "k", "seed": 2},
        "boundary": {"shape": "rectangle", "width": 100, "height": 60},
        "seeds": {"method": "poisson", "radius": 10},
        "cells": {"web": 3},
        "output": {"formats": ["dxf"], "kerf": 6},
    }
    with pytest.warns(DesignWarning, match=r"output\.kerf: (\d+) of (\d+) openings") as rec:
        (path,) = build(spec, tmp_path / "o")
    lost, total = map(int, re.search(r"(\d+) of (\d+) openings", str(rec[0].message)).groups())
    assert 0 < lost < total
    rings = len(ezdxf.readfile(path).modelspace().query("LWPOLYLINE"))
    assert rings == 1 + total - lost  # the outline and the openings that can be cut
    with warnings.catch_warnings():
        warnings.simplefilter("error", DesignWarning)
        build({**spec, "output": {"formats": ["dxf"], "kerf": 0.2}}, tmp_path / "p")
