"""Fabrication outputs and checks: DXF with true arcs, layered SVG, the fabrication report."""

import math
import xml.etree.ElementTree as ET

import ezdxf
import numpy as np
import pytest
import shapely
from ezdxf.math import bulge_to_arc
from hypothesis import given
from hypothesis import strategies as st

from voroforge.io.dxf import arc_runs, ring_bulges, write_dxf
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
