"""Writers and readers: invariants of the files they produce, and their error messages."""

import json
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest
import shapely
from PIL import Image

import voroforge as vf
from voroforge import io
from voroforge.io.render import PathContext, RingContext, palette, trace

SVG = "{http://www.w3.org/2000/svg}"


@pytest.fixture(scope="module")
def domain():
    return shapely.box(0, 0, 100, 60).difference(shapely.Point(50, 30).buffer(12))


@pytest.fixture(scope="module")
def diagram(domain):
    rng = np.random.default_rng(3)
    pts = rng.uniform((0, 0), (100, 60), size=(200, 2))
    pts = pts[shapely.contains_xy(domain, pts[:, 0], pts[:, 1])][:80]
    return vf.voronoi(pts, domain)


def _svg_layers(path):
    root = ET.parse(path).getroot()
    assert root.tag == SVG + "svg"
    return root, {g.get("id"): g for g in root.iter(SVG + "g")}


def _subpaths(d):
    """Rings of an SVG path string written by PathContext, as (k, 2) arrays in SVG coordinates."""
    assert d.endswith("Z")
    rings = []
    for part in d.split("M")[1:]:
        assert part.endswith("Z"), "every sub-path is closed"
        nums = [float(v) for v in re.split(r"[L,]", part[:-1])]
        rings.append(np.array(nums).reshape(-1, 2))
    return rings


# --- render context ---------------------------------------------------------------------


def test_path_context_writes_closed_subpaths_for_holes():
    poly = shapely.box(0, 0, 4, 4).difference(shapely.box(1, 1, 2, 2))
    ctx = PathContext(digits=3)
    assert trace(ctx, poly) == 2
    d = str(ctx)
    assert d.count("M") == 2 and d.count("Z") == 2
    rings = _subpaths(d)
    assert sorted(len(r) for r in rings) == [4, 4]  # closing point not repeated


def test_ring_context_and_transform():
    ctx = RingContext()
    trace(
        ctx,
        shapely.MultiPolygon([shapely.box(0, 0, 1, 1), shapely.box(2, 0, 3, 1)]),
        lambda xy: xy * 10,
    )
    assert len(ctx.rings) == 2
    assert max(x for ring in ctx.rings for x, _ in ring) == 30
    assert trace(RingContext(), shapely.Polygon()) == 0


def test_palette_is_deterministic_and_distinct():
    a, b = palette(50, seed=1), palette(50, seed=1)
    assert a.dtype == np.uint8 and a.shape == (50, 3)
    assert np.array_equal(a, b)
    assert not np.array_equal(a, palette(50, seed=2))
    assert len({tuple(c) for c in a.tolist()}) == 50


# --- SVG ---------------------------------------------------------------------------------


def test_svg_one_closed_path_per_nonempty_cell(diagram, tmp_path):
    out = io.write_svg(
        diagram.cells, tmp_path / "d.svg", sites=diagram.sites, boundary=diagram.boundary
    )
    root, layers = _svg_layers(out)
    assert {"cells", "boundary", "sites"} <= set(layers)
    paths = layers["cells"].findall(SVG + "path")
    nonempty = [i for i, c in enumerate(diagram.cells) if not c.is_empty]
    assert [p.get("id") for p in paths] == [f"cell-{i}" for i in nonempty]
    assert layers["cells"].get("fill-rule") == "evenodd"
    for p in paths:
        _subpaths(p.get("d"))
    assert len(layers["sites"].findall(SVG + "circle")) == len(diagram.sites)
    assert layers["boundary"].find(SVG + "path").get("d").count("M") == 2  # outline + hole


def test_svg_is_upright_in_data_units(diagram, tmp_path):
    out = io.write_svg(diagram.cells, tmp_path / "d.svg", boundary=diagram.boundary)
    root, layers = _svg_layers(out)
    vx, vy, vw, vh = (float(v) for v in root.get("viewBox").split())
    bx0, by0, bx1, by1 = diagram.boundary.bounds
    assert vx <= bx0 and vx + vw >= bx1 and vy <= -by1 and vy + vh >= -by0
    for p in layers["cells"].findall(SVG + "path"):
        i = int(p.get("id").split("-")[1])
        rings = [np.column_stack((r[:, 0], -r[:, 1])) for r in _subpaths(p.get("d"))]
        # Even-odd area of the rings read back equals the cell's area.
        areas = [abs(shapely.Polygon(r).area) for r in rings]
        exterior = max(areas)
        area = exterior - (sum(areas) - exterior)
        assert area == pytest.approx(diagram.areas[i], rel=1e-5, abs=1e-6)
        x0, y0, x1, y1 = diagram.cells[i].bounds
        xy = np.concatenate(rings)
        assert np.allclose(xy.min(axis=0), (x0, y0), atol=1e-4)
        assert np.allclose(xy.max(axis=0), (x1, y1), atol=1e-4)


def test_svg_units_mm_and_geometry_edge_cases(tmp_path):
    geoms = [
        shapely.box(0, 0, 10, 5),
        shapely.Polygon(),
        shapely.MultiPolygon([shapely.box(20, 0, 25, 5), shapely.box(30, 0, 35, 5)]),
        None,
    ]
    out = io.write_svg(geoms, tmp_path / "mm.svg", units="mm", fill="none")
    root, layers = _svg_layers(out)
    assert root.get("width").endswith("mm") and root.get("height").endswith("mm")
    assert float(root.get("width")[:-2]) == pytest.approx(float(root.get("viewBox").split()[2]))
    paths = layers["cells"].findall(SVG + "path")
    assert [p.get("id") for p in paths] == ["cell-0", "cell-2"]
    assert paths[1].get("d").count("M") == 2  # one path, two parts
    assert "boundary" not in layers and "sites" not in layers


def test_svg_rejects_bad_input(tmp_path):
    with pytest.raises(ValueError, match="units"):
        io.write_svg([shapely.box(0, 0, 1, 1)], tmp_path / "x.svg", units="furlong")
    with pytest.raises(ValueError, match="not a shapely geometry"):
        io.write_svg([[0, 0]], tmp_path / "x.svg")


# --- PNG ---------------------------------------------------------------------------------


def test_png_size_aspect_and_colours(diagram, tmp_path):
    out = io.write_png(
        diagram.cells, tmp_path / "d.png", size=300, sites=diagram.sites, boundary=diagram.boundary
    )
    with Image.open(out) as img:
        assert img.format == "PNG"
        w, h = img.size
        rgb = np.asarray(img.convert("RGB"))
    assert w == 300 and h < w
    assert h / w == pytest.approx(60 / 100, abs=0.03)
    colours = {tuple(c) for c in rgb.reshape(-1, 3).tolist()}
    assert len(colours) > 40


def test_png_is_upright_and_respects_holes():
    top, bottom = shapely.box(0, 5, 10, 10), shapely.box(0, 0, 10, 5)
    ring = shapely.box(20, 0, 30, 10).difference(shapely.box(23, 3, 27, 7))
    img = io.render_image(
        [top, bottom, ring], size=200, colors=["#ff0000", "#0000ff", "#00ff00"], supersample=1
    )
    a = np.asarray(img)
    h, w, _ = a.shape
    assert w == 200
    x_left = int(w * 0.15)
    assert tuple(a[int(h * 0.3), x_left]) == (255, 0, 0)  # upper half is the top box
    assert tuple(a[int(h * 0.7), x_left]) == (0, 0, 255)
    cx, cy = int(w * 0.83), h // 2  # centre of the ring's hole
    assert tuple(a[cy, cx]) == (255, 255, 255)
    assert tuple(a[cy, int(w * 0.7)]) == (0, 255, 0)


def test_png_colours_are_deterministic():
    geoms = [shapely.box(i, 0, i + 1, 1) for i in range(5)]
    a = np.asarray(io.render_image(geoms, size=64, seed=4))
    b = np.asarray(io.render_image(geoms, size=64, seed=4))
    c = np.asarray(io.render_image(geoms, size=64, seed=5))
    assert np.array_equal(a, b) and not np.array_equal(a, c)
    with pytest.raises(ValueError, match="colors has 2 entries for 5"):
        io.render_image(geoms, colors=["red", "blue"])


def test_png_lines_are_stroked_to_their_width_over_the_cells():
    # a 2-unit wide red line across a blue box: red exactly within 1 unit of the line
    box = shapely.box(0, 0, 100, 50)
    line = shapely.LineString([(10, 25), (90, 25)])
    img = io.render_image(
        [box], size=400, colors=["#0000ff"], lines=[(line, 2.0, "#ff0000")], supersample=1
    )
    a = np.asarray(img.convert("RGB")).astype(int)
    h, w, _ = a.shape
    red = (a[:, :, 0] > 200) & (a[:, :, 2] < 60)
    rows = np.flatnonzero(red[:, w // 2])
    px_per_unit = (w - 2 * max(4, round(400 * 0.02))) / 100
    assert abs(len(rows) - 2 * px_per_unit) <= 1.5  # the stroke's width, in pixels
    assert abs(rows.mean() - (h - 1) / 2) <= 1.0  # centred on y = 25
    assert tuple(a[h // 2, int(w * 0.05)]) == (0, 0, 255)  # the box beyond the line's end
    for bad, match in (
        ([(line, -1.0, "red")], "width"),
        ([(line, 1.0)], "triples"),
        ([([(0, 0), (1, 1)], 1.0, "red")], "shapely geometry"),
    ):
        with pytest.raises(ValueError, match=match):
            io.render_image([box], lines=bad)


# --- GeoJSON ------------------------------------------------------------------------------


def test_geojson_round_trip(diagram, tmp_path):
    out = io.write_geojson(diagram.cells, tmp_path / "d.geojson", sites=diagram.sites)
    data = json.loads(out.read_text())
    assert data["type"] == "FeatureCollection"
    feats = data["features"]
    assert len(feats) == len(diagram.cells)
    for i, f in enumerate(feats):
        assert f["properties"]["index"] == i
        assert f["properties"]["site"] == pytest.approx(diagram.sites[i].tolist())
        assert f["properties"]["area"] == pytest.approx(diagram.areas[i])
        geom = shapely.from_geojson(json.dumps(f["geometry"]))
        assert geom.area == pytest.approx(diagram.areas[i], rel=1e-12, abs=1e-12)
        assert geom.equals(diagram.cells[i])
    collection = shapely.from_geojson(out.read_text())
    assert collection.area == pytest.approx(diagram.boundary.area, rel=1e-9)


def test_geojson_empty_cells_and_properties(tmp_path):
    geoms = [shapely.box(0, 0, 1, 2), shapely.Polygon()]
    out = io.write_geojson(
        geoms, tmp_path / "e.json", properties={"name": ["a", "b"], "w": np.array([1.5, np.nan])}
    )
    feats = json.loads(out.read_text())["features"]
    assert feats[1]["geometry"] is None
    assert feats[0]["properties"] == {"index": 0, "area": 2.0, "name": "a", "w": 1.5}
    assert feats[1]["properties"]["w"] is None
    with pytest.raises(ValueError, match="sites has 1 points for 2"):
        io.write_geojson(geoms, tmp_path / "e.json", sites=[[0, 0]])


def test_write_dispatch_and_triangles(tmp_path):
    tris = io.triangle_polygons([[0, 0], [1, 0], [0, 1], [1, 1]], [[0, 1, 2], [1, 3, 2]])
    assert shapely.area(tris).tolist() == [0.5, 0.5]
    for name in ("t.svg", "t.png", "t.geojson", "t.json", "t.dxf"):
        assert io.write(tris, tmp_path / name, size=32).exists()
    with pytest.raises(ValueError, match="unsupported output type '.pdf'"):
        io.write(tris, tmp_path / "t.pdf")


def test_write_dxf_cells_boundary_sites(tmp_path):
    import ezdxf

    pts = np.array([[0.2, 0.3], [0.7, 0.6], [0.4, 0.8]])
    d = vf.voronoi(pts, (0, 0, 1, 1))
    path = io.write(d.cells, tmp_path / "c.dxf", sites=d.sites, boundary=d.bounds, units="mm")
    doc = ezdxf.readfile(path)
    msp = doc.modelspace()
    cells = msp.query("LWPOLYLINE[layer=='CELLS']")
    # every shared edge once: the polylines' segments are unique and node back into the cells
    lines = [np.array([p[:2] for p in e.get_points()]) for e in cells]
    lines = [
        np.vstack((ln, ln[:1])) if e.closed else ln for ln, e in zip(lines, cells, strict=True)
    ]
    segs = [
        tuple(sorted(map(tuple, np.round(s, 9).tolist())))
        for ln in lines
        for s in zip(ln[:-1], ln[1:], strict=True)
    ]
    assert len(segs) == len(set(segs))
    faces = shapely.get_parts(
        shapely.polygonize(shapely.get_parts(shapely.node(shapely.MultiLineString(lines))))
    )
    assert np.allclose(np.sort(shapely.area(faces)), np.sort(d.areas), rtol=1e-9)
    assert len(msp.query("LWPOLYLINE[layer=='BOUNDARY']")) == 1
    assert len(msp.query("POINT[layer=='SITES']")) == 3
    assert len(msp.query("CIRCLE[layer=='SITES']")) == 3  # lasers ignore POINTs
    assert doc.header["$INSUNITS"] == 4  # millimetres


# --- readers ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "text",
    [
        "1,2\n3.5,4\n-5e-1,6\n",
        "x,y\n1,2\n3.5,4\n-5e-1,6\n",
        "id,Y,X\na,2,1\nb,4,3.5\nc,6,-5e-1\n",
        "# comment\nx y\n1 2\n\n3.5 4\n-5e-1\t6\n",
        "x;y\n1;2\n3.5;4\n-5e-1;6\n",
        '"x","y"\n1,2\n3.5,4\n-0.5,6\n',
    ],
)
def test_read_points_text(tmp_path, text):
    f = tmp_path / "p.csv"
    f.write_text(text)
    assert read(f).tolist() == [[1, 2], [3.5, 4], [-0.5, 6]]


def read(path):
    pts = io.read_points(path)
    assert pts.dtype == np.float64 and pts.shape[1] == 2 and pts.flags.c_contiguous
    return pts


def test_read_points_npy_and_geojson(tmp_path):
    np.save(tmp_path / "p.npy", np.array([[1, 2], [3, 4]], dtype=np.int32))
    assert read(tmp_path / "p.npy").tolist() == [[1, 2], [3, 4]]
    fc = {
        "type": "FeatureCollection",
        "features": [
            {
                "type": "Feature",
                "properties": {},
                "geometry": {"type": "Point", "coordinates": [1, 2]},
            },
            {
                "type": "Feature",
                "properties": {},
                "geometry": {"type": "MultiPoint", "coordinates": [[3, 4, 9], [5, 6]]},
            },
        ],
    }
    (tmp_path / "p.geojson").write_text(json.dumps(fc))
    assert read(tmp_path / "p.geojson").tolist() == [[1, 2], [3, 4], [5, 6]]
    # a feature without a point is named, not skipped (checker12 F8: skipping renumbered
    # the rows after it; test_checker12_io has the cases)
    fc["features"].append({"type": "Feature", "properties": {}, "geometry": None})
    (tmp_path / "p.geojson").write_text(json.dumps(fc))
    with pytest.raises(ValueError, match="feature 2 has no geometry"):
        read(tmp_path / "p.geojson")
    (tmp_path / "g.json").write_text(json.dumps({"type": "MultiPoint", "coordinates": [[0, 1]]}))
    assert read(tmp_path / "g.json").tolist() == [[0, 1]]


@pytest.mark.parametrize(
    ("name", "content", "message"),
    [
        ("missing.csv", None, "missing.csv: no such file"),
        ("empty.csv", "\n# nothing\n", "no points"),
        ("header.csv", "x,y\n", "only a header"),
        ("cols.csv", "a,b,c\n1,2,3\n", "no columns named x and y"),
        ("bad.csv", "x,y\n1,2\n3,oops\n", "line 3: 'oops' is not a number"),
        ("short.csv", "1,2\n3\n", "line 2: expected at least 2 columns"),
        ("nan.txt", "1 2\nnan 4\n", "line 2: 'nan' is not a finite number"),
        ("ragged.csv", "0,0\n1,2,3\n4,5\n", "line 2: 3 columns, but line 1 has 2"),
        ("wide.csv", "x,y\n0,0\n1,2,3\n", "line 3: 3 columns, but the header on line 1 has 2"),
        ("pts.shp", "", "unsupported point file type '.shp'"),
        (
            "poly.geojson",
            '{"type": "Polygon", "coordinates": [[[0,0],[1,0],[0,1],[0,0]]]}',
            "no Point or MultiPoint geometries (found Polygon)",
        ),
        ("broken.json", '{"type": \n', "line 2: invalid JSON"),
    ],
)
def test_read_points_errors(tmp_path, name, content, message):
    f = tmp_path / name
    if content is not None:
        f.write_text(content)
    with pytest.raises(ValueError, match=re.escape(message)) as err:
        io.read_points(f)
    assert name in str(err.value)


def test_read_points_npy_errors(tmp_path):
    np.save(tmp_path / "three.npy", np.zeros((4, 3)))
    with pytest.raises(
        ValueError, match=r"three.npy: expected an \(n, 2\) array, got shape \(4, 3\)"
    ):
        io.read_points(tmp_path / "three.npy")
    # complex would lose its imaginary part and bool is no coordinate: both refused
    for name, arr in (("c.npy", np.ones((3, 2), complex)), ("b.npy", np.ones((3, 2), bool))):
        np.save(tmp_path / name, arr)
        with pytest.raises(ValueError, match=f"{name}: array of dtype .* is not real numbers"):
            io.read_points(tmp_path / name)
    np.save(tmp_path / "e.npy", np.zeros((0, 2)))
    with pytest.raises(ValueError, match="e.npy: no points"):
        io.read_points(tmp_path / "e.npy")


def test_read_points_trailing_delimiter_and_three_columns(tmp_path):
    f = tmp_path / "t.csv"
    f.write_text("0,0,\n1,2,\n")  # a trailing comma is not a header nor a third column
    assert read(f).tolist() == [[0, 0], [1, 2]]
    from voroforge.cli.voronoi3d import read_points3d

    f.write_text("id;height;x;y\na;5;1;2\nb;6;3;4\n")
    assert read_points3d(f).tolist() == [[1, 2, 5], [3, 4, 6]]
    f.write_text("x,y,z\n")
    with pytest.raises(ValueError, match="only a header row"):
        read_points3d(f)
    np.save(tmp_path / "p3.npy", np.zeros((2, 2)))
    with pytest.raises(ValueError, match=r"expected an \(n, 3\) array"):
        read_points3d(tmp_path / "p3.npy")


def test_read_boundary(tmp_path):
    assert io.read_boundary("0, -1.5, 10, 20") == (0.0, -1.5, 10.0, 20.0)
    assert io.read_boundary((0, 0, 1, 1)) == (0, 0, 1, 1)
    poly = shapely.box(0, 0, 10, 10).difference(shapely.box(4, 4, 6, 6))
    fc = {
        "type": "FeatureCollection",
        "features": [
            {
                "type": "Feature",
                "properties": {},
                "geometry": {"type": "Point", "coordinates": [0, 0]},
            },
            {"type": "Feature", "properties": {}, "geometry": json.loads(shapely.to_geojson(poly))},
        ],
    }
    (tmp_path / "one.geojson").write_text(json.dumps(fc))
    assert io.read_boundary(str(tmp_path / "one.geojson")).equals(poly)
    fc["features"].append(
        {
            "type": "Feature",
            "properties": {},
            "geometry": json.loads(shapely.to_geojson(shapely.box(20, 0, 30, 10))),
        }
    )
    (tmp_path / "two.geojson").write_text(json.dumps(fc))
    both = io.read_boundary(tmp_path / "two.geojson")
    assert both.area == pytest.approx(poly.area + 100)


@pytest.mark.parametrize(
    ("spec", "message"),
    [
        ("nope.geojson", "no such file, and not xmin,ymin,xmax,ymax"),
        ("0,0,1", "no such file, and not xmin,ymin,xmax,ymax"),
        ("5,0,1,1", "xmin < xmax and ymin < ymax"),
    ],
)
def test_read_boundary_errors(spec, message):
    with pytest.raises(ValueError, match=re.escape(message)):
        io.read_boundary(spec)


def test_read_boundary_needs_polygons(tmp_path):
    f = tmp_path / "pts.geojson"
    f.write_text(json.dumps({"type": "Point", "coordinates": [0, 0]}))
    with pytest.raises(ValueError, match="no Polygon or MultiPolygon geometries"):
        io.read_boundary(f)


def test_read_boundary_dispatches_svg_and_dxf_by_suffix(tmp_path):
    import ezdxf

    from voroforge.design import boundary as bd
    from voroforge.io.readers import read_dxf, read_svg

    svg = tmp_path / "outline.svg"
    svg.write_text(
        '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10">'
        '<rect x="0" y="0" width="10" height="10"/><rect x="2" y="2" width="3" height="3"/></svg>'
    )
    g = io.read_boundary(svg)
    assert g.area == pytest.approx(100 - 9)
    assert g.equals(read_svg(svg)) and g.equals(bd.from_svg(svg))
    assert io.read_boundary(str(svg), tolerance=0.5).area == pytest.approx(91)

    doc = ezdxf.new()
    doc.modelspace().add_lwpolyline([(0, 0), (4, 0), (4, 3), (0, 3)], close=True)
    dxf = tmp_path / "outline.dxf"
    doc.saveas(dxf)
    d = io.read_boundary(dxf)
    assert d.area == pytest.approx(12) and d.equals(read_dxf(dxf))

    gj = tmp_path / "outline.geojson"
    gj.write_text(shapely.to_geojson(shapely.box(0, 0, 1, 1)))
    with pytest.raises(ValueError, match="GeoJSON boundaries take no options"):
        io.read_boundary(gj, tolerance=0.1)
    with pytest.raises(ValueError, match="is a directory"):
        io.read_points(tmp_path)


def test_io_does_not_import_the_design_layer():
    import subprocess
    import sys

    code = "import sys, voroforge.io; print([m for m in sys.modules if 'design' in m])"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip().splitlines()[-1] == "[]"


def test_docstring_examples_of_readers_and_arcs():
    import doctest

    import voroforge.io.arcs
    import voroforge.io.readers

    for module in (voroforge.io.readers, voroforge.io.arcs):
        result = doctest.testmod(module)
        assert result.attempted > 0 and result.failed == 0, module.__name__


def test_open_svg_outline_is_an_error_naming_file_and_element(tmp_path):
    from voroforge.io.readers.svg import read_svg

    f = tmp_path / "open.svg"
    f.write_text(
        '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">'
        '<path id="outline" d="M 0 0 L 100 0 L 100 100 L 0 100 L 0 0.5"/></svg>'
    )
    with pytest.raises(ValueError, match=r"open\.svg: <path id='outline'>: subpath 1 is open"):
        read_svg(f)
    with pytest.raises(ValueError, match="0.5 user units apart"):
        read_svg(f, close_tolerance=0.1)
    assert read_svg(f, close_tolerance=1.0).area == pytest.approx(10000.0)
    assert read_svg(f, close_tolerance=None).area == pytest.approx(10000.0)  # as a fill
    g = tmp_path / "closed.svg"
    g.write_text(f.read_text().replace('0.5"', '0.5 Z"'))
    assert read_svg(g).area == pytest.approx(10000.0)
    # from a design file: the key and the file's element
    from voroforge.design.build import check_design
    from voroforge.design.designfile import DesignError

    design = tmp_path / "d.toml"
    design.write_text(
        '[boundary]\nshape = "file"\nfile = "open.svg"\n[seeds]\nmethod = "random"\ncount = 5\n'
    )
    with pytest.raises(DesignError, match=r"d\.toml:3: boundary\.file: .*<path id='outline'>"):
        check_design(design)
    check_design(design, overrides={"boundary.close_tolerance": 1})


def test_gif_streams_frames_of_several_sizes_and_is_written_whole(tmp_path, monkeypatch):
    from voroforge.io.gif import write_gif

    rng = np.random.default_rng(3)
    colours = rng.integers(0, 256, (6, 3), dtype=np.uint8)
    shapes = [(40, 30), (24, 36), (40, 30)]
    arrays = [colours[rng.integers(0, 6, s)] for s in shapes]
    made = []

    def frames():
        for a in arrays:
            made.append(len(made))
            yield Image.fromarray(a, "RGB")

    path = write_gif(frames(), tmp_path / "a.gif", fps=10)
    with Image.open(path) as im:
        assert im.n_frames == 3 and im.size == (36, 40)
        for k, a in enumerate(arrays):
            im.seek(k)
            shown = np.asarray(im.convert("RGB"))
            y, x = (40 - a.shape[0]) // 2, (36 - a.shape[1]) // 2
            want = np.broadcast_to(a[0, 0], (40, 36, 3)).copy()  # its corner colour around it
            want[y : y + a.shape[0], x : x + a.shape[1]] = a
            assert np.array_equal(shown, want)  # 6 colours: the palette is exact
    old = path.read_bytes()

    def failing():
        yield Image.fromarray(arrays[0], "RGB")
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        write_gif(failing(), path)
    assert path.read_bytes() == old and [p.name for p in tmp_path.iterdir()] == ["a.gif"]
