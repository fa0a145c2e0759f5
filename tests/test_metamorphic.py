"""Metamorphic tests: move, rotate, scale or reorder the input and the answer follows."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from shapely.geometry import box

import voroforge as vf

from catalogue import CATALOGUE
from validate import symmetric_difference_areas, validate_diagram


def _dyadic(n: int, seed: int) -> np.ndarray:
    """Points on a 2**-20 lattice in [0, 1): translations and 90-degree turns are exact."""
    rng = np.random.default_rng(seed)
    pts = np.unique(rng.integers(0, 2**20, size=(n, 2)), axis=0)
    return rng.permutation(pts).astype(np.float64) / 2**20


def _triples(triangles) -> set[tuple[int, ...]]:
    return {tuple(sorted(t)) for t in np.asarray(triangles).tolist()}


UNIT = (-0.05, -0.05, 1.05, 1.05)

# name -> (map of points, map of a (xmin, ymin, xmax, ymax) box, area factor)
TRANSFORMS = {
    "translate_small": (
        lambda p: p + [3.0, -7.5],
        lambda b: (b[0] + 3, b[1] - 7.5, b[2] + 3, b[3] - 7.5),
        1.0,
    ),
    "translate_utm": (
        lambda p: p + [500000.0, 4000000.0],
        lambda b: (b[0] + 5e5, b[1] + 4e6, b[2] + 5e5, b[3] + 4e6),
        1.0,
    ),
    "rotate90": (
        lambda p: np.column_stack((-p[:, 1], p[:, 0])),
        lambda b: (-b[3], b[0], -b[1], b[2]),
        1.0,
    ),
    "rotate180": (lambda p: -p, lambda b: (-b[2], -b[3], -b[0], -b[1]), 1.0),
}
for _k in range(-9, 10, 3):
    _s = 10.0**_k
    TRANSFORMS[f"scale_1e{_k}"] = (
        lambda p, s=_s: p * s,
        lambda b, s=_s: tuple(v * s for v in b),
        _s * _s,
    )
NAMES = list(TRANSFORMS)


def _cell_map(name):
    """The same transform as a function of shapely coordinate arrays."""
    fp, _, _ = TRANSFORMS[name]
    return lambda xy: np.asarray(fp(np.asarray(xy)), dtype=np.float64)


@pytest.mark.parametrize("name", NAMES)
def test_triangulation_follows(name):
    pts = _dyadic(300, 1)
    fp = TRANSFORMS[name][0]
    a = vf.delaunay(pts)
    b = vf.delaunay(fp(pts))
    assert _triples(a.triangles) == _triples(b.triangles)
    assert set(np.asarray(a.hull).tolist()) == set(np.asarray(b.hull).tolist())


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("case", ["random", "grid"])
def test_cells_follow(name, case, algorithm):
    fp, fb, factor = TRANSFORMS[name]
    if case == "random":
        pts, bnd = _dyadic(150, 2), UNIT
    else:
        pts = CATALOGUE["grid_shuffled"][0] / 8.0  # cocircular everywhere, exact
        bnd = (-0.0625, -0.0625, 1.4375, 1.4375)
    a = vf.voronoi(pts, bnd, algorithm=algorithm)
    tp = fp(pts)
    tb = fb(bnd)
    b = vf.voronoi(tp, tb, algorithm=algorithm)
    validate_diagram(b, tp, box(*tb), samples=300)
    dom_area = b.boundary.area
    assert np.allclose(b.areas, a.areas * factor, rtol=0, atol=1e-9 * dom_area), "areas"
    scale = np.sqrt(dom_area)
    want = fp(a.centroids)
    atol = 1e-9 * scale + 8 * np.spacing(np.abs(tb).max())
    assert np.allclose(b.centroids, want, rtol=0, atol=atol), "centroids"
    moved = shapely.transform(np.asarray(a.cells, dtype=object), _cell_map(name))
    diff = symmetric_difference_areas(moved, b.cells, b.boundary)
    assert diff.max() <= 1e-9 * dom_area, f"cells differ by up to {diff.max()}"


@pytest.mark.parametrize("name", ["translate_utm", "rotate90", "scale_1e-9", "scale_1e9"])
def test_padded_domain_follows(name, algorithm):
    """With boundary=None the padded bounding box transforms along with the sites."""
    fp, fb, factor = TRANSFORMS[name]
    pts = _dyadic(100, 3)
    a = vf.voronoi(pts, algorithm=algorithm)
    b = vf.voronoi(fp(pts), algorithm=algorithm)
    want = fb(a.boundary.bounds)
    scale = np.sqrt(b.boundary.area)
    atol = 1e-12 * scale + 8 * np.spacing(np.abs(want).max())
    assert np.allclose(b.boundary.bounds, want, rtol=0, atol=atol)
    assert np.allclose(b.areas, a.areas * factor, rtol=0, atol=1e-9 * b.boundary.area)


@pytest.mark.parametrize("case", ["random", "duplicates", "grid_20x20", "holes_with_sites_inside"])
def test_permutation(case, algorithm):
    """Reordering the sites reorders the cells (and the triangles' indices), nothing else."""
    if case == "random":
        pts, bnd = _dyadic(200, 4), UNIT
    else:
        pts, bnd = CATALOGUE[case]
    perm = np.random.default_rng(5).permutation(len(pts))
    a = vf.voronoi(pts, bnd, algorithm=algorithm)
    b = vf.voronoi(pts[perm], bnd, algorithm=algorithm)
    dup = np.asarray(a.duplicate_of) >= 0
    if dup.any():
        # the first occurrence owns the cell, so only compare the union per coordinate
        ua = {tuple(p): a.areas[i] for i, p in enumerate(pts.tolist()) if not dup[i]}
        dupb = np.asarray(b.duplicate_of) >= 0
        ub = {tuple(p): b.areas[i] for i, p in enumerate(pts[perm].tolist()) if not dupb[i]}
        assert ua.keys() == ub.keys()
        assert all(abs(ua[k] - ub[k]) <= 1e-12 * b.boundary.area for k in ua)
        return
    diff = symmetric_difference_areas(np.asarray(a.cells)[perm], b.cells, b.boundary)
    assert diff.max() <= 1e-9 * b.boundary.area
    if case == "random":
        ta = vf.delaunay(pts)
        tb = vf.delaunay(pts[perm])
        assert _triples(perm[np.asarray(tb.triangles)]) == _triples(ta.triangles)
