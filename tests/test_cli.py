"""The command line: each command writes each format; bad input exits 2 with one clear line."""

import json
import subprocess
import sys
import xml.etree.ElementTree as ET

import ezdxf
import numpy as np
import pytest
import shapely
from PIL import Image

from voroforge.cli import main
from voroforge.cli.progress import progress


@pytest.fixture
def points_csv(tmp_path):
    rng = np.random.default_rng(11)
    pts = rng.uniform(0, 50, size=(40, 2))
    f = tmp_path / "pts.csv"
    f.write_text("x,y\n" + "\n".join(f"{x!r},{y!r}" for x, y in pts.tolist()) + "\n")
    return f


def _run(capsys, *argv):
    rc = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return rc, out, err


def test_voronoi_writes_every_format(tmp_path, points_csv, capsys):
    outs = [tmp_path / "c.svg", tmp_path / "c.png", tmp_path / "c.geojson"]
    argv = ["voronoi", points_csv, "--size", 200, "--boundary", "0,0,50,50"]
    for o in outs:
        argv += ["-o", o]
    rc, out, err = _run(capsys, *argv)
    assert rc == 0, err
    assert out.split() == [str(o) for o in outs]  # only the written paths on stdout
    assert err == ""
    ET.parse(outs[0])
    with Image.open(outs[1]) as img:
        assert img.size == (200, 200)
    feats = json.loads(outs[2].read_text())["features"]
    assert len(feats) == 40
    assert sum(f["properties"]["area"] for f in feats) == pytest.approx(2500.0)


def test_voronoi_boundary_file(tmp_path, points_csv, capsys):
    domain = shapely.box(0, 0, 50, 50).difference(shapely.box(20, 20, 30, 30))
    bfile = tmp_path / "domain.geojson"
    bfile.write_text(shapely.to_geojson(domain))
    out = tmp_path / "cells.json"
    rc, _, err = _run(capsys, "voronoi", points_csv, "-o", out, "--boundary", bfile)
    assert rc == 0, err
    feats = json.loads(out.read_text())["features"]
    total = sum(f["properties"]["area"] for f in feats)
    assert total == pytest.approx(domain.area)


def test_delaunay_writes_triangles(tmp_path, points_csv, capsys):
    svg, gj = tmp_path / "t.svg", tmp_path / "t.geojson"
    rc, out, err = _run(capsys, "delaunay", points_csv, "-o", svg, "-o", gj)
    assert rc == 0, err
    feats = json.loads(gj.read_text())["features"]
    assert all(len(f["properties"]["vertices"]) == 3 for f in feats)
    ns = "{http://www.w3.org/2000/svg}"
    paths = [p for p in ET.parse(svg).getroot().iter(ns + "path") if p.get("id")]
    assert len(paths) == len(feats) > 40
    pts = np.loadtxt(points_csv, delimiter=",", skiprows=1)
    hull = shapely.MultiPoint(pts).convex_hull
    assert sum(f["properties"]["area"] for f in feats) == pytest.approx(hull.area)


def test_demo(tmp_path, capsys):
    rc, out, err = _run(capsys, "demo", "-o", tmp_path / "demo")
    assert rc == 0, err
    names = [p.rsplit("/", 1)[-1] for p in out.split()]
    assert names == ["laser-panel.svg", "laser-panel.dxf", "laser-panel.png"]
    root = ET.parse(tmp_path / "demo" / "laser-panel.svg").getroot()
    # 600 x 400 mm panel cut with a 0.15 mm kerf: the page holds the compensated outline
    assert root.get("width") == "600.15mm" and root.get("height") == "400.15mm"
    doc = ezdxf.readfile(tmp_path / "demo" / "laser-panel.dxf")
    ents = list(doc.modelspace())
    assert len(ents) > 50
    assert all(e.dxftype() == "LWPOLYLINE" and e.closed and e.dxf.layer == "CUT" for e in ents)


def test_demo_is_the_flagship_example():
    from pathlib import Path

    from voroforge.demo import FLAGSHIP

    example = Path(__file__).resolve().parent.parent / "examples" / "laser-panel.toml"
    assert FLAGSHIP == example.read_text()


# --- design files: build / new / check ---------------------------------------------------

PANEL = """\
[design]
name = "p"
seed = 2

[boundary]
shape = "rectangle"
width = 120
height = 80
margin = 4

[seeds]
method = "poisson"
radius = 16

[cells]
web = 3
fillet = 1

[output]
formats = ["svg", "dxf"]

[fabrication]
min_web = 2.5
"""


def test_build_writes_and_prints_paths(tmp_path, capsys):
    f = tmp_path / "p.toml"
    f.write_text(PANEL)
    rc, out, err = _run(capsys, "build", f, "-o", tmp_path / "o")
    assert rc == 0, err
    assert out.split() == [str(tmp_path / "o" / "p.svg"), str(tmp_path / "o" / "p.dxf")]
    first = (tmp_path / "o" / "p.dxf").read_bytes()
    rc, out, _ = _run(capsys, "build", f, "-o", tmp_path / "o", "--set", "seeds.radius=10")
    assert rc == 0
    assert (tmp_path / "o" / "p.dxf").read_bytes() != first
    rc, out, _ = _run(capsys, "build", f, "-o", tmp_path / "o", "--preview")
    assert rc == 0 and out.split() == [str(tmp_path / "o" / "p.png")]


def test_build_bad_design_exits_2_with_file_line_key(tmp_path, capsys):
    f = tmp_path / "p.toml"
    f.write_text(PANEL.replace("radius = 16", "radius = -16").replace("fillet = 1", "filet = 1"))
    rc, out, err = _run(capsys, "build", f, "-o", tmp_path / "o")
    assert rc == 2 and out == ""
    lines = err.splitlines()
    assert f"voroforge: error: {f}:13: seeds.radius: input should be greater than 0" in lines[0]
    assert lines[1].startswith(f"voroforge: error: {f}:17: cells.filet: unknown key")
    assert "did you mean 'fillet'?" in lines[1]
    assert "Traceback" not in err
    rc, _, err = _run(capsys, "build", f, "--set", "nonsense")
    assert rc == 2 and "KEY=VALUE" in err
    rc, _, err = _run(capsys, "build", tmp_path / "missing.toml")
    assert rc == 2 and "missing.toml" in err


def test_new_writes_a_starter_that_builds(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    rc, out, err = _run(capsys, "new")
    assert rc == 0 and out.strip() == "design.toml"
    assert (tmp_path / "design.toml").read_text().startswith("# A voroforge design file")
    rc, _, err = _run(capsys, "new")
    assert rc == 2 and "already exists" in err
    rc, out, err = _run(
        capsys, "build", "design.toml", "-o", "o", "--set", 'output.formats=["svg"]'
    )
    assert rc == 0, err


def test_check_prints_table_and_strict_exit(tmp_path, capsys):
    f = tmp_path / "p.toml"
    f.write_text(PANEL)
    rc, out, err = _run(capsys, "check", f, "--strict")
    assert rc == 0 and "no violations" in out
    rc, out, err = _run(capsys, "check", f, "--set", "cells.web=1")
    assert rc == 0 and "web" in out and "violations" in out
    rc, out, err = _run(capsys, "check", f, "--strict", "--set", "cells.web=1")
    assert rc == 1 and out.splitlines()[0].split()[:3] == ["kind", "x", "y"]
    overlay = tmp_path / "check.png"
    rc, out, err = _run(capsys, "check", f, "--set", "cells.web=1", "--overlay", overlay)
    assert rc == 0 and overlay.exists()
    with Image.open(overlay) as img:
        assert img.format == "PNG"
    rc, _, err = _run(capsys, "check", f, "--overlay", tmp_path / "x.pdf")
    assert rc == 2 and "must be a .png or .svg" in err


def test_check_all_lists_every_row_worst_first_and_names_the_keys(tmp_path, capsys):
    f = tmp_path / "p.toml"
    f.write_text(PANEL)
    sets = ["--set", "cells.web=0.5", "--set", "fabrication.tool_radius=2"]
    rc, short, _ = _run(capsys, "check", f, *sets)
    rc, full, _ = _run(capsys, "check", f, *sets, "--all")
    total = int(full.splitlines()[-1].split()[0])
    rows = [ln for ln in full.splitlines()[2:-1]]
    assert len(rows) == total > 50 and "--all" in short and "more" not in full
    assert "fabrication.tool_radius" in full.splitlines()[-1]
    # worst first across kinds: relative shortfall of value against limit never increases
    sev = [(float(r.split()[4]) - float(r.split()[3])) / float(r.split()[4]) for r in rows]
    assert all(a >= b - 1e-9 for a, b in zip(sev, sev[1:], strict=False))


def test_voronoi_edges_and_cells_dxf_cut_every_edge_once(tmp_path, points_csv, capsys):
    from test_plotter import duplicate_segments

    cells, edges, svg = tmp_path / "c.dxf", tmp_path / "e.dxf", tmp_path / "e.svg"
    rc, _, err = _run(capsys, "voronoi", points_csv, "-o", cells, "--boundary", "0,0,50,50")
    assert rc == 0, err
    rc, _, err = _run(
        capsys, "voronoi", points_csv, "-o", edges, "-o", svg, "--edges", "--boundary", "0,0,50,50"
    )
    assert rc == 0, err
    assert duplicate_segments(cells) == 0 and duplicate_segments(edges) == 0
    n_lines = len(ezdxf.readfile(edges).modelspace().query("LWPOLYLINE"))
    assert 0 < n_lines < 60  # long strokes, not one polyline per edge
    rc, _, err = _run(capsys, "voronoi", points_csv, "-o", tmp_path / "e.png", "--edges")
    assert rc == 2 and "--edges" in err


def test_svg_units_error_names_file_and_line(tmp_path, capsys):
    f = tmp_path / "m.toml"
    f.write_text(PANEL.replace("seed = 2", 'seed = 2\nunits = "m"', 1))
    rc, _, err = _run(capsys, "build", f, "-o", tmp_path / "o")
    line = f.read_text().splitlines().index('formats = ["svg", "dxf"]') + 1
    assert rc == 2 and f"{f}:{line}: output.formats: svg needs design.units" in err
    rc, _, err = _run(capsys, "build", f, "-o", tmp_path / "o", "--set", 'output.formats=["svg"]')
    assert rc == 2 and "(from --set)" in err


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["voronoi", "{tmp}/missing.csv", "-o", "{tmp}/x.svg"], "missing.csv: no such file"),
        (["voronoi", "{pts}", "-o", "{tmp}/x.pdf"], "unsupported output type '.pdf'"),
        (["voronoi", "{pts}", "-o", "{tmp}/x.svg", "--boundary", "1,2"], "not xmin,ymin,xmax,ymax"),
        (["voronoi", "{bad}", "-o", "{tmp}/x.svg"], "line 3: 'oops' is not a number"),
        (["voronoi", "{pts}", "-o", "{tmp}/no/such/dir/x.svg"], "x.svg"),
        (["delaunay", "{pts}", "-o", "{tmp}/x.txt"], "unsupported output type '.txt'"),
    ],
)
def test_bad_input_exits_2_with_one_line(tmp_path, points_csv, capsys, argv, message):
    bad = tmp_path / "bad.csv"
    bad.write_text("x,y\n1,2\n3,oops\n")
    argv = [a.format(tmp=tmp_path, pts=points_csv, bad=bad) for a in argv]
    rc, out, err = _run(capsys, *argv)
    assert rc == 2
    assert out == ""
    assert err.startswith("voroforge: error: ") and message in err
    assert err.count("\n") == 1 and "Traceback" not in err


def test_usage_errors_exit_2(capsys):
    assert _run(capsys, "voronoi")[0] == 2
    assert _run(capsys, "frobnicate")[0] == 2
    for command in ("voronoi", "delaunay", "demo", "build", "new", "check"):
        rc, out, _ = _run(capsys, command, "--help")
        assert rc == 0 and "examples:" in out
    assert "--boundary" in _run(capsys, "voronoi", "--help")[1]


def test_progress_context_is_quiet_when_disabled(capsys):
    with progress(False) as stage:
        stage("reading")
    with progress(True) as stage:  # a real spinner; must not break on a non-terminal stream
        stage("computing")
    assert capsys.readouterr().out == ""


def test_help_and_errors_via_subprocess(tmp_path):
    run = [sys.executable, "-m", "voroforge"]
    top = subprocess.run([*run, "--help"], capture_output=True, text=True, timeout=60)
    assert top.returncode == 0
    for word in ("voronoi", "delaunay", "demo", "examples:"):
        assert word in top.stdout
    bad = subprocess.run(
        [*run, "voronoi", str(tmp_path / "nope.csv"), "-o", str(tmp_path / "x.svg")],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert bad.returncode == 2
    assert bad.stdout == ""
    assert bad.stderr.strip() == f"voroforge: error: {tmp_path / 'nope.csv'}: no such file"


def test_cli_field_names_match_the_raster_writer():
    # the raster command repeats the field names so that --help does not import numpy
    from voroforge.cli.raster import FIELDS
    from voroforge.io.raster_png import FIELDS as WRITER_FIELDS

    assert FIELDS == WRITER_FIELDS


def test_help_and_version_do_not_import_the_cli_commands_dependencies():
    code = (
        "import sys; from voroforge.cli import main\n"
        "for argv in (['--version'], ['--help'], ['raster', '--help'], ['build', '--help']):\n"
        "    try:\n"
        "        main(argv)\n"
        "    except SystemExit:\n"
        "        pass\n"
        "heavy = [m for m in ('rich', 'PIL', 'ezdxf', 'voroforge.io', 'voroforge.design')\n"
        "         if m in sys.modules]\n"
        "print(heavy)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip().splitlines()[-1] == "[]"
