"""Every example recipe builds, and its files are what a cutter, plotter or GIS expects."""

import json
import xml.etree.ElementTree as ET
from pathlib import Path

import ezdxf
import pytest
import shapely
from PIL import Image

from test_plotter import duplicate_segments
from voroforge.design.build import build, check_design
from voroforge.design.designfile import load

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = sorted((ROOT / "examples").glob("*.toml"))
SVG = "{http://www.w3.org/2000/svg}"
INKSCAPE = "{http://www.inkscape.org/namespaces/inkscape}"


def test_there_are_at_least_eight_examples_each_with_a_gallery_png():
    assert len(EXAMPLES) >= 8
    for design in EXAMPLES:
        png = ROOT / "docs" / "gallery" / f"{design.stem}.png"
        assert png.exists(), f"run examples/gallery.py: {png.name} is missing"
        assert png.stat().st_size < 300_000
        assert f"docs/gallery/{design.stem}.png" in (ROOT / "README.md").read_text()


@pytest.mark.parametrize("design_file", EXAMPLES, ids=[e.stem for e in EXAMPLES])
def test_example_builds_and_reads_back(tmp_path, design_file):
    design, _ = load(design_file)
    paths = build(design_file, tmp_path)
    formats = design.output.formats
    assert [p.suffix[1:] for p in paths[: len(formats)]] == formats
    layers = {name.upper() for name in design.output.layers}
    for path in paths:
        assert path.exists() and path.stat().st_size > 0
        kind = path.suffix
        if kind == ".dxf":
            doc = ezdxf.readfile(path)
            assert (
                doc.header["$INSUNITS"] == {"mm": 4, "cm": 5, "m": 6, "in": 1}[design.design.units]
            )
            ents = list(doc.modelspace())
            assert ents
            for e in ents:
                assert e.dxf.layer in layers
                if e.dxftype() == "LWPOLYLINE" and design.output.layers.get(e.dxf.layer) != "edges":
                    assert e.closed
            # no line is cut twice: zero duplicate (or overlapping) segments on every layer
            assert duplicate_segments(path) == 0
        elif kind == ".svg":
            root = ET.parse(path).getroot()
            assert root.get("width").endswith(design.design.units)
            assert root.get("height").endswith(design.design.units)
            vb = [float(v) for v in root.get("viewBox").split()]
            assert vb[2] == pytest.approx(float(root.get("width")[:-2]))
            groups = [g for g in root.iter(SVG + "g") if g.get(INKSCAPE + "groupmode") == "layer"]
            assert {g.get("id") for g in groups} == layers
            assert sum(len(g.findall(SVG + "path")) for g in groups) > 0
        elif kind == ".png":
            with Image.open(path) as img:
                assert img.format == "PNG" and max(img.size) >= 100
        elif kind == ".gif":
            with Image.open(path) as img:
                assert img.format == "GIF" and img.n_frames >= 2
        elif kind == ".geojson":
            feats = json.loads(path.read_text())["features"]
            assert feats and all(f["geometry"] for f in feats)


def test_laser_panel_is_the_brief():
    design, _ = load(ROOT / "examples" / "laser-panel.toml")
    assert (design.boundary.width, design.boundary.height) == (600, 400)
    assert design.cells.web.value == 3 and design.cells.fillet.value == 2
    assert check_design(ROOT / "examples" / "laser-panel.toml").ok


def test_cnc_divider_passes_its_tool_and_fails_with_small_fillets():
    cnc = ROOT / "examples" / "cnc-divider.toml"
    assert check_design(cnc).ok
    report = check_design(cnc, overrides={"cells.fillet": 1.0})
    assert report.counts()["corner"] > 10


def test_service_areas_cover_the_district(tmp_path):
    design_file = ROOT / "examples" / "service-areas.toml"
    (gj, _) = build(design_file, tmp_path)
    feats = json.loads(gj.read_text())["features"]
    stations = json.loads((ROOT / "examples" / "data" / "stations.geojson").read_text())["features"]
    assert len(feats) == len(stations)
    district = shapely.from_geojson((ROOT / "examples" / "data" / "district.geojson").read_text())
    district = shapely.union_all(shapely.get_parts(district))
    cells = [shapely.geometry.shape(f["geometry"]) for f in feats]
    assert sum(c.area for c in cells) == pytest.approx(district.area, rel=1e-9)
    # Each station lies in its own service area, and coordinates stay in metres.
    for f, s in zip(feats, stations, strict=True):
        pt = shapely.Point(s["geometry"]["coordinates"])
        assert shapely.geometry.shape(f["geometry"]).buffer(1e-6).contains(pt)
        assert f["properties"]["name"] == s["properties"]["name"]  # carried from the input
        assert f["properties"]["site"] == s["geometry"]["coordinates"]
        assert f["properties"]["area"] == pytest.approx(shapely.geometry.shape(f["geometry"]).area)
    assert 490_000 < cells[0].centroid.x < 520_000 and 4_170_000 < cells[0].centroid.y < 4_195_000


def test_rebuild_in_a_fresh_process_is_byte_identical(tmp_path):
    import os
    import subprocess
    import sys

    design_file = ROOT / "examples" / "lamp-tile.toml"  # SVG, DXF, PNG and GIF
    here = build(design_file, tmp_path / "a")
    env = {**os.environ, "PYTHONHASHSEED": "12345"}
    run = subprocess.run(
        [sys.executable, "-m", "voroforge", "build", str(design_file), "-o", str(tmp_path / "b")],
        capture_output=True,
        text=True,
        timeout=120,
        env=env,
    )
    assert run.returncode == 0, run.stderr
    assert [Path(p).name for p in run.stdout.split()] == [p.name for p in here]
    for p in here:
        assert (tmp_path / "b" / p.name).read_bytes() == p.read_bytes(), p.name
