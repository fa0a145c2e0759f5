"""The 3D build's page hints and one-pass helpers give the same values as numpy (s58)."""

import numpy as np

from voroforge.config3d import SMALL_PAGES_FROM
from voroforge.engine import voronoi3d as v3
from voroforge.engine.containers import as_container
from voroforge.engine.jointable3d import rows_box
from voroforge.engine.slots3d import minus_ones, small_pages


def test_small_pages_keeps_contents_and_minus_ones_is_full():
    big = np.arange(SMALL_PAGES_FROM // 8 + 1000, dtype=np.float64)
    small = np.arange(100, dtype=np.int32)
    want_big, want_small = big.copy(), small.copy()
    small_pages(big, small, big[1:])  # (an unaligned view too)
    big[::4096] += 1.0  # still writable
    want_big[::4096] += 1.0
    assert np.array_equal(big, want_big) and np.array_equal(small, want_small)
    for size, dtype in ((7, np.int32), (SMALL_PAGES_FROM // 4 + 3, np.int32), (1 << 20, np.int64)):
        t = minus_ones(size, dtype)
        assert t.dtype == dtype and t.shape == (size,) and (t == -1).all()


def test_rows_box_is_numpys_min_and_max():
    rng = np.random.default_rng(3)
    for n in (1, 2, 17, 1000):
        P = rng.normal(size=(n, 3)) * 10.0 ** rng.integers(-8, 8, size=3)
        P[rng.random((n, 3)) < 0.2] = 0.0
        lo, hi = rows_box(P)
        assert np.array_equal(lo, P.min(axis=0)) and np.array_equal(hi, P.max(axis=0))


def test_in_box_matches_the_numpy_test():
    rng = np.random.default_rng(4)
    for _ in range(40):
        n = int(rng.integers(1, 300))
        P = rng.uniform(-1.2, 1.2, size=(n, 3)) * 10.0 ** int(rng.integers(-3, 3))
        P[: n // 4, int(rng.integers(3))] = 1.0  # on a wall, and just past it
        P[n // 4 : n // 3, 0] = np.nextafter(1.0, 2.0)
        t = as_container((-1, -1, -1, 1, 1, 1), P)
        _, scale = v3._walls_frame(P, t)
        assert np.array_equal(scale, np.abs(t.WP[:, 3]) + np.abs(P).max() + 1e-300)
        lo, hi = t.bounds
        ref = ((P >= lo - 1e-12 * scale[0::2]) & (P <= hi + 1e-12 * scale[1::2])).all(axis=1)
        assert np.array_equal(v3._in_box(P, t), ref)


def test_join_in_small_pages_is_the_same_diagram(monkeypatch):
    from voroforge.engine import slots3d

    pts = np.random.default_rng(5).random((3000, 3))
    a = v3.voronoi3d(pts, (0, 0, 0, 1, 1, 1))
    monkeypatch.setattr(slots3d, "SMALL_PAGES_FROM", 0)  # every join array in 4 KB pages
    b = v3.voronoi3d(pts, (0, 0, 0, 1, 1, 1))
    for x, y in (
        (a.volumes, b.volumes),
        (a.vertices, b.vertices),
        (a.neighbors[1], b.neighbors[1]),
        (a.faces.indices, b.faces.indices),
    ):
        assert np.array_equal(x, y)
    assert abs(float(b.volumes.sum()) - 1.0) < 1e-12 and b.unmatched_vertices == 0
