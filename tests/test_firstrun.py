"""First use: quick --version/--help, and the warm-up that compiles the kernels ahead."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import pytest

from voroforge.warmup import Step, example_designs, plan, run_plan

ROOT = Path(__file__).resolve().parents[1]


def _modules_after(argv: list[str]) -> set[str]:
    """Modules loaded by ``voroforge ARGV`` in a fresh interpreter (printed on exit)."""
    code = (
        "import sys\n"
        "from voroforge.cli import main\n"
        f"rc = main({argv!r})\n"
        "print('MODULES', ' '.join(sorted(sys.modules)))\n"
        "sys.exit(rc)\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=300, check=True
    )
    line = [x for x in done.stdout.splitlines() if x.startswith("MODULES ")][-1]
    return set(line.split()[1:])  # not the help text, which may name numba


def test_version_and_help_do_not_import_the_engine():
    for argv in (["--version"], ["--help"], ["warmup", "--help"], ["warmup", "--list"]):
        loaded = _modules_after(argv)
        assert "voroforge.cli" in loaded  # the probe itself worked
        heavy = {m for m in loaded if m.split(".")[0] in ("numpy", "numba", "shapely", "scipy")}
        assert not heavy, (argv, sorted(heavy)[:5])
        assert not any(m.startswith("voroforge.engine") for m in loaded), argv


def test_warmup_names_a_missing_design_before_any_step(tmp_path, capsys):
    from voroforge.cli import main

    missing = tmp_path / "nope.toml"
    assert main(["warmup", str(missing)]) == 2
    err = capsys.readouterr().err
    assert err.strip() == f"voroforge: error: {missing}: no such design file"  # no step ran


def test_the_plan_warms_every_example_raster_and_explain(tmp_path):
    designs = example_designs(ROOT)
    assert designs == sorted((ROOT / "examples").glob("*.toml")) and designs
    steps = plan(designs, tmp_path)
    built = [s.argv[1] for s in steps if s.argv[0] == "build"]
    assert built == [str(d) for d in designs]
    assert all(s.argv[s.argv.index("-o") + 1].startswith(str(tmp_path)) for s in steps)
    assert {s.argv[0] for s in steps} == {"build", "raster", "explain", "voronoi3d"}
    methods = {s.argv[s.argv.index("--method") + 1] for s in steps if s.argv[0] == "raster"}
    assert methods == {"exact", "jfa"}
    # without a checkout's examples/ (an installed wheel) the packaged starter is warmed
    starter = example_designs(tmp_path)
    assert [p.name for p in starter] == ["starter.toml"] and starter[0].is_file()


def test_a_failing_step_is_reported_and_the_rest_still_run(tmp_path):
    missing = tmp_path / "no-such-design.toml"
    steps = [
        Step("build missing", ("build", str(missing), "-o", str(tmp_path / "o"))),
        Step("version", ("--version",)),
    ]
    lines: list[str] = []
    done = run_plan(steps, report=lines.append)
    assert [s.label for s in done] == ["build missing", "version"]
    assert "no-such-design.toml" in done[0].error
    assert done[1].error == ""
    assert all(math.isfinite(s.seconds) and s.seconds >= 0 for s in done)
    assert all(math.isfinite(s.cpu) and s.cpu >= 0 for s in done)
    assert len(lines) == 2 and "FAILED" in lines[0] and lines[1].rstrip().endswith("ok")


def test_a_2d_build_loads_only_what_it_needs(tmp_path):
    # a first build pays every import: a laser panel (Poisson seeds, fillets, SVG + DXF +
    # PNG) needs no KD-tree, sparse graphs, mesh stack, 3D or studio code
    loaded = _modules_after(
        ["build", str(ROOT / "examples" / "laser-panel.toml"), "-o", str(tmp_path)]
    )
    assert "voroforge.io.dxf" in loaded and "voroforge.design.compute" in loaded  # it ran
    assert (tmp_path / "laser-panel.dxf").is_file()
    # the R2000 DXF is written without ezdxf (0.2-0.3 s to import)
    unwanted = ("scipy.spatial", "scipy.sparse", "trimesh", "manifold3d", "skimage", "starlette")
    unwanted += ("ezdxf",)
    assert not {m for m in loaded if m.startswith(unwanted)}
    # numba's BLAS check found the preloaded extension: scipy.linalg's __init__ did not run
    assert "scipy.linalg.cython_blas" in loaded and "numba.np.arraymath" in loaded
    assert "scipy.linalg" not in loaded and "scipy._lib._util" not in loaded
    for sub in ("solid.build", "surface.build", "studio.server", "engine.voronoi3d", "scale"):
        assert f"voroforge.{sub}" not in loaded, sub
    # the design schema reads the surface section without loading the surface modules, and
    # the SVG writer escapes without xml.sax.saxutils (which loads urllib.request and ssl)
    assert "voroforge.surface.schema" in loaded
    for sub in ("morph", "panels", "shapes", "unroll", "voronoi"):
        assert f"voroforge.surface.{sub}" not in loaded, sub
    assert not {"xml.sax.saxutils", "urllib.request", "ssl"} & loaded


def test_first_runs_are_timed_in_fresh_processes(tmp_path):
    from voroforge.warmup import time_first_runs

    steps = [
        Step("version", ("--version",)),
        Step("build missing", ("build", str(tmp_path / "none.toml"), "-o", str(tmp_path))),
    ]
    lines: list[str] = []
    done = time_first_runs(steps, report=lines.append, repeat=2)
    assert [s.label for s in done] == ["version", "build missing"]
    assert done[0].error == "" and "none.toml" in done[1].error
    # a fresh interpreter: measurable wall and CPU time, the CPU within the wall (one thread)
    assert all(0 < s.cpu and 0 < s.seconds for s in done)
    assert done[0].cpu <= done[0].seconds * 1.5 + 0.05
    assert len(lines) == 2 and "wall" in lines[0] and "FAILED" in lines[1]
    with pytest.raises(ValueError, match="repeat"):
        time_first_runs(steps, repeat=0)


def test_the_stored_dxf_skeleton_is_what_ezdxf_writes():
    from voroforge.io.dxf import dxf_skeleton, stored_skeleton

    assert stored_skeleton() == dxf_skeleton()


def _dxf_cases():
    import numpy as np
    import shapely

    pts = np.random.default_rng(1).random((30, 2)) * 100
    lines = [shapely.LineString([(0, 0), (1, 1), (2, 0.5)])]
    lines.append(shapely.MultiLineString([[(5, 5), (6, 7)], [(6, 7), (8, 1)]]))
    holed = shapely.box(50, 0, 60, 10).difference(shapely.box(52, 2, 55, 5))
    return {
        "fillets": ([shapely.box(0, 0, 40, 20).buffer(3, quad_segs=8), holed], {}),
        "layers": (
            [shapely.box(0, 0, 4, 2)],
            {"layers": {"ENGRAVE": lines, "SITES": [shapely.MultiPoint(pts)]}, "units": "in"},
        ),
        "crosses": (
            [],
            {
                "layers": {"sites": [shapely.MultiPoint(pts[:5]), shapely.Point(1e-7, -3.3)]},
                "point_marks": "cross",
                "point_radius": 1,
            },
        ),
        "no marks": (
            None,
            {
                "layers": {"A": [shapely.Point(1, 2)], "b": [shapely.box(0, 0, 1, 1)]},
                "point_marks": "none",
                "units": "unitless",
            },
        ),
        "travel": (
            [shapely.box(i, 0, i + 0.5, 0.5) for i in range(40)],
            {"order": "travel", "colours": {"CUT": 3}},
        ),
        "chords": ([shapely.Point(0, 0).buffer(5)], {"arcs": False, "units": "cm"}),
        "raw": (
            [shapely.Point(*p).buffer(1.5) for p in pts],
            {"layers": {"EDGES": [shapely.LineString(pts)]}, "merge": False, "dedupe": False},
        ),
    }


@pytest.mark.parametrize("case", list(_dxf_cases()))
def test_the_direct_r2000_writer_writes_ezdxf_s_bytes(tmp_path, monkeypatch, case):
    from voroforge.io import dxf

    geoms, options = _dxf_cases()[case]
    direct = dxf.write_dxf(geoms, tmp_path / "direct.dxf", **options)
    monkeypatch.setattr(dxf, "_skeleton_holds", lambda content: False)
    through = dxf.write_dxf(geoms, tmp_path / "ezdxf.dxf", **options)
    assert direct.read_bytes() == through.read_bytes()


def test_unrolled_sheets_write_ezdxf_s_bytes_without_ezdxf(tmp_path, monkeypatch):
    import ezdxf

    from voroforge import surface

    S = surface.saddle(2.0, 2.0, 0.3)
    panels = surface.voronoi(S, 12, relax=2, seed=1).panels()
    sheets = panels.unroll(sheet=(3.0, 1.5))
    direct = sheets.write_dxf(tmp_path / "direct.dxf", units="m").read_bytes()
    monkeypatch.setattr(ezdxf.options, "write_fixed_meta_data_for_testing", True)
    through = sheets._write_dxf_ezdxf(tmp_path / "ezdxf.dxf", "CUT", "LABELS", "m").read_bytes()
    assert direct == through
    assert direct.count(b"\nTEXT\n") == len(panels)


SMALL_SURFACE = """
[design]
name = "small-saddle"
units = "m"
seed = 3

[boundary]
shape = "rectangle"
width = 1
height = 1

[seeds]
method = "random"
count = 12

[relax]
iterations = 2

[output]
formats = ["png"]
png_size = 200

[surface]
shape = "saddle"
width = 2
depth = 2
rise = 0.3
mode = "voronoi"
frame = 0.04
thickness = 0.01
meshes = ["3mf"]
"""


def test_a_surface_build_writes_its_meshes_without_trimesh(tmp_path):
    # the panel solids go to 3MF/PLY as bare arrays: trimesh's import (about 0.3 s) is not
    # paid; the files are the bytes the Trimeshes would give
    design = tmp_path / "small.toml"
    design.write_text(SMALL_SURFACE, encoding="utf-8")
    out = tmp_path / "out"
    loaded = _modules_after(["build", str(design), "-o", str(out)])
    assert "voroforge.surface.build" in loaded
    assert not {m for m in loaded if m.startswith(("trimesh", "manifold3d", "skimage"))}

    from voroforge.design.designfile import load
    from voroforge.io.mesh import Arrays, write
    from voroforge.surface.build import surface_panels

    _, panels, _ = surface_panels(*load(design))
    meshes = panels.thicken(0.01) + panels.frame(0.04)
    arrays = panels.thicken(0.01, arrays=True) + panels.frame(0.04, arrays=True)
    assert all(isinstance(a, Arrays) for a in arrays)
    built = (out / "small-saddle-panels.3mf").read_bytes()
    assert write(meshes, tmp_path / "t.3mf", units="m").read_bytes() == built
    assert write(arrays, tmp_path / "a.3mf", units="m").read_bytes() == built
    # the other formats take Arrays too, with the same bytes
    for ext in ("ply", "stl", "obj"):
        a = write(arrays[0], tmp_path / f"a.{ext}").read_bytes()
        assert a == write(meshes[0], tmp_path / f"t.{ext}").read_bytes()


def test_the_blas_preload_leaves_numba_and_scipy_working():
    code = (
        "import sys\n"
        "from voroforge.cli.startup import preload_blas\n"
        "assert preload_blas() and not preload_blas()\n"
        "import numba.np.arraymath as am\n"
        "assert am._HAVE_BLAS and 'scipy.linalg' not in sys.modules\n"
        "import numpy as np, scipy.linalg\n"
        "from scipy.linalg import cython_blas\n"
        "assert cython_blas is sys.modules['scipy.linalg.cython_blas']\n"
        "x = scipy.linalg.solve(np.array([[2.0, 1.0], [1.0, 3.0]]), np.array([3.0, 5.0]))\n"
        "assert np.allclose(x, [0.8, 1.4])\n"
        "print('OK')\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=60, check=False
    )
    assert done.stdout.strip() == "OK", done.stderr[-2000:]
