"""``[surface]`` height fields and parametric surfaces in design files; the safe expressions."""

from __future__ import annotations

import numpy as np
import pytest

from voroforge import surface
from voroforge.design.designfile import DesignError, load
from voroforge.surface.build import surface_of
from voroforge.surface.expr import compile_expression, parametric_map

BASE = {"boundary": {"shape": "rectangle", "width": 4, "height": 4}, "seeds": {"count": 20}}


def _design(**sec):
    return load({**BASE, "surface": {"mode": "voronoi", **sec}})


def test_inline_heightfield_is_the_bilinear_surface_over_the_rectangle():
    heights = [[0.0, 0.1, 0.0], [0.2, 0.5, 0.2], [0.0, 0.1, 0.4]]
    design, base = _design(shape="heightfield", width=4, depth=2, heights=heights)
    S = surface_of(design.surface, base)
    ref = surface.heightfield(np.array(heights), (-2, -1, 2, 1))
    assert np.array_equal(S.vertices, ref.vertices) and np.array_equal(S.faces, ref.faces)
    assert S.vertices[:, 0].min() == -2 and S.vertices[:, 1].max() == 1
    # the sample at row 1, column 1 sits at the centre
    centre = S.vertices[np.argmin(np.abs(S.vertices[:, :2]).sum(axis=1))]
    assert centre == pytest.approx([0, 0, 0.5])


@pytest.mark.parametrize("ext", ["csv", "npy", "png"])
def test_heightfield_from_a_file(tmp_path, ext):
    z = np.array([[0.0, 1.0], [2.0, 3.0], [4.0, 5.0]])
    path = tmp_path / f"h.{ext}"
    sec = {"shape": "heightfield", "width": 2, "file": path.name}
    if ext == "csv":
        path.write_text("\n".join(",".join(map(str, r)) for r in z), encoding="utf-8")
    elif ext == "npy":
        np.save(path, z)
    else:
        from PIL import Image

        Image.fromarray((z[::-1] / 5 * 255).astype(np.uint8)).save(path)  # top row = far edge
        sec["rise"] = 5.0
    toml = tmp_path / "d.toml"
    toml.write_text(
        '[boundary]\nshape = "rectangle"\nwidth = 2\nheight = 2\n[seeds]\ncount = 5\n[surface]\n'
        + "".join(f"{k} = {v!r}\n".replace("'", '"') for k, v in sec.items()),
        encoding="utf-8",
    )
    design, base = load(toml)
    S = surface_of(design.surface, base)
    assert np.sort(S.vertices[:, 2]) == pytest.approx(np.arange(6.0), abs=1e-12)
    # row j is at y = ymin + j dy: z grows with y
    order = np.lexsort((S.vertices[:, 0], S.vertices[:, 1]))
    assert S.vertices[order, 2] == pytest.approx(z.ravel(), abs=1e-12)


def test_parametric_surface_from_expressions_matches_the_analytic_one():
    design, base = _design(
        shape="parametric",
        x="cos(tau * u) * (1 + 0.4 * cos(tau * v))",
        y="sin(tau * u) * (1 + 0.4 * cos(tau * v))",
        z="0.4 * sin(tau * v)",
        resolution=24,
    )
    S = surface_of(design.surface, base)
    T = surface.torus(1.0, 0.4, resolution=(24, 24))
    assert S.closed and S.area == pytest.approx(T.area, rel=1e-9)
    u = np.linspace(0, 1, 7)
    assert S.evaluate(u, u) == pytest.approx(T.evaluate(u, u), abs=1e-12)
    vd = surface.voronoi(S, 30)
    assert abs(vd.areas.sum() - S.area) <= 1e-9 * S.area


@pytest.mark.parametrize(
    "sec, key",
    [
        ({"shape": "heightfield", "width": 2}, "heights"),
        ({"shape": "heightfield", "heights": [[0, 1], [1, 0]]}, "width"),
        ({"shape": "heightfield", "width": 2, "heights": [[0, 1], [1]]}, "heights"),
        ({"shape": "heightfield", "width": 2, "heights": [[0, 1]]}, "heights"),
        ({"shape": "parametric", "x": "u", "y": "v"}, "z"),
        ({"shape": "parametric", "x": "u", "y": "v", "z": "__import__('os')"}, "z"),
        ({"shape": "parametric", "x": "u.real", "y": "v", "z": "0"}, "x"),
        ({"shape": "parametric", "x": "u", "y": "v +", "z": "0"}, "y"),
        ({"shape": "parametric", "x": "u", "y": "w", "z": "0"}, "y"),
        ({"shape": "saddle", "width": 2, "x": "u"}, "x"),
        ({"shape": "saddle", "width": 2, "heights": [[0, 1], [1, 0]]}, "heights"),
    ],
)
def test_bad_sections_name_their_key(sec, key):
    with pytest.raises(DesignError, match=rf"surface\.{key}"):
        _design(**sec)


def test_expressions_are_arithmetic_only():
    f = compile_expression("atan2(v, u) + max(u, 0.5) ** 2 - -1 % 3")
    u, v = np.array([1.0, 0.0]), np.array([0.0, 1.0])
    assert f(u, v) == pytest.approx(np.arctan2(v, u) + np.maximum(u, 0.5) ** 2 - 2)
    assert compile_expression("2")(u, v).shape == (2,)
    for bad in ("open('x')", "(lambda: 1)()", "[u]", "u if v else 1", "True", "'a'", "", "u; v"):
        with pytest.raises(ValueError):
            compile_expression(bad)
    with pytest.raises(ValueError, match="non-finite"):
        surface.parametric(parametric_map("log(u - 1)", "v", "0"), resolution=4)
