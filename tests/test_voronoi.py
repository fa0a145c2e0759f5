"""2D Voronoi diagrams: invariants on the catalogue, the brute-force oracle, every domain kind."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from scipy.spatial import cKDTree
from shapely.geometry import MultiPolygon, Polygon, box

import voroforge as vf

from catalogue import CATALOGUE, NAMES, as_domain, general_position
from reference import brute_voronoi
from validate import symmetric_difference_areas, validate_diagram, validate_triangulation

ORACLE_NAMES = [k for k in NAMES if len(CATALOGUE[k][0]) > 0]
_ORACLE_CELLS: dict[tuple[bytes, bytes], np.ndarray] = {}


def _oracle(pts, dom) -> np.ndarray:
    """``brute_voronoi(pts, dom)``, built once per input and shared by every algorithm."""
    key = (np.asarray(pts, dtype=np.float64).tobytes(), shapely.to_wkb(dom))
    if key not in _ORACLE_CELLS:
        _ORACLE_CELLS[key] = brute_voronoi(pts, dom)
    return _ORACLE_CELLS[key]


def _assert_cells_equal(got, want, dom, rtol: float = 1e-9) -> None:
    domain_area = dom.area
    got = np.asarray(got, dtype=object)
    want = np.asarray(want, dtype=object)
    assert got.shape == want.shape
    diff = symmetric_difference_areas(got, want, dom)
    bad = np.flatnonzero(diff > rtol * domain_area)
    assert not len(bad), (
        f"{len(bad)} cells differ from the oracle, e.g. cell {bad[:5].tolist()} by areas "
        f"{diff[bad[:5]].tolist()} (domain area {domain_area})"
    )


@pytest.mark.parametrize("name", NAMES, ids=NAMES)
def test_catalogue_invariants(name, algorithm):
    pts, boundary = CATALOGUE[name]
    d = vf.voronoi(pts, boundary, algorithm=algorithm)
    validate_diagram(d, pts, as_domain(boundary))


@pytest.mark.parametrize("name", ORACLE_NAMES, ids=ORACLE_NAMES)
def test_catalogue_matches_oracle(name, algorithm):
    pts, boundary = CATALOGUE[name]
    d = vf.voronoi(pts, boundary, algorithm=algorithm)
    dom = d.boundary
    _assert_cells_equal(d.cells, _oracle(pts, dom), dom)


@pytest.mark.parametrize("seed", range(3))
@pytest.mark.parametrize(
    "kind", ["box", "tuple_offset", "holes", "multipolygon", "concave", "none"]
)
def test_random_matches_oracle(kind, seed, algorithm):
    pts = general_position(120, seed)
    boundary = {
        "box": (0.0, 0.0, 1.0, 1.0),
        "tuple_offset": (-0.3, 0.1, 0.9, 1.4),
        "holes": Polygon(
            [(0, 0), (1, 0), (1, 1), (0, 1)],
            [
                [(0.2, 0.2), (0.45, 0.2), (0.45, 0.4), (0.2, 0.4)],
                [(0.6, 0.6), (0.8, 0.65), (0.7, 0.9)],
            ],
        ),
        "multipolygon": MultiPolygon([box(0, 0, 0.4, 1), box(0.5, 0.2, 1.2, 0.7)]),
        "concave": Polygon([(0, 0), (1, 0), (1, 1), (0.5, 0.3), (0, 1)]),
        "none": None,
    }[kind]
    d = vf.voronoi(pts, boundary, algorithm=algorithm)
    validate_diagram(d, pts, as_domain(boundary), samples=500)
    _assert_cells_equal(d.cells, _oracle(pts, d.boundary), d.boundary)


@pytest.mark.parametrize(
    "pts",
    [
        general_position(40, 9),
        general_position(40, 9) * [3.0, 0.5] + [10.0, -2.0],
        np.array([[0.0, 0.0], [0.0, 5.0], [1.0, 5.0]]),
    ],
    ids=["unit", "stretched", "three"],
)
def test_none_boundary_is_padded_bbox(pts, algorithm):
    d = vf.voronoi(pts, algorithm=algorithm)
    lo, hi = pts.min(0), pts.max(0)
    pad = 0.1 * (hi - lo)
    want = np.concatenate((lo - pad, hi + pad))
    assert np.allclose(d.boundary.bounds, want, rtol=0, atol=1e-12 * (hi - lo).max())
    assert d.boundary.area == pytest.approx(np.prod(hi - lo + 2 * pad), rel=1e-12)
    assert d.areas.sum() == pytest.approx(d.boundary.area, rel=1e-9)


@pytest.mark.parametrize(
    "pts",
    [np.array([[3.0, 4.0]]), np.array([[1.0, 1.0], [1.0, 4.0]]), np.array([[1.0, 1.0]] * 3)],
    ids=["one", "vertical_pair", "triplicate"],
)
def test_none_boundary_degenerate_extent(pts, algorithm):
    d = vf.voronoi(pts, algorithm=algorithm)
    xmin, ymin, xmax, ymax = d.boundary.bounds
    assert xmin < pts[:, 0].min() <= pts[:, 0].max() < xmax
    assert ymin < pts[:, 1].min() <= pts[:, 1].max() < ymax
    validate_diagram(d, pts)


BOUNDARIES = {
    "tuple": (0.0, 0.0, 2.0, 1.0),
    "polygon": Polygon([(0, 0), (2, 0), (2, 1), (0, 1)]),
    "holes": Polygon([(0, 0), (2, 0), (2, 1), (0, 1)], [[(0.2, 0.2), (0.4, 0.2), (0.3, 0.4)]]),
    "multipolygon": MultiPolygon([box(0, 0, 0.8, 1), box(1.2, 0, 2, 1)]),
    "concave": Polygon([(0, 0), (2, 0), (2, 1), (1, 0.2), (0, 1)]),
}


@pytest.mark.parametrize("kind", list(BOUNDARIES))
def test_one_site_owns_domain(kind, algorithm):
    dom = as_domain(BOUNDARIES[kind])
    for site in ([1.0, 0.5], [0.3, 0.3], [-5.0, 7.0]):  # inside, in a hole (for "holes"), outside
        d = vf.voronoi([site], BOUNDARIES[kind], algorithm=algorithm)
        assert shapely.symmetric_difference(d.cells[0], dom).area <= 1e-12 * dom.area
        assert d.areas[0] == pytest.approx(dom.area, rel=1e-12)
        assert len(d.edges.pairs) == 0
        assert len(d.neighbors[1]) == 0


@pytest.mark.parametrize("kind", list(BOUNDARIES))
def test_two_sites_bisect(kind, algorithm):
    dom = as_domain(BOUNDARIES[kind])
    pts = np.array([[0.25, 0.5], [1.75, 0.5]])
    d = vf.voronoi(pts, BOUNDARIES[kind], algorithm=algorithm)
    left = dom.intersection(box(-1, -1, 1, 2))
    right = dom.intersection(box(1, -1, 3, 2))
    _assert_cells_equal(d.cells, [left, right], dom)
    validate_diagram(d, pts, dom)
    coords, pairs = d.edges
    if kind != "multipolygon":  # the parts do not touch x = 1 there: no shared edge
        assert pairs.tolist() == [[0, 1]]
        assert np.allclose(coords[0, :, 0], 1.0, rtol=0, atol=1e-15)
    else:
        assert len(pairs) == 0


def test_sites_outside_domain(algorithm):
    unit = (0.0, 0.0, 1.0, 1.0)
    # one inside, one outside but still nearest to a strip of the domain
    d = vf.voronoi([[0.5, 0.5], [1.2, 0.5]], unit, algorithm=algorithm)
    _assert_cells_equal(d.cells, [box(0, 0, 0.85, 1), box(0.85, 0, 1, 1)], box(*unit))
    # an outside site too far away to own anything
    d = vf.voronoi([[0.5, 0.5], [3.0, 0.5]], unit, algorithm=algorithm)
    assert d.cells[1].is_empty and d.areas[1] == 0 and np.isnan(d.centroids[1]).all()
    assert d.areas[0] == pytest.approx(1.0, rel=1e-12)
    # every site outside
    pts = np.array([[-1.0, 0.5], [2.0, 0.5], [0.5, 5.0]])
    d = vf.voronoi(pts, unit, algorithm=algorithm)
    _assert_cells_equal(d.cells, brute_voronoi(pts, box(*unit)), box(*unit))
    validate_diagram(d, pts, box(*unit))


def test_grid_has_no_point_contact_neighbours(algorithm):
    pts, _ = CATALOGUE["grid_20x20"]
    d = vf.voronoi(pts, (-0.5, -0.5, 19.5, 19.5), algorithm=algorithm)
    indptr, indices = d.neighbors
    deg = np.diff(indptr)
    x, y = pts.T
    interior = (x > 0) & (x < 19) & (y > 0) & (y < 19)
    assert np.all(deg[interior] == 4), "diagonal (point-contact) cells counted as neighbours"
    assert np.allclose(d.areas, 1.0, rtol=1e-12)
    assert len(d.edges.pairs) == 2 * 20 * 19


@pytest.mark.parametrize(
    "name", ["holes_with_sites_inside", "multipolygon", "concave_star", "duplicates"]
)
def test_to_geoarrow_round_trip(name, algorithm):
    pts, boundary = CATALOGUE[name]
    d = vf.voronoi(pts, boundary, algorithm=algorithm)
    coords, offsets = d.to_geoarrow()
    back = shapely.from_ragged_array(shapely.GeometryType.MULTIPOLYGON, coords, offsets)
    assert back.shape == (len(pts),)
    cells = d.cells
    for i in range(len(pts)):
        if cells[i].is_empty:
            assert back[i].is_empty
            continue
        want = cells[i] if cells[i].geom_type == "MultiPolygon" else MultiPolygon([cells[i]])
        assert back[i].geom_type == "MultiPolygon"
        assert shapely.equals(back[i], want), f"cell {i} differs after the round trip"


@pytest.mark.parametrize("boundary", [None, (0.0, 0.0, 1.0, 1.0), BOUNDARIES["holes"]])
def test_input_not_mutated(boundary, algorithm):
    pts = general_position(80, 3)
    pts[5] = pts[2]
    keep = pts.copy()
    ro = pts.copy()
    ro.setflags(write=False)
    bkeep = shapely.to_wkb(boundary) if isinstance(boundary, shapely.Geometry) else boundary
    for arr in (pts, ro):
        writeable = arr.flags.writeable
        d = vf.voronoi(arr, boundary, algorithm=algorithm)
        assert np.array_equal(arr, keep)
        assert arr.flags.writeable == writeable
        assert not np.shares_memory(np.asarray(d.sites), arr)
    if isinstance(boundary, shapely.Geometry):
        assert shapely.to_wkb(boundary) == bkeep
    else:
        assert boundary == bkeep
    lst = keep.tolist()
    vf.voronoi(lst, boundary, algorithm=algorithm)
    assert lst == keep.tolist()


def test_zero_sites(algorithm):
    d = vf.voronoi(np.zeros((0, 2)), (0.0, 0.0, 1.0, 1.0), algorithm=algorithm)
    assert len(d.cells) == 0 and d.areas.shape == (0,) and d.centroids.shape == (0, 2)
    assert len(d.edges.pairs) == 0
    with pytest.raises(ValueError):
        vf.voronoi(np.zeros((0, 2)), algorithm=algorithm)


@pytest.mark.parametrize(
    "name", ["clustered", "grid_shuffled", "utm_random", "sites_outside", "duplicates", "hex_grid"]
)
def test_shared_edges_are_watertight(name, algorithm):
    """On rectangular domains both cells of an edge carry its end points bit for bit.

    Otherwise neighbouring cells leave slivers or overlaps of an ulp, which GEOS overlays
    (unions of cells, say) can turn into gross errors.
    """
    pts, boundary = CATALOGUE[name]
    d = vf.voronoi(pts, boundary, algorithm=algorithm)
    verts = [set(map(tuple, shapely.get_coordinates(c).tolist())) for c in d.cells]
    coords, pairs = d.edges
    bad = []
    for k, (i, j) in enumerate(np.asarray(pairs).tolist()):
        for p in map(tuple, np.asarray(coords[k]).tolist()):
            if p not in verts[i] or p not in verts[j]:
                bad.append((i, j, p))
    assert not bad, f"{len(bad)} edge end points missing from a cell, e.g. {bad[:3]}"


# --- the validator itself must reject broken diagrams ----------------------------------------


def _fake_diagram(d, **changes):
    from types import SimpleNamespace

    fields = ("sites", "cells", "areas", "centroids", "duplicate_of", "boundary", "neighbors")
    base = {k: getattr(d, k) for k in fields}
    base["cells"] = np.array(d.cells, dtype=object)
    base["edges"] = tuple(d.edges)
    base.update(changes)
    return SimpleNamespace(**base)


def test_validator_rejects_broken_diagrams():
    pts = general_position(50, 6)
    d = vf.voronoi(pts, (0.0, 0.0, 1.0, 1.0))
    validate_diagram(d, pts)
    cells = np.array(d.cells, dtype=object)

    swapped = cells.copy()
    swapped[[3, 4]] = swapped[[4, 3]]
    areas_s = d.areas.copy()
    areas_s[[3, 4]] = areas_s[[4, 3]]
    cen_s = d.centroids.copy()
    cen_s[[3, 4]] = cen_s[[4, 3]]

    grown = cells.copy()
    grown[0] = grown[0].buffer(0.01, join_style="mitre")
    shrunk = cells.copy()
    shrunk[0] = shapely.affinity.scale(shrunk[0], 0.99, 0.99)

    coords, pairs = d.edges
    bent = np.array(coords).copy()
    bent[0, 0] += 1e-4
    pairs_wrong = np.array(pairs).copy()
    pairs_wrong[0] = [pairs_wrong[0, 0], (pairs_wrong[0, 1] + 1) % 50]

    broken = {
        "swapped_cells": {"cells": swapped, "areas": areas_s, "centroids": cen_s},
        "overlap": {
            "cells": grown,
            "areas": shapely.area(grown),
            "centroids": shapely.get_coordinates(shapely.centroid(grown)),
        },
        "gap": {
            "cells": shrunk,
            "areas": shapely.area(shrunk),
            "centroids": shapely.get_coordinates(shapely.centroid(shrunk)),
        },
        "areas": {"areas": d.areas * 1.001},
        "centroids": {"centroids": d.centroids + 1e-6},
        "edge_off_bisector": {"edges": (bent, pairs)},
        "edge_missing": {"edges": (np.array(coords)[1:], np.array(pairs)[1:])},
        "edge_wrong_pair": {"edges": (coords, pairs_wrong)},
    }
    for name, change in broken.items():
        with pytest.raises(AssertionError):
            validate_diagram(_fake_diagram(d, **change), pts)
            print(name)


@pytest.mark.parametrize("exp", [-1000, -600, 600, 1000])
def test_extreme_scales_are_exact_power_of_two_images(exp):
    """Past 1e±150 products of coordinates leave the double range (and shapely's checks
    fail there), so check that scaling by 2**exp, which is exact, maps the result exactly."""
    pts = np.random.default_rng(5).random((80, 2)) + 0.25
    ref = vf.voronoi(pts)
    validate_diagram(ref, pts)
    big = np.ldexp(pts, exp)
    d = vf.voronoi(big)
    assert np.array_equal(d.sites, big)
    coords, offsets = d.to_geoarrow()
    rcoords, roffsets = ref.to_geoarrow()
    assert all(np.array_equal(a, b) for a, b in zip(offsets, roffsets, strict=True))
    assert np.array_equal(np.ldexp(coords, -exp), rcoords)
    assert np.array_equal(d.edges.pairs, ref.edges.pairs)
    tri = vf.delaunay(big)
    assert np.array_equal(tri.triangles, vf.delaunay(pts).triangles)
    assert np.array_equal(tri.points, big)


def test_extreme_dynamic_range_rounds_only_negligible_values():
    """Values below 2**-188 of the largest magnitude are rounded to the predicates'
    resolution; everything else is untouched and the result is valid."""
    pts = np.array(
        [
            [0.0, 0.0],
            [0.0, 1e-60],
            [0.0, 7e-104],
            [-31.8, -45.7],
            [-98.5, 0.0],
            [0.0, 94.1],
            [2e-247, 0.0],
        ]
    )
    tri = vf.delaunay(pts)
    validate_triangulation(tri)
    moved = np.flatnonzero((tri.points != pts).any(axis=1))
    assert set(moved.tolist()) <= {1, 2, 6}  # the ones below 2**-188 * 94.1
    assert np.abs(tri.points - pts).max() <= 94.1 * 2.0**-238
    d = vf.voronoi(pts)
    validate_diagram(d, pts)


@pytest.mark.parametrize(
    "outline",
    [
        [(10, 0), (0, 10), (10, 10)],  # right triangle, axis-aligned legs: corners only
        [(0, 0), (10, 0), (0, 10)],
        [(0, 0), (10, 0), (10, 5), (10, 10), (0, 10)],  # the box with an extra edge vertex
    ],
)
def test_polygons_with_box_corner_vertices(outline, algorithm):
    """Only the full box is clipped as a rectangle; a corner-vertex triangle is a polygon."""
    dom = Polygon(outline)
    pts = general_position(60, 3) * 10.0
    d = vf.voronoi(pts, dom, algorithm=algorithm)
    assert d.areas.sum() == pytest.approx(dom.area, rel=1e-12)
    validate_diagram(d, pts, dom)


def test_cocircular_cut_cells_share_merged_centres():
    """Cut (hull) cells of a cocircular lattice use the merged centre their neighbours use.

    Sites on an integer lattice a few thousand ulps apart at UTM-like offsets: before the fix a
    hull cell kept its own clipped value of a merged circumcentre, one ulp off, and the areas
    missed the domain's by ~1e-9 relative.
    """
    rng = np.random.default_rng(1)
    for trial in range(40):
        step = 2.0 ** (-34 + int(rng.integers(12, 26)))
        pts = rng.integers(0, 8, size=(int(rng.integers(5, 40)), 2)) * step
        pts = pts + [500000.0, 4000000.0 * (trial % 2)]
        d = vf.voronoi(pts)
        assert abs(d.areas.sum() - d.boundary.area) <= 1e-12 * d.boundary.area, trial
        x0, y0, x1, y1 = d.bounds
        v = np.unique(d.to_geoarrow()[0], axis=0)
        v = v[(v[:, 0] != x0) & (v[:, 0] != x1) & (v[:, 1] != y0) & (v[:, 1] != y1)]
        close = cKDTree(v - v.mean(axis=0)).query_pairs(1e-3 * step)
        assert not close, trial  # interior vertices: one value each


# --- regressions from the QA pass of issue 4 ------------------------------------------------


def test_areas_and_centroids_are_read_only():
    # they are cached: writing into d.areas changed every later d.areas of that diagram
    pts = np.random.default_rng(0).random((30, 2))
    for d in (
        vf.voronoi(pts, (0, 0, 1, 1)),
        vf.power(pts, np.linspace(0, 0.01, 30), (0, 0, 1, 1)),
        vf.voronoi(pts, (0, 0, 1, 1), periodic=True),
    ):
        for arr in (d.areas, d.centroids):
            with pytest.raises(ValueError, match="read-only"):
                arr[0] = 5.0
