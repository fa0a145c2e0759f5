"""The teaching tracer of Fortune's sweep and its GIF: final edges equal vf.voronoi's."""

import math
from itertools import pairwise

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from PIL import Image

import voroforge as vf
from voroforge.cli import main
from voroforge.explain.fortune import breakpoint_x, parabola_y, trace
from voroforge.explain.render import COLORS, frame_size, render_frames, sweep_positions


def merged_edges(edges):
    """pair -> (2, 2) end points; collinear pieces of one pair (a vertex where a third
    cell only touches can split an edge) are merged into one segment."""
    out = {}
    for pair, c in zip(edges.pairs.tolist(), edges.coords, strict=True):
        key = tuple(pair)
        if key in out:
            pts = np.vstack([out[key], c])
            t = (pts - pts[0]) @ (pts[np.argmax(np.abs(pts - pts[0]).sum(axis=1))] - pts[0])
            c = pts[[np.argmin(t), np.argmax(t)]]
        out[key] = c
    return out


def assert_same_edges(points, tol=1e-9):
    """The tracer's final edges equal ``vf.voronoi(points).edges`` within ``tol`` of the
    domain's size; an edge that only one side lists must be shorter than that."""
    d = vf.voronoi(points)
    e = trace(points).edges()
    want = merged_edges(d.edges)
    got = merged_edges(e)
    size = max(d.bounds[2] - d.bounds[0], d.bounds[3] - d.bounds[1])
    for pair in set(got) ^ set(want):
        c = got.get(pair, want.get(pair))
        assert np.hypot(*(c[1] - c[0])) <= tol * size, (pair, pair in got, c.tolist())
    for pair in set(got) & set(want):
        g, c = got[pair], want[pair]
        err = min(np.abs(g - c).max(), np.abs(g[::-1] - c).max())
        assert err <= tol * size, (pair, c.tolist(), g.tolist())
    return e


def _circle_points():
    # 12 integer points on the circle of radius 5: exactly cocircular.
    base = [(5, 0), (4, 3), (3, 4), (0, 5)]
    pts = {(sx * x, sy * y) for x, y in base for sx in (1, -1) for sy in (1, -1)}
    return np.array(sorted(pts), dtype=float)


g5 = np.arange(5.0)
DEGENERATE = {
    "one_site": np.array([[0.3, 0.7]]),
    "two_sites_side_by_side": np.array([[0.0, 0.0], [1.0, 0.0]]),
    "two_sites_stacked": np.array([[0.0, 0.0], [0.0, 1.0]]),
    "horizontal_line": np.stack([np.arange(9.0), np.zeros(9)], axis=1),
    "horizontal_line_and_more": np.array(
        [[0.0, 1.0], [1.0, 1.0], [2.0, 1.0], [3.0, 1.0], [1.5, 0.0], [0.5, 2.5], [2.5, -1.0]]
    ),
    "two_horizontal_lines": np.array([[x, y] for y in (0.0, 1.0) for x in (0.0, 1.5, 3.0, 4.5)]),
    "vertical_line": np.stack([np.zeros(7), np.arange(7.0)], axis=1),
    "diagonal": np.stack([np.arange(6.0), np.arange(6.0)], axis=1),
    "square_grid": np.stack(np.meshgrid(g5, g5), axis=-1).reshape(-1, 2),
    "square_grid_shuffled": np.random.default_rng(1).permutation(
        np.stack(np.meshgrid(g5, g5), axis=-1).reshape(-1, 2)
    ),
    "cocircular_12": _circle_points(),
    "cocircular_12_and_centre": np.vstack([_circle_points(), [[0.0, 0.0]]]),
    "site_below_breakpoint": np.array([[0.0, 1.0], [2.0, 1.0], [1.0, 0.0]]),
    "duplicates": np.array([[0.0, 0.0], [1.0, 0.2], [0.0, 0.0], [0.4, 1.0], [1.0, 0.2]]),
    "hexagonal": np.array(
        [[i + 0.5 * (j % 2), j * 0.75] for i in range(5) for j in range(5)], dtype=float
    ),
    "large_offset": 4e6 + np.random.default_rng(2).random((40, 2)) * 100.0,
    # Four sites within 1e-14 of one horizontal line: the circle through three of them is
    # huge and its lowest point must not cancel away (it was once off by 0.02).
    "nearly_one_row": np.array(
        [
            [1.5277116991555254e-14, 5.0000000000000098],
            [3.0000000000000062, 5.0],
            [2.0000000000000107, 4.9999999999999982],
            [3.9999999999999964, 5.0000000000000151],
            [-3.6199084189374655e-15, 2.0000000000000102],
        ]
    ),
}


@pytest.mark.parametrize("name", sorted(DEGENERATE))
def test_degenerate_inputs_match_voronoi(name):
    assert_same_edges(DEGENERATE[name])


@pytest.mark.parametrize("n", [3, 10, 60, 250])
def test_random_inputs_match_voronoi(n):
    e = assert_same_edges(np.random.default_rng(n).random((n, 2)))
    assert len(e.pairs) > (0 if n < 10 else n)


@given(
    st.lists(st.tuples(st.integers(0, 5), st.integers(0, 5)), min_size=1, max_size=25).map(
        lambda v: np.array(v, dtype=float) * 0.5
    )
)
def test_small_integer_grids_match_voronoi(points):
    # Integer coordinates: ties, cocircular quadruples and shared rows everywhere.
    assert_same_edges(points)


@pytest.mark.parametrize("seed", range(4))
def test_nearly_degenerate_grids_match_voronoi(seed):
    # Integer grids moved by 1e-6 ... 1e-13: breakpoints and circle events nearly coincide.
    # One site per grid point. (Sites closer than ~1e-15 of the extent are out of scope:
    # vf.voronoi leaves their ulp-thin cells empty, while the exact sweep keeps their edges.)
    rng = np.random.default_rng(seed)
    grid = np.unique(rng.integers(0, 6, (40, 2)), axis=0).astype(float)
    pts = grid + rng.normal(size=grid.shape) * 10.0 ** -(6 + 2 * seed)
    assert_same_edges(pts, tol=1e-7)


def test_states_are_consistent():
    pts = np.random.default_rng(7).random((40, 2))
    tr = trace(pts)
    kinds = [s.kind for s in tr.states]
    assert kinds[0] == "start" and kinds[-1] == "end"
    assert kinds.count("site") == 40
    assert kinds.count("circle") > 0
    ys = [s.y for s in tr.states]
    assert all(a >= b for a, b in pairwise(ys))  # the sweep only goes down
    for s in tr.states:
        assert len(s.starts) == max(len(s.arcs) - 1, 0)
        assert all(a != b for a, b in pairwise(s.arcs))
        assert all(ev.y <= s.y + 1e-12 for ev in s.pending)  # events lie ahead
        assert s.finished <= len(tr.segments)
    # a circle event's centre is equidistant from its three sites
    for s in tr.states:
        for ev in s.pending:
            dist = [math.dist(ev.centre, tr.sites[i]) for i in ev.sites]
            assert max(dist) - min(dist) < 1e-12


@pytest.mark.parametrize("sweep", [0.8, 0.5, 0.2])
def test_beach_line_is_the_lower_envelope(sweep):
    pts = np.random.default_rng(3).random((30, 2))
    tr = trace(pts)
    st_ = tr.state_at(sweep)
    above = tr.sites[tr.sites[:, 1] > sweep]
    assert st_.swept == len(above)
    xs = np.linspace(-0.05, 1.05, 401)
    envelope = np.min([parabola_y(tuple(p), xs, sweep) for p in above], axis=0)
    arcs = st_.arcs
    bps = [breakpoint_x(tuple(tr.sites[a]), tuple(tr.sites[b]), sweep) for a, b in pairwise(arcs)]
    assert bps == sorted(bps)
    which = np.searchsorted(np.array(bps), xs)
    ours = np.array(
        [parabola_y(tuple(tr.sites[arcs[k]]), x, sweep) for k, x in zip(which, xs, strict=True)]
    )
    np.testing.assert_allclose(ours, envelope, rtol=0, atol=1e-12)


def test_breakpoint_of_equal_heights_and_degenerate_parabola():
    assert breakpoint_x((0.0, 1.0), (2.0, 1.0), 0.0) == 1.0
    assert breakpoint_x((0.0, 1.0), (3.0, 0.0), 0.0) == 3.0  # site on the sweep line
    # generic: the breakpoint is on both parabolas and has a on the left
    a, b, sweep = (0.1, 0.9), (0.7, 0.4), 0.2
    x = breakpoint_x(a, b, sweep)
    assert parabola_y(a, x, sweep) == pytest.approx(parabola_y(b, x, sweep), abs=1e-14)
    assert parabola_y(a, x - 0.01, sweep) < parabola_y(b, x - 0.01, sweep)


@pytest.mark.parametrize(
    ("points", "match"),
    [
        (np.zeros((0, 2)), "at least one"),
        ([[0.0, np.nan]], "NaN"),
        ([[0.0, 0.0, 0.0]], "shape"),
        (np.random.default_rng(0).random((2001, 2)), "at most 2000"),
    ],
)
def test_trace_rejects_bad_input(points, match):
    with pytest.raises(ValueError, match=match):
        trace(points)


def test_trace_bounds_and_input_untouched():
    pts = np.random.default_rng(5).random((12, 2))
    before = pts.copy()
    tr = trace(pts, (0.0, 0.0, 1.0, 1.0))
    np.testing.assert_array_equal(pts, before)
    want = vf.voronoi(pts, (0.0, 0.0, 1.0, 1.0)).edges
    assert tr.edges().pairs.tolist() == sorted(want.pairs.tolist())
    with pytest.raises(ValueError, match="xmin < xmax"):
        trace(pts, (1.0, 0.0, 0.0, 1.0))


# --- the animation ----------------------------------------------------------------------------


def _rgb(img):
    return np.asarray(img.convert("RGB"))


def test_frames_show_the_sweep_moving_down():
    pts = np.random.default_rng(9).random((20, 2))
    tr = trace(pts)
    frames = render_frames(tr, frames=9, size=160)
    w, h = frame_size(tr.bounds, 160)
    assert len(frames) == 9 and all(f.size == (w, h) for f in frames)
    red = np.array(COLORS["sweep"])
    rows = []
    for img in frames[:-1]:
        is_red = np.all(_rgb(img) == red, axis=-1)
        rows.append(np.flatnonzero(is_red.sum(axis=1) > w // 2))
    # the sweep line is drawn where sweep_positions puts it, lower in each frame
    sy = h / (tr.bounds[3] - tr.bounds[1])
    for r, y in zip(rows[1:-1], sweep_positions(tr.bounds, 9)[1:-1], strict=True):
        assert r.size and abs(r.mean() - (tr.bounds[3] - y) * sy) <= 2
    centres = [r.mean() for r in rows if r.size]
    assert centres == sorted(centres)
    for a, b in pairwise(frames):
        assert not np.array_equal(_rgb(a), _rgb(b))
    # the beach line appears once the sweep has passed sites; the final frame has no sweep
    assert np.all(_rgb(frames[4]) == COLORS["beach"], axis=-1).any()
    assert not np.all(_rgb(frames[-1]) == red, axis=-1).any()
    assert np.all(_rgb(frames[-1]) == COLORS["edge"], axis=-1).sum() > 100


def test_render_rejects_bad_options():
    pts = [[0.0, 0.0], [1.0, 1.0]]
    with pytest.raises(ValueError, match="frames"):
        render_frames(pts, frames=1, size=64)
    with pytest.raises(ValueError, match="frames"):
        render_frames(pts, frames=65, size=64)
    with pytest.raises(ValueError, match="size"):
        render_frames(pts, frames=4, size=8)


def test_cli_writes_gif(tmp_path, capsys):
    pts = np.random.default_rng(4).random((15, 2)) * [2.0, 1.0]
    src = tmp_path / "pts.csv"
    src.write_text("\n".join(f"{x!r},{y!r}" for x, y in pts.tolist()))
    out = tmp_path / "sweep.gif"
    argv = ["explain", "fortune", str(src), "-o", str(out), "--frames", "12", "--size", "200"]
    assert main(argv) == 0
    assert capsys.readouterr().out.strip() == str(out)
    with Image.open(out) as gif:
        assert gif.format == "GIF" and gif.n_frames == 12
        assert gif.size == frame_size(vf.voronoi(pts).bounds, 200)
        assert gif.size[0] == 200 and 90 < gif.size[1] < 130
        seen = []
        for k in range(gif.n_frames):
            gif.seek(k)
            seen.append(_rgb(gif))
    assert all(not np.array_equal(a, b) for a, b in pairwise(seen))
    assert main([*argv[:4], str(tmp_path / "sweep.png")]) == 2
    assert ".gif" in capsys.readouterr().err
    assert main([*argv[:-4], "--frames", "500", "--size", "200"]) == 2
    assert "frames" in capsys.readouterr().err
    assert main(["explain", "--help"]) == 0
    assert "fortune" in capsys.readouterr().out


def test_docstring_examples():
    import doctest

    import voroforge.explain.fortune

    result = doctest.testmod(voroforge.explain.fortune)
    assert result.attempted > 0 and result.failed == 0


@pytest.mark.parametrize("name", ["one_site", "horizontal_line", "cocircular_12_and_centre"])
def test_frames_of_degenerate_inputs(name):
    frames = render_frames(DEGENERATE[name], frames=6, size=96)
    assert len(frames) == 6
    rgb = [_rgb(f) for f in frames]
    assert all(not np.array_equal(a, b) for a, b in pairwise(rgb))
    # once the sweep has passed every site, every site is drawn as swept (black)
    grey = np.all(rgb[-2] == COLORS["pending_site"], axis=-1)
    assert not grey.any()
