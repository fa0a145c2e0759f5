"""QA regressions for the design layer: bugs found by using it as designers and fabricators do."""

import xml.etree.ElementTree as ET

import ezdxf
import numpy as np
import pytest
import shapely

from voroforge.design.fabrication import kerf
from voroforge.design.pipeline import build

SVG = "{http://www.w3.org/2000/svg}"


def _dxf_rings(path):
    """Layer, vertices (k, 2) and bulges (k,) of every LWPOLYLINE of a DXF file."""
    out = []
    for e in ezdxf.readfile(path).modelspace().query("LWPOLYLINE"):
        xyb = np.asarray([p[:3] for p in e.get_points("xyb")], dtype=np.float64)
        out.append((e.dxf.layer, xyb[:, :2], xyb[:, 2]))
    return out


def test_kerf_grows_the_outline_on_a_cut_layer(tmp_path):
    # Cutting the openings and the outline (a common layer set-up): with a kerf the holes
    # shrink by kerf/2 and the outline must grow by kerf/2, like the frame's outline does.
    design = {
        "boundary": {"width": 100, "height": 50},
        "seeds": {"method": "grid", "spacing": 25},
        "cells": {"web": 4},
        "output": {
            "formats": ["dxf", "svg"],
            "kerf": 0.2,
            "layers": {"CUT": ["openings", "boundary"], "SCORE": "frame"},
        },
    }
    dxf, svg = build(design, tmp_path)
    boxes = {layer: [] for layer in ("CUT", "SCORE")}
    for layer, xy, _ in _dxf_rings(dxf):
        boxes[layer].append(shapely.Polygon(xy).bounds)
    outline = (-0.1, -0.1, 100.1, 50.1)
    assert any(np.allclose(b, outline) for b in boxes["CUT"])
    assert any(np.allclose(b, outline) for b in boxes["SCORE"])
    assert not any(np.allclose(b, (0, 0, 100, 50)) for b in boxes["CUT"])
    # The SVG page holds the compensated outline (it used to stick out of the viewBox).
    root = ET.parse(svg).getroot()
    x, y, w, h = map(float, root.get("viewBox").split())
    assert (x, y, w, h) == pytest.approx((-0.1, -50.1, 100.2, 50.2))
    assert root.get("width") == "100.2mm"
    for p in root.iter(f"{SVG}path"):
        nums = np.asarray(
            [
                float(t)
                for t in p.get("d")
                .replace("M", " ")
                .replace("L", " ")
                .replace("Z", " ")
                .replace(",", " ")
                .split()
            ]
        ).reshape(-1, 2)
        assert (nums[:, 0] >= x - 1e-9).all() and (nums[:, 0] <= x + w + 1e-9).all()
        assert (nums[:, 1] >= y - 1e-9).all() and (nums[:, 1] <= y + h + 1e-9).all()


def test_kerf_keeps_rounded_corners_as_true_dxf_arcs(tmp_path):
    # A panel with rounded corners and a kerf: the compensated corners are still circular
    # arcs (bulges), not hundreds of short segments from round offset joins.
    design = {
        "boundary": {"width": 120, "height": 80, "corner_radius": 12},
        "seeds": {"method": "grid", "spacing": 200},
        "output": {"formats": ["dxf"], "kerf": 0.15, "layers": {"CUT": "boundary"}},
    }
    (dxf,) = build(design, tmp_path)
    ((_, xy, bulge),) = _dxf_rings(dxf)
    assert (np.abs(bulge) > 0).sum() >= 4  # one arc per corner at least
    assert len(xy) < 40
    assert shapely.Polygon(xy).bounds == pytest.approx((-0.075, -0.075, 120.075, 80.075))


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


@pytest.mark.parametrize(
    "seeds", [{"method": "random", "count": 1}, {"method": "grid", "spacing": 500}]
)
def test_one_seed_gives_one_opening(tmp_path, seeds):
    # count = 1 (allowed by the schema) or a lattice coarser than the panel: one cell, the
    # whole domain; it used to be refused with "need 2 or more".
    design = {
        "boundary": {"width": 120, "height": 80},
        "seeds": seeds,
        "cells": {"web": 4},
        "output": {"formats": ["dxf", "geojson"]},
    }
    dxf, _ = build(design, tmp_path)
    rings = sorted(shapely.Polygon(xy).bounds for _, xy, _ in _dxf_rings(dxf))
    assert np.allclose(rings, [(0, 0, 120, 80), (2, 2, 118, 78)])


def test_no_seed_inside_is_a_design_error(tmp_path):
    from voroforge.design.schema import DesignError

    design = {
        "boundary": {"width": 10, "height": 10},
        "seeds": {"method": "grid", "spacing": 500, "offset": [100, 100]},
    }
    with pytest.raises(DesignError, match="seeds: no seeds"):
        build(design, tmp_path)


BASE = '[boundary]\nwidth = 100\nheight = 80\n[seeds]\nmethod = "random"\ncount = 20\n'


@pytest.mark.parametrize(
    "extra, where, message",
    [
        # a negative seed used to be reported as "seeds: expected non-negative integer"
        ("[design]\nseed = -1\n", "8: design.seed", "greater than or equal to 0"),
        (
            "[openings]\nselect = 'random'\nprobability = 0.5\nseed = -2\n",
            "10: openings.seed",
            "greater than or equal to 0",
        ),
        # graded numbers of the wrong type: name what is expected
        ("[cells]\nweb = true\n", "8: cells.web", "expected a number or { near = ..., far = ... }"),
        ("[cells]\nfillet = [1, 2]\n", "8: cells.fillet", "expected a number or {"),
        # a key given twice on the last line: tomllib says "at end of document", no line
        ("[cells]\nweb = 1\nweb = 2", "9: (top level)", "TOML syntax: Cannot overwrite a value"),
        # a bad GIF sweep value: the file and the line of output.gif.key, not "<design>"
        (
            "[output]\nformats = ['gif']\n[output.gif]\nkey = 'cells.web'\nvalues = [1, -2]\n",
            "10: output.gif.key",
            "cells.web = -2: cells.web: must be >= 0",
        ),
    ],
)
def test_design_errors_name_file_line_and_key(tmp_path, capsys, extra, where, message):
    from voroforge.cli import main

    path = tmp_path / "bad.toml"
    path.write_text(BASE + extra, encoding="utf-8")
    rc = main(["build", str(path), "-o", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert rc == 2
    assert err.startswith(f"voroforge: error: {path}:{where}: "), err
    assert message in err and "(from --set)" not in err and "Traceback" not in err


def test_subdivide_does_not_launch_the_parallel_area_kernel_per_cell(monkeypatch):
    # Recursion builds one small diagram per cell; Diagram.areas runs a numba parallel
    # kernel whose thread wake-up cost ~10 ms a call on a busy machine (a depth-3 design
    # took 15 s instead of 1 s). The tiling guard uses shapely's areas of the built cells.
    import voroforge.engine.voronoi as engine
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


def test_geojson_output_keeps_the_input_crs(tmp_path):
    # Projected (UTM) GeoJSON from QGIS carries a "crs" member; dropping it on output makes
    # GIS tools read the service areas as lon/lat, thousands of km away from the input.
    import json

    crs = {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32633"}}
    district = {
        "type": "FeatureCollection",
        "crs": crs,
        "features": [
            {
                "type": "Feature",
                "properties": {},
                "geometry": {
                    "type": "Polygon",
                    "coordinates": [
                        [[500000, 4100000], [510000, 4100000], [505000, 4108000], [500000, 4100000]]
                    ],
                },
            }
        ],
    }
    (tmp_path / "district.geojson").write_text(json.dumps(district))
    design = tmp_path / "d.toml"
    design.write_text(
        '[design]\nunits = "m"\n[boundary]\nshape = "file"\nfile = "district.geojson"\n'
        '[seeds]\ncount = 5\n[output]\nformats = ["geojson"]\n'
    )
    (out,) = build(design, tmp_path / "out")
    data = json.loads(out.read_text())
    assert data["crs"] == crs and len(data["features"]) == 5
    # Without a crs in the input, none is written (RFC 7946: WGS 84).
    (plain,) = build(
        {
            "boundary": {"width": 10, "height": 10},
            "seeds": {"count": 3},
            "output": {"formats": ["geojson"]},
        },
        tmp_path / "plain",
    )
    assert "crs" not in json.loads(plain.read_text())


def test_design_file_encodings(tmp_path, capsys):
    from voroforge.cli import main

    # Windows Notepad's UTF-8 with a BOM builds (tomllib alone says "Invalid statement"),
    # and build-time errors still find their lines.
    bom = tmp_path / "bom.toml"
    bom.write_bytes(b"\xef\xbb\xbf" + BASE.encode() + b"[cells]\nweb = 2\n")
    assert main(["build", str(bom), "-o", str(tmp_path / "o")]) == 0
    bad = tmp_path / "bom2.toml"
    bad.write_bytes(
        b'\xef\xbb\xbf[boundary]\nshape = "file"\nfile = "none.svg"\n[seeds]\ncount = 3\n'
    )
    assert main(["build", str(bad)]) == 2
    assert f"{bad}:3: boundary.file: file not found" in capsys.readouterr().err
    # Latin-1 text: the file, the line and what to do, not a bare codec message.
    latin = tmp_path / "latin.toml"
    latin.write_bytes(BASE.encode() + b"# caf\xe9\n")
    assert main(["build", str(latin)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"voroforge: error: {latin}:7: ") and "UTF-8" in err


def test_jittered_seeds_follow_the_documented_offset():
    # seeds.offset ("lattice shift") was silently ignored for method = "jittered".
    from voroforge.design import populate
    from voroforge.design.pipeline import compute
    from voroforge.design.schema import load

    box = shapely.box(0, 0, 100, 60)
    plain = populate.grid(box, 10, offset=(3, 4))
    still = populate.jittered(box, 10, jitter=0.0, seed=1, offset=(3, 4))
    assert np.allclose(np.sort(still, axis=0), np.sort(plain, axis=0))
    seeds = {"method": "jittered", "spacing": 10, "jitter": 0.0, "offset": [3, 4]}
    design, base = load({"boundary": {"width": 100, "height": 60}, "seeds": seeds})
    sites = compute(design, base).sites
    assert np.allclose(np.sort(sites, axis=0), np.sort(plain, axis=0))


def test_seed_file_errors_name_seeds_file(tmp_path):
    from voroforge.design.schema import DesignError

    (tmp_path / "pts.csv").write_text("10,10\n20,abc\n")
    (tmp_path / "d.toml").write_text(
        '[boundary]\nwidth = 60\nheight = 60\n[seeds]\nmethod = "file"\nfile = "pts.csv"\n'
    )
    with pytest.raises(DesignError, match=r"d\.toml:6: seeds\.file: .*'abc' is not a number"):
        build(tmp_path / "d.toml", tmp_path / "out")


@pytest.mark.parametrize("units, width", [("mm", "0.01"), ("cm", "0.001"), ("in", "0.000394")])
def test_svg_default_stroke_is_a_hairline_in_any_units(tmp_path, units, width):
    # The default stroke was 0.01 *units*: 0.254 mm in an inch design, which laser drivers
    # (hairline <= 0.001 in) engrave instead of cutting.
    design = {
        "design": {"units": units},
        "boundary": {"width": 10, "height": 8},
        "seeds": {"count": 4},
        "cells": {"web": 0.5},
        "output": {"formats": ["svg"]},
    }
    (svg,) = build(design, tmp_path)
    root = ET.parse(svg).getroot()
    assert root.get("width") == f"10{units}"
    assert {g.get("stroke-width") for g in root.iter(f"{SVG}g")} == {width}
    design["output"]["stroke_width"] = 0.2
    (svg,) = build(design, tmp_path / "given")
    assert {g.get("stroke-width") for g in ET.parse(svg).getroot().iter(f"{SVG}g")} == {"0.2"}


def test_corner_radius_of_half_the_side_makes_a_stadium(tmp_path):
    # width 100, height 80, corner_radius 40: a pill shape, refused as "too large" because
    # GEOS drops the degenerate core of the rounding; 40.1 is still refused.
    from voroforge.design.pipeline import compute
    from voroforge.design.schema import DesignError, load

    for width in (100, 80):  # a stadium and a disc
        b = {"width": width, "height": 80, "corner_radius": 40}
        design, base = load({"boundary": b, "seeds": {"count": 5}})
        outline = compute(design, base).boundary
        assert outline.bounds == pytest.approx((0, 0, width, 80))
        core = shapely.LineString([(40, 40), (width - 40, 40)]) if width > 80 else None
        exact = (core if core is not None else shapely.Point(40, 40)).buffer(40, quad_segs=64)
        assert outline.hausdorff_distance(exact) < 0.05  # 16 segments per quarter circle
    with pytest.raises(DesignError, match="corner_radius: 40.1 is too large"):
        load_and = load(
            {"boundary": {"width": 100, "height": 80, "corner_radius": 40.1}, "seeds": {"count": 5}}
        )
        compute(*load_and)


@pytest.mark.parametrize("units, size", [("mm", 609.6), ("cm", 60.96), ("in", 24.0)])
def test_svg_files_are_read_in_the_design_units(tmp_path, units, size):
    # An SVG with width="24in" is read in mm; in a cm or inch design it was used as if the
    # mm numbers were design units (a 24 in panel came out 609.6 in wide).
    from voroforge.design.pipeline import compute
    from voroforge.design.schema import load

    svg = (
        '<svg xmlns="http://www.w3.org/2000/svg" width="24in" height="12in" '
        'viewBox="0 0 24 12"><rect x="0" y="0" width="24" height="12"/>'
        '<path d="M 2 6 L 22 6" fill="none"/></svg>'
    )
    (tmp_path / "panel.svg").write_text(svg)
    design, base = load(
        {
            "design": {"units": units},
            "boundary": {"shape": "file", "file": str(tmp_path / "panel.svg")},
            "seeds": {"count": 4},
            "attractors": [{"type": "curve", "file": str(tmp_path / "panel.svg"), "radius": 1}],
            "cells": {"web": {"near": 0, "far": 0}},
        }
    )
    r = compute(design, base)
    assert r.boundary.bounds == pytest.approx((0, 0, size, size / 2))
    # the curve attractor (the outline and the midline) is in the same units: field 1 on it
    from voroforge.design.pipeline import _field

    field = _field(design, base)
    assert field(np.array([[size / 2, size / 4]]))[0] == pytest.approx(1.0)


def test_build_warns_about_an_empty_cut_layer(tmp_path, capsys):
    # No web: the openings tile the boundary, the frame is empty and the SVG/DXF cut
    # nothing, silently. The CLI now says so (and still builds).
    from voroforge.cli import main

    path = tmp_path / "d.toml"
    path.write_text(BASE + '[output]\nformats = ["svg"]\n')
    assert main(["build", str(path), "-o", str(tmp_path / "o")]) == 0
    err = capsys.readouterr().err
    assert err.startswith(f"voroforge: warning: {path}: output.layers.CUT: the layer is empty")
    assert "cells.web" in err
    path.write_text(BASE + '[cells]\nweb = 2\n[output]\nformats = ["svg"]\n')
    assert main(["build", str(path), "-o", str(tmp_path / "o")]) == 0
    assert capsys.readouterr().err == ""


def test_periodic_tile_check_looks_across_the_seams():
    # A tileable pattern is cut as copies side by side: openings cut by the tile's edge are
    # not "0 mm from the outline" (29 false web violations on the lamp-tile example).
    from voroforge.design.pipeline import check_design

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


@pytest.mark.parametrize(
    "extra, where, message",
    [
        # 'cut' and 'CUT' both became layer CUT: the frame was silently dropped
        ('[output]\nlayers = { cut = "frame", CUT = "edges" }\n', "8: output.layers", "same layer"),
        # a DXF-invalid name failed late with "invalid DXF layer name" and no file or key
        ('[output]\nlayers = { "a/b" = "frame" }\n', "8: output.layers", "not a valid layer"),
        ('[design]\nname = "out/panel"\n', "8: design.name", "without folders"),
    ],
)
def test_layer_and_output_names_are_checked_up_front(tmp_path, capsys, extra, where, message):
    from voroforge.cli import main

    path = tmp_path / "bad.toml"
    path.write_text(BASE + extra, encoding="utf-8")
    assert main(["build", str(path), "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"voroforge: error: {path}:{where}: ") and message in err, err
