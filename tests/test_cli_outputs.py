"""A command that fails on one of its outputs writes none of them (checked before any work)."""

from __future__ import annotations

import numpy as np
import pytest

from voroforge.cli import main


@pytest.fixture
def pts2(tmp_path):
    f = tmp_path / "p.csv"
    xy = np.random.default_rng(3).random((30, 2))
    f.write_text("x,y\n" + "\n".join(f"{x!r},{y!r}" for x, y in xy.tolist()) + "\n")
    return f


@pytest.fixture
def pts3(tmp_path):
    f = tmp_path / "p3.csv"
    f.write_text(
        "\n".join(",".join(map(repr, r)) for r in np.random.default_rng(4).random((20, 3)).tolist())
    )
    return f


def _fails(capsys, argv, *unwritten, says):
    rc = main([str(a) for a in argv])
    err = capsys.readouterr().err
    assert rc == 2
    assert says in err
    for p in unwritten:
        assert not p.exists(), p


def test_voronoi_missing_folder_writes_nothing(tmp_path, pts2, capsys):
    a = tmp_path / "a.geojson"
    _fails(
        capsys,
        ["voronoi", pts2, "-o", a, "-o", tmp_path / "nope" / "b.svg"],
        a,
        says="does not exist",
    )


def test_voronoi_png_too_large_writes_nothing(tmp_path, pts2, capsys):
    a, b = tmp_path / "a.geojson", tmp_path / "b.png"
    _fails(capsys, ["voronoi", pts2, "-o", a, "-o", b, "--size", "1000000"], a, b, says="too large")
    _fails(
        capsys,
        ["voronoi", pts2, "--edges", "-o", a, "-o", tmp_path / "x" / "e.svg"],
        a,
        says="does not exist",
    )


def test_delaunay_png_too_large_writes_nothing(tmp_path, pts2, capsys):
    a, b = tmp_path / "t.svg", tmp_path / "t.png"
    _fails(
        capsys, ["delaunay", pts2, "-o", a, "-o", b, "--size", "1000000"], a, b, says="too large"
    )


def test_voronoi3d_checks_every_output_first(tmp_path, pts3, capsys):
    c, png = tmp_path / "c.csv", tmp_path / "c.png"
    box = "--container=-1,-1,-1,2,2,2"
    _fails(
        capsys,
        ["voronoi3d", pts3, "-o", c, "-o", png, "--size", "100000x100000", box],
        c,
        png,
        says="too large",
    )
    _fails(
        capsys,
        ["voronoi3d", pts3, "-o", c, "-o", tmp_path / "no" / "b.obj", box],
        c,
        says="does not exist",
    )
    (tmp_path / "d.csv").mkdir()
    _fails(
        capsys, ["voronoi3d", pts3, "-o", c, "-o", tmp_path / "d.csv", box], c, says="is a folder"
    )
    # and a good run writes both
    assert main(["voronoi3d", str(pts3), "-o", str(c), "-o", str(png), "--size", "64x48", box]) == 0
    assert c.exists() and png.exists()


def test_raster_missing_folder_writes_nothing(tmp_path, pts2, capsys):
    a = tmp_path / "r.npy"
    _fails(
        capsys,
        ["raster", pts2, "-o", a, "-o", tmp_path / "nope" / "r.png", "--size", "64"],
        a,
        says="does not exist",
    )
