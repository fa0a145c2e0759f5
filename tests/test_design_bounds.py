"""Design-file values past what float64 can draw are schema errors at their key and line."""

from __future__ import annotations

import pytest

from voroforge.design.designfile import DesignError, load

BASE = """[design]
name = "t"
seed = 1

[boundary]
shape = "polygon"
points = [[0, 0], [100, 0], [100, 80], [0, 80]]

[seeds]
method = "random"
count = 30
"""
POLY = "points = [[0, 0], [100, 0], [100, 80], [0, 80]]"


def _issues(tmp_path, text):
    path = tmp_path / "d.toml"
    path.write_text(text)
    with pytest.raises(DesignError) as info:
        load(path)
    return [(i.key, i.line, i.message) for i in info.value.issues]


@pytest.mark.parametrize(
    ("old", "new", "key", "line", "words"),
    [
        # a polygon at 1e155 overflowed its area to NaN: "seeds: cannot convert float NaN"
        (POLY, "points = [[0, 0], [1e155, 0], [1e155, 1e155]]", "boundary.points.1.0", 7, "1e+100"),
        (
            'shape = "polygon"\n' + POLY,
            'shape = "circle"\nradius = 1e-200',
            "boundary.radius",
            7,
            "at least",
        ),
        (
            'shape = "polygon"\n' + POLY,
            'shape = "rectangle"\nwidth = 1e-200\nheight = 1',
            "boundary.width",
            7,
            "at least",
        ),
        ("count = 30", "count = 30\noffset = [1e300, 0]", "seeds.offset.0", 12, "1e+100"),
    ],
)
def test_sizes_and_coordinates_are_bounded(tmp_path, old, new, key, line, words):
    issues = _issues(tmp_path, BASE.replace(old, new))
    assert (key, line) == issues[0][:2]
    assert {ln for _, ln, _ in issues} == {line}  # each coordinate past the bound, one line
    assert all(words in m for _, _, m in issues)


@pytest.mark.parametrize(
    ("path", "words"),
    [
        ("M 0 0 Q", "expected a number at character 7"),
        ("M 0 0 L nan 5", "expected a number"),
        ("M 0 0 L 1e400 5", "finite"),
        ("", "draws nothing"),
    ],
)
def test_attractor_path_data_is_checked_at_its_key(tmp_path, path, words):
    text = BASE + f'\n[[attractors]]\ntype = "curve"\npath = "{path}"\nradius = 10\n'
    issues = _issues(tmp_path, text)
    assert [(k, ln) for k, ln, _ in issues] == [("attractors.0.path", 15)]
    assert words in issues[0][2]


def test_seed_curve_path_data_is_checked_at_its_key(tmp_path):
    text = BASE.replace(
        'method = "random"\ncount = 30', 'method = "curves"\nspacing = 5\npath = "M 0"'
    )
    assert [(k, ln) for k, ln, _ in _issues(tmp_path, text)] == [("seeds.path", 12)]


def test_an_empty_area_range_is_refused(tmp_path):
    text = BASE + '\n[openings]\nselect = "area"\nmin_area = 100\nmax_area = 10\n'
    issues = _issues(tmp_path, text)
    assert [(k, ln) for k, ln, _ in issues] == [("openings.max_area", 16)]
    assert "at least min_area" in issues[0][2]


def test_a_union_value_error_is_one_line_at_its_key(tmp_path):
    # solid.wall is a size or a (far, near) pair: pydantic reports both branches
    text = '[design]\nname = "t"\n\n[solid]\nkind = "foam"\n'
    text += "container = [0, 0, 0, 20, 20, 20]\nwall = -1\n"
    issues = _issues(tmp_path, text)
    assert [(k, ln) for k, ln, _ in issues] == [("solid.wall", 7)]
    assert "greater than 0" in issues[0][2]


def test_a_bad_solid_box_adds_no_2d_errors(tmp_path):
    text = '[design]\nname = "t"\n\n[solid]\nkind = "foam"\ncontainer = [0, 0, 0, 20, 20, 0]\n'
    keys = [k for k, _, _ in _issues(tmp_path, text)]
    assert "boundary" not in keys and "seeds" not in keys, keys


def test_values_inside_the_bounds_load(tmp_path):
    path = tmp_path / "d.toml"
    path.write_text(BASE.replace(POLY, "points = [[0, 0], [1e99, 0], [1e99, 1e99]]"))
    assert load(path)[0].boundary.points[1] == (1e99, 0.0)


def test_a_nan_in_the_solid_box_is_one_error_at_its_line(tmp_path):
    # the tuple branch's "finite number", not also the str branch's "valid string"
    text = '[design]\nname = "t"\n\n[solid]\nkind = "foam"\n'
    text += "container = [0, 0, 0, 20, 20, nan]\n"
    issues = _issues(tmp_path, text)
    assert [(k, ln) for k, ln, _ in issues] == [("solid.container.5", 6)]
    assert "finite" in issues[0][2]


def test_a_boundary_of_zero_area_is_an_error_at_the_boundary(tmp_path):
    from voroforge.design.compute import outline

    path = tmp_path / "d.toml"
    # its area underflows: GEOS calls it invalid, an error at the boundary (not "seeds")
    tiny = "points = [[0, 0], [1e-200, 0], [1e-200, 8e-201], [0, 8e-201]]"
    path.write_text(BASE.replace(POLY, tiny))
    design, base = load(path)
    with pytest.raises(DesignError) as info:
        outline(design, base)
    assert [i.key for i in info.value.issues] == ["boundary"]
