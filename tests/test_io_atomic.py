"""voroforge.io.atomic: the one atomic write every writer uses."""

import os

import pytest
import shapely

from voroforge.io.atomic import new_file_mode, write_atomically, write_bytes
from voroforge.io.svg import write_svg


def test_write_replaces_whole_with_an_ordinary_mode(tmp_path):
    out = tmp_path / "a.bin"
    out.write_bytes(b"old")
    assert write_bytes(out, b"new") == out
    assert out.read_bytes() == b"new"
    assert os.stat(out).st_mode & 0o777 == new_file_mode()  # not mkstemp's 0600
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.bin"]


def test_a_failed_write_leaves_the_old_file_and_no_temporary(tmp_path):
    out = tmp_path / "a.txt"
    out.write_text("old")

    def fail(tmp):
        with open(tmp, "w") as fh:
            fh.write("half")
        raise RuntimeError("disk full")

    with pytest.raises(RuntimeError):
        write_atomically(out, fail)
    assert out.read_text() == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt"]


def test_the_temporary_keeps_the_suffix_and_svg_gets_an_ordinary_mode(tmp_path):
    seen = []

    def write(tmp):
        seen.append(tmp)
        with open(tmp, "w") as fh:
            fh.write("ply")

    write_atomically(tmp_path / "m.ply", write)
    assert seen[0].endswith(".ply")  # writers that choose the format by suffix
    svg = write_svg([shapely.box(0, 0, 1, 1)], tmp_path / "s.svg")
    assert os.stat(svg).st_mode & 0o777 == new_file_mode()


def test_a_symbolic_link_is_written_through(tmp_path):
    # checker8: the rename onto a link replaced the link with a file
    from voroforge.io.atomic import write_bytes

    target = tmp_path / "real.csv"
    target.write_text("old")
    link = tmp_path / "link.csv"
    link.symlink_to("real.csv")
    write_bytes(link, b"new")
    assert link.is_symlink() and target.read_bytes() == b"new"


def test_an_unwritable_folder_names_the_file_asked_for(tmp_path):
    from voroforge.io.atomic import write_bytes

    missing = tmp_path / "no" / "such" / "out.csv"
    with pytest.raises(OSError, match=r"cannot write .*out\.csv"):
        write_bytes(missing, b"x")


def test_explode_must_be_finite():
    # checker8: --explode nan drew an all-white PNG and exited 0
    import numpy as np

    import voroforge as vf
    from voroforge.io.render3d import diagram_meshes

    d = vf.voronoi3d(np.random.default_rng(0).random((20, 3)), (0, 0, 0, 1, 1, 1))
    for bad in (float("nan"), float("inf"), -0.5, "0.1", 1e20, 5.5):  # 1e20: a blank PNG
        with pytest.raises(ValueError, match="explode"):
            diagram_meshes(d, explode=bad)
    assert len(diagram_meshes(d, explode=0.2)) == 20 == len(diagram_meshes(d, explode=5))


_FULL_DISK = """
import resource, signal, sys
import numpy as np, shapely
import voroforge as vf
from voroforge.explain.render import write_gif
from voroforge.io import write
from voroforge.io.geojson import write_geojson
from voroforge.io.raster_png import write_raster
signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # past the limit a write fails (EFBIG)
pts = np.random.default_rng(0).random((3000, 2))
d = vf.voronoi(pts)
r = vf.rasterize(pts, (400, 400))
resource.setrlimit(resource.RLIMIT_FSIZE, (20000, 20000))
writers = {
    "cells.geojson": lambda p: write_geojson(d.cells, p),
    "cells.svg": lambda p: write(d.cells, p),
    "cells-drawn.png": lambda p: write(d.cells, p),
    "cells.png": lambda p: write_raster(r, p),
    "labels.npy": lambda p: write_raster(r, p),
    "sweep.gif": lambda p: write_gif(pts[:300], p, frames=40, size=300),
}
for name, w in writers.items():
    try:
        w(sys.argv[1] + "/" + name)
    except OSError as exc:
        print(name, "failed:", exc.errno)
"""


def test_writers_leave_the_old_file_when_the_disk_fills(tmp_path):
    # checker19 F4: GeoJSON, the cells' SVG, raster PNG/.npy and the sweep's GIF were written
    # in place, so a failed write left a truncated file
    import subprocess
    import sys

    names = [
        "cells.geojson",
        "cells.svg",
        "cells-drawn.png",
        "cells.png",
        "labels.npy",
        "sweep.gif",
    ]
    for name in names:
        (tmp_path / name).write_text("old")
    run = subprocess.run(
        [sys.executable, "-c", _FULL_DISK, str(tmp_path)], capture_output=True, text=True
    )
    assert run.returncode == 0, run.stderr
    assert run.stdout.count("failed:") == len(names), run.stdout  # EFBIG (numpy: errno None)
    for name in names:
        assert (tmp_path / name).read_text() == "old", name
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(names)  # no temporaries


def test_cli_explode_past_the_bound_is_refused_before_computing(tmp_path, capsys):
    # checker24 F3: --explode 1e20 wrote a blank PNG with exit 0
    import numpy as np

    from voroforge.cli import main

    src = tmp_path / "p.csv"
    np.savetxt(src, np.random.default_rng(0).random((20, 3)), delimiter=",")
    out = tmp_path / "c.png"
    assert main(["voronoi3d", str(src), "-o", str(out), "--explode", "1e20"]) == 2
    assert "explode must be a number from 0 to 5" in capsys.readouterr().err
    assert not out.exists()
