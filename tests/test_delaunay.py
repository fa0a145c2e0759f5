"""Delaunay triangulation: invariants on the degenerate catalogue and comparison with scipy."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import ConvexHull, Delaunay

import voroforge as vf
from voroforge.kernels.predicates import orient2d

from catalogue import CATALOGUE, NAMES, general_position
from reference import brute_convex_hull, brute_delaunay_ok, brute_nearest, first_occurrence
from validate import validate_triangulation


def _triples(triangles) -> set[tuple[int, ...]]:
    return {tuple(sorted(t)) for t in np.asarray(triangles).tolist()}


def _strict_hull(tri) -> set[int]:
    """Hull vertices that are corners (collinear points along hull edges dropped)."""
    h = np.asarray(tri.hull)
    p = tri.points
    out = set()
    for i in range(len(h)):
        a, b, c = p[h[i - 1]], p[h[i]], p[h[(i + 1) % len(h)]]
        if orient2d(*a, *b, *c) != 0:
            out.add(int(h[i]))
    return out


@pytest.mark.parametrize("name", NAMES, ids=NAMES)
def test_catalogue(name):
    pts, _ = CATALOGUE[name]
    validate_triangulation(vf.delaunay(pts))


@pytest.mark.parametrize("dist", ["uniform", "clustered"])
def test_random(dist):
    rng = np.random.default_rng(11)
    if dist == "uniform":
        pts = rng.random((1000, 2))
    else:
        centres = rng.random((8, 2))
        pts = centres[rng.integers(0, 8, 1000)] + rng.normal(0, 0.01, (1000, 2))
    validate_triangulation(vf.delaunay(pts))


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_matches_scipy(seed):
    pts = general_position(600, seed)
    tri = vf.delaunay(pts)
    ref = Delaunay(pts)
    assert _triples(tri.triangles) == _triples(ref.simplices)
    assert _strict_hull(tri) == set(ConvexHull(pts).vertices.tolist())


@pytest.mark.parametrize("name", ["grid_20x20", "hex_grid", "circle_integer", "clustered"])
def test_hull_vertices_match_scipy(name):
    pts, _ = CATALOGUE[name]
    tri = vf.delaunay(pts)
    assert _strict_hull(tri) == set(ConvexHull(pts).vertices.tolist())


@pytest.mark.parametrize("seed", range(4))
def test_small_exact(seed):
    """Exhaustive rational empty-circle check and hull on small inputs, cocircular ones too."""
    rng = np.random.default_rng(seed)
    pts = np.concatenate((rng.integers(0, 5, (25, 2)).astype(float), rng.random((5, 2)) * 4))
    tri = vf.delaunay(pts)
    assert brute_delaunay_ok(pts, tri.triangles)
    assert _strict_hull(tri) == brute_convex_hull(pts)
    validate_triangulation(tri)


@pytest.mark.parametrize("name", ["clustered", "grid_20x20", "duplicates", "line_plus_few"])
def test_neighbors_are_triangle_edges(name):
    pts, _ = CATALOGUE[name]
    tri = vf.delaunay(pts)
    indptr, indices = tri.neighbors
    n = len(pts)
    assert len(indptr) == n + 1
    got = set()
    for i in range(n):
        row = np.asarray(indices[indptr[i] : indptr[i + 1]]).tolist()
        assert len(set(row)) == len(row)
        got |= {(i, j) for j in row}
    want = set()
    for a, b, c in np.asarray(tri.triangles).tolist():
        want |= {(a, b), (b, a), (b, c), (c, b), (c, a), (a, c)}
    assert got == want


def test_neighbors_collinear():
    pts = np.array([[2.0, 0.0], [0.0, 0.0], [1.0, 0.0], [3.0, 0.0], [1.0, 0.0]])
    tri = vf.delaunay(pts)
    indptr, indices = tri.neighbors
    rows = [sorted(np.asarray(indices[indptr[i] : indptr[i + 1]]).tolist()) for i in range(5)]
    assert rows == [[2, 3], [2], [0, 1], [0], []]


@pytest.mark.parametrize("name", ["clustered", "grid_20x20", "duplicates", "utm_random"])
def test_find_is_nearest(name):
    pts, _ = CATALOGUE[name]
    tri = vf.delaunay(pts)
    lo, hi = pts.min(0), pts.max(0)
    span = np.maximum(hi - lo, 1e-300)
    rng = np.random.default_rng(3)
    q = lo - 0.2 * span + rng.random((3000, 2)) * 1.4 * span
    q = np.concatenate((q, pts[:50]))  # queries exactly on sites
    got = np.asarray(tri.find(q))
    assert got.shape == (len(q),)
    _, best = brute_nearest(pts, q)
    d2 = ((q - pts[got]) ** 2).sum(1)
    assert np.all(d2 <= best), "find did not return a nearest point"
    dup = first_occurrence(pts)
    assert np.all(dup[got] < 0), "find returned a duplicate instead of its first occurrence"
    one = tri.find(q[7])
    assert isinstance(one, int | np.integer) and int(one) == int(got[7])


@pytest.mark.parametrize(
    "pts",
    [
        np.zeros((0, 2)),
        np.array([[1.0, 2.0]]),
        np.array([[1.0, 2.0], [1.0, 2.0]]),
        np.array([[0.0, 0.0], [3.0, 1.0]]),
        np.array([[0.0, 0.0], [2.0, 2.0], [1.0, 1.0], [3.0, 3.0], [1.0, 1.0]]),
    ],
    ids=["zero", "one", "one_duplicated", "two", "collinear_with_duplicate"],
)
def test_degenerate_no_triangles(pts):
    tri = vf.delaunay(pts)
    assert tri.triangles.shape == (0, 3)
    assert tri.halfedges.shape == (0,)
    uniq = np.flatnonzero(first_occurrence(pts) < 0)
    assert sorted(np.asarray(tri.hull).tolist()) == uniq.tolist()
    validate_triangulation(tri)


def test_three_points_one_triangle():
    tri = vf.delaunay([[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]])  # given clockwise
    assert _triples(tri.triangles) == {(0, 1, 2)}
    assert sorted(np.asarray(tri.hull).tolist()) == [0, 1, 2]
    validate_triangulation(tri)


def test_input_not_mutated():
    pts = general_position(200, 5)
    pts[7] = pts[3]
    keep = pts.copy()
    pts.setflags(write=False)
    tri = vf.delaunay(pts)
    assert np.array_equal(pts, keep) and not pts.flags.writeable
    assert not np.shares_memory(tri.points, pts)
    as_list = keep.tolist()
    vf.delaunay(as_list)
    assert as_list == keep.tolist()


# --- the validator itself must reject broken triangulations ---------------------------------


def _rebuild_halfedges(triangles: np.ndarray) -> np.ndarray:
    t = np.asarray(triangles)
    where = {}
    for e in range(3 * len(t)):
        a = t[e // 3, e % 3]
        b = t[e // 3, (e + 1) % 3]
        where[(a, b)] = e
    return np.array(
        [where.get((t[e // 3, (e + 1) % 3], t[e // 3, e % 3]), -1) for e in range(3 * len(t))],
        dtype=np.int32,
    )


def _fake(tri, **changes):
    from types import SimpleNamespace

    fields = ("points", "triangles", "halfedges", "hull", "duplicate_of")
    base = {k: np.array(getattr(tri, k)) for k in fields}
    base.update(changes)
    return SimpleNamespace(**base)


def _flip_some_edge(tri) -> np.ndarray:
    t = np.array(tri.triangles)
    p = tri.points
    for e, f in enumerate(np.asarray(tri.halfedges).tolist()):
        if f < e:
            continue
        a, b, c = t[e // 3, e % 3], t[e // 3, (e + 1) % 3], t[e // 3, (e + 2) % 3]
        d = t[f // 3, (f + 2) % 3]
        if orient2d(*p[a], *p[d], *p[c]) > 0 and orient2d(*p[d], *p[b], *p[c]) > 0:
            t[e // 3] = (a, d, c)
            t[f // 3] = (d, b, c)
            return t
    raise AssertionError("no flippable edge")


def test_validator_rejects_broken_triangulations():
    tri = vf.delaunay(general_position(60, 4))
    validate_triangulation(tri)
    flipped = _flip_some_edge(tri)
    t = np.array(tri.triangles)
    cw = t.copy()
    cw[0] = cw[0, ::-1]
    he = np.array(tri.halfedges)
    inner = np.flatnonzero(he >= 0)
    swapped = he.copy()
    swapped[inner[0]], swapped[inner[1]] = swapped[inner[1]], swapped[inner[0]]
    broken = {
        "not_delaunay": {"triangles": flipped, "halfedges": _rebuild_halfedges(flipped)},
        "clockwise": {"triangles": cw, "halfedges": _rebuild_halfedges(cw)},
        "halfedges": {"halfedges": swapped},
        "hull_reversed": {"hull": np.array(tri.hull)[::-1].copy()},
        "hull_short": {"hull": np.array(tri.hull)[:-1].copy()},
        "missing_triangle": {"triangles": t[1:], "halfedges": _rebuild_halfedges(t[1:])},
        "duplicate_of": {"duplicate_of": np.r_[0, np.full(59, -1)]},
    }
    for name, change in broken.items():
        with pytest.raises(AssertionError):
            validate_triangulation(_fake(tri, **change))
            print(name)  # reached only when the validator missed the breakage


def test_large_uses_neighbourhood_empty_circle_check():
    """Above EXHAUSTIVE_MAX points the empty-circle check goes through a KD-tree."""
    validate_triangulation(vf.delaunay(general_position(3000, 8)))


def test_neighbourhood_check_rejects_non_delaunay(monkeypatch):
    import validate

    monkeypatch.setattr(validate, "EXHAUSTIVE_MAX", 10)
    tri = vf.delaunay(general_position(60, 4))
    validate_triangulation(tri)
    flipped = _flip_some_edge(tri)
    fake = _fake(tri, triangles=flipped, halfedges=_rebuild_halfedges(flipped))
    with pytest.raises(AssertionError, match="circumcircle"):
        validate_triangulation(fake)


# --- the exact repair pass after the filtered sweep ------------------------------------------


def _scramble(tri, rng, flips: int) -> np.ndarray:
    """Apply random valid (convex-quad) flips: a valid, far from Delaunay triangulation."""
    t = np.array(tri.triangles)
    p = tri.points
    for _ in range(flips):
        he = _rebuild_halfedges(t)
        inner = np.flatnonzero(he > np.arange(len(he)))
        for e in rng.permutation(inner).tolist():
            f = int(he[e])
            a, b, c = t[e // 3, e % 3], t[e // 3, (e + 1) % 3], t[e // 3, (e + 2) % 3]
            d = t[f // 3, (f + 2) % 3]
            if orient2d(*p[a], *p[d], *p[c]) > 0 and orient2d(*p[d], *p[b], *p[c]) > 0:
                t[e // 3] = (a, d, c)
                t[f // 3] = (d, b, c)
                break
    return t


@pytest.mark.parametrize("name", ["grid_shuffled", "circle_integer", "utm_grid", "general"])
def test_repair_reaches_delaunay_from_any_triangulation(name):
    """``_repair`` (exact Lawson flips from the suspect edges) fixes whatever the sweep left."""
    from voroforge.kernels.delaunay import _repair, _suspect_edges

    pts = general_position(80, 11) if name == "general" else CATALOGUE[name][0]
    pts = np.asarray(pts, dtype=np.float64)[first_occurrence(pts) < 0]
    tri = vf.delaunay(pts)
    scrambled = _scramble(tri, np.random.default_rng(5), flips=2 * len(pts))
    flat = scrambled.ravel().astype(np.int32)
    he = _rebuild_halfedges(scrambled)
    # strided writable views, the array types the engine passes (no second compilation)
    xy = np.array(tri.points)
    xs, ys = xy[:, 0], xy[:, 1]
    suspects = _suspect_edges(xs, ys, flat, he, len(flat))
    assert len(suspects) > 0  # the scramble broke local Delaunayness somewhere
    with pytest.raises(AssertionError, match="circumcircle"):
        validate_triangulation(_fake(tri, triangles=scrambled, halfedges=he))
    hull_tri = np.full(len(pts), -1, dtype=np.int32)
    assert _repair(xs, ys, flat, he, hull_tri, suspects) > 0
    validate_triangulation(_fake(tri, triangles=flat.reshape(-1, 3), halfedges=he))
