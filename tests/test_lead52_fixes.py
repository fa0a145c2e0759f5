"""Fixes of the lead's session s52 (checker findings), each against an independent expectation."""

from __future__ import annotations

import json

import numpy as np
import pytest

import voroforge as vf
from voroforge.design.designfile import DesignError, load, parse_value
from voroforge.io.atomic import write_atomically
from voroforge.io.parquet import write_cells

_DESIGN = '[design]\nname = "t"\n[boundary]\nwidth = 100\nheight = 60\n[cells]\n'


@pytest.mark.parametrize(
    "value",
    ["[" * 3000 + "]" * 3000, "{a = " * 600 + "1" + "}" * 600],
    ids=["arrays", "inline-tables"],
)
def test_a_value_nested_past_the_recursion_limit_is_a_design_error_at_its_line(tmp_path, value):
    # checker31 F1: tomllib's RecursionError came out as a 40-line traceback
    path = tmp_path / "d.toml"
    path.write_text(_DESIGN + '# a "quoted [" comment\nweb = ' + value + "\n")
    with pytest.raises(DesignError) as err:
        load(path)
    (issue,) = err.value.issues
    assert issue.line == _DESIGN.count("\n") + 2
    assert "nested too deeply" in issue.message


def test_a_deep_set_value_stays_the_string_it_was():
    text = "[" * 3000 + "]" * 3000
    assert parse_value(text) == text
    assert parse_value("[1, [2]]") == [1, [2]]


def test_writing_onto_a_folder_names_the_folder_not_a_temporary_file(tmp_path):
    # checker31 F2: "Is a directory: .../.s.gif.e3ch9hll.gif"
    folder = tmp_path / "s.gif"
    folder.mkdir()
    with pytest.raises(IsADirectoryError, match=r"cannot write .*s\.gif: is a folder"):
        write_atomically(folder, lambda tmp: open(tmp, "w").close())
    assert folder.is_dir() and not any(tmp_path.glob(".s.gif*"))


def test_geoparquet_through_a_link_writes_the_linked_file_and_keeps_the_link(tmp_path):
    # checker31 F3: the link was replaced by a plain file; the linked file kept "old"
    pq = pytest.importorskip("pyarrow.parquet")
    d = vf.voronoi(np.random.default_rng(1).random((12, 2)))
    real, link = tmp_path / "real.parquet", tmp_path / "link.parquet"
    real.write_text("old")
    link.symlink_to(real.name)
    write_cells(d, link)
    assert link.is_symlink()
    table = pq.read_table(real)
    assert table.num_rows == 12
    assert json.loads(table.schema.metadata[b"geo"])["primary_column"] == "geometry"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link.parquet", "real.parquet"]


def _example(name: str) -> dict:
    import tomllib
    from pathlib import Path

    return tomllib.loads((Path(__file__).parent.parent / "examples" / name).read_text())


@pytest.mark.parametrize(
    ("example", "section", "key", "value", "words"),
    [
        ("solid-lamp-shade.toml", "solid", "openings", "90", "not the text"),
        ("solid-lamp-shade.toml", "solid", "seed", True, "not true/false"),
        ("solid-lamp-shade.toml", "solid", "thickness", "1.6", "valid number"),
        ("solid-lamp-shade.toml", "solid", "thickness", True, "valid number"),
        ("solid-lamp-shade.toml", "solid", "view", [True, 20], "valid number"),
        ("solid-lamp-shade.toml", "solid", "profile", [["38", 0], [46, 15]], "valid number"),
        ("surface-dome.toml", "surface", "radius", "5", "valid number"),
        ("surface-dome.toml", "surface", "polar", ["0", 70], "valid number"),
        ("surface-dome.toml", "surface", "resolution", True, "not true/false"),
    ],
)
def test_solid_and_surface_numbers_must_be_written_as_numbers(example, section, key, value, words):
    # checker31 F5: "1.6" read as 1.6 and true as 1 in [solid] / [surface], silently
    data = _example(example)
    data[section][key] = value
    with pytest.raises(DesignError, match=rf"{section}\.{key}\b.*{words}"):
        load(data)


def test_shell_openings_are_capped_before_any_work():
    # checker31 F4: openings = 1e8 ran two minutes, then a 6.7 GiB MemoryError traceback
    from voroforge import config, solid
    from voroforge.solid.surfaces import revolve

    data = _example("solid-lamp-shade.toml")
    data["solid"]["openings"] = config.SOLID_MAX_OPENINGS + 1
    with pytest.raises(DesignError, match=r"solid\.openings.*less than or equal"):
        load(data)
    with pytest.raises(ValueError, match="openings: at most"):
        solid.shell(revolve([(1.0, 0.0), (1.0, 1.0)], 16), openings=10**8)


@pytest.mark.parametrize("suffix", [".stl", ".obj"])
def test_a_nan_vertex_in_a_container_file_is_named_not_called_open(tmp_path, suffix):
    # checker31 F7: trimesh's processing dropped the NaN vertex's faces: "the mesh is open"
    trimesh = pytest.importorskip("trimesh")
    box = trimesh.creation.box(extents=(2, 2, 2))
    v = box.vertices.copy()
    v[0] = [np.nan, 0.0, 0.0]
    path = tmp_path / f"nan{suffix}"
    trimesh.Trimesh(v, box.faces, process=False).export(path)
    pts = np.random.default_rng(0).random((10, 3)) - 0.5
    with pytest.raises(ValueError, match="NaN or infinite vertices"):
        vf.voronoi3d(pts, str(path))
    # the same box without the NaN, from its file, is still a container (soup merged exactly)
    box.export(tmp_path / f"box{suffix}")
    cells = vf.voronoi3d(pts, str(tmp_path / f"box{suffix}"))
    assert cells.volumes.sum() == pytest.approx(8.0, rel=1e-12)


def test_local_workers_are_capped_before_any_process_starts():
    # checker31 F6: --workers 100000 started processes for minutes with no output
    import os

    from voroforge import config
    from voroforge.scale.cluster import check_local_workers, local_cluster

    most = config.SCALE_LOCAL_WORKERS_PER_CORE * max(1, os.cpu_count() or 1)
    check_local_workers(most)
    with pytest.raises(ValueError, match=f"at most {most} local worker"):
        check_local_workers(most + 1)
    with pytest.raises(ValueError, match="at most"):
        local_cluster(100_000)
    with pytest.raises(ValueError, match="at least 1"):
        local_cluster(0)


def test_cli_scale_refuses_counts_before_the_cluster_starts(tmp_path, capsys):
    from voroforge.cli import main

    pts = tmp_path / "p.npy"
    np.save(pts, np.random.default_rng(0).random((50, 2)))
    for extra in (["--workers", "100000"], ["--tile-size", "0"]):
        assert main(["scale", str(pts), "-o", str(tmp_path / "out"), *extra]) == 2
        err = capsys.readouterr().err
        assert "voroforge: error:" in err and "dask dashboard" not in err


def test_deeply_nested_geojson_and_svg_boundaries(tmp_path):
    # checker31 F8, F9: RecursionError tracebacks from json and the SVG group walk
    from voroforge.io import read_boundary

    deep = tmp_path / "deep.geojson"
    nested = "[" * 100_000 + "]" * 100_000
    deep.write_text('{"type": "FeatureCollection", "features": ' + nested + "}")
    with pytest.raises(ValueError, match="deep.geojson: invalid JSON .*nested too deeply"):
        read_boundary(deep)
    svg = tmp_path / "deep.svg"
    svg.write_text(
        '<svg xmlns="http://www.w3.org/2000/svg">'
        + '<g transform="translate(1, 0)">' * 20_000
        + '<rect x="0" y="0" width="10" height="5"/>'
        + "</g>" * 20_000
        + "</svg>"
    )
    b = read_boundary(svg)
    assert b.area == pytest.approx(50.0) and b.bounds[0] == pytest.approx(20_000.0)


def test_svg_arcs_with_huge_radii(tmp_path):
    # checker31 F10: rx * rx overflowed: ZeroDivisionError; the small arc is its chord
    from voroforge.io import read_boundary

    def page(d):
        path = tmp_path / "a.svg"
        path.write_text(f'<svg xmlns="http://www.w3.org/2000/svg"><path d="{d}"/></svg>')
        return path

    square = read_boundary(page("M 0 0 A 1e300 1e300 0 0 1 100 0 L 100 100 L 0 100 Z"))
    assert square.area == pytest.approx(1e4, rel=1e-12)
    with pytest.raises(ValueError, match="large arc .* reaches past any drawing"):
        read_boundary(page("M 0 0 A 1e300 1e300 0 1 1 100 0 L 100 100 L 0 100 Z"))
    with pytest.raises(ValueError, match="needs .* points"):
        read_boundary(page("M 0 0 A 1e40 1e40 0 1 1 1e28 0 Z"))
    # an ordinary arc still bulges by its radius: a half disc of radius 50 on the square
    d = read_boundary(page("M 0 0 A 50 50 0 0 1 100 0 L 100 100 L 0 100 Z"))
    assert d.area == pytest.approx(1e4 + np.pi * 50**2 / 2, rel=2e-4)


def test_a_drawing_near_float64s_top_is_refused_before_writing(tmp_path):
    # checker31 F11: a box to 1e308 wrote width="inf" and the PNG overflowed
    from voroforge.io.png import write_png
    from voroforge.io.svg import write_svg

    pts = np.array([[1e307, 1e307], [5e307, 2e307], [9e307, 8e307]])
    d = vf.voronoi(pts, (0, 0, 1e308, 1e308))
    for suffix, write in ((".svg", write_svg), (".png", write_png)):
        with pytest.raises(ValueError, match="overflows float64"):
            write(list(d.cells), tmp_path / f"h{suffix}", sites=pts)
        assert not (tmp_path / f"h{suffix}").exists()


def test_sites_merged_by_a_huge_domains_frame_are_warned_of():
    # checker31 F11b: 29 of 30 distinct sites got duplicate_of = 0 silently
    p = np.random.default_rng(0).random((30, 2)) * 100
    with pytest.warns(RuntimeWarning, match="29 distinct sites are used as one"):
        d = vf.voronoi(p, (0, 0, 1e300, 1e300))
    assert (d.duplicate_of >= 0).sum() == 29
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        d = vf.voronoi(p, (0, 0, 1e200, 1e200))  # kept apart: no warning
    assert (d.duplicate_of < 0).all()


def test_a_npy_header_claiming_more_rows_than_the_file_holds(tmp_path):
    # checker31 F12: np.load allocated 1.46 TiB for a 64-byte file (MemoryError traceback)
    from voroforge.io.readers.points import read_npy_points

    path = tmp_path / "lie.npy"
    with open(path, "wb") as fh:
        header = {"descr": "<f8", "fortran_order": False, "shape": (10**11, 2)}
        np.lib.format.write_array_header_1_0(fh, header)
        fh.write(np.zeros(8).tobytes())
    with pytest.raises(ValueError, match=r"lie\.npy: not a readable \.npy array"):
        read_npy_points(path)
    np.save(path, np.arange(8.0).reshape(4, 2))
    assert read_npy_points(path).tolist() == np.arange(8.0).reshape(4, 2).tolist()


def test_a_build_refuses_to_write_over_the_files_its_design_reads(tmp_path):
    # checker31 F14: name = "pts" with seeds.file = "pts.geojson" replaced the seeds (rc 0)
    from voroforge.design.build import build

    seeds = tmp_path / "pts.geojson"
    feats = [
        {"type": "Feature", "properties": {}, "geometry": {"type": "Point", "coordinates": xy}}
        for xy in ([10, 10], [50, 30], [80, 40], [30, 50])
    ]
    seeds.write_text(json.dumps({"type": "FeatureCollection", "features": feats}))
    before = seeds.read_bytes()
    design = tmp_path / "t.toml"
    design.write_text(
        '[design]\nname = "pts"\n[boundary]\nshape = "rectangle"\nwidth = 100\nheight = 60\n'
        '[seeds]\nmethod = "file"\nfile = "pts.geojson"\n[output]\nformats = ["geojson"]\n'
    )
    with pytest.raises(DesignError, match=r"t\.toml:9: seeds\.file: .*would write over it"):
        build(design, tmp_path)
    assert seeds.read_bytes() == before
    written = build(design, tmp_path / "out")  # elsewhere it builds
    assert [p.name for p in written] == ["pts.geojson"] and seeds.read_bytes() == before


def test_cli_voronoi_refuses_to_write_over_its_boundary_file(tmp_path, capsys):
    from voroforge.cli import main

    outline = tmp_path / "ol.svg"
    outline.write_text(
        '<svg xmlns="http://www.w3.org/2000/svg"><rect width="100" height="60"/></svg>'
    )
    before = outline.read_bytes()
    pts = tmp_path / "p.npy"
    np.save(pts, np.random.default_rng(0).random((20, 2)) * 50)
    assert main(["voronoi", str(pts), "--boundary", str(outline), "-o", str(outline)]) == 2
    assert "is the input file" in capsys.readouterr().err
    assert outline.read_bytes() == before


def test_a_tiny_min_size_gives_the_answer_of_zero_quickly():
    # checker31 F15: min_size = 1e-300 asked GEOS for a 1e-303 tolerance: it never finished
    import shapely

    from voroforge.design.fabrication import inscribed_circles

    square = shapely.box(0.0, 0.0, 10.0, 10.0)
    _, r = inscribed_circles([square], tolerance=1e-303)
    assert r[0] == pytest.approx(5.0, rel=1e-9)


@pytest.mark.parametrize(("n", "r"), [(8, 0.1), (16, 0.25), (40, 0.3)])
def test_describe_counts_a_float_circle_about_a_periodic_corner(n, r):
    # checker30 F2: 8 float sites on a circle about the corner, unwrapped: Euler -1 for 0
    # (the cluster's ulp-long edges, whose images across the box rounded to one point)
    t = np.arange(n) * 2 * np.pi / n
    p = np.column_stack((r * np.cos(t), r * np.sin(t))) % 1.0
    for wrap in (False, True):
        d = vf.voronoi(p, (0.0, 0.0, 1.0, 1.0), periodic=True, wrap=wrap)
        de = d.describe()
        assert de.euler == de.euler_expected and (wrap or de.faces == n)
        assert d.areas.sum() == pytest.approx(1.0, rel=1e-12)


def test_natural_neighbor_errors_name_its_query_argument():
    # checker30: the shape and NaN errors said "xy"
    pts = np.random.default_rng(0).random((10, 2))
    with pytest.raises(ValueError, match=r"^query must be"):
        vf.natural_neighbor(pts, np.ones(10), [0.5, 0.5, 0.5])
    with pytest.raises(ValueError, match=r"query"):
        vf.natural_neighbor(pts, np.ones(10), [[np.nan, 0.5]])
