"""Issue 15: power cells far from the origin share every vertex bit for bit and tile the box.

Each power cell is the box cut by its own site's bisectors, in floats. Its vertices were
replaced by the ones computed from their names (the sorted owner triple, or a bisector and
a box side) only when the name lay within 1e-9 of the box's size of the cut: far from the
origin an ulp is larger than that, so the cut vertices stayed and neighbouring cells held
one vertex in different bits (``describe()``: Euler failed on ``lattice_offset_*`` and the
far float circles with random weights). Where four or more cells meet within rounding
(a lattice, a float circle's centre) neighbours also disagreed on which tiny edges exist.
Now every vertex is its name, and the rings are reconciled across neighbours
(``kernels.power._reconcile``).
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely

import voroforge as vf

from catalogue import CATALOGUE, FAR_CIRCLES

OFFSETS = [1e6, 1e9, 1e12, 1e15]


def _lattice(off, k=5, step=1.0):
    x, y = np.meshgrid(np.arange(k) * step, np.arange(k) * step)
    return np.column_stack((x.ravel(), y.ravel())) + off


def _random_sites(off, seed, n=60, size=10.0):
    return np.random.default_rng(seed).random((n, 2)) * size + off


def _weights(kind, pts, seed, spacing=1.0):
    if kind == "equal":
        return np.full(len(pts), 0.25)
    return np.random.default_rng(seed + 100).random(len(pts)) * 0.5 * spacing * spacing


def _box_of(pts, pad=0.5):
    lo = pts.min(0) - pad
    hi = pts.max(0) + pad
    return (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))


def _power_nearest_ok(d, pts, w, box, samples=300, seed=0):
    """Every sample point lies in a cell whose power distance is smallest, up to rounding.

    The slow reference: every site's ``|x - p|^2 - w`` at each sample (differences taken
    first, so far from the origin only the coordinates' own rounding counts). A sample in
    cell ``i`` may beat ``i`` by what moving a bisector by the vertices' rounding changes:
    ``2 delta |p_i - p_k|`` with ``delta`` 64 ulps of the coordinates.
    """
    g = np.random.default_rng(seed)
    x0, y0, x1, y1 = box
    q = np.column_stack((x0 + g.random(samples) * (x1 - x0), y0 + g.random(samples) * (y1 - y0)))
    diff = q[:, None, :] - pts[None, :, :]
    pd = (diff**2).sum(-1) - w[None, :]
    cells = np.asarray(d.cells, dtype=object)
    best = pd.min(axis=1)
    covered = np.zeros(samples, dtype=bool)
    delta = 64 * np.finfo(float).eps * np.abs(q).max()
    for i, c in enumerate(cells):
        if c is None or shapely.is_empty(c):
            continue
        rows = np.flatnonzero(shapely.intersects_xy(c, q[:, 0], q[:, 1]))
        covered[rows] = True
        gap = np.linalg.norm(pts - pts[i], axis=1)
        slack = 2 * delta * gap + 64 * np.finfo(float).eps * (np.abs(pd[rows]) + np.abs(w).max())
        # no site is nearer in power than i's, beyond what rounding the bisectors changes
        assert np.all(pd[rows, i][:, None] <= pd[rows] + slack), f"a sample of cell {i}"
        assert np.all(pd[rows, i] >= best[rows])
    assert covered.all(), "samples in no cell: a gap"


def _shared_bits(d):
    """Each vertex where three or more cells meet is in every one of them, in the same bits.

    A point that one cell holds inside the box must be held by at least two cells: else
    a neighbour has the vertex in other bits (or lacks it: a T-junction or a gap).
    """
    coords, (ring, poly, geom) = d.to_geoarrow()
    box = d.boundary.bounds
    cell_of_ring = (
        np.searchsorted(geom, np.searchsorted(poly, np.arange(len(ring) - 1), "right") - 1, "right")
        - 1
    )
    seen: dict[tuple[float, float], set[int]] = {}
    for r in range(len(ring) - 1):
        for k in range(ring[r], ring[r + 1] - 1):
            seen.setdefault((coords[k, 0], coords[k, 1]), set()).add(int(cell_of_ring[r]))
    for (x, y), cells in seen.items():
        on_side = x in (box[0], box[2]) or y in (box[1], box[3])
        assert on_side or len(cells) >= 3, f"vertex {(x, y)!r} only in cells {sorted(cells)}"
        assert len(cells) >= 1


def _check(d, pts, w, box):
    r = d.describe()
    assert r.euler_ok and r.convex_ok, str(r)
    assert r.mismatched_vertices == 0, str(r)
    _shared_bits(d)
    area = (box[2] - box[0]) * (box[3] - box[1])
    assert abs(d.areas.sum() - area) <= 1e-9 * area
    _power_nearest_ok(d, pts, w, box)


@pytest.mark.parametrize("off", OFFSETS)
@pytest.mark.parametrize("weights", ["equal", "random"])
@pytest.mark.parametrize("seed", [0, 1])
def test_lattice_far_away(off, weights, seed):
    pts = _lattice(off)
    w = _weights(weights, pts, seed)
    box = _box_of(pts)
    _check(vf.power(pts, w, box), pts, w, box)


@pytest.mark.parametrize("off", OFFSETS)
@pytest.mark.parametrize("weights", ["equal", "random"])
@pytest.mark.parametrize("seed", [0, 1])
def test_random_sites_far_away(off, weights, seed):
    # 60 sites about 1 apart, in a square 10 wide, or 1e-12 of the offset where that is more
    # (at 1e15: sites about 100 ulps apart; closer ones are the Voronoi engine's limit)
    size = max(10.0, 1e-12 * off)
    pts = _random_sites(off, seed, size=size)
    w = _weights(weights, pts, seed, spacing=size / 10)
    box = _box_of(pts, pad=0.05 * size)
    _check(vf.power(pts, w, box), pts, w, box)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_random_weights_on_sites_an_ulp_apart(seed):
    # 60 sites in a square 10 wide at 1e15 fall on the 1/8 grid there (an ulp): many are 1-2
    # ulps apart and many quadruples exactly cocircular; random weights split the vertices
    pts = _random_sites(1e15, seed)
    w = _weights("random", pts, seed)
    box = _box_of(pts)
    _check(vf.power(pts, w, box), pts, w, box)


@pytest.mark.parametrize("off", [0.0, 1e6, 1e15])
@pytest.mark.parametrize("shift", [(0.25, 0.125), (-0.375, 0.0)])
def test_linear_weights_give_exact_shifted_squares(off, shift):
    # w_p = -2 t.(p - p0) gives the Voronoi cells of the sites moved by t: here squares whose
    # corners are float64 numbers at every offset (multiples of 1/8; an ulp of 1e15 is 1/8),
    # so each cell must be its square exactly
    pts = _lattice(off, k=4)
    t = np.array(shift)
    w = -2.0 * ((pts - off) @ t)
    box = (off - 1.0, off - 1.0, off + 4.0, off + 4.0)
    d = vf.power(pts, w, box)
    first = pts.min(0)
    last = pts.max(0)
    for i, p in enumerate(pts):
        # the square of side 1 round p + t, out to the box for the lattice's outer rows
        lo = np.where(p == first, box[:2], p + t - 0.5)
        hi = np.where(p == last, box[2:], p + t + 0.5)
        want = shapely.box(*lo, *hi)
        got = d.cells[i]
        assert shapely.equals_exact(shapely.normalize(got), shapely.normalize(want), 0.0), (i, got)
    _check(d, pts, w, box)


@pytest.mark.parametrize(
    "name", ["lattice_offset_1e+15", "lattice_offset_5e+13", "lattice_offset_none"]
)
@pytest.mark.parametrize("scale", [0.01, 0.1, 1.0])
def test_catalogue_lattices_with_random_weights(name, scale):
    pts, boundary = CATALOGUE[name]
    pts = np.asarray(pts, dtype=np.float64)
    w = np.random.default_rng(0).random(len(pts)) * scale
    d = vf.power(pts, w, boundary)
    box = d.boundary.bounds
    _check(d, pts, w, box)


@pytest.mark.parametrize("name", [n for n in FAR_CIRCLES if "r0.001" in n][:2])
@pytest.mark.parametrize("scale", [0.01, 1.0])
def test_far_circles_with_random_weights(name, scale):
    # sites on a 1e-3 circle at 5e4 .. 3e6: the power vertices near the centre are spread
    # over a few ulps, where the cells' float cuts disagree on which tiny edges exist
    pts, boundary = FAR_CIRCLES[name]
    spacing = 2 * np.pi * 1e-3 / len(pts)
    w = np.random.default_rng(0).random(len(pts)) * scale * spacing * spacing
    d = vf.power(pts, w, boundary)
    r = d.describe()
    assert r.euler_ok and r.convex_ok and r.mismatched_vertices == 0, str(r)
    _shared_bits(d)
    x0, y0, x1, y1 = d.boundary.bounds
    area = (x1 - x0) * (y1 - y0)
    assert abs(d.areas.sum() - area) <= 1e-12 * area
