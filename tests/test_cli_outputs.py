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


ANIMATION = """
[design]
name = "st"
seed = 3
[boundary]
shape = "rectangle"
width = 100
height = 80
[seeds]
method = "random"
count = 30
[cells]
web = 2
[animation]
frames = 5
[[animation.tracks]]
key = "cells.web"
values = [1, 4]
"""


def test_animate_frame_folder_is_replaced_whole(tmp_path, monkeypatch):
    from voroforge.design import build as build_module

    design = tmp_path / "a.toml"
    design.write_text(ANIMATION, encoding="utf-8")
    out = tmp_path / "frames"
    args = ["animate", str(design), "-o", str(out), "--size", "40"]
    assert main([*args, "--frames", "5"]) == 0
    mine = ["frame-7.png", "frame-00009.png", "frame-0009.txt", "notes.txt"]
    for name in mine:
        (out / name).write_text("not ours", encoding="utf-8")
    assert main([*args, "--frames", "2"]) == 0  # frames 3..5 of the older run removed
    assert sorted(p.name for p in out.iterdir()) == sorted(
        ["frame-0001.png", "frame-0002.png", *mine]
    )
    old = {p.name: p.read_bytes() for p in out.iterdir()}
    calls = []
    real = build_module.render_preview

    def stop_at_second(result, **kwargs):
        calls.append(1)
        if len(calls) == 2:
            raise KeyboardInterrupt
        return real(result, **kwargs)

    monkeypatch.setattr(build_module, "render_preview", stop_at_second)
    assert main([*args, "--frames", "4"]) == 130  # Ctrl-C: the older animation as it was
    assert {p.name: p.read_bytes() for p in out.iterdir()} == old


def test_animate_refuses_a_gif_past_its_memory_budget(tmp_path, capsys):

    design = tmp_path / "a.toml"
    design.write_text(ANIMATION, encoding="utf-8")
    gif = tmp_path / "a.gif"
    assert main(["animate", str(design), "-o", str(gif), "--frames", "2000", "--size", "4096"]) == 2
    err = capsys.readouterr().err
    assert "voroforge: error: a GIF of 2000 frames of up to 4096 x 4096 px" in err
    assert "33.6 GB" in err and not gif.exists()
