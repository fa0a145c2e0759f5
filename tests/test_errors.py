"""Bad input fails early with a ValueError that says what is wrong."""

from __future__ import annotations

import numpy as np
import pytest
from shapely.geometry import LineString, MultiPolygon, Polygon

import voroforge as vf

GOOD = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]]

BAD_POINTS = {
    "nan": ([[0.0, 0.0], [np.nan, 1.0], [1.0, 1.0]], r"NaN"),
    "inf": ([[0.0, 0.0], [1.0, np.inf], [1.0, 1.0]], r"(?i)inf"),
    "minus_inf": (np.array([[0.0, -np.inf], [1.0, 2.0]]), r"(?i)inf"),
    "three_columns": (np.zeros((4, 3)), r"(?i)shape|\(n, 2\)"),
    "one_d": (np.arange(6.0), r"(?i)shape|\(n, 2\)"),
    "three_d": (np.zeros((2, 2, 2)), r"(?i)shape|\(n, 2\)"),
    "ragged": ([[0.0, 0.0], [1.0], [1.0, 1.0]], r"(?i)shape|\(n, 2\)|ragged|inhomogeneous"),
    "strings": ([["a", "b"], ["c", "d"]], r"(?i)real|numeric|number|float|convert"),
    "objects": ([[object(), 1.0]], r"(?i)real|numeric|number|float|convert"),
    "complex": (np.array([[1 + 1j, 0], [0, 1]]), r"(?i)real|complex|numeric|number"),
    "dates": (np.array([[1, 2], [3, 4], [5, 1]], "datetime64[s]"), r"dates and durations"),
    "durations": (np.array([[1, 2], [3, 4], [5, 1]], "timedelta64[ms]"), r"dates and durations"),
}


@pytest.mark.parametrize("name", list(BAD_POINTS))
@pytest.mark.parametrize("func", ["delaunay", "voronoi"])
def test_bad_points(name, func):
    pts, pattern = BAD_POINTS[name]
    call = vf.delaunay if func == "delaunay" else vf.voronoi
    with pytest.raises(ValueError, match=pattern):
        call(pts)


def test_durations_as_weights_are_refused():
    with pytest.raises(ValueError, match="dates and durations"):
        vf.power(GOOD, np.arange(4).astype("timedelta64[s]"), (-1, -1, 2, 2))


def test_nan_message_names_the_row():
    pts = np.zeros((5, 2))
    pts[3, 1] = np.nan
    with pytest.raises(ValueError, match=r"3"):
        vf.voronoi(pts)


BOWTIE = Polygon([(0, 0), (1, 1), (1, 0), (0, 1)])

BAD_BOUNDARIES = {
    "bowtie": (BOWTIE, r"Self-intersection"),
    "bowtie_in_multipolygon": (
        MultiPolygon([Polygon([(5, 5), (6, 5), (6, 6)]), BOWTIE]),
        r"(?i)self-intersection|invalid",
    ),
    "hole_outside_shell": (
        Polygon([(0, 0), (1, 0), (1, 1), (0, 1)], [[(2, 2), (3, 2), (3, 3)]]),
        r"(?i)hole|invalid",
    ),
    "empty_polygon": (Polygon(), r"(?i)empty"),
    "empty_multipolygon": (MultiPolygon(), r"(?i)empty"),
    "zero_area": (Polygon([(0, 0), (1, 0), (2, 0)]), r"(?i)area|invalid|empty|degenerate"),
    "linestring": (LineString([(0, 0), (1, 1)]), r"(?i)polygon"),
    "xmin_ge_xmax": ((1.0, 0.0, 1.0, 1.0), r"(?i)xmin"),
    "xmin_gt_xmax": ((2.0, 0.0, 1.0, 1.0), r"(?i)xmin"),
    "ymin_gt_ymax": ((0.0, 2.0, 1.0, 1.0), r"(?i)ymin"),
    "nan_tuple": ((0.0, 0.0, np.nan, 1.0), r"(?i)finite|nan"),
    "short_tuple": ((0.0, 0.0, 1.0), r"(?i)xmin|4|shape"),
    "string": ("unit square", r"(?i)boundary"),
}


@pytest.mark.parametrize("name", list(BAD_BOUNDARIES))
def test_bad_boundary(name):
    boundary, pattern = BAD_BOUNDARIES[name]
    with pytest.raises(ValueError, match=pattern):
        vf.voronoi(GOOD, boundary)


def test_no_extent_without_boundary():
    with pytest.raises(ValueError, match=r"(?i)boundary|extent|site|empty|point"):
        vf.voronoi(np.zeros((0, 2)))


def test_unknown_algorithm():
    with pytest.raises(ValueError, match=r"(?i)algorithm"):
        vf.voronoi(GOOD, algorithm="no-such-thing")


@pytest.mark.parametrize("xy", [[np.nan, 0.0], [[0.0, 0.0], [np.inf, 1.0]], [[0.0, 1.0, 2.0]]])
def test_find_rejects_bad_queries(xy):
    tri = vf.delaunay(GOOD)
    with pytest.raises(ValueError):
        tri.find(xy)


def test_errors_do_not_mutate_input():
    pts = np.array([[0.0, 0.0], [np.nan, 1.0], [1.0, 1.0]])
    keep = pts.copy()
    with pytest.raises(ValueError):
        vf.voronoi(pts)
    assert np.array_equal(pts, keep, equal_nan=True)


def test_picture_sizes_are_bounded_before_any_memory_is_taken(tmp_path, capsys):
    # --size 100000 used to be killed for memory (24 GB); now a clear error, exit 2
    from voroforge.cli import main

    pts = tmp_path / "p.csv"
    pts.write_text("0,0\n1,1\n0,1\n")
    assert main(["voronoi", str(pts), "-o", str(tmp_path / "o.png"), "--size", "100000"]) == 2
    err = capsys.readouterr().err
    assert "too large" in err and "use at most 16384" in err
    assert not (tmp_path / "o.png").exists()
    with pytest.raises(ValueError, match="too large"):
        vf.rasterize(np.random.default_rng(0).random((5, 2)), shape=(100_000, 100_000))


def test_poisson_refuses_a_runaway_count_up_front():
    import shapely

    from voroforge.design import populate

    with pytest.raises(ValueError, match=r"about 2,680,000 points expected, at most 200,000"):
        populate.poisson(shapely.box(0, 0, 100, 100), 0.05, seed=1)


def test_text_points_and_boolean_seeds_are_refused(tmp_path):
    with pytest.raises(ValueError, match="text and true/false are not coordinates"):
        vf.voronoi([["0", "0"], ["1", "1"], ["0", "1"]])
    from voroforge.design.designfile import DesignError, load

    f = tmp_path / "d.toml"
    f.write_text(
        '[design]\nname = "x"\nseed = true\n[boundary]\nshape = "rectangle"\nwidth = 10\n'
        'height = 10\n[seeds]\nmethod = "random"\ncount = 5\n'
    )
    with pytest.raises(DesignError, match=r"3.*design\.seed.*true/false"):
        load(f)


@pytest.mark.parametrize(
    "points",
    [
        [[True, 2.0], [0.5, 0.3], [0.2, 0.9]],
        [(0.5, np.bool_(False)), (0.1, 0.2), (0.7, 0.7)],
        [[1, 1], [0, 0], [True, 0.5]],
        [np.array([True, False]), [0.5, 0.5], [0.2, 0.1]],
    ],
)
def test_a_boolean_among_numbers_is_refused(points):
    """numpy turns ``[[True, 2.0]]`` into floats; the mix must still be refused."""
    with pytest.raises(ValueError, match="true/false among the numbers is not a coordinate"):
        vf.voronoi(points)
    with pytest.raises(ValueError, match="true/false among the numbers is not a number"):
        vf.power([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], [True, 0.5, 0.25])


def test_zeros_and_ones_without_booleans_are_coordinates():
    d = vf.voronoi([[1, 1], [0, 0], [1.0, 0.5], [0, 1]], (0, 0, 1, 1))
    assert np.isclose(d.areas.sum(), 1.0)
    assert (d.duplicate_of == -1).all()


@pytest.mark.parametrize(
    ("section", "key", "value"),
    [
        ("attractors", "points", '[["10", "20"]]'),
        ("attractors", "points", "[[true, 20]]"),
        ("seeds", "radius", "true"),
        ("seeds", "count", '"5"'),
        ("design", "seed", '"3"'),
        ("boundary", "width", '"100"'),
    ],
)
def test_design_numbers_written_as_text_or_booleans_are_refused(tmp_path, section, key, value):
    """A number in a design file is a TOML number: "10" and true were read as 10 and 1."""
    from voroforge.design.designfile import DesignError, load

    body = {
        "design": {"name": '"x"', "seed": "1"},
        "boundary": {"shape": '"rectangle"', "width": "10", "height": "10"},
        "seeds": {"method": '"poisson"', "radius": "1.5"},
        "attractors": {},
    }
    body[section][key] = value
    if section == "seeds" and key == "count":
        body["seeds"] = {"method": '"random"', "count": value}
    if section == "attractors":
        body["attractors"]["radius"] = "5"
    text = "".join(
        ("[[attractors]]\n" if name == "attractors" else f"[{name}]\n")
        + "".join(f"{k} = {v}\n" for k, v in keys.items())
        for name, keys in body.items()
        if keys
    )
    f = tmp_path / "d.toml"
    f.write_text(text)
    with pytest.raises(DesignError, match=rf"{section}(\.0)?\.{key}"):
        load(f)


def test_explain_gif_size_has_an_upper_bound(tmp_path):
    """``explain --size 200000`` ran out of memory with a traceback; now a clear error."""
    from voroforge.explain.render import render_frames

    pts = np.random.default_rng(0).random((10, 2))
    with pytest.raises(ValueError, match="size must be an int from 16 to 8192"):
        render_frames(pts, frames=2, size=200_000)
    with pytest.raises(ValueError, match="at most"):
        render_frames(pts, frames=4000, size=8192)
    assert len(render_frames(pts, frames=3, size=64)) == 3
