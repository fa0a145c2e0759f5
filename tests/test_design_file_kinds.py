"""Files a design names must be regular files of a sane size (checker16 F5).

A FIFO as ``seeds.file`` hung ``voroforge build`` forever (and the studio under its lock); a
link to /dev/zero was read until memory ran out. They are refused at the key, with the path.
"""

from __future__ import annotations

import os

import pytest

from voroforge.design import designfile
from voroforge.design.compute import compute
from voroforge.design.designfile import DesignError, load

DESIGN = """[boundary]
shape = "rectangle"
width = 10
height = 10

[seeds]
method = "file"
file = "{name}"
"""


def _build(tmp_path, name):
    path = tmp_path / "d.toml"
    path.write_text(DESIGN.format(name=name))
    design, base = load(path)
    return compute(design, base)


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs here")
def test_a_fifo_is_refused_not_read(tmp_path):
    os.mkfifo(tmp_path / "pipe.csv")
    with pytest.raises(DesignError, match=r"seeds\.file.*not a regular file.*pipe\.csv"):
        _build(tmp_path, "pipe.csv")


def test_a_directory_and_a_device_are_refused(tmp_path):
    (tmp_path / "folder.csv").mkdir()
    with pytest.raises(DesignError, match=r"seeds\.file.*not a regular file"):
        _build(tmp_path, "folder.csv")
    if os.path.exists("/dev/zero"):
        (tmp_path / "zero.csv").symlink_to("/dev/zero")
        with pytest.raises(DesignError, match=r"seeds\.file.*not a regular file"):
            _build(tmp_path, "zero.csv")


def test_a_file_over_the_limit_is_refused(tmp_path, monkeypatch):
    (tmp_path / "pts.csv").write_text("x,y\n1,1\n2,2\n3,7\n")
    assert len(_build(tmp_path, "pts.csv").sites) == 3  # (under the limit: read)
    monkeypatch.setattr(designfile, "DESIGN_FILE_MAX_BYTES", 8)
    with pytest.raises(DesignError, match=r"seeds\.file.*GiB, more than"):
        _build(tmp_path, "pts.csv")
