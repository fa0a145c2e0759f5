"""Fixes of the eighth independent check's findings (lead): rasters at 1e308, messages."""

from __future__ import annotations

import numpy as np
import pytest

import voroforge as vf


@pytest.mark.parametrize("method", ["exact", "jfa"])
@pytest.mark.parametrize("e", [1000, 1020, -1000])
def test_rasters_near_float64s_limits_are_the_unit_raster_scaled(method, e):
    # bounds (0, 0, 1e308, 1e308) gave inf distances; (-1e308, ..., 1e308) raised numpy's
    # "cannot convert float NaN to integer" (the box's width overflowed)
    pts = np.random.default_rng(0).random((50, 2))
    s = 2.0**e
    for box in ((0, 0, 1, 1), (-1, -1, 1, 1)):
        ref = vf.rasterize(pts, (16, 16), box, method=method, f2=True)
        r = vf.rasterize(pts * s, (16, 16), tuple(np.array(box) * s), method=method, f2=True)
        assert np.array_equal(r.labels, ref.labels)
        assert np.array_equal(r.distance, np.ldexp(ref.distance, e))
        assert np.array_equal(r.f2, np.ldexp(ref.f2, e))
        assert r.bounds == tuple(float(v) * s for v in box)


@pytest.mark.parametrize("command", ["check", "build"])
def test_gif_sweeps_are_refused_alike_by_check_and_build(tmp_path, capsys, command):
    # checker8: `check` accepted a sweep of a key that does not exist, or of values the key
    # refuses, which `build` refused; a bad value is reported on the values' line
    from voroforge.cli import main

    base = (
        '[design]\nname = "x"\n[boundary]\nshape = "rectangle"\nwidth = 100\nheight = 50\n'
        '[seeds]\nmethod = "random"\ncount = 20\n[output]\nformats = ["gif"]\n[output.gif]\n'
    )
    for sweep, where in (
        ('key = "nonexistent.key"\nstart = 1\nstop = 2\n', ":13: output.gif.key: "),
        ('key = "cells.web"\nvalues = [1, "a"]\n', ":14: output.gif.values: "),
    ):
        f = tmp_path / "d.toml"
        f.write_text(base + sweep)
        assert (
            main(
                [command, str(f), "-o", str(tmp_path / "o")]
                if command == "build"
                else [command, str(f)]
            )
            == 2
        )
        assert f"{f}{where}" in capsys.readouterr().err


def test_nan_and_inf_in_a_design_name_their_key(tmp_path):
    from voroforge.design.designfile import DesignError, load

    f = tmp_path / "d.toml"
    f.write_text(
        '[boundary]\nshape = "rectangle"\nwidth = 10\nheight = inf\n[seeds]\nmethod = "random"\n'
        "count = 5\n[cells]\nweb = nan\nfillet = { near = nan, far = 1 }\n"
    )
    with pytest.raises(DesignError) as info:
        load(f)
    got = [(i.key, i.line) for i in info.value.issues]
    assert got == [("boundary.height", 4), ("cells.web", 9), ("cells.fillet.near", 10)]
    assert all("finite number" in i.message for i in info.value.issues)


def test_no_queries_is_an_empty_answer():
    # checker8: vf.locate(pts, []) said "xy must have shape (n, 2); got shape (1, 0)"
    p = np.random.default_rng(0).random((5, 2))
    assert vf.locate(p, []).shape == (0,)
    assert vf.voronoi(p).locate([]).shape == (0,)
    assert vf.natural_neighbor(p, np.arange(5.0), []).shape == (0,)
    q = np.random.default_rng(0).random((10, 3))
    assert vf.voronoi3d(q).locate([]).shape == (0,)


def test_a_csv_of_a_header_alone_has_no_points(tmp_path):
    from voroforge.scale.sources import open_source

    f = tmp_path / "h.csv"
    f.write_text("x,y\n")
    with pytest.raises(ValueError, match=r"no points: .*h\.csv has no rows"):
        open_source(f, tmp_path, 1000)


def test_all_cells_as_one_triangle_mesh_equal_the_meshes_joined():
    # checker8: writing 100k cells as .ply took ~43 s (mesh by mesh); triangles() at once
    import trimesh

    rng = np.random.default_rng(1)
    p = rng.random((400, 3))
    for d in (
        vf.voronoi3d(np.vstack([p, p[:20]]), (0, 0, 0, 1, 1, 1)),  # duplicates: empty cells
        vf.voronoi3d(p, (0, 0, 0, 1, 1, 1), periodic=True),
    ):
        live = [(i, m) for i, m in enumerate(d.to_trimesh()) if len(m.faces)]
        joined = trimesh.util.concatenate([m for _, m in live])
        v, f, c = d.triangles()
        assert np.array_equal(v, joined.vertices) and np.array_equal(f, joined.faces)
        assert np.array_equal(c, np.concatenate([np.full(len(m.faces), i) for i, m in live]))


def test_an_output_may_not_replace_the_input(tmp_path, capsys):
    # checker8: `voroforge voronoi3d p.csv -o p.csv` replaced the points with the cells
    from voroforge.cli import main

    f = tmp_path / "p.csv"
    np.savetxt(f, np.random.default_rng(0).random((20, 3)), delimiter=",")
    before = f.read_bytes()
    assert main(["voronoi3d", str(f), "-o", str(f)]) == 2
    assert "is the input file" in capsys.readouterr().err and f.read_bytes() == before
    g = tmp_path / "q.npy"
    np.save(g, np.random.default_rng(0).random((20, 2)))
    assert main(["raster", str(g), "-o", str(g)]) == 2
    assert "is the input file" in capsys.readouterr().err
