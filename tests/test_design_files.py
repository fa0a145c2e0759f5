"""Design files: schema validation, errors that name key and line, overrides, the starter."""

import tomllib

import pytest

from voroforge.design.pipeline import STARTER
from voroforge.design.schema import (
    Design,
    DesignError,
    Graded,
    apply_overrides,
    key_lines,
    load,
    parse_value,
)

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
