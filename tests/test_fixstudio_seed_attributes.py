"""Studio saves of hand-edited sites keep the seed file's attribute columns (checker16 F8).

The reference is the seed file itself, parsed here with ``json``/plain text (not the
package's readers): each saved site's properties are those of the row it was placed from.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
import shapely

from voroforge.design.build import build
from voroforge.io.readers import read_point_table
from voroforge.studio.session import Session

PTS = [(10.5, 20.25), (70.0, 15.0), (40.0, 60.0), (85.5, 80.0), (20.0, 85.0), (55.0, 35.0)]
# a CSV whose columns the text reader types: int, float, text with leading zeros, text
CSV = "x,y,id,height,code,name\n" + "\n".join(
    f"{x!r},{y!r},{i},{1.5 * i},{i:05d},site {i}" for i, (x, y) in enumerate(PTS)
)
# GeoJSON properties of every JSON type, one feature missing a key, one outside the box
GEO = {
    "type": "FeatureCollection",
    "features": [
        {
            "type": "Feature",
            "properties": {"name": f"s{i}", "n": i, "w": i / 3, "ok": i % 2 == 0, "tag": None}
            if i != 2
            else {"name": "two", "extra": [1, {"a": "b"}]},
            "geometry": {"type": "Point", "coordinates": list(p)},
        }
        for i, p in enumerate([*PTS, (500.0, 500.0)])
    ],
}
DESIGN = """[design]
name = "attrs"
units = "mm"

[boundary]
shape = "rectangle"
width = 100
height = 100

[seeds]
method = "file"
file = "{file}"

[output]
formats = ["geojson"]
"""


def _folder(tmp_path, kind):
    if kind == "csv":
        (tmp_path / "pts.csv").write_text(CSV + "\n", encoding="utf-8")
        rows = [line.split(",") for line in CSV.splitlines()[1:]]
        expected = [
            {"id": int(r[2]), "height": float(r[3]), "code": r[4], "name": r[5]} for r in rows
        ]
    else:
        (tmp_path / "pts.geojson").write_text(json.dumps(GEO), encoding="utf-8")
        keys = ["name", "n", "w", "ok", "tag", "extra"]
        props = [f["properties"] for f in GEO["features"]]
        expected = [{k: p.get(k) for k in keys} for p in props]
    (tmp_path / "d.toml").write_text(DESIGN.format(file=f"pts.{kind}"), encoding="utf-8")
    return tmp_path / "d.toml", expected


def _saved(path):
    doc = json.loads(path.read_text(encoding="utf-8"))
    xy = np.array([f["geometry"]["coordinates"] for f in doc["features"]], dtype=np.float64)
    return xy, [f["properties"] for f in doc["features"]]


@pytest.mark.parametrize("kind", ["csv", "geojson"])
def test_moved_added_removed_sites_keep_their_rows_attributes(tmp_path, kind):
    path, expected = _folder(tmp_path, kind)
    s = Session(path)
    assert np.array_equal(s.result.sites, np.array(PTS))  # the row outside the box is left out
    assert s.apply({"op": "move", "i": 1, "x": 71.0, "y": 16.5}).kind == "update"
    assert s.apply({"op": "remove", "i": 3}).kind == "update"
    assert s.apply({"op": "add", "x": 30.0, "y": 30.0}).kind == "update"
    assert s.apply({"op": "move", "i": 5, "x": 31.0, "y": 29.0}).kind == "update"  # the added
    r = s.apply({"op": "save", "name": "edited.toml"})
    assert r.kind == "saved" and r.files == ["edited.seeds.geojson", "edited.toml"]
    rows = [0, 1, 2, 4, 5, -1]
    xy, props = _saved(tmp_path / "edited.seeds.geojson")
    assert np.array_equal(xy, s.sites)  # bit for bit
    nulls = dict.fromkeys(expected[0])
    assert props == [expected[r] if r >= 0 else nulls for r in rows]
    # the package's reader gives back the same values and types
    pts, attrs = read_point_table(tmp_path / "edited.seeds.geojson")
    assert np.array_equal(pts, s.sites)
    for k in expected[0]:
        got = attrs.get(k, [None] * len(rows))
        want = [expected[r][k] if r >= 0 else None for r in rows]
        assert got == want and [type(v) for v in got] == [type(v) for v in want], k
    # the rebuilt design's cells carry them: the cell holding a site has its row's name
    out = build(tmp_path / "edited.toml", tmp_path / "out")
    cells = json.loads(next(p for p in out if p.suffix == ".geojson").read_text())["features"]
    assert len(cells) == len(rows)
    for f in cells:
        poly = shapely.geometry.shape(f["geometry"])
        inside = [i for i, p in enumerate(xy) if poly.covers(shapely.Point(p))]
        assert len(inside) == 1
        r = rows[inside[0]]
        assert f["properties"].get("name") == (expected[r]["name"] if r >= 0 else None)
    # the studio's own export gives the same features
    name, raw = s.export("geojson")
    assert [f["properties"].get("name") for f in json.loads(raw)["features"]] == [
        f["properties"].get("name") for f in cells
    ]


def test_undo_redo_and_reseed_keep_rows_in_step(tmp_path):
    path, expected = _folder(tmp_path, "csv")
    s = Session(path)
    assert s.apply({"op": "remove", "i": 0}).kind == "update"
    assert s.apply({"op": "remove", "i": 0}).kind == "update"
    assert s.apply({"op": "undo"}).kind == "update"  # one removed: rows 1..5
    _, csv = s.saved_data("x.seeds.csv")
    assert [p["id"] for p in _saved_text(csv)] == [1, 2, 3, 4, 5]
    assert s.apply({"op": "redo"}).kind == "update"
    assert [p["id"] for p in _saved_text(s.saved_data("x.seeds.csv")[1])] == [2, 3, 4, 5]
    # a boundary that leaves a site out drops it and its row together
    assert s.apply({"op": "set", "key": "boundary.width", "value": 60}).kind == "update"
    data, text = s.saved_data("x.seeds.csv")
    assert data["seeds"]["file"] == "x.seeds.geojson"
    assert [p["id"] for p in _saved_text(text)] == [
        2,
        4,
        5,
    ]  # x < 60: rows 2, 4 and 5 (x 40, 20, 55)
    assert s.apply({"op": "reset_sites"}).kind == "update"
    assert s.saved_data("x.seeds.csv") == (s.data, None)


def test_sites_without_attributes_still_save_as_csv(tmp_path):
    (tmp_path / "pts.csv").write_text(
        "x,y\n" + "\n".join(f"{x!r},{y!r}" for x, y in PTS), encoding="utf-8"
    )
    (tmp_path / "d.toml").write_text(DESIGN.format(file="pts.csv"), encoding="utf-8")
    s = Session(tmp_path / "d.toml")
    assert s.apply({"op": "move", "i": 0, "x": 11.0, "y": 21.0}).kind == "update"
    r = s.apply({"op": "save", "name": "e.toml"})
    assert r.files == ["e.seeds.csv", "e.toml"]
    pts, attrs = read_point_table(tmp_path / "e.seeds.csv")
    assert np.array_equal(pts, s.sites) and attrs == {}


def _saved_text(text):
    return [f["properties"] for f in json.loads(text)["features"]]
