"""Input attributes and CRS carried to the cells (voroforge voronoi, the point readers)."""

from __future__ import annotations

import json
import warnings

import numpy as np
import pytest
import shapely
import shapely.geometry

import voroforge as vf
from voroforge.cli import main
from voroforge.io.readers import boundary_crs, read_point_table

CRS = {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::2056"}}


def _boundary(tmp_path):
    f = tmp_path / "bnd.geojson"
    ring = [[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]]
    f.write_text(
        json.dumps(
            {
                "type": "FeatureCollection",
                "crs": CRS,
                "features": [
                    {
                        "type": "Feature",
                        "properties": {},
                        "geometry": {"type": "Polygon", "coordinates": [ring]},
                    }
                ],
            }
        )
    )
    return f


def test_csv_columns_become_attributes(tmp_path):
    f = tmp_path / "trees.csv"
    f.write_text("id;x;y;species;height;note\n7;0.1;0.1;oak;12.5;\n8;0.5;0.5;elm;8;old\n")
    pts, attrs = read_point_table(f)
    assert pts.tolist() == [[0.1, 0.1], [0.5, 0.5]]
    assert attrs == {
        "id": [7.0, 8.0],
        "species": ["oak", "elm"],
        "height": [12.5, 8.0],
        "note": [None, "old"],
    }
    f2 = tmp_path / "bare.csv"
    f2.write_text("0,1\n2,3\n")  # no header: no attributes
    assert read_point_table(f2)[1] == {}


def test_geojson_properties_follow_each_point(tmp_path):
    f = tmp_path / "pts.geojson"
    feats = [
        {
            "type": "Feature",
            "properties": {"kind": "a"},
            "geometry": {"type": "Point", "coordinates": [0.2, 0.2]},
        },
        {
            "type": "Feature",
            "properties": {"kind": "b", "n": 2},
            "geometry": {"type": "MultiPoint", "coordinates": [[0.6, 0.6], [0.8, 0.3]]},
        },
    ]
    f.write_text(json.dumps({"type": "FeatureCollection", "features": feats}))
    pts, attrs = read_point_table(f)
    assert len(pts) == 3
    assert attrs == {"kind": ["a", "b", "b"], "n": [None, 2, 2]}


def test_voronoi_cli_carries_rows_attributes_and_crs(tmp_path, capsys):
    pts = tmp_path / "pts.csv"
    pts.write_text("x,y,name,area\n0.1,0.1,oak,1\n0.5,0.5,elm,2\n9,9,outside,3\n0.3,0.8,fir,4\n")
    bnd = _boundary(tmp_path)
    assert boundary_crs(bnd) == CRS and boundary_crs("0,0,1,1") is None
    out = tmp_path / "cells.geojson"
    assert main(["voronoi", str(pts), "--boundary", str(bnd), "-o", str(out)]) == 0
    doc = json.loads(out.read_text())
    assert doc["crs"] == CRS
    feats = doc["features"]
    assert [f["properties"]["index"] for f in feats] == [0, 1, 2, 3]  # no renumbering
    assert [f["properties"]["name"] for f in feats] == ["oak", "elm", "outside", "fir"]
    assert feats[2]["geometry"] is None and feats[2]["properties"]["area"] == 0.0
    # an input column named like a computed one is kept beside it
    assert [f["properties"]["input_area"] for f in feats] == [1.0, 2.0, 3.0, 4.0]
    assert abs(sum(f["properties"]["area"] for f in feats) - 1.0) < 1e-12


def test_voronoi_cli_geoparquet_attributes_and_crs(tmp_path):
    gpd = pytest.importorskip("geopandas")
    pts = tmp_path / "pts.csv"
    pts.write_text("x,y,name\n0.1,0.1,oak\n0.5,0.5,elm\n0.9,0.2,ash\n")
    out = tmp_path / "cells.parquet"
    assert main(["voronoi", str(pts), "--boundary", str(_boundary(tmp_path)), "-o", str(out)]) == 0
    df = gpd.read_parquet(out)
    assert df.crs.to_epsg() == 2056
    assert df["name"].tolist() == ["oak", "elm", "ash"]
    assert np.isclose(df["area"].sum(), 1.0)


@pytest.mark.parametrize("relax", [0, 3])
def test_design_file_seeds_keep_rows_columns_and_crs(tmp_path, relax):
    from voroforge.design.build import build

    pts = tmp_path / "trees.csv"
    rows = ["x,y,name,area,cell", "0.1,0.1,oak,1,a", "0.5,0.5,elm,2,b", "9,9,far,3,c"]
    rows += ["0.3,0.8,fir,4,d", "0.8,0.3,ash,5,e"]
    pts.write_text("\n".join(rows) + "\n")
    _boundary(tmp_path)
    design = tmp_path / "d.toml"
    design.write_text(
        'boundary = { shape = "file", file = "bnd.geojson" }\n'
        'seeds = { method = "file", file = "trees.csv" }\n'
        f"relax = {{ iterations = {relax} }}\n"
        'output = { formats = ["geojson"] }\n'
    )
    (gj,) = build(design, tmp_path / "out")
    doc = json.loads(gj.read_text())
    assert doc["crs"] == CRS  # the boundary file's
    props = [f["properties"] for f in doc["features"]]
    assert [p["index"] for p in props] == [0, 1, 2, 3, 4]  # one feature per row, in order
    assert [p["name"] for p in props] == ["oak", "elm", "far", "fir", "ash"]
    # columns named like computed properties are kept beside them
    assert [p["input_area"] for p in props] == [1.0, 2.0, 3.0, 4.0, 5.0]
    assert [p["input_cell"] for p in props] == ["a", "b", "c", "d", "e"]
    assert [p["cell"] for p in props] == [0, 1, None, 2, 3]
    far = doc["features"][2]
    assert far["geometry"] is None and far["properties"]["site"] == [9.0, 9.0]
    assert far["properties"]["area"] == 0.0 and far["properties"]["opening"] is None
    cells = [shapely.geometry.shape(f["geometry"]) for f in doc["features"] if f["geometry"]]
    assert sum(c.area for c in cells) == pytest.approx(1.0, rel=1e-9)
    for f in doc["features"]:  # each row's cell holds that row's site (moved by relax)
        if f["geometry"]:
            cell = shapely.geometry.shape(f["geometry"]).buffer(1e-9)
            assert cell.contains(shapely.Point(f["properties"]["site"]))
    moved = [p["site"] for p in props if p["cell"] is not None]
    original = [[0.1, 0.1], [0.5, 0.5], [0.3, 0.8], [0.8, 0.3]]
    assert (moved == original) == (relax == 0)


def test_design_geoparquet_has_the_geojson_rows(tmp_path):
    gpd = pytest.importorskip("geopandas")
    from voroforge.design.build import build

    (tmp_path / "trees.csv").write_text(
        "x,y,name,area\n0.1,0.1,oak,1\n9,9,far,2\n0.6,0.5,elm,3\n0.3,0.8,fir,4\n"
    )
    _boundary(tmp_path)
    design = tmp_path / "d.toml"
    design.write_text(
        'boundary = { shape = "file", file = "bnd.geojson" }\n'
        'seeds = { method = "file", file = "trees.csv" }\n'
        'output = { formats = ["geojson", "parquet"] }\n'
    )
    gj, pq = build(design, tmp_path / "out")
    df = gpd.read_parquet(pq)
    feats = json.loads(gj.read_text())["features"]
    assert df.crs.to_epsg() == 2056  # the boundary file's CRS, as PROJJSON
    assert df["index"].tolist() == [f["properties"]["index"] for f in feats] == [0, 1, 2, 3]
    assert df["name"].tolist() == ["oak", "far", "elm", "fir"]
    assert df["input_area"].tolist() == [1.0, 2.0, 3.0, 4.0]
    assert df.geometry.isna().tolist() == [False, True, False, False]  # the row outside
    for f, (_, row) in zip(feats, df.iterrows(), strict=True):
        assert row["area"] == pytest.approx(f["properties"]["area"], abs=1e-12)
        if f["geometry"]:
            assert shapely.geometry.shape(f["geometry"]).equals_exact(row.geometry, 1e-12)
    assert np.isclose(df["area"].sum(), 1.0)


def test_design_seed_file_points_on_the_outline_get_their_cells(tmp_path):
    # a row on the boundary's edge or corner is inside (it had no cell, and its region went
    # to its neighbours); its cell is the one vf.voronoi gives the same sites in the box
    from voroforge.design.build import build

    pts = np.array([[10, 10], [50, 40], [100, 40], [0, 0], [70, 20], [120, 5]], float)
    (tmp_path / "pts.csv").write_text("x,y\n" + "".join(f"{x},{y}\n" for x, y in pts))
    (tmp_path / "d.toml").write_text(
        '[design]\nname = "sf"\n[boundary]\nshape = "rectangle"\nwidth = 100\nheight = 80\n'
        '[seeds]\nmethod = "file"\nfile = "pts.csv"\n[output]\nformats = ["geojson"]\n'
    )
    build(tmp_path / "d.toml", tmp_path / "out")
    feats = json.loads((tmp_path / "out" / "sf.geojson").read_text())["features"]
    ref = vf.voronoi(pts[:5], (0, 0, 100, 80))
    got = [shapely.geometry.shape(f["geometry"]).area if f["geometry"] else 0.0 for f in feats]
    assert np.allclose(got[:5], ref.areas, rtol=1e-12, atol=1e-9)
    assert got[2] > 1300 and got[3] == pytest.approx(50.0)  # the edge's and the corner's
    assert feats[5]["geometry"] is None  # outside: no cell


def test_a_crs_dict_must_be_projjson_pyproj_reads(tmp_path):
    pyproj = pytest.importorskip("pyproj")
    from voroforge.io.parquet import projjson

    good = pyproj.CRS.from_epsg(2056).to_json_dict()
    assert projjson(good) == good
    for bad in ({"type": "bogus"}, {"hello": 1}):
        with pytest.raises(ValueError, match="is not a coordinate reference system"):
            projjson(bad)
    from voroforge.io.parquet import write_cells

    d = vf.voronoi([[0.1, 0.1], [0.5, 0.5]], (0, 0, 1, 1))
    with pytest.raises(ValueError, match="is not a coordinate reference system"):
        write_cells(d, tmp_path / "c.parquet", crs={"hello": 1})
    assert not list(tmp_path.iterdir())


def test_design_file_seeds_keep_an_area_beside_an_input_area(tmp_path):
    # checker25 F3: `area` renamed to `input_area` overwrote the file's own `input_area`
    # (a file-seeded design's GeoJSON has both, so a round trip lost a column)
    import pyarrow.parquet as pq

    from voroforge.design.build import build

    (tmp_path / "pts.csv").write_text("x,y,area,input_area\n10,10,111,keep-me\n60,40,222,too\n")
    spec = {
        "design": {"name": "rt"},
        "boundary": {"shape": "rectangle", "width": 100, "height": 80},
        "seeds": {"method": "file", "file": str(tmp_path / "pts.csv")},
        "output": {"formats": ["geojson", "parquet"]},
    }
    build(spec, tmp_path / "o")
    props = [
        f["properties"] for f in json.loads((tmp_path / "o" / "rt.geojson").read_text())["features"]
    ]
    assert [p["input_area"] for p in props] == ["keep-me", "too"]
    assert [p["input_input_area"] for p in props] == [111, 222]
    assert np.isclose(sum(p["area"] for p in props), 8000.0)
    table = pq.read_table(tmp_path / "o" / "rt.parquet").to_pydict()
    assert table["input_area"] == ["keep-me", "too"] and table["input_input_area"] == [111, 222]


def test_seeds_in_another_crs_than_the_boundary_are_named(tmp_path):
    # checker25 F8: boundary and seed GeoJSON in different CRSs were mixed silently, the
    # output claiming the boundary's
    from voroforge.design.build import DesignWarning, build

    _boundary(tmp_path)
    other = {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32633"}}
    feats = [
        {"type": "Feature", "properties": {}, "geometry": {"type": "Point", "coordinates": p}}
        for p in ([0.2, 0.3], [0.7, 0.6], [0.4, 0.8])
    ]
    seeds = {"type": "FeatureCollection", "crs": other, "features": feats}
    (tmp_path / "s.geojson").write_text(json.dumps(seeds))
    spec = {
        "boundary": {"shape": "file", "file": str(tmp_path / "bnd.geojson")},
        "seeds": {"method": "file", "file": str(tmp_path / "s.geojson")},
        "output": {"formats": ["geojson"]},
    }
    with pytest.warns(DesignWarning, match="EPSG::32633 is not boundary.file's .*EPSG::2056"):
        build(spec, tmp_path / "o")
    seeds["crs"] = CRS  # the same CRS: no warning
    (tmp_path / "s.geojson").write_text(json.dumps(seeds))
    with warnings.catch_warnings():
        warnings.simplefilter("error", DesignWarning)
        build(spec, tmp_path / "p")
