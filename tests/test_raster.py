"""vf.rasterize: exact labels/distances against brute force, JFA accuracy, PNG and CLI helpers."""

import os
import subprocess
import sys
import textwrap
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from PIL import Image

import voroforge as vf
from voroforge.engine.raster import pixel_centers, rasterize
from voroforge.io.raster_png import cell_colors, colorize, label_adjacency, write_raster_png

from reference import exact_pixel_labels

METRICS = ("euclidean", "manhattan", "chebyshev")


def brute(points, bounds, shape, metric="euclidean"):
    """Brute force: nearest site (argmin, ties -> lowest index), F1, and F2 (distinct sites)."""
    pts = np.asarray(points, dtype=np.float64)
    x, y = pixel_centers(bounds, shape)
    xx, yy = np.meshgrid(x, y)
    dx = xx[..., None] - pts[:, 0]
    dy = yy[..., None] - pts[:, 1]
    if metric == "euclidean":
        key = dx**2 + dy**2
    elif metric == "manhattan":
        key = np.abs(dx) + np.abs(dy)
    else:
        key = np.maximum(np.abs(dx), np.abs(dy))
    labels = key.argmin(axis=-1)
    k1 = np.take_along_axis(key, labels[..., None], axis=-1)[..., 0]
    labels = exact_pixel_labels(key, labels, xx, yy, pts, metric)  # near ties exactly
    k1 = np.take_along_axis(key, labels[..., None], axis=-1)[..., 0]
    # F2: smallest key over sites at a different position from the nearest one.
    same = (pts[:, 0] == pts[labels][..., 0:1]) & (pts[:, 1] == pts[labels][..., 1:2])
    k2 = np.where(same, np.inf, key).min(axis=-1)
    if metric == "euclidean":
        k1, k2 = np.sqrt(k1), np.sqrt(k2)
    return labels, k1, k2


def assert_matches_brute(points, bounds, shape, metric, f2=True):
    r = rasterize(points, shape, bounds, metric=metric, f2=f2)
    labels, d1, d2 = brute(points, r.bounds, shape, metric)
    np.testing.assert_array_equal(r.labels, labels)
    np.testing.assert_array_equal(r.distance, d1)
    if f2:
        np.testing.assert_array_equal(r.f2, d2)
    return r


@pytest.fixture
def mixed_sites():
    """200 sites with duplicates and a few outside the unit square."""
    rng = np.random.default_rng(3)
    pts = rng.random((200, 2))
    pts[50] = pts[10]
    pts[51] = pts[10]
    pts[120] = pts[7]
    pts[5] = [1.7, 0.4]
    pts[6] = [-0.3, -0.2]
    pts[199] = [0.5, 3.0]
    return pts


# --- exact method ----------------------------------------------------------------------------


@pytest.mark.parametrize("metric", METRICS)
def test_exact_equals_brute_force(mixed_sites, metric):
    r = assert_matches_brute(mixed_sites, (0.0, 0.0, 1.0, 1.0), (48, 64), metric)
    assert r.labels.dtype == np.int32 and r.distance.dtype == np.float64
    assert r.shape == (48, 64) and r.method == "exact" and r.metric == metric
    # duplicates never own pixels; the first occurrence does
    assert not np.isin([50, 51, 120], r.labels).any()
    assert np.all(r.f2 >= r.distance)
    np.testing.assert_array_equal(r.edge, r.f2 - r.distance)


@pytest.mark.parametrize("metric", METRICS)
def test_exact_integer_grid_ties(metric):
    # Sites on integers, pixel centres on half-integers: many exact ties between sites.
    rng = np.random.default_rng(5)
    pts = rng.integers(0, 12, size=(40, 2)).astype(float)
    assert_matches_brute(pts, (0.0, 0.0, 12.0, 12.0), (12, 12), metric)
    assert_matches_brute(pts[::-1], (0.0, 0.0, 12.0, 12.0), (24, 24), metric)


@given(
    st.lists(st.tuples(st.integers(-4, 12), st.integers(-4, 12)), min_size=1, max_size=30).map(
        lambda v: np.array(v, dtype=float) / 2.0
    ),
    st.sampled_from(METRICS),
)
def test_exact_hypothesis_small_grids(points, metric):
    assert_matches_brute(points, (0.0, 0.0, 4.0, 3.0), (9, 13), metric)


def test_exact_clustered_far_from_image():
    # A dense cluster far from most pixels: tiles get many candidates and are split.
    rng = np.random.default_rng(8)
    pts = np.concatenate([rng.normal(0.9, 0.004, (400, 2)), rng.random((5, 2))])
    for metric in METRICS:
        assert_matches_brute(pts, (0.0, 0.0, 1.0, 1.0), (40, 56), metric)


def test_exact_sites_all_outside():
    pts = np.array([[-1.0, 0.5], [2.0, 0.5], [0.5, 5.0], [-1.0, 0.5]])
    assert_matches_brute(pts, (0.0, 0.0, 1.0, 1.0), (16, 20), "euclidean")


def test_single_site_and_all_duplicates():
    r = assert_matches_brute([[0.3, 0.6]], (0, 0, 1, 1), (7, 5), "euclidean", f2=False)
    assert (r.labels == 0).all()
    r = rasterize([[0.3, 0.6]] * 3, (7, 5), (0, 0, 1, 1), f2=True)
    assert (r.labels == 0).all()
    assert np.isinf(r.f2).all()  # no second distinct site
    r = rasterize([[0.3, 0.6]] * 3, (7, 5), (0, 0, 1, 1), method="jfa", f2=True)
    assert (r.labels == 0).all() and np.isinf(r.f2).all()


def test_collinear_sites():
    pts = np.stack([np.linspace(0, 1, 30), np.full(30, 0.5)], axis=1)
    for metric in METRICS:
        assert_matches_brute(pts, (0, 0, 1, 1), (20, 33), metric)
    assert_matches_brute(pts[:, ::-1], (0, 0, 1, 1), (33, 20), "euclidean")


def test_pixel_centre_convention():
    # Left/right: bisector x = 0.5, pixel centres 0.05, 0.15, ..., 0.95.
    r = rasterize([[0.3, 0.5], [0.7, 0.5]], (1, 10), (0.0, 0.0, 1.0, 1.0))
    assert r.labels.tolist() == [[0] * 5 + [1] * 5]
    np.testing.assert_allclose(r.distance[0, :3], [0.25, 0.15, 0.05])
    np.testing.assert_allclose(r.x, np.arange(10) / 10 + 0.05)
    # Top/bottom: row 0 is the top (largest y).
    r = rasterize([[0.5, 0.9], [0.5, 0.1]], (4, 1), (0.0, 0.0, 1.0, 1.0))
    assert r.labels[:, 0].tolist() == [0, 0, 1, 1]
    np.testing.assert_allclose(r.y, [0.875, 0.625, 0.375, 0.125])
    assert r.distance[0, 0] == abs(0.875 - 0.9)


def test_ties_go_to_lowest_index():
    # Pixel centre (0.5, 0.5) is equidistant from both sites, whichever order they come in.
    a, b = [0.25, 0.5], [0.75, 0.5]
    for pts, want in (([a, b], 0), ([b, a], 0)):
        for method in ("exact", "jfa"):
            r = rasterize(pts, (1, 1), (0.0, 0.0, 1.0, 1.0), method=method, f2=True)
            assert r.labels[0, 0] == want
            assert r.f2[0, 0] == r.distance[0, 0] == 0.25
            assert r.edge[0, 0] == 0.0


@pytest.mark.parametrize("method", ["exact", "jfa"])
def test_near_ties_go_to_the_exactly_nearest_site(method):
    # pixel (1, 1) of an 8 x 8 image over the default bounds of (0, 0) and (1, 1) is at
    # x = 0.12500000000000003, y = 0.875: x + y > 1, so site 1 is strictly nearer, though
    # the float squared distances tie; the labels must agree with Diagram.locate
    pts = np.array([[0.0, 0.0], [1.0, 1.0]])
    r = rasterize(pts, (8, 8), method=method, f2=True)
    assert Fraction(float(r.x[1])) + Fraction(float(r.y[1])) > 1
    assert r.labels[1, 1] == 1
    assert r.f2[1, 1] == r.distance[1, 1]  # the float distances still tie
    d = vf.voronoi(pts)
    # a regular 300-gon: 24 of 1024 pixel centres sit within rounding of a tie
    t = np.linspace(0.0, 2.0 * np.pi, 300, endpoint=False)
    gon = np.column_stack((np.cos(t), np.sin(t)))
    for p, shape in ((pts, (8, 8)), (gon, (32, 32))):
        r = rasterize(p, shape, method=method)
        xx, yy = np.meshgrid(r.x, r.y)
        d = vf.voronoi(p)
        want = d.locate(np.column_stack((xx.ravel(), yy.ravel())))
        np.testing.assert_array_equal(r.labels.ravel(), want)
    for metric in METRICS if method == "exact" else ():
        assert_matches_brute(gon, None, (32, 32), metric)


def test_scaling_by_two_is_exact(mixed_sites):
    r1 = rasterize(mixed_sites, (30, 40), (0.0, 0.0, 1.0, 1.0), f2=True)
    r2 = rasterize(mixed_sites * 1024.0, (30, 40), (0.0, 0.0, 1024.0, 1024.0), f2=True)
    np.testing.assert_array_equal(r1.labels, r2.labels)
    np.testing.assert_array_equal(r1.distance * 1024.0, r2.distance)
    np.testing.assert_array_equal(r1.f2 * 1024.0, r2.f2)


def test_large_offset_coordinates():
    rng = np.random.default_rng(2)
    pts = 4_000_000.0 + rng.random((60, 2)) * 100.0
    assert_matches_brute(pts, None, (25, 30), "euclidean")


def test_default_bounds_are_padded_bbox():
    r = rasterize([[0.0, 0.0], [10.0, 5.0]], (4, 4))
    assert r.bounds == (-1.0, -0.5, 11.0, 5.5)
    r = rasterize([[2.0, 3.0]], (4, 4))  # one site: 10% of max(1, |coordinate|), as voronoi
    assert r.bounds == pytest.approx((1.7, 2.7, 2.3, 3.3), abs=1e-15)
    for pts in ([[0.0, 0.0], [10.0, 5.0]], [[2.0, 3.0]], [[0.0, 1.0], [4.0, 1.0]]):
        assert rasterize(pts, (2, 2)).bounds == vf.voronoi(pts).bounds
    r = rasterize([[0.0, 1.0], [4.0, 1.0]], (4, 4))  # zero height: padded like the width
    assert r.bounds == (-0.4, 0.6, 4.4, 1.4)


def test_inputs_not_mutated_and_results_read_only(mixed_sites):
    before = mixed_sites.copy()
    bounds = [0.0, 0.0, 1.0, 1.0]
    r = rasterize(mixed_sites, (8, 8), bounds, method="jfa", f2=True)
    np.testing.assert_array_equal(mixed_sites, before)
    assert bounds == [0.0, 0.0, 1.0, 1.0]
    for arr in (r.labels, r.distance, r.f2, r.edge):
        assert not arr.flags.writeable
    assert "RasterVoronoi" in repr(r)


def test_edge_needs_f2():
    r = rasterize([[0, 0], [1, 1]], (4, 4))
    assert r.f2 is None
    with pytest.raises(ValueError, match="f2=True"):
        _ = r.edge


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"points": [[0, 0], [np.nan, 1]]}, "NaN"),
        ({"points": [[0, 0], [np.inf, 1]]}, "infinite"),
        ({"points": [[0, 0, 0]]}, "shape"),
        ({"points": np.zeros((0, 2))}, "at least one"),
        ({"shape": (0, 4)}, "positive ints"),
        ({"shape": (4, -1)}, "positive ints"),
        ({"shape": (4.0, 4)}, "positive ints"),
        ({"shape": (True, 4)}, "positive ints"),
        ({"shape": (4, 4, 4)}, "positive ints"),
        ({"shape": 4}, "positive ints"),
        ({"bounds": (0, 0, 1)}, "4 numbers"),
        ({"bounds": (1, 0, 0, 1)}, "xmin < xmax"),
        ({"bounds": (0, 1, 1, 1)}, "ymin < ymax"),
        ({"bounds": (0, 0, np.nan, 1)}, "finite"),
        ({"bounds": "abcd"}, "bounds"),
        ({"method": "voronoi"}, "method"),
        ({"metric": "cosine"}, "metric"),
        ({"method": "jfa", "metric": "manhattan"}, "supports metric=.euclidean. only"),
    ],
)
def test_validation(kwargs, match):
    args = {"points": [[0.0, 0.0], [1.0, 1.0]], "shape": (4, 4), "bounds": None, **kwargs}
    with pytest.raises(ValueError, match=match):
        rasterize(args.pop("points"), args.pop("shape"), args.pop("bounds"), **args)


# --- Jump Flooding ---------------------------------------------------------------------------


def test_jfa_close_to_exact():
    rng = np.random.default_rng(0)
    pts = rng.random((1000, 2))
    bounds = (0.0, 0.0, 1.0, 1.0)
    ex = rasterize(pts, (512, 512), bounds, f2=True)
    jf = rasterize(pts, (512, 512), bounds, method="jfa")
    assert jf.method == "jfa" and jf.f2 is None
    assert np.mean(jf.labels != ex.labels) <= 0.005  # the target share
    # JFA distances are to real sites: never below the true F1, and only slightly above.
    pixel = 1.0 / 512
    assert np.all(jf.distance >= ex.distance)
    assert np.max(jf.distance - ex.distance) < 2 * pixel
    # where the labels agree the distances are identical
    same = jf.labels == ex.labels
    np.testing.assert_array_equal(jf.distance[same], ex.distance[same])
    # the two-label variant is at least as good and approximates F2
    jf2 = rasterize(pts, (512, 512), bounds, method="jfa", f2=True)
    assert np.mean(jf2.labels != ex.labels) <= np.mean(jf.labels != ex.labels)
    assert np.mean(np.abs(jf2.f2 - ex.f2) > 1e-12) < 0.02
    assert np.all(jf2.f2 >= jf2.distance)


@pytest.mark.parametrize(("n", "size"), [(3000, 256), (2000, 280), (1500, 300)])
def test_jfa_dense_sites_close_to_exact(n, size):
    """20-60 pixels per site: sites sharing a pixel are seeded next to it, not lost."""
    pts = np.random.default_rng(n).random((n, 2))
    ex = rasterize(pts, (size, size), (0.0, 0.0, 1.0, 1.0))
    jf = rasterize(pts, (size, size), (0.0, 0.0, 1.0, 1.0), method="jfa")
    assert np.mean(jf.labels != ex.labels) <= 0.005
    assert set(np.unique(jf.labels)) == set(np.unique(ex.labels))  # no cell lost
    assert np.all(jf.distance >= ex.distance)


def test_jfa_duplicates_outside_sites_and_rectangular_image(mixed_sites):
    ex = rasterize(mixed_sites, (96, 160), (0.0, 0.0, 1.0, 1.0))
    jf = rasterize(mixed_sites, (96, 160), (0.0, 0.0, 1.0, 1.0), method="jfa")
    assert not np.isin([50, 51, 120], jf.labels).any()
    assert np.mean(jf.labels != ex.labels) < 0.02
    assert np.all(jf.distance >= ex.distance)


def test_jfa_few_sites_is_exact():
    pts = [[0.1, 0.2], [0.8, 0.7], [0.4, 0.9]]
    ex = rasterize(pts, (50, 70), (0, 0, 1, 1))
    jf = rasterize(pts, (50, 70), (0, 0, 1, 1), method="jfa")
    np.testing.assert_array_equal(jf.labels, ex.labels)


def test_kernels_run_without_jit(tmp_path):
    # The kernels must stay plain Python too (coverage runs with NUMBA_DISABLE_JIT=1).
    code = textwrap.dedent(
        """
        import numpy as np
        from voroforge.engine.raster import rasterize
        pts = np.random.default_rng(1).random((25, 2))
        pts[3] = pts[2]
        ex = rasterize(pts, (12, 10), (0, 0, 1, 1), f2=True)
        ex2 = rasterize(pts, (12, 10), (0, 0, 1, 1), metric="chebyshev")
        jf = rasterize(pts, (12, 10), (0, 0, 1, 1), method="jfa", f2=True)
        np.save("out.npy", np.stack([ex.labels, ex2.labels, jf.labels]))
        """
    )
    env = {**os.environ, "NUMBA_DISABLE_JIT": "1"}
    subprocess.run([sys.executable, "-c", code], check=True, env=env, cwd=tmp_path, timeout=120)
    got = np.load(tmp_path / "out.npy")
    pts = np.random.default_rng(1).random((25, 2))
    pts[3] = pts[2]
    np.testing.assert_array_equal(got[0], brute(pts, (0, 0, 1, 1), (12, 10))[0])
    np.testing.assert_array_equal(got[1], brute(pts, (0, 0, 1, 1), (12, 10), "chebyshev")[0])
    assert got[2].shape == (12, 10)


# --- PNG and CLI helpers ---------------------------------------------------------------------


def test_write_png_fields(tmp_path, mixed_sites):
    r = rasterize(mixed_sites, (30, 40), (0, 0, 1, 1), f2=True)
    for field in ("labels", "distance", "f2", "edge"):
        path = write_raster_png(r, tmp_path / f"{field}.png", field=field)
        img = np.asarray(Image.open(path))
        assert img.shape[:2] == (30, 40)
    rgb = np.asarray(Image.open(tmp_path / "labels.png"))
    np.testing.assert_array_equal(rgb, cell_colors(r.labels)[r.labels])
    grey = colorize(r, field="distance")
    assert grey.dtype == np.uint8 and grey.max() == 255
    np.testing.assert_array_equal(np.asarray(Image.open(tmp_path / "distance.png")), grey)
    # greyscale is monotone in the distance
    order = np.argsort(r.distance, axis=None, kind="stable")
    assert np.all(np.diff(grey.ravel()[order].astype(int)) >= 0)
    edge = colorize(r, field="edge")
    assert edge.min() == 0  # on cell boundaries
    with pytest.raises(ValueError, match="field"):
        colorize(r, field="nope")
    with pytest.raises(ValueError, match="f2=True"):
        colorize(rasterize(mixed_sites, (4, 4)), field="edge")


def brute_adjacency(labels):
    """Set of unordered label pairs that touch (8-neighbourhood), by plain loops."""
    h, w = labels.shape
    out = set()
    for r in range(h):
        for c in range(w):
            for dr, dc in ((0, 1), (1, 0), (1, 1), (1, -1)):
                rr, cc = r + dr, c + dc
                if 0 <= rr < h and 0 <= cc < w and labels[r, c] != labels[rr, cc]:
                    a, b = sorted((int(labels[r, c]), int(labels[rr, cc])))
                    out.add((a, b))
    return out


def test_cell_colors_distinguish_neighbours(mixed_sites):
    r = rasterize(mixed_sites, (60, 80), (0, 0, 1, 1))
    n = int(r.labels.max()) + 1  # site 199 lies far outside and owns no pixel
    indptr, indices = label_adjacency(r.labels, n)
    got = {(i, int(j)) for i in range(n) for j in indices[indptr[i] : indptr[i + 1]] if i < j}
    want = brute_adjacency(r.labels)
    assert got == want and want
    colors = cell_colors(r.labels)
    assert colors.shape == (n, 3) and colors.dtype == np.uint8
    for a, b in want:
        assert not np.array_equal(colors[a], colors[b]), (a, b)
    # deterministic; the seed changes the choice
    np.testing.assert_array_equal(cell_colors(r.labels), colors)
    assert not np.array_equal(cell_colors(r.labels, seed=1), colors)
    # several colours in use, not just two
    assert len(np.unique(colors[np.unique(r.labels)], axis=0)) >= 6


@pytest.mark.parametrize("kind", ["random", "grid_with_duplicates"])
def test_exact_labels_lie_in_their_voronoi_cells(kind):
    import shapely

    rng = np.random.default_rng(11)
    if kind == "random":
        pts = rng.random((80, 2))
    else:  # integer grid: many pixel centres exactly on cell edges, plus duplicate sites
        g = np.arange(6, dtype=float)
        pts = np.stack(np.meshgrid(g, g), axis=-1).reshape(-1, 2)
        pts = np.concatenate([pts, pts[[3, 17]]])
    d = vf.voronoi(pts)
    r = vf.rasterize(pts, (70, 90))
    assert r.bounds == d.bounds
    xx, yy = np.meshgrid(r.x, r.y)
    cells = d.cells[r.labels.ravel()]
    inside = shapely.intersects_xy(cells, xx.ravel(), yy.ravel())
    # pixel centres on a cell edge (exact ties) may miss the float polygon by rounding
    gap = shapely.distance(cells[~inside], shapely.points(xx.ravel()[~inside], yy.ravel()[~inside]))
    assert np.all(gap <= 1e-12 * np.ptp(pts))
    assert inside.mean() > 0.9
    assert not np.isin(np.flatnonzero(d.duplicate_of >= 0), r.labels).any()


@pytest.mark.parametrize(
    ("kind", "shape", "bounds"),
    [
        ("uniform", (256, 256), (0.0, 0.0, 1.0, 1.0)),
        ("clustered", (200, 300), (0.0, 0.0, 1.0, 1.0)),
        ("few", (128, 96), (0.0, 0.0, 1.0, 1.0)),
        ("outside", (100, 100), (0.2, 0.2, 0.8, 0.8)),
        ("uniform", (64, 512), (0.0, 0.0, 1.0, 0.05)),  # pixels 20x taller than wide
    ],
)
def test_jfa_first_step_reaches_every_nearest_site(kind, shape, bounds):
    # JFA starts at the step K of _jfa_reach: every pixel's nearest site must be seeded
    # within 2K - 1 pixels per axis, or the flooding could not bring it there.
    from voroforge.engine.raster import _jfa_reach, _jfa_steps

    rng = np.random.default_rng(6)
    pts = {
        "uniform": rng.random((400, 2)),
        "clustered": np.concatenate([rng.normal(0.2, 0.01, (300, 2)), rng.random((4, 2))]),
        "few": rng.random((3, 2)),
        "outside": rng.random((40, 2)),
    }[kind]
    h, w = shape
    xmin, ymin, xmax, ymax = bounds
    geom = np.array([xmin, ymax, (xmax - xmin) / w, (ymax - ymin) / h])
    reach = _jfa_reach(pts[:, 0], pts[:, 1], geom, shape)
    k = int(_jfa_steps(h, w, reach)[0])
    ex = rasterize(pts, shape, bounds)
    seed_c = np.clip(np.floor((pts[:, 0] - xmin) / geom[2]), 0, w - 1)
    seed_r = np.clip(np.floor((ymax - pts[:, 1]) / geom[3]), 0, h - 1)
    rows, cols = np.indices(shape)
    offset = np.maximum(np.abs(rows - seed_r[ex.labels]), np.abs(cols - seed_c[ex.labels]))
    assert offset.max() <= min(reach, 2 * k - 1)
    jf = rasterize(pts, shape, bounds, method="jfa")
    assert np.mean(jf.labels != ex.labels) < 0.01


def test_docstring_examples():
    import doctest

    import voroforge.engine.raster
    import voroforge.io.raster_png

    for module in (voroforge.engine.raster, voroforge.io.raster_png):
        result = doctest.testmod(module)
        assert result.attempted > 0 and result.failed == 0, module.__name__
