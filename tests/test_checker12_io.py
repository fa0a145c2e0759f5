"""checker12's input/output findings F3, F4, F5, F8, F10, F11 (s44).

F3: the raster size guard is on estimated bytes. F4: CSV attribute columns keep their
integers and codes. F5: graded bounds are schema errors, listed with the others. F8: a
points GeoJSON feature without a point is an error naming it (never a renumbering); a
MultiPolygon's overlapping parts are united. F10: stipple's option errors name the
option. F11: a scale attribute named like a cell column is kept as ``input_<name>``.
"""

from __future__ import annotations

import json
import re

import numpy as np
import pytest
import shapely

import voroforge as vf
from voroforge.cli import main
from voroforge.io.readers import read_boundary, read_point_table

# --- F3: the raster guard on bytes ------------------------------------------------------------

_PEAK = r"""
import resource, sys, numpy as np, voroforge as vf
from voroforge.io.raster_png import write_raster
side, field, out = int(sys.argv[1]), sys.argv[2], sys.argv[3]
pts = np.random.default_rng(1).random((int(sys.argv[4]), 2)) * 100
f2 = field in ("f2", "edge")
write_raster(vf.rasterize(pts, (64, 64), f2=f2), out, field=field)  # compiled, imported
r = vf.rasterize(pts, (side, side), f2=f2, method=sys.argv[5])
write_raster(r, out, field=field)
print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024)
"""


@pytest.mark.parametrize(
    ("field", "sites", "method"),
    [("labels", 20, "exact"), ("labels", 3000, "jfa"), ("edge", 300, "exact")],
)
def test_raster_estimate_bounds_the_measured_peak(tmp_path, field, sites, method):
    import subprocess
    import sys

    from voroforge.engine.raster import raster_bytes

    peaks = []
    sides = (400, 1200)
    for side in sides:
        argv = [sys.executable, "-c", _PEAK, str(side), field, str(tmp_path / "r.png")]
        run = subprocess.run([*argv, str(sites), method], capture_output=True, text=True)
        assert run.returncode == 0, run.stderr
        peaks.append(int(run.stdout.split()[-1]))
    # the peak's growth per pixel (reference: the kernel's resident memory) is within the
    # estimate, which the guard compares with RASTER_MAX_BYTES
    per = (peaks[1] - peaks[0]) / (sides[1] ** 2 - sides[0] ** 2)
    f2 = field in ("f2", "edge")
    assert per <= raster_bytes((1, 1), f2=f2, field=field), per


def test_raster_guard_refuses_before_any_work(tmp_path, capsys):
    from voroforge.engine.raster import RASTER_MAX_BYTES, check_raster_size, raster_bytes

    with pytest.raises(ValueError, match=r"32768 x 32768 is too large: .* GiB .* at most"):
        vf.rasterize([[0, 0], [1, 1]], (32768, 32768))
    most = RASTER_MAX_BYTES // raster_bytes((1, 1), f2=True, field="edge")
    check_raster_size((1, most), f2=True, field="edge")  # the largest allowed passes
    with pytest.raises(ValueError, match=f"at most {most:,} pixels"):
        check_raster_size((1, most + 1), f2=True, field="edge")
    src, out = tmp_path / "p.npy", tmp_path / "r.png"
    np.save(src, np.random.default_rng(0).random((20, 2)))
    assert main(["raster", str(src), "-o", str(out), "--size", "32768x32768"]) == 2
    err = capsys.readouterr().err
    assert "voroforge: error: --size 32768x32768: " in err and "GiB" in err
    assert not out.exists()


# --- F4: CSV attribute columns ----------------------------------------------------------------

IDS = ["9007199254740993", "2", "-3", "9223372036854775807"]
ZIPS = ["00501", "02134", "10001", "99950"]


def _csv(tmp_path, extra_header, extra_rows):
    f = tmp_path / "p.csv"
    pts = [(1, 1), (5, 2), (3, 7), (8, 8)]
    lines = [f"x,y,{extra_header}"]
    lines += [f"{x},{y},{row}" for (x, y), row in zip(pts, extra_rows, strict=True)]
    f.write_text("\n".join(lines) + "\n")
    return f


def test_csv_integer_and_code_columns_keep_their_text(tmp_path):
    rows = [f"{i},{z},{z}.5,1e3" for i, z in zip(IDS, ZIPS, strict=True)]
    f = _csv(tmp_path, "id,zip,leading,sci", rows)
    _, attrs = read_point_table(f)
    # reference: Python's int of the CSV text (every digit), and the text itself
    assert attrs["id"] == [int(t) for t in IDS]
    assert all(type(v) is int for v in attrs["id"])
    assert attrs["zip"] == ZIPS
    assert attrs["leading"] == [f"{z}.5" for z in ZIPS]  # 00501.5: a number drops the zeros
    assert attrs["sci"] == [1000.0] * 4 and all(type(v) is float for v in attrs["sci"])


@pytest.mark.parametrize(
    ("cells", "expected"),
    [
        (["1", "2.5", "", "-4"], [1.0, 2.5, None, -4.0]),  # mixed: floats, exact
        (["1", "", "3", "0"], [1, None, 3, 0]),  # ints with an empty cell
        (["9007199254740993", "1.5", "2", "3"], ["9007199254740993", "1.5", "2", "3"]),
        (["9223372036854775808", "1", "2", "3"], ["9223372036854775808", "1", "2", "3"]),
        (["abc", "1", "2", "3"], ["abc", "1", "2", "3"]),
        (["0.1", "-0.5", "7e-3", "3"], [0.1, -0.5, 7e-3, 3.0]),
    ],
)
def test_csv_column_types(tmp_path, cells, expected):
    f = _csv(tmp_path, "v", cells)
    _, attrs = read_point_table(f)
    got = attrs["v"]
    assert got == expected
    assert [type(v) for v in got] == [type(v) for v in expected]


def test_cli_geojson_and_parquet_keep_ids_and_zips(tmp_path):
    pq = pytest.importorskip("pyarrow.parquet")
    rows = [f"{i},{z}" for i, z in zip(IDS, ZIPS, strict=True)]
    f = _csv(tmp_path, "id,zip", rows)
    gj, par = tmp_path / "c.geojson", tmp_path / "c.parquet"
    assert main(["voronoi", str(f), "-o", str(gj), "-o", str(par)]) == 0
    feats = json.loads(gj.read_text())["features"]
    assert [ft["properties"]["id"] for ft in feats] == [int(t) for t in IDS]
    assert [ft["properties"]["zip"] for ft in feats] == ZIPS
    table = pq.read_table(par)
    assert str(table.schema.field("id").type) == "int64"
    assert table.column("id").to_pylist() == [int(t) for t in IDS]
    assert table.column("zip").to_pylist() == ZIPS


# --- F5: graded bounds in the schema ------------------------------------------------------------

PANEL = """\
[design]
name = "panel"

[boundary]
shape = "rectangle"
width = 100
height = 80

[seeds]
method = "random"
count = 20

[cells]
web = WEB
fillet = FILLET
scale = SCALE

[recursion]
probability = PROB

[output]
png_size = PNG
"""


def _line(key):
    """The 1-based line of ``key = ...`` in PANEL (the reference for the reported lines)."""
    return next(i for i, t in enumerate(PANEL.splitlines(), 1) if t.startswith(f"{key} ="))


def _check(tmp_path, capsys, **values):
    text = PANEL
    base = {"WEB": "3", "FILLET": "1", "SCALE": "1", "PROB": "1", "PNG": "1000"}
    for key, value in {**base, **values}.items():
        text = text.replace(key, value)
    f = tmp_path / "panel.toml"
    f.write_text(text)
    rc = main(["check", str(f)])
    err = capsys.readouterr().err
    lines = {int(m[1]): m[2] for m in re.finditer(r"panel\.toml:(\d+): (\S+):", err)}
    return rc, err, lines


def test_check_lists_every_value_error_with_its_line(tmp_path, capsys):
    rc, err, lines = _check(tmp_path, capsys, WEB="-1", PNG="-5")
    assert rc == 2
    assert lines == {_line("web"): "cells.web", _line("png_size"): "output.png_size"}, err
    rc, err, lines = _check(
        tmp_path, capsys, WEB="{ near = -1, far = 2 }", FILLET="-2", SCALE="-1", PROB="1.5"
    )
    assert rc == 2
    assert lines == {
        _line("web"): "cells.web",
        _line("fillet"): "cells.fillet",
        _line("scale"): "cells.scale",
        _line("probability"): "recursion.probability",
    }, err
    assert "near and far must be >= 0" in err and "must be between 0 and 1" in err


@pytest.mark.parametrize("values", [{}, {"WEB": "0", "FILLET": "0", "SCALE": "0"}, {"PROB": "0"}])
def test_check_accepts_the_bounds_themselves(tmp_path, capsys, values):
    rc, err, _ = _check(tmp_path, capsys, **values)
    assert rc == 0, err


# --- F8: GeoJSON points without a point; MultiPolygon boundaries -----------------------------


def _points_file(tmp_path, middle):
    def point(x, y, i):
        geom = {"type": "Point", "coordinates": [x, y]}
        return {"type": "Feature", "properties": {"id": i}, "geometry": geom}

    feats = [point(1, 1, 0), {"type": "Feature", "properties": {"id": 1}, "geometry": middle}]
    feats += [point(5, 5, 2), point(2, 7, 3)]
    f = tmp_path / "p.geojson"
    f.write_text(json.dumps({"type": "FeatureCollection", "features": feats}))
    return f


@pytest.mark.parametrize(
    ("middle", "says"),
    [
        (None, "no geometry (null)"),
        ({"type": "MultiPoint", "coordinates": []}, "an empty MultiPoint"),
        ({"type": "LineString", "coordinates": [[0, 0], [1, 1]]}, "a LineString"),
        (
            {
                "type": "GeometryCollection",
                "geometries": [{"type": "LineString", "coordinates": []}],
            },
            "no point in its GeometryCollection",
        ),
    ],
)
def test_pointless_feature_is_named_not_dropped(tmp_path, capsys, middle, says):
    f = _points_file(tmp_path, middle)
    with pytest.raises(ValueError, match=f"feature 1 .*{re.escape(says)}"):
        read_point_table(f)
    out = tmp_path / "c.geojson"
    assert main(["voronoi", str(f), "-o", str(out), "--boundary", "0,0,10,10"]) == 2
    err = capsys.readouterr().err
    assert "voroforge: error:" in err and "feature 1" in err and not out.exists()


def test_multipoint_rows_and_point_features_still_read(tmp_path):
    f = _points_file(tmp_path, {"type": "MultiPoint", "coordinates": [[3, 3], [4, 6]]})
    pts, attrs = read_point_table(f)
    assert pts.tolist() == [[1, 1], [3, 3], [4, 6], [5, 5], [2, 7]]
    assert attrs["id"] == [0, 1, 1, 2, 3]


def test_multipolygon_parts_are_united(tmp_path):
    a = [[0, 0], [8, 0], [8, 6], [0, 6], [0, 0]]
    b = [[5, 3], [11, 3], [11, 9], [5, 9], [5, 3]]  # overlaps a in [5, 8] x [3, 6]
    c = [[11, 0], [13, 0], [13, 3], [11, 3], [11, 0]]  # touches b at the point (11, 3)
    d = [[8, 0], [11, 0], [11, 3], [8, 3], [8, 0]]  # shares edges with a, b and c
    geom = {"type": "MultiPolygon", "coordinates": [[a], [b], [c], [d]]}
    f = tmp_path / "b.geojson"
    f.write_text(json.dumps({"type": "Feature", "properties": {}, "geometry": geom}))
    g = read_boundary(f)
    # by hand: 48 + 36 - 9 (overlap) + 6 + 9
    assert g.is_valid and g.area == 48 + 36 - 9 + 6 + 9
    assert g.equals(shapely.union_all([shapely.Polygon(r) for r in (a, b, c, d)]))
    d2 = vf.voronoi([[1, 1], [9, 8], [4, 4], [12, 1]], g)
    assert abs(sum(c.area for c in d2.cells) - g.area) < 1e-12 * g.area


def test_invalid_part_is_still_refused(tmp_path):
    bow = [[0, 0], [2, 2], [2, 0], [0, 2], [0, 0]]  # a bow tie: not repaired
    geom = {"type": "MultiPolygon", "coordinates": [[bow], [[[5, 5], [6, 5], [6, 6], [5, 5]]]]}
    f = tmp_path / "b.geojson"
    f.write_text(json.dumps(geom))
    with pytest.raises(ValueError, match="invalid"):
        vf.voronoi([[1, 0.5], [5.8, 5.2]], read_boundary(f))


# --- F10: stipple option errors ------------------------------------------------------------------


@pytest.fixture
def black_png(tmp_path):
    from PIL import Image

    f = tmp_path / "black.png"
    Image.new("L", (16, 8), 0).save(f)
    return f


@pytest.mark.parametrize(
    ("option", "value"),
    [("--dot", "-1"), ("--dot", "0"), ("--dot", "nan"), ("--width", "1e308"), ("--width", "0")],
)
def test_stipple_option_errors_name_the_option(tmp_path, capsys, black_png, option, value):
    out = tmp_path / "s.svg"
    argv = ["stipple", str(black_png), "-o", str(out), "--points", "5", option, value]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert f"voroforge: error: {option} " in err and not out.exists(), err


@pytest.mark.parametrize("size", [(1, 1), (1, 7), (7, 1)])
def test_stipple_one_pixel_images(tmp_path, size):
    from PIL import Image

    img, out = tmp_path / "one.png", tmp_path / "s.svg"
    Image.new("L", size, 0).save(img)
    argv = ["stipple", str(img), "-o", str(out), "--points", "6", "--iterations", "2"]
    assert main(argv) == 0
    w, h = size
    page = (200.0, 200.0 * h / w)
    circles = re.findall(r'<circle cx="([^"]+)" cy="([^"]+)" r="([^"]+)"', out.read_text())
    assert len(circles) == 6
    for cx, cy, r in circles:
        # SVG's y points down: the page is [0, width] x [-height, 0]
        assert 0 <= float(cx) <= page[0] and 0 <= -float(cy) <= page[1] and float(r) == 0.4


def test_stipple_api_errors():
    from voroforge.design.stipple import grey_image, stipple, stipple_svg

    assert grey_image([[0.5]]).shape == (1, 1)
    with pytest.raises(ValueError, match="at least 1 x 1"):
        grey_image(np.zeros((0, 3)))
    with pytest.raises(ValueError, match="dot must be a positive radius"):
        stipple_svg([[1, 1]], "unused.svg", width=10, height=10, dot=-1)
    with pytest.raises(ValueError, match="height"):
        stipple(np.zeros((8, 2)), 5, width=1e308, iterations=0)


# --- F11: scale attributes named like cell columns ---------------------------------------------


def test_scale_attribute_named_like_a_cell_column(tmp_path, dask_client):
    pq = pytest.importorskip("pyarrow.parquet")
    src = tmp_path / "p.csv"
    rows = ["x,y,area,geometry,site_id,neighbors,bbox,input_bbox,kind"]
    pts = [(1, 1), (5, 2), (3, 7), (8, 8)]
    rows += [
        f"{x},{y},{10 + i},{20 + i},{30 + i},{40 + i},{50 + i},{60 + i},k{i}"
        for i, (x, y) in enumerate(pts)
    ]
    src.write_text("\n".join(rows) + "\n")
    out = tmp_path / "out"
    argv = ["scale", str(src), "-o", str(out), "--boundary", "0,0,10,10"]
    assert main([*argv, "--scheduler", dask_client.scheduler.address]) == 0
    table = pq.read_table(out)
    names = table.column_names
    assert len(names) == len(set(names))
    renamed = {
        "input_area": 10,
        "input_geometry": 20,
        "input_site_id": 30,
        "input_neighbors": 40,
        "input_input_bbox": 50,  # bbox -> input_bbox, which the file already has
        "input_bbox": 60,
    }
    order = np.argsort(table.column("site_id").to_numpy())
    for name, first in renamed.items():
        assert np.array_equal(table.column(name).to_numpy()[order], first + np.arange(4)), name
    assert [table.column("kind").to_pylist()[i] for i in order] == [f"k{i}" for i in range(4)]
    # the cell columns are the cells': areas tile the box
    assert abs(sum(table.column("area").to_pylist()) - 100.0) < 1e-9


@pytest.mark.parametrize("delimiter", [",", ";", "\t"])
def test_csv_quoted_fields_are_read_as_the_csv_module_writes_them(tmp_path, delimiter):
    # F12: a quoted field holding the delimiter or a doubled quote is one field
    import csv

    from voroforge.io.readers.points import read_text_point_table

    rows = [[1, 1, f"Smith{delimiter} John"], [5, 2, 'say "hi"'], [3.5, 7, ""], [8, 8, "d"]]
    path = tmp_path / "p.csv"
    with open(path, "w", newline="") as f:
        w = csv.writer(f, delimiter=delimiter)
        w.writerow(["x", "y", "name"])
        w.writerows(rows)
    pts, attrs = read_text_point_table(path)
    assert pts.tolist() == [[1, 1], [5, 2], [3.5, 7], [8, 8]]
    assert attrs["name"] == [f"Smith{delimiter} John", 'say "hi"', None, "d"]


def test_voronoi_cli_keeps_both_an_area_and_an_input_area_column(tmp_path):
    # `area` is renamed past the computed column and past the file's own `input_area`
    (tmp_path / "p.csv").write_text("x,y,area,input_area\n1,1,10,20\n5,2,11,21\n3,7,12,22\n")
    out = tmp_path / "c.geojson"
    args = ["voronoi", str(tmp_path / "p.csv"), "-o", str(out), "--boundary", "0,0,10,10"]
    assert main(args) == 0
    props = [f["properties"] for f in json.loads(out.read_text())["features"]]
    assert [p["input_area"] for p in props] == [20, 21, 22]
    assert [p["input_input_area"] for p in props] == [10, 11, 12]
    assert sum(p["area"] for p in props) == pytest.approx(100.0)
