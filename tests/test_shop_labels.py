"""Single-stroke cell labels, their legend, and cut-apart pieces (io/labels, build)."""

import csv
import json

import numpy as np
import pytest
import shapely

import voroforge as vf
from test_plotter import duplicate_segments
from voroforge.design.build import build
from voroforge.design.fabrication import pack_pieces
from voroforge.io.labels import GLYPHS, cell_labels, text_lines, text_width


def test_every_glyph_is_single_stroke_inside_its_box_and_distinct():
    shapes = set()
    for c, strokes in GLYPHS.items():
        for s in strokes:
            xy = np.asarray(s, dtype=float)
            assert xy.ndim == 2 and len(xy) >= 2
            assert (xy[:, 0] >= 0).all() and (xy[:, 0] <= 4).all()
            assert (xy[:, 1] >= 0).all() and (xy[:, 1] <= 6).all()
        key = tuple(tuple(map(tuple, s)) for s in strokes)
        assert key not in shapes or c == " ", c
        shapes.add(key)
    assert set("0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ-.# ") <= set(GLYPHS)


def test_text_is_centred_and_sized():
    t = text_lines("1088", 10.0, 20.0, 6.0)
    xmin, ymin, xmax, ymax = t.bounds
    assert ymax - ymin == pytest.approx(6.0) and (ymin + ymax) / 2 == pytest.approx(20.0)
    assert xmax - xmin <= text_width("1088", 6.0) + 1e-9
    assert (xmin + xmax) / 2 == pytest.approx(10.0, abs=0.6)
    assert t.geom_type == "MultiLineString" and len(t.geoms) == 8  # 2 strokes each
    with pytest.raises(ValueError, match="glyph"):
        text_lines("a~", 0, 0, 1)
    with pytest.raises(ValueError, match="height"):
        text_lines("1", 0, 0, 0)


@pytest.mark.parametrize("seed", range(3))
def test_labels_lie_inside_their_cells(seed):
    pts = np.random.default_rng(seed).random((80, 2)) * 100
    d = vf.voronoi(pts, (0, 0, 100, 100))
    cells = np.asarray(d.cells, dtype=object)
    cells[5] = shapely.Polygon()  # an empty cell gets no label
    lines, centres, heights = cell_labels(cells)
    assert lines[5].is_empty and heights[5] == 0 and np.isnan(centres[5]).all()
    for i in np.flatnonzero(heights > 0):
        assert cells[i].contains(lines[i]), i
    capped = cell_labels(cells, max_height=1.0)[2]
    assert capped.max() <= 1.0


def test_pack_pieces_keeps_the_gap_and_the_width():
    parts = [shapely.box(0, 0, w, h) for w, h in [(10, 5), (4, 8), (7, 7), (30, 2), (3, 3)]]
    shift = pack_pieces(parts, width=25.0, gap=1.5)
    moved = [
        shapely.transform(p, lambda xy, d=d: xy + d) for p, d in zip(parts, shift, strict=True)
    ]
    for i in range(len(moved)):
        for j in range(i + 1, len(moved)):
            assert moved[i].distance(moved[j]) >= 1.5 - 1e-9
    assert all(m.bounds[2] <= 30 + 1e-9 for m in moved)  # the 30-wide one has its own row
    assert np.allclose([m.area for m in moved], [p.area for p in parts])


def test_build_writes_labels_legend_and_pieces(tmp_path):
    design = {
        "design": {"name": "m"},
        "boundary": {"shape": "rectangle", "width": 120, "height": 80},
        "seeds": {"method": "random", "count": 25},
        "output": {
            "formats": ["svg", "dxf"],
            "layers": {"CUT": "cells", "ENGRAVE": "labels"},
            "pieces": True,
        },
    }
    paths = {p.name: p for p in build(design, tmp_path)}
    assert set(paths) >= {
        "m.svg",
        "m.dxf",
        "m-labels.csv",
        "m-labels.json",
        "m-pieces.svg",
        "m-pieces.dxf",
    }
    rows = list(csv.DictReader(paths["m-labels.csv"].open()))
    assert [r["label"] for r in rows] == [str(i) for i in range(25)]
    assert json.loads(paths["m-labels.json"].read_text())[3]["cell"] == 3
    assert (
        duplicate_segments(paths["m.dxf"]) == 0 and duplicate_segments(paths["m-pieces.dxf"]) == 0
    )
    import ezdxf

    msp = ezdxf.readfile(paths["m-pieces.dxf"]).modelspace()
    cut = [e for e in msp.query("LWPOLYLINE[layer=='CUT']")]
    assert len(cut) == 25 and all(e.closed for e in cut)  # each piece its own closed part
    polys = [shapely.Polygon([p[:2] for p in e.get_points()]) for e in cut]
    assert sum(p.area for p in polys) == pytest.approx(120 * 80, rel=1e-9)
    assert shapely.union_all(polys).area == pytest.approx(120 * 80, rel=1e-9)  # apart
    assert len(msp.query("LWPOLYLINE[layer=='ENGRAVE']")) > 0
