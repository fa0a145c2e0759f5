"""Design-file values that failed without ``file:line: key:`` or with a traceback (checker17).

Each case is a one-line change to a working design; the error must name the file's line of
that key, the dotted key and a message in the file's terms (degrees, the key's name), from
the schema (``voroforge check``) or the builder, never a traceback (``voroforge build``
exits 2).
"""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from voroforge.design.designfile import DesignError, load

SURFACE = """[design]
name = "t"
units = "m"
seed = 3

[boundary]
shape = "rectangle"
width = 4
height = 4

[seeds]
method = "random"
count = 12

[output]
formats = ["png"]
png_size = 120

[surface]
mode = "voronoi"
count = 12
relax = 0
"""

SOLID = """[design]
name = "s"
units = "mm"
seed = 7

[solid]
formats = ["png"]
cells = 8
"""

SADDLE = 'shape = "saddle"\nwidth = 4\ndepth = 4\n'
PARAM = 'shape = "parametric"\ny = "v"\nz = "u * v"\n'
PATCH = 'shape = "sphere_patch"\nradius = 2\n'
FOAM = 'kind = "foam"\ncontainer = [0, 0, 0, 20, 20, 20]\n'
SHELL = 'kind = "shell"\n'

CASES = [
    # (head, body, the changed line, key, message fragment)
    (SURFACE, SADDLE, 'x = "10 ** 400 * u"', None, ""),  # not parametric: x is refused
    (SURFACE, PARAM, 'x = "10 ** 400 * u"', "surface.x", "must be finite"),
    (SURFACE, PARAM, 'x = "9 ** 9 ** 9"', "surface.x", "gives inf"),
    (SURFACE, PARAM, 'x = "1' + "0" * 400 + ' * u"', "surface.x", "not a finite double"),
    (SURFACE, PARAM, 'x = "1/u"', "surface.x", "gives inf at (u, v) = (0, "),
    (SURFACE, PARAM, 'x = "log(u)"', "surface.x", "gives -inf"),
    (SURFACE, PARAM, 'x = "sqrt(u - 2)"', "surface.x", "gives nan"),
    (SURFACE, SADDLE, "view = [nan, 0]", "surface.view.0", "finite"),
    (SURFACE, 'shape = "cylinder"\nheight = 2\n', "radius = inf", "surface.radius", "finite"),
    (SURFACE, 'shape = "cylinder"\nheight = 2\n', "radius = 1e300", "surface.radius", "range"),
    (
        SURFACE,
        'shape = "heightfield"\nwidth = 4\n',
        "heights = [[0.0, nan], [0.0, 1.0]]",
        "surface.heights.0.1",
        "finite",
    ),
    (
        SURFACE,
        'shape = "heightfield"\nwidth = 4\n',
        "heights = [[0.0, 1e300], [0.0, 1.0]]",
        "surface.heights.0.1",
        "range",
    ),
    (SURFACE, PATCH, "polar = [90, 0]", "surface.polar", "<= 180; got [90, 0]"),
    (SURFACE, PATCH, "polar = [0, 200]", "surface.polar", "<= 180; got [0, 200]"),
    (SURFACE, PATCH, "polar = [30, 30]", "surface.polar", "start < stop"),
    (SURFACE, PATCH, "azimuth = [0, 720]", "surface.azimuth", "start + 360; got [0, 720]"),
    (SURFACE, 'shape = "torus"\nmajor = 1\n', "minor = 2", "surface.minor", "minor < major"),
    (
        SURFACE.replace("count = 12\nrelax", "relax"),
        SADDLE,
        "count = 1",
        "surface.count",
        "equal to 2",
    ),
    (SURFACE, SADDLE, 'unroll = "yes"', "surface.unroll", "boolean"),
    (SOLID, FOAM, "view = [nan, 0]", "solid.view.0", "finite"),
    (SOLID, FOAM, "seed = -1", "solid.seed", "greater than or equal to 0"),
    (SOLID, SHELL, "profile = [[1, 0], [nan, 5], [1, 10]]", "solid.profile.1.0", "finite"),
    (SOLID, SHELL, "profile = [[1, 0]]", "solid.profile", "at least 2 points"),
    (SOLID, SHELL, "profile = [[-1, 0], [2, 5], [1, 10]]", "solid.profile", ">= 0"),
    # checker25 F6: profiles sweeping no area ended in an IndexError from sample_even
    (SOLID, SHELL, "profile = [[10, 0], [10, 0], [10, 0]]", "solid.profile", "no length"),
    (SOLID, SHELL, "profile = [[0, 0], [0, 5]]", "solid.profile", "on the z axis"),
    (
        SOLID,
        FOAM,
        '[[solid.fields]]\ntype = "point"\nradius = 5\npoints = [[nan, 0, 0]]',
        "solid.fields.0.points.0.0",
        "finite",
    ),
    (
        SOLID,
        FOAM,
        '[[solid.fields]]\ntype = "curve"\nradius = 5\npoints = [[0, 0, 0]]',
        "solid.fields.0.points",
        "at least two points",
    ),
]


def _write(tmp_path, head, body, line):
    text = head + body + line + "\n"
    path = tmp_path / "f.toml"
    path.write_text(text)
    last = line.splitlines()[-1]
    return path, text.splitlines().index(last) + 1


@pytest.mark.parametrize(("head", "body", "line", "key", "fragment"), CASES)
def test_bad_value_is_an_error_at_its_key_and_line(tmp_path, head, body, line, key, fragment):
    path, lineno = _write(tmp_path, head, body, line)
    with pytest.raises(DesignError) as info:
        load(path)
    text = info.value.format()
    if key is None:  # only: an error, no traceback
        return
    want = f"f.toml:{lineno}: {key}: "
    hit = [ln for ln in text.splitlines() if want in ln]
    assert hit, text
    assert fragment in hit[0], text
    # the file's terms: degrees, not radians
    assert "pi" not in hit[0] and "tol " not in hit[0], text


def test_good_values_still_load(tmp_path):
    for head, body, line in [
        (SURFACE, PARAM, 'x = "10 ** 2 * u + 2 ** 0.5"'),
        (SURFACE, PARAM, 'x = "sqrt(u) + log(1 + u)"'),
        (SURFACE, PATCH, "polar = [0, 180]\nazimuth = [-90, 270]"),
        (SURFACE, 'shape = "torus"\nmajor = 2\n', "minor = 1"),
        (SURFACE, SADDLE, "unroll = true"),
        (SOLID, SHELL, "profile = [[0, 0], [2, 5], [1, 10]]"),
    ]:
        path, _ = _write(tmp_path, head, body, line)
        load(path)


def test_expression_constants_evaluate_as_doubles():
    from voroforge.surface.expr import compile_expression

    u = np.array([0.0, 0.5, 1.0])
    # an overflowing power of constants is inf, as in IEEE arithmetic (no OverflowError)
    assert np.isinf(compile_expression("10 ** 400 + u")(u, u)).all()
    # ordinary constants: the same doubles as Python's
    got = compile_expression("2 ** 0.5 * u + 7 % 3 - tau / e")(u, u)
    np.testing.assert_array_equal(got, 2**0.5 * u + 7 % 3 - np.float64(6.283185307179586) / np.e)


def test_heightfield_file_with_nan_is_an_error_at_surface_file(tmp_path):
    from voroforge.surface.build import surface_of

    (tmp_path / "h.csv").write_text("0,1\nnan,2\n")
    path, _ = _write(tmp_path, SURFACE, 'shape = "heightfield"\nwidth = 4\n', 'file = "h.csv"')
    design, base = load(path)
    with pytest.raises(DesignError) as info:
        surface_of(design.surface, base)
    assert info.value.issues[0].key == "surface.file"
    assert "must be finite; row 1, column 0 is nan" in info.value.issues[0].message


def test_build_exits_2_with_the_line_not_a_traceback(tmp_path):
    path, lineno = _write(tmp_path, SURFACE, PARAM, 'x = "9 ** 9 ** 9"')
    r = subprocess.run(
        [sys.executable, "-m", "voroforge", "build", str(path), "-o", str(tmp_path / "o")],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert r.returncode == 2, r.stderr
    assert "Traceback" not in r.stderr
    assert f"f.toml:{lineno}: surface.x: " in r.stderr


def test_point_header_naming_a_coordinate_twice_is_refused(tmp_path):
    from voroforge.io.readers.points import read_text_point_table

    p = tmp_path / "p.csv"
    p.write_text("x,x,y,z\n9,0.1,0.2,0.3\n9,0.4,0.5,0.6\n")
    with pytest.raises(
        ValueError, match=r"names the coordinate column 'x' 2 times \(columns 1, 2\)"
    ):
        read_text_point_table(p, dims=3)
    # an alias beside the axis's own name is an attribute, as before
    p.write_text("x,y,z,height\n1,2,3,4\n")
    pts, attrs = read_text_point_table(p, dims=3)
    np.testing.assert_array_equal(pts, [[1.0, 2.0, 3.0]])
    p.write_text("X,y,x\n1,2,3\n")  # names are case-blind
    with pytest.raises(ValueError, match="2 times"):
        read_text_point_table(p, dims=2)


@pytest.mark.parametrize(
    ("table", "key", "value"),
    [("design", "name", "x\\ny"), ("design", "name", "x\\ty"), ("output", "stem", "a\\u0000b")],
)
def test_output_names_with_control_characters_are_errors_at_their_line(tmp_path, table, key, value):
    # checker25 F2: a name with a newline wrote DIR/x<LF>y.svg; a NUL ended in "embedded null
    # byte" with no key or line
    path = tmp_path / "f.toml"
    path.write_text(f'[{table}]\n{key} = "{value}"\n')
    with pytest.raises(DesignError) as info:
        load(path)
    text = str(info.value)
    assert f"f.toml:2: {table}.{key}" in text and "control characters" in text


@pytest.mark.parametrize("name", ["nope.stl", "c.toml"])
def test_a_solid_container_file_that_is_no_mesh_is_an_error_at_its_line(tmp_path, name):
    # checker25 F6: a missing or non-mesh container file gave an error naming neither the
    # design file's line nor solid.container
    from voroforge.design.build import build

    (tmp_path / "c.toml").write_text("")
    path = tmp_path / "f.toml"
    path.write_text(f'[design]\nname = "x"\n[solid]\nkind = "lattice"\ncontainer = "{name}"\n')
    with pytest.raises(DesignError) as info:
        build(path, tmp_path / "o")
    assert "f.toml:5: solid.container: " in info.value.format()
