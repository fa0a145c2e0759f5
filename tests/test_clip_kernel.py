"""The one convex cut (kernels/clip) tested on the kernel directly."""

from __future__ import annotations

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from voroforge.kernels.clip import crossing, cut_ring, dedupe_ring, plane_values


def _cut(ring, normal, origin, h, label=99, owners=None):
    """Cut an open ring (m, 2) by ``normal . (x - origin) <= h``; returns (xy, owners)."""
    m = len(ring)
    px = np.ascontiguousarray(ring[:, 0], dtype=np.float64)
    py = np.ascontiguousarray(ring[:, 1], dtype=np.float64)
    po = np.arange(m, dtype=np.int64) if owners is None else np.asarray(owners, dtype=np.int64)
    ss = np.zeros(m)
    plane_values(px, py, 0, m, normal[0], normal[1], origin[0], origin[1], h, ss)
    qx = np.zeros(m + 1)
    qy = np.zeros(m + 1)
    qo = np.zeros(m + 1, dtype=np.int64)
    k = cut_ring(px, py, po, 0, m, ss, qx, qy, qo, 0, label)
    return np.column_stack((qx[:k], qy[:k])), qo[:k]


def _halfplane(normal, origin, h, big=1e3):
    """A large polygon for ``normal . (x - origin) <= h`` (for shapely)."""
    n = np.asarray(normal, dtype=float)
    n = n / np.hypot(*n)
    t = np.array([-n[1], n[0]])
    p0 = np.asarray(origin) + n * h / np.hypot(*normal)
    return shapely.Polygon(
        [p0 + big * t, p0 - big * t, p0 - big * t - big * n, p0 + big * t - big * n]
    )


def test_cut_matches_shapely_on_random_convex_rings():
    rng = np.random.default_rng(0)
    for _ in range(300):
        hull = shapely.MultiPoint(rng.random((rng.integers(3, 12), 2))).convex_hull
        if hull.geom_type != "Polygon":
            continue
        ring = np.asarray(shapely.orient_polygons(hull).exterior.coords)[:-1]
        normal = rng.normal(size=2)
        origin = rng.random(2)
        h = float(rng.normal() * 0.2)
        xy, _ = _cut(ring, normal, origin, h)
        want = hull.intersection(_halfplane(normal, origin, h))
        got = shapely.Polygon(xy) if len(xy) >= 3 else shapely.Polygon()
        assert abs(got.area - want.area) <= 1e-12
        if len(xy) >= 3:
            assert got.is_valid
            assert got.symmetric_difference(want).area <= 1e-12


def test_vertex_on_the_line_is_kept_exactly_and_starts_the_new_edge():
    ring = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    # the line x = 1 - y through (1, 0) and (0, 1): keep x + y <= 1
    xy, own = _cut(ring, (1.0, 1.0), (0.0, 0.0), 1.0, label=7)
    assert [tuple(p) for p in xy] == [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)]
    # edge 0 -> 1 keeps its owner, the edge along the line is the label's, then the old one
    assert own.tolist() == [0, 7, 3]


def test_owners_are_carried_through_a_cut():
    ring = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]])
    xy, own = _cut(ring, (1.0, 0.0), (0.0, 0.0), 1.0, label=5, owners=[10, 11, 12, 13])
    assert [tuple(p) for p in xy] == [(0.0, 0.0), (1.0, 0.0), (1.0, 2.0), (0.0, 2.0)]
    assert own.tolist() == [10, 5, 12, 13]


def test_nothing_left_and_nothing_cut():
    ring = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
    xy, _ = _cut(ring, (1.0, 0.0), (0.0, 0.0), -1.0)
    assert len(xy) == 0
    xy, own = _cut(ring, (1.0, 0.0), (0.0, 0.0), 5.0)
    assert np.array_equal(xy, ring) and own.tolist() == [0, 1, 2]


fl = st.floats(-1e6, 1e6, allow_nan=False, allow_infinity=False)
val = st.floats(1e-300, 1e6, allow_nan=False, allow_infinity=False)


@settings(max_examples=300, deadline=None)
@given(fl, fl, fl, fl, val, val)
def test_crossing_stays_inside_the_segments_box(ax, ay, bx, by, sa, sb):
    x, y = crossing(ax, ay, -sa, bx, by, sb)
    assert min(ax, bx) <= x <= max(ax, bx)
    assert min(ay, by) <= y <= max(ay, by)
    x, y = crossing(ax, ay, sa, bx, by, -sb)
    assert min(ax, bx) <= x <= max(ax, bx)
    assert min(ay, by) <= y <= max(ay, by)


def test_corner_spike_case():
    # a line through a box corner to rounding: the crossing next to the corner must not
    # round past it (interpolated from the nearer endpoint), so the ring stays simple
    rng = np.random.default_rng(1)
    box = np.array([[0.1, 0.3], [0.7, 0.3], [0.7, 0.9], [0.1, 0.9]])
    for _ in range(500):
        corner = box[rng.integers(4)]
        angle = rng.random() * np.pi
        normal = np.array([np.cos(angle), np.sin(angle)])
        eps = rng.normal() * 1e-16
        xy, _ = _cut(box, normal, corner, eps)
        if len(xy) < 3:
            continue
        assert (xy[:, 0] >= 0.1).all() and (xy[:, 0] <= 0.7).all()
        assert (xy[:, 1] >= 0.3).all() and (xy[:, 1] <= 0.9).all()
        poly = shapely.Polygon(xy)
        assert poly.is_valid or poly.area == 0.0


def test_dedupe_ring_drops_repeats_and_keeps_the_later_owner():
    qx = np.array([0.0, 1.0, 1.0, 1.0, 0.0, 0.0])
    qy = np.array([0.0, 0.0, 0.0, 1.0, 1.0, 0.0])
    qo = np.array([1, 2, 3, 4, 5, 6], dtype=np.int64)
    m = dedupe_ring(qx, qy, qo, 6)
    assert m == 4
    assert list(zip(qx[:m], qy[:m], strict=True)) == [
        (0.0, 0.0),
        (1.0, 0.0),
        (1.0, 1.0),
        (0.0, 1.0),
    ]
    assert qo[:m].tolist() == [1, 3, 4, 5]
    assert dedupe_ring(np.zeros(3), np.zeros(3), np.zeros(3, dtype=np.int64), 3) == 0
