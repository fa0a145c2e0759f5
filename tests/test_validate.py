"""validate.py catches what it claims to: each check fails on a result broken in that one way."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

import voroforge as vf

import validate
from validate import check_circumcentres, orient_signs, validate_diagram, validate_triangulation

FIELDS_TRI = ("points", "triangles", "halfedges", "hull", "duplicate_of", "circumcenters")
FIELDS_DIAGRAM = (
    "sites",
    "boundary",
    "cells",
    "duplicate_of",
    "areas",
    "centroids",
    "neighbors",
    "edges",
)


def _copy(obj, fields, **changes):
    base = {k: getattr(obj, k) for k in fields}
    base.update(changes)
    return SimpleNamespace(**base)


def test_orient_signs_are_exact_near_collinear():
    a = np.array([[0.5, 0.5]] * 3)
    b = np.array([[12.0, 12.0]] * 3)
    # 24.0 and the doubles either side of it: collinear, left, right
    c = np.array([[24.0, 24.0], [24.0, np.nextafter(24.0, 25)], [24.0, np.nextafter(24.0, 23)]])
    assert orient_signs(a, b, c).tolist() == [0, 1, -1]


@pytest.mark.parametrize("exhaustive", [True, False])
def test_a_wrong_circumcentre_is_caught(monkeypatch, exhaustive):
    if not exhaustive:
        monkeypatch.setattr(validate, "EXHAUSTIVE_MAX", 5)  # the float screen, then exact
    pts = np.random.default_rng(0).random((40, 2))
    tri = vf.delaunay(pts)
    validate_triangulation(tri)
    cc = np.array(tri.circumcenters)
    radius = np.hypot(*(cc[7] - pts[tri.triangles[7, 0]]))
    for delta in (1e-6 * radius, 1e3 * radius):
        wrong = cc.copy()
        wrong[7, 1] += delta
        with pytest.raises(AssertionError, match="circumcentres off"):
            validate_triangulation(_copy(tri, FIELDS_TRI, circumcenters=wrong))
    nan = cc.copy()
    nan[3] = np.nan  # a NaN is never within tolerance
    with pytest.raises(AssertionError, match="circumcentres off"):
        check_circumcentres(pts, np.asarray(tri.triangles, dtype=np.int64), nan)


def test_a_sliver_gets_a_wide_but_finite_tolerance():
    pts = np.array([[0.0, 0.0], [1.0, 0.0], [0.5, 1e-9]])
    tri = np.array([[0, 1, 2]])
    tol = validate._circumcentre_tol(pts, tri)
    assert np.isfinite(tol).all() and tol[0] > 1e-9
    centre = np.array([[0.5, 0.5e-9 - 0.125e9]])  # the exact centre, a long way below
    check_circumcentres(pts, tri, centre)
    with pytest.raises(AssertionError):
        check_circumcentres(pts, tri, centre + [0.0, 1e3 * tol[0]])


def test_an_edge_end_slid_along_its_bisector_is_caught():
    pts = np.random.default_rng(1).random((30, 2)) * 0.8 + 0.1
    d = vf.voronoi(pts, (0, 0, 1, 1))
    validate_diagram(d, pts)
    coords = np.array(d.edges.coords)
    pairs = np.asarray(d.edges.pairs)
    ends = coords.reshape(-1, 2)
    inner = np.flatnonzero((ends.min(1) > 1e-6) & (ends.max(1) < 1 - 1e-6))
    k = int(inner[0]) // 2  # an edge with an end inside the box
    along = coords[k, 1] - coords[k, 0]
    coords[k] += 0.05 * along  # both ends move along the bisector: still on it
    broken = _copy(d, FIELDS_DIAGRAM, edges=(coords, pairs))
    with pytest.raises(AssertionError, match="Voronoi vertices"):
        validate_diagram(broken, pts)


def test_a_diagram_without_edges_is_not_passed():
    pts = np.random.default_rng(2).random((10, 2))
    d = vf.voronoi(pts, (0, 0, 1, 1))
    no_edges = _copy(
        d,
        FIELDS_DIAGRAM,
        edges=(np.zeros((0, 2, 2)), np.zeros((0, 2), dtype=np.int64)),
        neighbors=(np.zeros(11, dtype=np.int64), np.zeros(0, dtype=np.int64)),
    )
    with pytest.raises(AssertionError, match="not neighbours"):
        validate_diagram(no_edges, pts)
