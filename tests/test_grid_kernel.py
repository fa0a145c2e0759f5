"""The bucket grid kernel on its own: counting sort, ring search, stop test.

Checked against brute force on random and clustered sites: the sort is a permutation that
puts every site in the bucket containing it, the rings tile the block of buckets around a
bucket (each bucket once), and the stop test never stops a search while an unscanned bucket
could hold a site nearer than the bound.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from voroforge.kernels.grid import (
    adaptive_grid,
    block_box,
    box_dist2,
    bucket_of,
    bucket_sort,
    counting_sort,
    grid_shape,
    heap_pop,
    heap_push,
    kd_buckets,
    outside_dist2,
    rect_dist2,
    ring_gap,
    ring_row,
    ring_rows,
    skip_lists,
)


def _sites(kind, n, seed):
    rng = np.random.default_rng(seed)
    if kind == "uniform":
        p = rng.random((n, 2))
    elif kind == "clustered":
        p = rng.random((4, 2))[rng.integers(0, 4, n)] + rng.normal(0, 0.002, (n, 2))
    elif kind == "strip":
        p = np.column_stack((rng.random(n) * 7.0, rng.random(n) * 0.01))
    elif kind == "line":
        p = np.column_stack((rng.random(n), np.full(n, 0.5)))
    else:  # all sites in one point
        p = np.full((n, 2), 3.0)
    return p[:, 0].copy(), p[:, 1].copy()


def _bucket_xy(x, y, grid):
    x0, y0, hx, hy, nx, ny = grid
    return bucket_of(x, x0, hx, nx), bucket_of(y, y0, hy, ny)


def _ring(ci, cj, r, nx, ny):
    """Buckets of ring ``r`` as the kernel enumerates them."""
    out = []
    j0, j1 = ring_rows(cj, r, ny)
    for j in range(j0, j1 + 1):
        i0, i1, step = ring_row(ci, cj, r, j, nx)
        out.extend((i, j) for i in range(i0, i1 + 1, step))
    return out


def test_halfplane_grid_and_bucket_sort():
    """Every site lands in the bucket that contains it; the CSR covers all sites once."""
    rng = np.random.default_rng(5)
    xs, ys = rng.random(1000) * 7.0, rng.random(1000) * 0.01  # a flat strip
    grid = grid_shape(xs, ys, 2.0)
    x0, y0, hx, hy, nx, ny = grid
    start, sx, sy, sidx = bucket_sort(xs, ys, grid)
    assert start[0] == 0 and start[-1] == 1000 and np.all(np.diff(start) >= 0)
    assert sorted(sidx.tolist()) == list(range(1000))
    assert np.array_equal(sx, xs[sidx]) and np.array_equal(sy, ys[sidx])
    for b in range(nx * ny):
        ix, iy = b % nx, b // nx
        for t in range(start[b], start[b + 1]):
            assert x0 + ix * hx <= sx[t] <= x0 + (ix + 1) * hx * (1 + 1e-12)
            assert y0 + iy * hy <= sy[t] <= y0 + (iy + 1) * hy * (1 + 1e-12)


def test_halfplane_grid_refines_for_clusters():
    """Clustered sites get finer buckets (the half-plane kernel's 2 per bucket, refine <= 32)."""
    rng = np.random.default_rng(9)
    uniform = rng.random((4000, 2))
    blobs = rng.random((4, 2))[rng.integers(0, 4, 4000)] + rng.normal(0, 0.002, (4000, 2))
    (_, _, _, _, ux, uy), _ = adaptive_grid(uniform[:, 0].copy(), uniform[:, 1].copy(), 2.0, 32.0)
    bx, by = blobs[:, 0].copy(), blobs[:, 1].copy()
    (_, _, _, _, cx, cy), (start, *_) = adaptive_grid(bx, by, 2.0, 32.0)
    assert ux * uy <= 2000
    assert cx * cy >= 8 * ux * uy

    def median_occupancy(start):
        occ = np.diff(start)
        return np.median(np.repeat(occ, occ))

    coarse = bucket_sort(bx, by, grid_shape(bx, by, 2.0))[0]
    assert median_occupancy(start) <= median_occupancy(coarse) / 4


@pytest.mark.parametrize("kind", ["uniform", "clustered", "strip", "line", "point"])
@pytest.mark.parametrize("per_bucket", [0.25, 2.0, 10.0])
def test_bucket_sort_is_a_permutation_into_containing_buckets(kind, per_bucket):
    xs, ys = _sites(kind, 700, 1)
    grid = grid_shape(xs, ys, per_bucket)
    x0, y0, hx, hy, nx, ny = grid
    assert nx >= 1 and ny >= 1 and hx > 0.0 and hy > 0.0
    assert nx * ny <= max(1.0, 700 / per_bucket)
    start, sx, sy, sidx = bucket_sort(xs, ys, grid)
    assert start[0] == 0 and start[-1] == len(xs) and np.all(np.diff(start) >= 0)
    assert np.array_equal(np.sort(sidx), np.arange(len(xs)))
    assert np.array_equal(sx, xs[sidx]) and np.array_equal(sy, ys[sidx])
    # the grid covers the sites without clamping
    assert np.all((xs - x0) / hx < nx) and np.all((ys - y0) / hy < ny)
    for b in range(nx * ny):
        members = sidx[start[b] : start[b + 1]]
        assert np.all(np.diff(members) > 0), "stable: increasing index within a bucket"
        for i in members:
            assert _bucket_xy(xs[i], ys[i], grid) == (b % nx, b // nx)


@given(st.lists(st.integers(0, 9), max_size=200), st.integers(10, 14))
def test_counting_sort_is_stable_argsort(keys, nb):
    key = np.array(keys, dtype=np.int64)
    start, order = counting_sort(key, nb)
    assert np.array_equal(order, np.argsort(key, kind="stable"))
    assert np.array_equal(start, np.searchsorted(np.sort(key), np.arange(nb + 1)))


def test_bucket_of_clamps():
    assert bucket_of(-5.0, 0.0, 1.0, 4) == 0
    assert bucket_of(np.nan, 0.0, 1.0, 4) == 0
    assert bucket_of(3.5, 0.0, 1.0, 4) == 3
    assert bucket_of(1e300, 0.0, 1e-300, 4) == 3
    assert bucket_of(2.0, 0.0, 1.0, 4) == 2


@given(st.integers(1, 9), st.integers(1, 9), st.data())
@settings(max_examples=150)
def test_rings_visit_every_bucket_once(nx, ny, data):
    """Rings 0..R around a bucket tile the (clipped) block within Chebyshev distance R."""
    ci = data.draw(st.integers(0, nx - 1))
    cj = data.draw(st.integers(0, ny - 1))
    radius = data.draw(st.integers(0, 12))
    seen = []
    for r in range(radius + 1):
        ring = _ring(ci, cj, r, nx, ny)
        assert all(max(abs(i - ci), abs(j - cj)) == r for i, j in ring)
        seen.extend(ring)
    want = [(i, j) for i in range(nx) for j in range(ny) if max(abs(i - ci), abs(j - cj)) <= radius]
    assert len(seen) == len(set(seen)), "a bucket visited twice"
    assert set(seen) == set(want)


def test_skip_lists():
    rng = np.random.default_rng(3)
    nx, ny = 7, 5
    occ = rng.integers(0, 3, (ny, nx)) * (rng.random((ny, nx)) < 0.4)
    start = np.concatenate(([0], np.cumsum(occ.ravel())))
    rownext, bnext = skip_lists(start, nx, ny)
    for j in range(ny + 1):
        rows = [r for r in range(j, ny) if occ[r].sum() > 0]
        assert rownext[j] == (rows[0] if rows else ny)
    for j in range(ny):
        for i in range(nx + 1):
            cols = [c for c in range(i, nx) if occ[j, c] > 0]
            assert bnext[j * (nx + 1) + i] == (cols[0] if cols else nx)


def _buckets(xs, ys, grid):
    """Each site's bucket ``(i, j)``, one ``bucket_of`` per coordinate, as an (n, 2) array."""
    return np.array([_bucket_xy(x, y, grid) for x, y in zip(xs, ys, strict=True)], np.int64)


def _unscanned(buckets, ci, cj, r):
    """Indices of the sites outside the block of rings 0..r (brute force over all sites)."""
    ring = np.maximum(np.abs(buckets[:, 0] - ci), np.abs(buckets[:, 1] - cj))
    return np.flatnonzero(ring > r)


@pytest.mark.parametrize("kind", ["uniform", "clustered", "strip"])
def test_stop_test_is_a_lower_bound(kind):
    """ring_gap and outside_dist2 never exceed the distance to any unscanned site."""
    xs, ys = _sites(kind, 400, 2)
    grid = grid_shape(xs, ys, 2.0)
    x0, y0, hx, hy, nx, ny = grid
    scale = max(np.abs(xs).max(), np.abs(ys).max())
    eps = 1e-12 * scale  # bucket_of rounds at bucket boundaries
    buckets = _buckets(xs, ys, grid)  # the sites' buckets, found once for every query
    rng = np.random.default_rng(4)
    for _ in range(60):
        q = rng.integers(0, len(xs))
        qx, qy = xs[q], ys[q]
        ci, cj = _bucket_xy(qx, qy, grid)
        # a small rectangle around the site, inside its bucket's block
        w = rng.random() * 0.5 * min(hx, hy)
        rect = (qx - w, qx + w, qy - w, qy + w)
        for r in range(0, max(nx, ny) + 1):
            rest = _unscanned(buckets, ci, cj, r)
            gap = ring_gap(qx, qx, qy, qy, ci, cj, r, grid)
            block = block_box(ci, cj, r, grid)
            if len(rest) == 0:
                continue
            assert gap < np.inf, "the block does not cover the grid: something is left"
            d2 = (xs[rest] - qx) ** 2 + (ys[rest] - qy) ** 2
            assert gap <= np.sqrt(d2.min()) + eps
            # any point, even outside the grid or the block
            for px, py in ((qx, qy), (x0 - 1.0, y0 + 0.3), (qx + 2 * hx, qy - 3 * hy)):
                e2 = (xs[rest] - px) ** 2 + (ys[rest] - py) ** 2
                assert np.sqrt(outside_dist2(px, py, block, grid)) <= np.sqrt(e2.min()) + eps
            rgap = ring_gap(*rect, ci, cj, r, grid)
            if rgap >= 0.0:
                dx = np.maximum.reduce([rect[0] - xs[rest], xs[rest] - rect[1], 0 * xs[rest]])
                dy = np.maximum.reduce([rect[2] - ys[rest], ys[rest] - rect[3], 0 * ys[rest]])
                assert rgap <= np.sqrt((dx * dx + dy * dy).min()) + eps


@pytest.mark.parametrize("kind", ["uniform", "clustered", "strip", "line"])
def test_ring_search_finds_the_nearest_site(kind):
    """Nearest site by ring search with the stop test equals brute force."""
    xs, ys = _sites(kind, 500, 6)
    grid = grid_shape(xs, ys, 2.0)
    start, sx, sy, sidx = bucket_sort(xs, ys, grid)
    x0, y0, hx, hy, nx, ny = grid
    rng = np.random.default_rng(7)
    lo = np.array([xs.min(), ys.min()]) - 0.2
    hi = np.array([xs.max(), ys.max()]) + 0.2
    for q in lo + (hi - lo) * rng.random((200, 2)):
        ci, cj = _bucket_xy(q[0], q[1], grid)
        best = np.inf
        r = 0
        while True:
            for i, j in _ring(ci, cj, r, nx, ny):
                b = j * nx + i
                d = (sx[start[b] : start[b + 1]] - q[0]) ** 2 + (
                    sy[start[b] : start[b + 1]] - q[1]
                ) ** 2
                if len(d):
                    best = min(best, d.min())
            # the query may lie outside the grid: the exact point test then decides
            block = block_box(ci, cj, r, grid)
            if outside_dist2(q[0], q[1], block, grid) > best:
                break
            r += 1
        brute = ((xs - q[0]) ** 2 + (ys - q[1]) ** 2).min()
        assert best == brute


def test_rect_dist2():
    assert rect_dist2(0.5, 0.5, 0.0, 0.0, 1.0, 1.0) == 0.0
    assert rect_dist2(2.0, 3.0, 0.0, 0.0, 1.0, 1.0) == 1.0 + 4.0
    assert rect_dist2(0.0, 0.0, 1.0, 1.0, 1.0, 2.0) == np.inf  # empty


@pytest.mark.parametrize("kind", ["uniform", "clustered", "line", "dups_x"])
def test_kd_buckets_partition_and_boxes(kind):
    """k-d buckets: a permutation; nested ranges; tight boxes; at most ``leaf`` per bucket."""
    g = np.random.default_rng(4)
    n = 777
    if kind == "uniform":
        xs, ys = g.random(n), g.random(n)
    elif kind == "clustered":
        xs, ys = (g.normal(0.0, 1e-3, (2, n)) + g.integers(0, 3, n) * 5.0).astype(float)
    elif kind == "line":
        xs, ys = np.linspace(0.0, 1.0, n), np.zeros(n)
    else:  # many equal x: the median split must still halve
        xs, ys = np.round(g.random(n) * 3), g.random(n)
    (lo, hi, left, boxes), (sx, sy, sidx) = kd_buckets(xs, ys, 8)
    assert sorted(sidx.tolist()) == list(range(n))
    assert np.array_equal(sx, xs[sidx]) and np.array_equal(sy, ys[sidx])
    assert lo[0] == 0 and hi[0] == n
    for v in range(len(lo)):
        s = slice(lo[v], hi[v])
        assert boxes[v].tolist() == [sx[s].min(), sy[s].min(), sx[s].max(), sy[s].max()]
        if left[v] < 0:
            assert 1 <= hi[v] - lo[v] <= 8
        else:
            c = left[v]
            assert (lo[c], hi[c], lo[c + 1], hi[c + 1]) == (lo[v], lo[c + 1], hi[c], hi[v])
            assert abs((hi[c] - lo[c]) - (hi[c + 1] - lo[c + 1])) <= 1


@given(st.lists(st.floats(-1e6, 1e6), min_size=1, max_size=60))
def test_heap_pops_in_order(keys):
    hk = np.zeros(64)
    hv = np.zeros(64, np.int64)
    size = 0
    for i, k in enumerate(keys):
        size = heap_push(hk, hv, size, k, i)
    out = []
    while size:
        k, v, size = heap_pop(hk, hv, size)
        assert keys[v] == k
        out.append(k)
    assert out == sorted(keys)


def test_box_dist2_flat_boxes():
    """Flat and point boxes (a k-d bucket of collinear sites) are boxes, not empty."""
    boxes = np.array([[0.0, 0.0, 1.0, 0.0], [2.0, 3.0, 2.0, 3.0], [0.0, 0.0, 1.0, 1.0]])
    assert box_dist2(0.5, 2.0, boxes, 0) == 4.0
    assert box_dist2(0.5, -1.0, boxes, 0) == 1.0
    assert box_dist2(2.0, 0.0, boxes, 1) == 9.0
    assert box_dist2(0.5, 0.5, boxes, 2) == 0.0
