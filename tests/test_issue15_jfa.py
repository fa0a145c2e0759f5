"""Issue 15, "Jump Flooding at every density": JFA's labels on crowded arrangements.

The flood alone loses sites where they crowd (one site per pixel; cells thinner than a pixel
break the chain of jumps): sites along a circle gave 16% wrong labels at 41 pixels per site,
along a slanted line 51-73%. ``rasterize(method="jfa")`` now checks every pixel against the
sites within the distance the flood found for it, so its labels and distances must equal a
brute-force argmin (ties to the lowest index) on every arrangement and density.
"""

from __future__ import annotations

import numpy as np
import pytest

import voroforge as vf
from voroforge.engine.raster import _jfa_reach, _jfa_steps, pixel_centers
from voroforge.kernels.raster import jfa_nearest

from reference import exact_pixel_labels

BOX = (0.0, 0.0, 1.0, 1.0)


def arrangement(kind: str, n: int, seed: int = 7) -> np.ndarray:
    """``n`` sites in the unit square, laid out as ``kind``."""
    g = np.random.default_rng(seed)
    if kind == "uniform":
        return g.random((n, 2))
    if kind == "jittered_grid":
        k = int(np.ceil(np.sqrt(n)))
        xx, yy = np.meshgrid(np.arange(k), np.arange(k))
        cells = np.stack((xx.ravel(), yy.ravel()), 1)
        return ((cells + 0.05 + 0.9 * g.random((k * k, 2))) / k)[:n]
    if kind == "gaussian":
        return g.random((20, 2))[g.integers(0, 20, n)] + g.normal(0, 0.02, (n, 2))
    if kind == "circle":
        t = np.arange(n) * 2 * np.pi / n
        return np.column_stack((np.cos(t), np.sin(t))) * 0.45 + 0.5
    if kind == "two_circles":
        a = n // 2
        t1 = np.arange(a) * 2 * np.pi / a
        t2 = np.arange(n - a) * 2 * np.pi / (n - a) + 0.1
        outer = np.column_stack((np.cos(t1), np.sin(t1))) * 0.45 + 0.5
        inner = np.column_stack((np.cos(t2), np.sin(t2))) * 0.2 + 0.5
        return np.vstack((outer, inner))
    if kind == "noisy_circle":
        t = g.random(n) * 2 * np.pi
        r = 0.45 + g.normal(0, 0.002, (n, 1))
        return np.column_stack((np.cos(t), np.sin(t))) * r + 0.5
    if kind == "line":
        return np.column_stack((np.linspace(0.1, 0.9, n), np.full(n, 0.5)))
    if kind == "slanted_line":
        s = np.linspace(0.1, 0.9, n)
        return np.column_stack((s, 0.3 + 0.4 * s))
    raise ValueError(kind)


def brute(pts, shape, bounds=BOX):
    """Nearest site (exactly; ties -> lowest index), F1 and F2, as the kernels round them."""
    x, y = pixel_centers(bounds, shape)
    h, w = shape
    lab = np.zeros(shape, dtype=np.int64)
    d1 = np.zeros(shape)
    d2 = np.zeros(shape)
    for r in range(h):  # one row at a time keeps memory small
        dx = x[:, None] - pts[:, 0]
        dy = y[r] - pts[:, 1]
        key = dx * dx + dy * dy
        lab[r] = exact_pixel_labels(key, key.argmin(axis=1), x, np.full(w, y[r]), pts)
        k1 = key[np.arange(w), lab[r]]
        key[np.arange(w), lab[r]] = np.inf  # the sites here are distinct
        d1[r] = np.sqrt(k1)
        d2[r] = np.sqrt(key.min(axis=1))
    return lab, d1, d2


def flood_only(pts, shape, bounds=BOX):
    """Labels of the flood alone (no exact check), as the engine would run it."""
    h, w = shape
    xs = np.ascontiguousarray(pts[:, 0])
    ys = np.ascontiguousarray(pts[:, 1])
    px, py = pixel_centers(bounds, shape)
    xmin, ymin, xmax, ymax = bounds
    geom = np.array([xmin, ymax, (xmax - xmin) / w, (ymax - ymin) / h])
    steps = _jfa_steps(h, w, _jfa_reach(xs, ys, geom, shape))
    return jfa_nearest(xs, ys, px, py, geom, steps, False)[0]


KINDS = (
    "uniform",
    "jittered_grid",
    "gaussian",
    "circle",
    "two_circles",
    "noisy_circle",
    "line",
    "slanted_line",
)


@pytest.mark.parametrize("per_site", [10, 40, 160])
@pytest.mark.parametrize("kind", KINDS)
def test_jfa_equals_brute_force(kind, per_site):
    shape = (64, 64)
    pts = arrangement(kind, shape[0] * shape[1] // per_site)
    assert len(np.unique(pts, axis=0)) == len(pts)
    lab, d1, d2 = brute(pts, shape)
    r = vf.rasterize(pts, shape, BOX, method="jfa", f2=per_site == 40)
    np.testing.assert_array_equal(r.labels, lab)
    np.testing.assert_array_equal(r.distance, d1)
    if r.f2 is not None:
        np.testing.assert_array_equal(r.f2, d2)


@pytest.mark.parametrize(
    ("kind", "n", "flood_wrong"),
    [("circle", 1600, 0.10), ("circle", 400, 0.01), ("slanted_line", 1600, 0.3)],
)
def test_crowded_sites_the_flood_loses(kind, n, flood_wrong):
    """The independent check's inputs (256^2, circle of radius 0.45: 41 and 164 px/site).

    The flood alone is wrong on many pixels here (so these inputs exercise the check);
    ``method="jfa"`` equals the exact method, labels and distances.
    """
    shape = (256, 256)
    pts = arrangement(kind, n)
    ex = vf.rasterize(pts, shape, BOX)
    flood = flood_only(pts, shape)
    assert np.mean(flood != ex.labels) > flood_wrong
    jf = vf.rasterize(pts, shape, BOX, method="jfa")
    np.testing.assert_array_equal(jf.labels, ex.labels)
    np.testing.assert_array_equal(jf.distance, ex.distance)


@pytest.mark.parametrize(
    ("offset", "scale", "shape"),
    [(0.0, 1.0, (48, 80)), (1e6, 1.0, (64, 64)), (-3.0, 1e-6, (80, 40)), (5e3, 1e4, (64, 64))],
)
def test_crowded_circle_moved_scaled_and_stretched(offset, scale, shape):
    """Neighbours of the circle: far offsets, tiny and huge scales, non-square pixels."""
    pts = arrangement("circle", 500) * scale + offset
    b = (offset, offset, offset + scale, offset + scale)
    lab, d1, _ = brute(pts, shape, b)
    r = vf.rasterize(pts, shape, b, method="jfa")
    np.testing.assert_array_equal(r.labels, lab)
    np.testing.assert_array_equal(r.distance, d1)


def test_duplicates_and_sites_outside_the_image():
    """Crowded sites partly outside the image, with duplicates: lowest index owns the cell."""
    pts = arrangement("circle", 600) * 1.6 - 0.3  # radius 0.72 around (0.5, 0.5)
    pts = np.vstack((pts, pts[::7]))
    r = vf.rasterize(pts, (60, 60), BOX, method="jfa", f2=True)
    ex = vf.rasterize(pts, (60, 60), BOX, f2=True)
    np.testing.assert_array_equal(r.labels, ex.labels)
    np.testing.assert_array_equal(r.distance, ex.distance)
    np.testing.assert_array_equal(r.f2, ex.f2)
    assert r.labels.max() < 600
