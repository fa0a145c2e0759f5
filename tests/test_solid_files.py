"""[solid] design-file sections: voroforge build writes meshes and a preview, check runs."""

from __future__ import annotations

import pytest

trimesh = pytest.importorskip("trimesh")
pytest.importorskip("manifold3d")

import numpy as np  # noqa: E402
from PIL import Image  # noqa: E402

from voroforge.design.build import build, check_design  # noqa: E402
from voroforge.design.designfile import DesignError, load  # noqa: E402
from voroforge.io.mesh import read  # noqa: E402

FOAM = """
[design]
name = "tiny-foam"
units = "mm"

[solid]
kind = "foam"
container = [0, 0, 0, 20, 20, 20]
cells = 10
relax = 0
wall = 1.0
formats = ["png", "3mf", "stl"]
min_pore = 50.0
"""


def test_build_foam_design(tmp_path):
    src = tmp_path / "foam.toml"
    src.write_text(FOAM)
    paths = build(src, tmp_path / "out")
    assert [p.suffix for p in paths] == [".png", ".3mf", ".stl"]
    m = read(paths[1])
    assert m.is_volume and m.metadata["units"] == "mm"
    assert 0 < m.volume < 20**3
    assert abs(read(paths[2]).volume - m.volume) < 1e-5 * m.volume  # STL: float32
    im = Image.open(paths[0])
    gray = np.asarray(im.convert("L"))
    assert im.size[0] > 100 and len(np.unique(gray)) > 20  # shaded, not blank


def test_a_bare_solid_writes_its_meshes_beside_the_preview(tmp_path, monkeypatch):
    import threading

    from voroforge.solid import build as solid_build
    from voroforge.solid import implicit
    from voroforge.solid.implicit import Bare

    src = tmp_path / "shell.toml"
    src.write_text(SHELL + 'formats = ["3mf", "png", "ply"]\npng_size = 64\n')
    box = trimesh.creation.box((12, 10, 8))  # the bare mesh a shell's make_solid returns
    bare = Bare(box.vertices, box.faces, {"decimals": 6})  # on the implicit route's grid
    monkeypatch.setattr(solid_build, "make_solid", lambda *a, **k: bare)
    monkeypatch.setattr(implicit, "THREADS", True)  # whatever the machine's load
    write, threads = solid_build._write_mesh, {}

    def watched(m, path, fmt, units):
        threads[fmt] = threading.current_thread().name
        return write(m, path, fmt, units)

    monkeypatch.setattr(solid_build, "_write_mesh", watched)
    paths = build(src, tmp_path / "out")
    assert [p.suffix for p in paths] == [".3mf", ".png", ".ply"]  # formats' order
    assert threads == {"3mf": "voroforge-solid-files", "ply": "voroforge-solid-files"}
    assert read(paths[0]).is_volume and read(paths[2]).is_volume

    def broken(m, path, fmt, units):
        raise OSError(f"no room for {path.name}")

    # the writer's error is raised after the preview is written
    monkeypatch.setattr(solid_build, "_write_mesh", broken)
    with pytest.raises(OSError, match="no room for tiny-shell.3mf"):
        build(src, tmp_path / "broken")
    assert (tmp_path / "broken" / "tiny-shell.png").is_file()

    # a preview's error comes first, once the mesh files are complete
    def failing(*a, **k):
        raise ValueError("preview failed")

    monkeypatch.setattr(solid_build, "_write_mesh", write)
    monkeypatch.setattr(solid_build, "preview", failing)
    with pytest.raises(ValueError, match="preview failed"):
        build(src, tmp_path / "nopng")
    assert read(tmp_path / "nopng" / "tiny-shell.3mf").is_volume


def test_check_design_reports_pores_and_voids(tmp_path):
    src = tmp_path / "foam.toml"
    src.write_text(FOAM)
    rep = check_design(src)
    kinds = rep.by_kind()
    assert kinds["small_pore"] == kinds["trapped_void"] >= 5
    text = rep.table(max_rows=None)
    assert "small_pore" in text and "trapped_void" in text
    with pytest.raises(ValueError, match="overlay"):
        rep.write_png(tmp_path / "x.png")


def test_solid_section_errors(tmp_path):
    src = tmp_path / "bad.toml"
    src.write_text(FOAM.replace("container = [0, 0, 0, 20, 20, 20]", ""))
    with pytest.raises(DesignError, match="container"):
        load(src)
    src.write_text(FOAM.replace('kind = "foam"', 'kind = "sponge"'))
    with pytest.raises(DesignError, match="kind"):
        load(src)
    src.write_text(FOAM.replace("[0, 0, 0, 20, 20, 20]", "[0, 0, 0, -1, 20, 20]"))
    with pytest.raises(DesignError, match="max must exceed"):
        load(src)


def test_recursive_subdivision_tiles_each_cell():
    from voroforge import solid

    cube = trimesh.creation.box((10, 10, 10))
    leaves = solid.cells.subdivide([cube], 5, levels=2, seed=1)
    assert 10 <= len(leaves) <= 25
    assert abs(sum(c.volume for c in leaves) - 1000.0) <= 1e-9 * 1000.0
    for c in leaves:
        assert c.is_volume
        assert (c.bounds[0] >= -5 - 1e-9).all() and (c.bounds[1] <= 5 + 1e-9).all()
    f = solid.fields.plane((0, 0, 5), (0, 0, 1), radius=10, falloff="linear")
    graded = solid.cells.subdivide([cube], (2, 8), field=f, seed=1)
    assert 2 <= len(graded) <= 8
    m = solid.lattice(leaves, radius=0.3, voxel=0.3, smoothing=0)
    assert m.is_volume


def test_relax_moves_sites_to_centroids():
    import numpy as np

    from voroforge import solid

    p = np.random.default_rng(0).random((12, 3)) * 10
    q = solid.cells.relax(p, (0, 0, 0, 10, 10, 10), iterations=3)
    assert q.shape == p.shape and not np.shares_memory(p, q)
    assert ((q > 0) & (q < 10)).all()


SLAB = """
[design]
name = "tiny-slab"
units = "mm"
seed = 4

[boundary]
shape = "rectangle"
width = 60
height = 40
margin = 4

[seeds]
method = "random"
count = 12

[cells]
web = 2

[solid]
kind = "extrude"
thickness = 3
formats = ["3mf", "png"]
"""


def test_build_extrude_design(tmp_path):
    # kind = "extrude": the file's 2D design computed, its frame as a 3 mm slab
    from voroforge.design.compute import compute

    src = tmp_path / "slab.toml"
    src.write_text(SLAB)
    paths = build(src, tmp_path / "out")
    assert [p.suffix for p in paths] == [".3mf", ".png"]
    m = read(paths[0])
    assert m.is_volume and m.metadata["units"] == "mm"
    frame = compute(*load(src)).frame
    assert frame.area < 60 * 40  # openings cut through
    assert abs(m.volume - 3.0 * frame.area) <= 1e-9 * m.volume
    assert np.allclose(m.bounds[:, 2], [0, 3])
    assert np.allclose(m.bounds[:, :2], np.reshape(frame.bounds, (2, 2)), atol=1e-9)


SHELL = """
[design]
name = "tiny-shell"
units = "mm"

[solid]
kind = "shell"
profile = [[10, 0], [12, 10], [10, 20]]
sections = 24
thickness = 1.0
openings = 10
web = 1.5
voxel = 0.5
smoothing = 1
"""


SKIN = """
[design]
name = "tiny-skin"
units = "mm"

[solid]
kind = "lattice"
container = "box.stl"
cells = 6
relax = 0
radius = [0.5, 0.7]
skin = 0.8
voxel = 0.5
smoothing = 2
formats = ["3mf", "png"]
png_size = 64

[[solid.fields]]
type = "point"
points = [[0, 0, 0]]
radius = 8
"""


def test_builders_survive_their_submodules_being_imported_first(tmp_path):
    # importing ``voroforge.solid.shell`` (the module) used to rebind the package's ``shell``
    # to it, so ``solid.shell(...)`` and the design build both failed ("'module' object is not
    # callable"); a fresh interpreter, since which comes first is what matters
    import subprocess
    import sys

    src = tmp_path / "shell.toml"
    src.write_text(SHELL)
    # first, in the same interpreter: a skinned lattice's build reads its binary STL and
    # previews and writes the implicit route's mesh without importing trimesh or
    # scipy.spatial (its strut graph and point field need neither), and so does a revolved
    # shell's (its surface, seeds and rim in numpy); their make_solid imports the lattice
    # and shell submodules as the statements below do, the other three come after them
    trimesh.creation.box((12, 10, 8)).export(tmp_path / "box.stl")
    (tmp_path / "skin.toml").write_text(SKIN)
    code = (
        "import sys, types\n"
        "from voroforge.design.build import build\n"
        f"build({str(tmp_path / 'skin.toml')!r}, {str(tmp_path / 'out')!r})\n"
        f"build({str(src)!r}, {str(tmp_path / 'out')!r}, overrides={{'solid.png_size': 64}})\n"
        "print('TRIMESH', 'trimesh' in sys.modules, 'scipy.spatial' in sys.modules)\n"
        "import voroforge.solid.shell, voroforge.solid.lattice, voroforge.solid.foam\n"
        "import voroforge.solid.extrude, voroforge.solid.check\n"
        "from voroforge import solid\n"
        "for name in ('shell', 'lattice', 'foam', 'extrude', 'check'):\n"
        "    f = getattr(solid, name)\n"
        "    assert isinstance(f, types.FunctionType) and f.__name__ == name, (name, f)\n"
        "from voroforge.design.designfile import load\n"
        "from voroforge.solid.build import check_solid, make_solid\n"
        f"design, base = load({str(src)!r})\n"
        "m = make_solid(design, base)\n"
        "print('SHELL', m.metadata['kind'], bool(m.is_volume))\n"
        "print('CHECK', type(check_solid(design, base)).__name__)\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    assert "SHELL shell True" in done.stdout and "CHECK Report" in done.stdout
    assert "TRIMESH False False" in done.stdout
    # the same files as from the Trimesh that make_solid returns (io.mesh.read's container)
    from voroforge.io.mesh import write
    from voroforge.solid.build import make_solid

    m = make_solid(*load(tmp_path / "skin.toml"))
    assert m.is_volume and m.metadata["skin"] == 0.8
    built = (tmp_path / "out" / "tiny-skin.3mf").read_bytes()
    assert built == write(m, tmp_path / "t.3mf").read_bytes()
    (stl,) = build(tmp_path / "skin.toml", tmp_path / "o2", overrides={"solid.formats": '["stl"]'})
    assert stl.read_bytes() == write(m, tmp_path / "t.stl").read_bytes()  # a Bare mesh's arrays
    shell = make_solid(*load(src))  # the Trimesh route of the same shell: the same file
    built = (tmp_path / "out" / "tiny-shell.3mf").read_bytes()
    assert built == write(shell, tmp_path / "s.3mf").read_bytes()


def test_3mf_text_is_python_repr():
    # solid.threemf writes grid values as ``%r`` does (shortest round trip, an exponent
    # under 1e-4, -0.0 signed), integers as ``%d``; None where it cannot (off the grid, NaN,
    # so large that a shorter decimal would read back the same)
    from voroforge.solid.threemf import on_grid, rows_text

    rng = np.random.default_rng(5)
    for d in (1, 3, 6, 9):
        x = np.concatenate(
            [
                rng.uniform(-100, 100, 400),
                rng.choice([-1, 1], 400) * 10.0 ** rng.uniform(-d, 3, 400),
                [0.0, -0.0, 1e-4, -1e-4, 10.0**-d, 1.5e-5, 3.0, 1234.0],
            ]
        )
        v = on_grid(x, d).reshape(-1, 2)
        tpl = '<v x="%r" y="%r"/>'
        assert rows_text(v, tpl, d) == ((tpl * len(v)) % tuple(v.ravel().tolist())).encode(), d
    f = rng.integers(-5, 10**12, (50, 3))
    assert rows_text(f, "%d %d %d;") == (("%d %d %d;" * 50) % tuple(f.ravel().tolist())).encode()
    assert rows_text([[0.1234567]], "%r", 6) is None  # off the grid
    assert rows_text([[np.nan]], "%r", 6) is None
    assert rows_text([[2.3e9]], "%r", 6) is None  # 1e-6 is below its float spacing's half
    assert rows_text([[2.2e9]], "%r", 6) == b"2200000000.0"


def test_implicit_3mf_same_bytes_as_io_mesh(tmp_path, monkeypatch):
    # the implicit route's vertices lie on its decimal grid; write_3mf's file is io.mesh's,
    # byte for byte, and reads back bit for bit; a mesh off the grid goes to io.mesh.write
    import zipfile

    from voroforge.io.mesh import write
    from voroforge.solid.implicit import capsules_mesh
    from voroforge.solid.threemf import write_3mf

    struts = {
        "a": np.array([[0.0, 0, 0], [0, 0, 0]]),
        "b": np.array([[3.0, 1, 0.5], [-1, 2.5, 1]]),
        "ra": np.array([0.5, 0.4]),
        "rb": np.array([0.3, 0.4]),
    }
    m = capsules_mesh(struts, voxel=0.15, smoothing=2, smooth=0.2)
    assert m.is_volume and m.metadata["decimals"] == 6
    fast = write_3mf(m, tmp_path / "fast.3mf").read_bytes()
    assert fast == write(m, tmp_path / "ref.3mf").read_bytes()
    assert (read(tmp_path / "fast.3mf").vertices == m.vertices).all()
    with zipfile.ZipFile(tmp_path / "fast.3mf") as z:
        assert b'x="-' in z.read("3D/3dmodel.model")  # negative coordinates among them
    off = trimesh.creation.icosphere(subdivisions=1)
    assert write_3mf(off, tmp_path / "o.3mf", decimals=6).read_bytes() == (
        write(off, tmp_path / "o_ref.3mf").read_bytes()
    )
    # the text deflated a few rows at a time: the same file; one vertex off the grid in
    # the last run of rows: io.mesh.write's file
    from voroforge.solid import threemf

    monkeypatch.setattr(threemf, "_CHUNK", 7)
    assert write_3mf(m, tmp_path / "runs.3mf").read_bytes() == fast
    m.vertices[-1, 0] += 1e-9
    assert (
        write_3mf(m, tmp_path / "o2.3mf").read_bytes() == write(m, tmp_path / "r2.3mf").read_bytes()
    )
