"""``voroforge voronoi3d`` outputs read back by independent readers; repeated ``-o`` refused.

checker36 (s54): the CSV (csv module), Parquet (pyarrow), OBJ (a plain parser here), PLY
(its binary body parsed here) and PNG (PIL) of one run are read back and checked against
the invariants of a box: one row/object per cell in input order, volumes summing to the box,
symmetric neighbour lists, every cell a closed mesh. voro++'s CLI, where installed, gives
the reference volumes and neighbours.
"""

from __future__ import annotations

import csv
import shutil
import subprocess

import numpy as np
import pytest

from voroforge.cli import main


@pytest.fixture
def pts3(tmp_path):
    f = tmp_path / "p3.csv"
    xyz = np.random.default_rng(36).random((40, 3))
    f.write_text("x,y,z\n" + "\n".join(",".join(map(repr, r)) for r in xyz.tolist()) + "\n")
    return f, xyz


def _closed(faces):
    """Every undirected edge of the polygons ``faces`` is used once each way."""
    edges = {}
    for f in faces:
        for a, b in zip(f, f[1:] + f[:1], strict=True):
            edges[(a, b)] = edges.get((a, b), 0) + 1
    return all(n == 1 and edges.get((b, a)) == 1 for (a, b), n in edges.items())


def _signed_volume(verts, faces):
    v = 0.0
    for f in faces:
        p0 = verts[f[0]]
        for j in range(1, len(f) - 1):
            v += np.dot(p0, np.cross(verts[f[j]], verts[f[j + 1]])) / 6
    return v


def _read_obj(path):
    verts, objects, cur = [], {}, None
    for line in path.read_text().splitlines():
        t = line.split()
        if t and t[0] == "v":
            verts.append([float(x) for x in t[1:4]])
        elif t and t[0] == "o":
            cur = objects.setdefault(t[1], [])
        elif t and t[0] == "f":
            cur.append([int(x.split("/")[0]) - 1 for x in t[1:]])
    return np.array(verts), objects


def _read_ply(path):
    head, body = path.read_bytes().split(b"end_header\n", 1)
    lines = head.decode().splitlines()
    nv = int(next(ln for ln in lines if ln.startswith("element vertex")).split()[2])
    nf = int(next(ln for ln in lines if ln.startswith("element face")).split()[2])
    assert "property double x" in lines and "property int cell" in lines
    verts = np.frombuffer(body[: 24 * nv], "<f8").reshape(nv, 3)
    off, faces, cells = 24 * nv, [], []
    for _ in range(nf):
        c = body[off]
        faces.append(np.frombuffer(body[off + 1 : off + 1 + 4 * c], "<i4").tolist())
        cells.append(int(np.frombuffer(body[off + 1 + 4 * c : off + 5 + 4 * c], "<i4")[0]))
        off += 5 + 4 * c
    assert off == len(body)
    return verts, faces, np.array(cells)


@pytest.mark.parametrize("periodic", [False, True])
def test_every_output_read_back_independently(tmp_path, pts3, periodic):
    pq = pytest.importorskip("pyarrow.parquet")
    from PIL import Image

    f, xyz = pts3
    n = len(xyz)
    outs = [tmp_path / f"c.{s}" for s in ("csv", "parquet", "obj", "ply", "png")]
    argv = ["voronoi3d", str(f), "--container", "0,0,0,1,1,1", "--size", "200x160"]
    argv += [a for o in outs for a in ("-o", str(o))] + (["--periodic"] if periodic else [])
    assert main(argv) == 0
    rows = list(csv.DictReader(outs[0].open()))
    assert [int(r["id"]) for r in rows] == list(range(n))
    vol = np.array([float(r["volume"]) for r in rows])
    nbs = [[int(v) for v in r["neighbors"].split()] for r in rows]
    assert (vol > 0).all() and abs(vol.sum() - 1) < 1e-12
    pairs = {(i, j) for i in range(n) for j in nbs[i] if j >= 0}
    assert all((j, i) in pairs and i != j for i, j in pairs)
    if periodic:
        assert all(j >= 0 for nb in nbs for j in nb)  # a torus has no walls
    cen = np.array([[float(r[k]) for k in ("cx", "cy", "cz")] for r in rows])
    if not periodic:  # a torus cell's centroid may lie past the box, near its site
        assert (cen >= 0).all() and (cen <= 1).all()
    t = pq.read_table(outs[1]).to_pydict()
    assert t["id"] == list(range(n)) and t["volume"] == vol.tolist() and t["neighbors"] == nbs
    verts, objects = _read_obj(outs[2])
    assert list(objects) == [f"cell_{i}" for i in range(n)]
    for i, faces in enumerate(objects.values()):
        assert _closed(faces)
        assert abs(_signed_volume(verts, faces) - vol[i]) < 1e-12
    pv, pf, pc = _read_ply(outs[3])
    assert sorted(set(pc.tolist())) == list(range(n))
    pv_total = sum(_signed_volume(pv, [pf[k] for k in np.flatnonzero(pc == i)]) for i in range(n))
    assert abs(pv_total - 1) < 1e-12
    im = np.asarray(Image.open(outs[4]).convert("RGB"))
    assert im.shape == (160, 200, 3)
    assert len(np.unique(im.reshape(-1, 3), axis=0)) > n  # shaded cells, not a blank frame
    exe = shutil.which("voro++")
    if exe:  # the reference: voro++ prints volumes to 6 digits
        src = tmp_path / "v.txt"
        src.write_text(
            "".join(f"{i} {x!r} {y!r} {z!r}\n" for i, (x, y, z) in enumerate(xyz.tolist()))
        )
        per = ["-p"] if periodic else []
        subprocess.run(
            [exe, *per, "-c", "%i %v %n", "0", "1", "0", "1", "0", "1", str(src)], check=True
        )
        ref = {int(t[0]): t[1:] for t in (ln.split() for ln in open(f"{src}.vol"))}
        for i in range(n):
            assert abs(float(ref[i][0]) - vol[i]) <= 1e-5 * vol[i]
            assert {int(v) for v in ref[i][1:] if int(v) >= 0} == {j for j in nbs[i] if j >= 0}


@pytest.mark.parametrize(
    "command",
    [
        ["voronoi3d", "P3", "-o", "a.csv", "-o", "./a.csv"],
        ["voronoi3d", "P3", "-o", "a.csv", "-o", "b.obj", "-o", "a.csv"],
        ["voronoi", "P2", "-o", "a.svg", "-o", "a.svg"],
        ["raster", "P2", "-o", "a.png", "-o", "a.png"],
        ["explain", "fortune", "P2", "-o", "a.gif", "-o", "b.gif"],
        ["stipple", "@sphere", "-o", "a.svg", "-o", "a.svg"],
        ["animate", "d.toml", "-o", "a.gif", "-o", "b.gif"],
    ],
)
def test_a_repeated_output_is_refused_before_any_work(tmp_path, pts3, command, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "P2").write_text("0,0\n1,0\n0,1\n1,1\n")
    (tmp_path / "P3").write_text(pts3[0].read_text())
    assert main(command) == 2
    err = capsys.readouterr().err
    assert "given twice" in err and "Traceback" not in err
    assert not list(tmp_path.glob("a.*")) and not list(tmp_path.glob("b.*"))
