"""Mesh files: every format reloads watertight with the same volume (io/mesh.py)."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

trimesh = pytest.importorskip("trimesh")

from voroforge.io import mesh as mio  # noqa: E402

FLOAT32 = (".stl", ".glb")  # formats that store float32 by definition


def _sphere():
    m = trimesh.creation.icosphere(2, radius=7.3)
    m.apply_translation([1.1, 2.2, 3.3])
    return m


def _expected(m, ext):
    if ext == ".stl":
        return trimesh.Trimesh(m.vertices.astype(np.float32).astype(np.float64), m.faces)
    return m


@pytest.mark.parametrize("ext", mio.FORMATS)
@pytest.mark.parametrize("several", [False, True])
def test_round_trip_volume(tmp_path, ext, several):
    a = _sphere()
    b = trimesh.creation.box((2.0, 3.0, 4.0))
    b.apply_translation([20.0, 0.0, 0.0])
    what = [a, b] if several else a
    r = mio.read(mio.write(what, tmp_path / f"m{ext}", units="mm"))
    exp = _expected(trimesh.util.concatenate([a, b]) if several else a, ext)
    assert r.is_volume
    # GLB: float32 relative to the meshes' centre (the translation is a double in the node)
    rtol = 1e-6 if ext == ".glb" else 1e-9
    assert abs(r.volume - exp.volume) <= rtol * abs(exp.volume)
    assert len(r.vertices) == len(exp.vertices)
    if ext not in FLOAT32:  # float64 formats: the vertices bit for bit
        assert set(map(tuple, r.vertices)) == set(map(tuple, exp.vertices))


@pytest.mark.parametrize("units", ["mm", "in", "m"])
def test_units_recorded(tmp_path, units):
    m = trimesh.creation.box((1, 1, 1))
    assert mio.read(mio.write(m, tmp_path / "u.3mf", units=units)).metadata["units"] == units
    assert mio.read(mio.write(m, tmp_path / "u.3dm", units=units)).metadata["units"] == units


def test_3mf_is_a_3mf(tmp_path):
    import zipfile

    p = mio.write({"part one": trimesh.creation.box((1, 2, 3))}, tmp_path / "x.3mf")
    with zipfile.ZipFile(p) as z:
        names = set(z.namelist())
        model = z.read("3D/3dmodel.model").decode()
    assert {"[Content_Types].xml", "_rels/.rels", "3D/3dmodel.model"} <= names
    assert 'unit="millimeter"' in model and 'name="part one"' in model


def test_curves_on_layers(tmp_path):
    import rhino3dm

    sq = shapely.box(0, 0, 10, 10).difference(shapely.box(2, 2, 4, 4))
    p = mio.write_curves_3dm(
        {"CUT": [sq], "SCORE": [np.array([[0, 0], [5, 5]])]}, tmp_path / "c.3dm"
    )
    f = rhino3dm.File3dm.Read(str(p))
    layers = {f.Layers[i].Name: i for i in range(len(f.Layers))}
    assert set(layers) == {"CUT", "SCORE"}
    per = {}
    for o in f.Objects:
        per.setdefault(o.Attributes.LayerIndex, []).append(o.Geometry)
    assert len(per[layers["CUT"]]) == 2  # outline and hole
    assert len(per[layers["SCORE"]]) == 1
    assert f.Settings.ModelUnitSystem == rhino3dm.UnitSystem.Millimeters


def test_bad_input(tmp_path):
    m = trimesh.creation.box((1, 1, 1))
    with pytest.raises(ValueError, match="unknown mesh format"):
        mio.write(m, tmp_path / "x.step")
    with pytest.raises(ValueError, match="unknown units"):
        mio.write(m, tmp_path / "x.stl", units="furlong")
    with pytest.raises(ValueError, match="no meshes"):
        mio.write([], tmp_path / "x.stl")
    with pytest.raises(ValueError, match="expected a trimesh"):
        mio.write([np.zeros(3)], tmp_path / "x.stl")
    with pytest.raises(ValueError, match="no such file"):
        mio.read(tmp_path / "missing.stl")
    bad = trimesh.Trimesh(
        np.array([[0, 0, 0], [1, 0, 0], [np.nan, 1, 0]]), [[0, 1, 2]], process=False
    )
    with pytest.raises(ValueError, match="NaN"):
        mio.write(bad, tmp_path / "x.obj")


def test_atomic_no_leftovers(tmp_path):
    mio.write(trimesh.creation.box((1, 1, 1)), tmp_path / "a.stl")
    assert [p.name for p in tmp_path.iterdir()] == ["a.stl"]


def _zip3mf(path, model: str):
    import zipfile

    with zipfile.ZipFile(path, "w") as z:
        z.writestr("[Content_Types].xml", mio.CONTENT_TYPES)
        z.writestr("_rels/.rels", mio.RELS)
        z.writestr("3D/3dmodel.model", model)
    return path


def test_3mf_fast_reader_agrees_with_the_xml_parser(tmp_path):
    a, b = _sphere(), trimesh.creation.box((2.0, 3.0, 4.0))
    data = mio._3mf_bytes([("a", a), ("b", b)], "mm")
    import io
    import zipfile

    model = zipfile.ZipFile(io.BytesIO(data)).read("3D/3dmodel.model")
    fast, slow = mio._3mf_meshes_fast(model), mio._3mf_meshes_xml(model)
    assert len(fast) == len(slow) == 2
    for (v1, f1), (v2, f2) in zip(fast, slow, strict=True):
        assert v1.tobytes() == v2.tobytes() and (f1 == f2).all()
    assert (fast[0][0] == a.vertices).all() and (fast[1][1] == b.faces).all()
    # same file byte for byte when written twice
    assert mio._3mf_bytes([("a", a)], "mm") == mio._3mf_bytes([("a", a)], "mm")


@pytest.mark.parametrize(
    ("vertex", "fast"),
    [
        ("<m:vertex z='{z}' y='{y}' x='{x}'/>", False),  # other order, single quotes: XML
        ('<m:vertex x="{x}" y="{y}" z="{z}" />', True),  # the common layout, prefixed
    ],
)
def test_3mf_other_layouts_read(tmp_path, vertex, fast):
    box = trimesh.creation.box((1.0, 2.0, 3.0))
    verts = "".join(vertex.format(x=x, y=y, z=z) for x, y, z in box.vertices.tolist())
    tris = "".join(f'<m:triangle v1="{a}" v2="{b}" v3="{c}"/>' for a, b, c in box.faces)
    model = (
        '<?xml version="1.0"?><m:model unit="centimeter" xmlns:m="'
        + mio.NS3MF
        + '"><m:resources><m:object id="1" type="model"><m:mesh><m:vertices>'
        + verts
        + "</m:vertices><m:triangles>"
        + tris
        + '</m:triangles></m:mesh></m:object></m:resources><m:build><m:item objectid="1"/>'
        + "</m:build></m:model>"
    )
    assert (mio._3mf_meshes_fast(model.encode()) is not None) == fast
    m = mio.read(_zip3mf(tmp_path / "x.3mf", model))
    assert m.is_volume and m.metadata["units"] == "cm"
    assert abs(m.volume - 6.0) <= 1e-12
