"""Design files: schema validation, errors that name key and line, overrides, the starter."""

import tomllib

import pytest

from voroforge.design.build import build, starter
from voroforge.design.designfile import (
    DesignError,
    apply_overrides,
    key_lines,
    load,
    parse_value,
)
from voroforge.design.schema import Design, Graded

STARTER = starter()

GOOD = """\
[design]
name = "t"
seed = 3

[boundary]
shape = "rectangle"
width = 100
height = 60

[seeds]
method = "poisson"
radius = 12

[[attractors]]
points = [[10, 20]]
radius = 50

[[attractors]]
type = "curve"
points = [
  [0, 0],
  [50, 10],
]
radius = 30

[cells]
web = { near = 3, far = 1 }
fillet = 1.5
"""


def write(tmp_path, text, name="d.toml"):
    f = tmp_path / name
    f.write_text(text)
    return f


def issues_of(tmp_path, text, **kw):
    with pytest.raises(DesignError) as info:
        load(write(tmp_path, text), **kw)
    return [(i.key, i.line, i.message) for i in info.value.issues], str(info.value)


def line_of(text, needle, nth=1):
    """1-based line of the nth line containing needle (the slow, obvious reference)."""
    hits = [i for i, line in enumerate(text.splitlines(), start=1) if needle in line]
    return hits[nth - 1]


def test_good_file_validates_with_defaults(tmp_path):
    design, base = load(write(tmp_path, GOOD))
    assert base == tmp_path.resolve()
    assert design.design.seed == 3 and design.boundary.width == 100
    assert design.cells.web == Graded(near=3, far=1)
    assert design.cells.inset_amount() == Graded(near=1.5, far=0.5)
    assert design.cells.fillet.value == 1.5
    assert design.attractors[1].type == "curve" and len(design.attractors[1].points) == 2
    assert design.output.formats == ["svg", "png"]  # defaults filled in
    assert design.output.layers == {"CUT": "frame"}


def test_key_lines_match_a_line_scan():
    lines = key_lines(GOOD)
    assert lines[("design", "seed")] == line_of(GOOD, "seed = 3")
    assert lines[("attractors", 0)] == line_of(GOOD, "[[attractors]]", 1)
    assert lines[("attractors", 1)] == line_of(GOOD, "[[attractors]]", 2)
    assert lines[("attractors", 1, "radius")] == line_of(GOOD, "radius = 30")
    assert lines[("attractors", 1, "points")] == line_of(GOOD, "points = [", 2)
    assert lines[("cells", "web", "far")] == line_of(GOOD, "web = {")
    # Multi-line arrays do not produce keys from their items.
    assert ("attractors", 1, "0") not in lines


@pytest.mark.parametrize(
    ("old", "new", "key", "needle", "words"),
    [
        ("height = 60", "heigth = 60", "boundary.heigth", "heigth", ["unknown key", "'height'"]),
        ("radius = 12", "radius = -12", "seeds.radius", "radius = -12", ["greater than 0", "-12"]),
        ("radius = 30", 'radius = "big"', "attractors.1.radius", 'radius = "big"', ["number"]),
        ("far = 1 }", 'far = "x" }', "cells.web.far", "web = {", ["number", "'x'"]),
        ('method = "poisson"', 'method = "posson"', "seeds.method", "posson", ["'poisson'"]),
        ("radius = 12", "spacing = 12", "seeds.radius", "[seeds]", ["needs radius"]),
        ("fillet = 1.5", "fillet = 1.5\nsmoth = 2", "cells.smoth", "smoth", ["'smooth'"]),
        ('[design]\nname = "t"', '[design]\nnme = "t"', "design.nme", "nme", ["'name'"]),
        ('name = "t"', 'name = "t"\nunits = "furlong"', "design.units", "furlong", ["'mm'"]),
    ],
)
def test_errors_name_key_line_and_expectation(tmp_path, old, new, key, needle, words):
    assert old in GOOD
    text = GOOD.replace(old, new, 1)
    issues, message = issues_of(tmp_path, text)
    found = [i for i in issues if i[0] == key]
    assert found, issues
    _, line, text_msg = found[0]
    assert line == line_of(text, needle)
    for w in words:
        assert w in text_msg
    assert f"d.toml:{line}: {key}: " in message


def test_unknown_section_and_missing_section(tmp_path):
    issues, _ = issues_of(tmp_path, GOOD + "\n[sedes]\ncount = 3\n")
    assert (
        "sedes",
        line_of(GOOD + "\n[sedes]\n", "[sedes]"),
        "unknown key; did you mean 'seeds'?",
    ) in issues
    no_seeds = GOOD.replace('[seeds]\nmethod = "poisson"\nradius = 12\n', "")
    issues, _ = issues_of(tmp_path, no_seeds)
    assert ("seeds", None, "required key is missing") in issues


def test_toml_syntax_error_has_line(tmp_path):
    bad = GOOD.replace("width = 100", "width = = 100")
    issues, message = issues_of(tmp_path, bad)
    assert issues[0][1] == line_of(bad, "width = = 100")
    assert "TOML syntax" in message


def test_every_issue_is_reported_once_per_key(tmp_path):
    bad = GOOD.replace("width = 100", "width = 0").replace("radius = 50", "radius = 0")
    issues, message = issues_of(tmp_path, bad)
    assert {i[0] for i in issues} == {"boundary.width", "attractors.0.radius"}
    assert message.count("\n") == 1


def test_overrides_set_values_and_lists(tmp_path):
    f = write(tmp_path, GOOD)
    design, _ = load(
        f, overrides={"seeds.radius": "20", "attractors.1.radius": 44, "cells.web": "2"}
    )
    assert design.seeds.radius == 20.0
    assert design.attractors[1].radius == 44.0
    assert design.cells.web == Graded(value=2.0)
    design, _ = load(f, overrides={"output.formats": '["dxf"]', "relax.iterations": "3"})
    assert design.output.formats == ["dxf"] and design.relax.iterations == 3
    # The input mapping is never changed.
    data = tomllib.loads(GOOD)
    apply_overrides(data, {"seeds.radius": 1})
    assert data["seeds"]["radius"] == 12


def test_override_errors(tmp_path):
    f = write(tmp_path, GOOD)
    with pytest.raises(DesignError, match=r"seeds\.radius: .*\(from --set\)"):
        load(f, overrides={"seeds.radius": "zero"})
    with pytest.raises(DesignError, match="not an index"):
        load(f, overrides={"attractors.7.radius": 1})
    with pytest.raises(DesignError, match="did you mean 'count'"):
        load(f, overrides={"seeds.cont": 5})


def test_parse_value():
    assert parse_value("500") == 500
    assert parse_value("2.5") == 2.5
    assert parse_value("true") is True
    assert parse_value("[1, 2]") == [1, 2]
    assert parse_value("{ near = 1, far = 2 }") == {"near": 1, "far": 2}
    assert parse_value("hexgrid") == "hexgrid"


def test_dict_source_and_graded_rules():
    base = tomllib.loads(GOOD)
    with pytest.raises(DesignError, match="both near and far"):
        load({**base, "cells": {"inset": {"near": 2}}})
    with pytest.raises(DesignError, match="not both"):
        load({**base, "cells": {"web": 2, "inset": 1}})
    design, base_dir = load(base)
    assert base_dir is None and isinstance(design, Design)


def test_starter_is_valid_and_commented(tmp_path):
    design, _ = load(write(tmp_path, STARTER))
    assert design.design.name == "my-panel"
    assert sum(1 for line in STARTER.splitlines() if "#" in line) >= 20
    # Every section of the schema appears in the starter or its comments.
    for section in (
        "design",
        "boundary",
        "seeds",
        "relax",
        "attractors",
        "cells",
        "openings",
        "output",
        "fabrication",
    ):
        assert f"[{section}]" in STARTER or f"[[{section}]]" in STARTER


def test_layer_product_errors_once_with_line(tmp_path):
    text = GOOD + '\n[output]\nlayers = { CUT = "frme" }\nformats = ["svg", "pdf"]\n'
    issues, _ = issues_of(tmp_path, text)
    keys = [i[0] for i in issues]
    assert keys.count("output.layers.CUT") == 1  # one message, not one per union branch
    (layer,) = [i for i in issues if i[0] == "output.layers.CUT"]
    assert layer[1] == line_of(text, "layers = {") and "'frame'" in layer[2]
    (fmt,) = [i for i in issues if i[0] == "output.formats.1"]
    assert fmt[1] == line_of(text, "formats = [") and "'pdf'" in fmt[2]


# --- folded from test_qa_design.py: bugs found by using the design layer as designers
# and fabricators do


BASE = '[boundary]\nwidth = 100\nheight = 80\n[seeds]\nmethod = "random"\ncount = 20\n'


@pytest.mark.parametrize(
    "extra, where, message",
    [
        # a negative seed used to be reported as "seeds: expected non-negative integer"
        ("[design]\nseed = -1\n", "8: design.seed", "greater than or equal to 0"),
        (
            "[openings]\nselect = 'random'\nprobability = 0.5\nseed = -2\n",
            "10: openings.seed",
            "greater than or equal to 0",
        ),
        # graded numbers of the wrong type: name what is expected
        ("[cells]\nweb = true\n", "8: cells.web", "expected a number or { near = ..., far = ... }"),
        ("[cells]\nfillet = [1, 2]\n", "8: cells.fillet", "expected a number or {"),
        # a key given twice on the last line: tomllib says "at end of document", no line
        ("[cells]\nweb = 1\nweb = 2", "9: (top level)", "TOML syntax: Cannot overwrite a value"),
        # a bad GIF sweep value: the file and the line of output.gif.values, not "<design>"
        (
            "[output]\nformats = ['gif']\n[output.gif]\nkey = 'cells.web'\nvalues = [1, -2]\n",
            "11: output.gif.values",
            "cells.web = -2: cells.web: must be >= 0",
        ),
    ],
)
def test_design_errors_name_file_line_and_key(tmp_path, capsys, extra, where, message):
    from voroforge.cli import main

    path = tmp_path / "bad.toml"
    path.write_text(BASE + extra, encoding="utf-8")
    rc = main(["build", str(path), "-o", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert rc == 2
    assert err.startswith(f"voroforge: error: {path}:{where}: "), err
    assert message in err and "(from --set)" not in err and "Traceback" not in err


def test_design_file_encodings(tmp_path, capsys):
    from voroforge.cli import main

    # Windows Notepad's UTF-8 with a BOM builds (tomllib alone says "Invalid statement"),
    # and build-time errors still find their lines.
    bom = tmp_path / "bom.toml"
    bom.write_bytes(b"\xef\xbb\xbf" + BASE.encode() + b"[cells]\nweb = 2\n")
    assert main(["build", str(bom), "-o", str(tmp_path / "o")]) == 0
    bad = tmp_path / "bom2.toml"
    bad.write_bytes(
        b'\xef\xbb\xbf[boundary]\nshape = "file"\nfile = "none.svg"\n[seeds]\ncount = 3\n'
    )
    assert main(["build", str(bad)]) == 2
    assert f"{bad}:3: boundary.file: file not found" in capsys.readouterr().err
    # Latin-1 text: the file, the line and what to do, not a bare codec message.
    latin = tmp_path / "latin.toml"
    latin.write_bytes(BASE.encode() + b"# caf\xe9\n")
    assert main(["build", str(latin)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"voroforge: error: {latin}:7: ") and "UTF-8" in err


def test_seed_file_errors_name_seeds_file(tmp_path):
    from voroforge.design.designfile import DesignError

    (tmp_path / "pts.csv").write_text("10,10\n20,abc\n")
    (tmp_path / "d.toml").write_text(
        '[boundary]\nwidth = 60\nheight = 60\n[seeds]\nmethod = "file"\nfile = "pts.csv"\n'
    )
    with pytest.raises(DesignError, match=r"d\.toml:6: seeds\.file: .*'abc' is not a number"):
        build(tmp_path / "d.toml", tmp_path / "out")


@pytest.mark.parametrize(
    "extra, where, message",
    [
        # 'cut' and 'CUT' both became layer CUT: the frame was silently dropped
        ('[output]\nlayers = { cut = "frame", CUT = "edges" }\n', "8: output.layers", "same layer"),
        # a DXF-invalid name failed late with "invalid DXF layer name" and no file or key
        ('[output]\nlayers = { "a/b" = "frame" }\n', "8: output.layers", "not a valid layer"),
        ('[design]\nname = "out/panel"\n', "8: design.name", "without folders"),
    ],
)
def test_layer_and_output_names_are_checked_up_front(tmp_path, capsys, extra, where, message):
    from voroforge.cli import main

    path = tmp_path / "bad.toml"
    path.write_text(BASE + extra, encoding="utf-8")
    assert main(["build", str(path), "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"voroforge: error: {path}:{where}: ") and message in err, err
