"""CLI options: one meaning for every output, checked before any is written (checker18 F4).

``voroforge voronoi -o v.svg -o v.dxf --units pt`` wrote v.svg, then failed on the DXF with a
units list the CLI does not accept, while ``--edges`` wrote the same units as a unitless DXF.
Now both DXF paths map pt/px to unitless (DXF has no name for them), every output's needs
are checked before the first is written, and an option no output uses is said on stderr.
"""

from __future__ import annotations

import importlib.util

import ezdxf
import numpy as np
import pytest

from voroforge.cli import main


@pytest.fixture
def pts(tmp_path):
    f = tmp_path / "p.csv"
    xy = np.random.default_rng(5).random((40, 2)) * 100
    f.write_text("x,y\n" + "\n".join(f"{x!r},{y!r}" for x, y in xy.tolist()) + "\n")
    return f


def _insunits(path) -> int:
    return ezdxf.readfile(path).header["$INSUNITS"]


@pytest.mark.parametrize(
    ("units", "code"), [(None, 0), ("pt", 0), ("px", 0), ("mm", 4), ("cm", 5), ("in", 1)]
)
def test_dxf_units_same_for_cells_and_edges(tmp_path, pts, units, code):
    # ezdxf's own $INSUNITS codes: 0 unitless, 1 inches, 4 mm, 5 cm
    extra = [] if units is None else ["--units", units]
    svg, cells, edges = tmp_path / "v.svg", tmp_path / "v.dxf", tmp_path / "e.dxf"
    assert main(["voronoi", str(pts), "-o", str(svg), "-o", str(cells), *extra]) == 0
    assert main(["voronoi", str(pts), "-o", str(edges), "--edges", *extra]) == 0
    assert _insunits(cells) == code == _insunits(edges)


def test_usage_errors_write_nothing(tmp_path, pts, capsys, monkeypatch):
    svg, png, pq = tmp_path / "a.svg", tmp_path / "b.png", tmp_path / "c.parquet"
    assert main(["voronoi", str(pts), "-o", str(svg), "-o", str(png), "--edges"]) == 2
    assert "--edges writes" in capsys.readouterr().err
    assert not svg.exists() and not png.exists()
    # a writer's missing library is said before the first file is written
    real = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util, "find_spec", lambda name, *a: None if name == "pyarrow" else real(name, *a)
    )
    assert main(["voronoi", str(pts), "-o", str(svg), "-o", str(pq)]) == 2
    assert "needs pyarrow" in capsys.readouterr().err
    assert not svg.exists() and not pq.exists()


def test_options_no_output_uses_are_said(tmp_path, pts, capsys):
    a, b = tmp_path / "a.svg", tmp_path / "b.svg"
    assert main(["voronoi", str(pts), "-o", str(a)]) == 0
    capsys.readouterr()
    assert main(["voronoi", str(pts), "-o", str(b), "--size", "300"]) == 0
    err = capsys.readouterr().err
    assert "warning: --size 300 is used only by .png outputs" in err
    assert a.read_bytes() == b.read_bytes()  # ignored indeed
    g = tmp_path / "t.geojson"
    assert main(["delaunay", str(pts), "-o", str(g), "--units", "mm"]) == 0
    assert "warning: --units mm is used only by .svg and .dxf outputs" in capsys.readouterr().err
    png = tmp_path / "c.png"
    assert main(["voronoi", str(pts), "-o", str(png), "--size", "64"]) == 0
    assert "warning" not in capsys.readouterr().err


def test_voronoi3d_and_raster_options(tmp_path, capsys):
    p3 = tmp_path / "p3.csv"
    p3.write_text(
        "\n".join(",".join(map(repr, r)) for r in np.random.default_rng(4).random((20, 3)).tolist())
    )
    c = tmp_path / "c.csv"
    box = "--container=-1,-1,-1,2,2,2"
    assert main(["voronoi3d", str(p3), "-o", str(c), "--explode", "0.3", box]) == 0
    assert "warning: --explode 0.3 is used only by .png outputs" in capsys.readouterr().err
    npy = tmp_path / "r.npy"
    p2 = tmp_path / "p2.csv"
    p2.write_text("x,y\n0,0\n1,1\n2,0\n")
    assert main(["raster", str(p2), "-o", str(npy), "--size", "8x8", "--seed", "3"]) == 0
    assert "warning: --seed 3 is used only by --field labels" in capsys.readouterr().err


def test_studio_port_in_use_names_it(tmp_path, capsys):
    import socket

    design = tmp_path / "s.toml"
    design.write_text(
        '[boundary]\nshape = "rectangle"\nwidth = 10\nheight = 8\n'
        '[seeds]\nmethod = "random"\ncount = 5\n'
    )
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        s.listen()
        port = s.getsockname()[1]
        argv = ["studio", str(design), "--port", str(port), "--no-browser"]
        assert main(argv) == 2
    err = capsys.readouterr().err
    assert f"error: --host 127.0.0.1 --port {port}: " in err
