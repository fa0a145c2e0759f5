"""Fixes of the lead's session s52 (checker findings), each against an independent expectation."""

from __future__ import annotations

import json

import numpy as np
import pytest

import voroforge as vf
from voroforge.design.designfile import DesignError, load, parse_value
from voroforge.io.atomic import write_atomically
from voroforge.io.parquet import write_cells

_DESIGN = '[design]\nname = "t"\n[boundary]\nwidth = 100\nheight = 60\n[cells]\n'


@pytest.mark.parametrize(
    "value",
    ["[" * 3000 + "]" * 3000, "{a = " * 600 + "1" + "}" * 600],
    ids=["arrays", "inline-tables"],
)
def test_a_value_nested_past_the_recursion_limit_is_a_design_error_at_its_line(tmp_path, value):
    # checker31 F1: tomllib's RecursionError came out as a 40-line traceback
    path = tmp_path / "d.toml"
    path.write_text(_DESIGN + '# a "quoted [" comment\nweb = ' + value + "\n")
    with pytest.raises(DesignError) as err:
        load(path)
    (issue,) = err.value.issues
    assert issue.line == _DESIGN.count("\n") + 2
    assert "nested too deeply" in issue.message


def test_a_deep_set_value_stays_the_string_it_was():
    text = "[" * 3000 + "]" * 3000
    assert parse_value(text) == text
    assert parse_value("[1, [2]]") == [1, [2]]


def test_writing_onto_a_folder_names_the_folder_not_a_temporary_file(tmp_path):
    # checker31 F2: "Is a directory: .../.s.gif.e3ch9hll.gif"
    folder = tmp_path / "s.gif"
    folder.mkdir()
    with pytest.raises(IsADirectoryError, match=r"cannot write .*s\.gif: is a folder"):
        write_atomically(folder, lambda tmp: open(tmp, "w").close())
    assert folder.is_dir() and not any(tmp_path.glob(".s.gif*"))


def test_geoparquet_through_a_link_writes_the_linked_file_and_keeps_the_link(tmp_path):
    # checker31 F3: the link was replaced by a plain file; the linked file kept "old"
    pq = pytest.importorskip("pyarrow.parquet")
    d = vf.voronoi(np.random.default_rng(1).random((12, 2)))
    real, link = tmp_path / "real.parquet", tmp_path / "link.parquet"
    real.write_text("old")
    link.symlink_to(real.name)
    write_cells(d, link)
    assert link.is_symlink()
    table = pq.read_table(real)
    assert table.num_rows == 12
    assert json.loads(table.schema.metadata[b"geo"])["primary_column"] == "geometry"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link.parquet", "real.parquet"]


def _example(name: str) -> dict:
    import tomllib
    from pathlib import Path

    return tomllib.loads((Path(__file__).parent.parent / "examples" / name).read_text())


@pytest.mark.parametrize(
    ("example", "section", "key", "value", "words"),
    [
        ("solid-lamp-shade.toml", "solid", "openings", "90", "not the text"),
        ("solid-lamp-shade.toml", "solid", "seed", True, "not true/false"),
        ("solid-lamp-shade.toml", "solid", "thickness", "1.6", "valid number"),
        ("solid-lamp-shade.toml", "solid", "thickness", True, "valid number"),
        ("solid-lamp-shade.toml", "solid", "view", [True, 20], "valid number"),
        ("solid-lamp-shade.toml", "solid", "profile", [["38", 0], [46, 15]], "valid number"),
        ("surface-dome.toml", "surface", "radius", "5", "valid number"),
        ("surface-dome.toml", "surface", "polar", ["0", 70], "valid number"),
        ("surface-dome.toml", "surface", "resolution", True, "not true/false"),
    ],
)
def test_solid_and_surface_numbers_must_be_written_as_numbers(example, section, key, value, words):
    # checker31 F5: "1.6" read as 1.6 and true as 1 in [solid] / [surface], silently
    data = _example(example)
    data[section][key] = value
    with pytest.raises(DesignError, match=rf"{section}\.{key}\b.*{words}"):
        load(data)


def test_shell_openings_are_capped_before_any_work():
    # checker31 F4: openings = 1e8 ran two minutes, then a 6.7 GiB MemoryError traceback
    from voroforge import config, solid
    from voroforge.solid.surfaces import revolve

    data = _example("solid-lamp-shade.toml")
    data["solid"]["openings"] = config.SOLID_MAX_OPENINGS + 1
    with pytest.raises(DesignError, match=r"solid\.openings.*less than or equal"):
        load(data)
    with pytest.raises(ValueError, match="openings: at most"):
        solid.shell(revolve([(1.0, 0.0), (1.0, 1.0)], 16), openings=10**8)
