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
