"""Issue 15: flagged sites must not leave holes, and T-junctions beside them must count.

- Cells ~35 ulps wide at 4e12 (10,000-20,000 sites in a 3 x 2 box): the Delaunay dual's
  ring of a site, its vertices rounded circumcentres, turned the wrong way by an ulp and was
  left empty as folded (``planar._drop_folded``); the exact cell rounded differs from its
  neighbours' vertices by up to 6 ulps, so ``restore`` could not snap it onto the gap, and
  the gap stayed a hole (20,000 sites, seeds 0 and 1: 83 and 68 flagged sites, Euler -5 for
  1 with every algorithm). The gap's own boundary (the neighbours' edges, reversed) now
  closes it as the ring of a lost site its edges name (``restore._fill_cycles``).
- On a wrapped torus at 1e14 (box 192 x 19 ulps, cells 3 ulps wide) a vertex exactly on
  another cell's side shared its place along the side with a vertex 6 ulps below it;
  ``junctions.split_plane`` put the far one in the chain and split nothing (Euler 0 for 1).

Checks against independent references: areas summed in exact rationals, the cells' union
without holes, every edge shared or on the box, samples in their exact nearest site's cell.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import shapely

import voroforge as vf
from voroforge.engine.restore import _fill_cycles, _loops

ALGORITHMS = ("delaunay", "fortune", "halfplane")
OFF = 4e12
ULP = 2.0**-11  # of 4e12


def _window(n, seed, site, r):
    """Sites of the 3 x 2 box at 4e12 within ``r`` of one of them, and a box on the ulps."""
    p = np.random.default_rng(seed).random((n, 2)) * [3, 2] + OFF
    c = p[site]
    lo = np.floor((c - r - OFF) / ULP) * ULP + OFF
    hi = np.ceil((c + r - OFF) / ULP) * ULP + OFF
    return p[((p >= lo) & (p <= hi)).all(1)], (lo[0], lo[1], hi[0], hi[1])


def _exact_area(cell) -> Fraction:
    total = Fraction(0)
    for part in shapely.get_parts(cell):
        for k, ring in enumerate((part.exterior, *part.interiors)):
            xy = [(Fraction(x), Fraction(y)) for x, y in np.asarray(ring.coords)]
            a = sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(xy[:-1], xy[1:], strict=True))
            total += abs(a) / 2 if k == 0 else -abs(a) / 2
    return total


def _tiles(d, box):
    """Exact areas sum to the box's; the union has no hole; edges shared or on the box."""
    want = (Fraction(box[2]) - Fraction(box[0])) * (Fraction(box[3]) - Fraction(box[1]))
    assert sum(_exact_area(c) for c in d.cells if not c.is_empty) == want
    u = shapely.union_all([shapely.affinity.translate(c, -OFF, -OFF) for c in d.cells])
    assert sum(len(p.interiors) for p in shapely.get_parts(u)) == 0
    edges = {}
    for i, c in enumerate(d.cells):
        for part in shapely.get_parts(c):
            xy = [
                tuple(t) for t in np.asarray(shapely.geometry.polygon.orient(part).exterior.coords)
            ]
            for a, b in zip(xy[:-1], xy[1:], strict=True):
                edges[a, b] = i
    for (a, b), i in edges.items():
        if (b, a) in edges:
            assert edges[b, a] != i
            continue
        on_box = (a[0] == b[0] and a[0] in (box[0], box[2])) or (
            a[1] == b[1] and a[1] in (box[1], box[3])
        )
        assert on_box, (i, a, b)


def _samples(d, pts, box, k=400):
    """Grid points away from bisectors lie in their exact nearest site's cell (or that site
    is flagged and the point in some cell)."""
    g = np.random.default_rng(1)
    xy = np.column_stack(
        [box[0] + g.random(k) * (box[2] - box[0]), box[1] + g.random(k) * (box[3] - box[1])]
    )
    ex = [(Fraction(x), Fraction(y)) for x, y in pts]
    flagged = set(d.unresolved.tolist())
    tested = 0
    for x, y in xy:
        fx, fy = Fraction(x), Fraction(y)
        d2 = sorted(((fx - a) ** 2 + (fy - b) ** 2, i) for i, (a, b) in enumerate(ex))
        (a, i), (b, j) = d2[0], d2[1]
        apart = (ex[i][0] - ex[j][0]) ** 2 + (ex[i][1] - ex[j][1]) ** 2
        # 2 |s_i - s_j| times the point's distance to the bisector: 8 ulps from it
        if (b - a) ** 2 <= 4 * apart * Fraction(8 * ULP) ** 2:
            continue
        tested += 1
        held = [c for c in range(len(pts)) if d.cells[c].intersects(shapely.Point(x, y))]
        assert held, (x, y)
        assert i in held or i in flagged, (x, y, i, held)
    assert tested > k // 4


@pytest.mark.parametrize("algorithm", ALGORITHMS)
def test_folded_ring_left_empty_is_no_hole(algorithm):
    # 57 sites about site 6817 of 10,000 (seed 0): its ring was left empty (folded by an
    # ulp), a hole of 4,660 ulps^2 (Euler 0 for 1, areas 1.1e-3 short). Since 1bdd7d6 the
    # tiny ring is kept where it is valid and matches its neighbours' edges bit for bit
    # (engine.planar._kept_tiny); kept or left empty, no hole
    pts, box = _window(10_000, 0, 6817, 0.08)
    d = vf.voronoi(pts, box, algorithm=algorithm)
    assert len(d.unresolved) <= 1
    assert shapely.is_valid(d.cells).all()
    _tiles(d, box)
    assert d.describe().euler_ok
    _samples(d, pts, box)


def test_ten_thousand_sites_at_4e12_have_no_holes():
    # seed 0: 21 flagged sites left 4 holes (two of a site's whole cell, one of two sites')
    p = np.random.default_rng(0).random((10_000, 2)) * [3, 2] + OFF
    box = (OFF, OFF, OFF + 3.0, OFF + 2.0)
    d = vf.voronoi(p, box)
    assert len(d.unresolved)  # still flagged: floats cannot give their cells
    u = shapely.union_all([shapely.affinity.translate(c, -OFF, -OFF) for c in d.cells])
    assert sum(len(q.interiors) for q in shapely.get_parts(u)) == 0
    assert u.area == 6.0
    assert d.describe().euler_ok


def test_fill_cycles_gives_a_gap_back_to_its_site():
    # an ordinary diagram with one inner ring taken out: the gap's cycle is that ring
    p = np.random.default_rng(3).random((40, 2))
    box = np.array([0.0, 0.0, 1.0, 1.0])
    from voroforge.engine.planar import _closed_cells

    closed, lengths, owner = _closed_cells(
        p[:, 0].copy(), p[:, 1].copy(), box, "delaunay", np.arange(40)
    )
    b = np.array(
        [
            closed[lengths[i] : lengths[i + 1]].min(0).tolist()
            + closed[lengths[i] : lengths[i + 1]].max(0).tolist()
            for i in range(40)
        ]
    )
    i = int(np.flatnonzero((b[:, :2] > 0.1).all(1) & (b[:, 2:] < 0.9).all(1))[0])
    ring = closed[lengths[i] : lengths[i + 1]].copy()
    keep = np.ones(len(closed), dtype=bool)
    keep[lengths[i] : lengths[i + 1]] = False
    cut = lengths.copy()
    cut[i + 1 :] -= lengths[i + 1] - lengths[i]
    rings = (closed[keep], cut, owner[keep])
    lost = np.array([i])
    (c2, l2, o2), still = _fill_cycles(
        p[:, 0].copy(), p[:, 1].copy(), box, rings, lost, lost, np.arange(40)
    )
    got = c2[l2[i] : l2[i + 1]]
    assert len(still) == 0  # a convex ring holding its site
    assert shapely.equals(shapely.Polygon(got), shapely.Polygon(ring))
    assert set(map(tuple, got.tolist())) == set(map(tuple, ring.tolist()))
    # the ring's neighbours now face it again
    assert np.array_equal(np.sort(o2), np.sort(owner))


@pytest.mark.parametrize("seed", [1, 3])
def test_wrapped_t_junction_beside_a_vertex_below_the_side(seed):
    # 300 sites in 3 x 0.3 at 1e14 (192 x 19 ulps), wrapped: Euler 0 for 1 before; the
    # cells tile the box (exact areas)
    off = 1e14
    box = (off, off, off + 3.0, off + 0.3)
    p = np.random.default_rng(seed).random((300, 2)) * [3.0, 0.3] + off
    for algorithm in ALGORITHMS:
        d = vf.voronoi(p, box, periodic=True, wrap=True, algorithm=algorithm)
        want = (Fraction(box[2]) - Fraction(box[0])) * (Fraction(box[3]) - Fraction(box[1]))
        assert sum(_exact_area(c) for c in d.cells if not c.is_empty) == want
        assert d.describe().euler_ok, algorithm


NESTED_BOX = (-2e6, -2e6, 2e6, 2e6)
NESTED_SCALES = [(1e-12, 1e-6, 1, 5e5), (1e-13, 1e-9, 1e-4, 1.0), (1e-11, 1e-3, 1e3, 5e5)]


def _nested(scale, seed, centre):
    """Normal clusters nested about ``centre`` (test_issue15_junctions' scan)."""
    g = np.random.default_rng(seed)
    k = 6 + seed % 3
    p = np.concatenate([g.normal(0, s, (k, 2)) for s in NESTED_SCALES[scale]])
    return (np.asarray(centre) + p).clip(NESTED_BOX[0], NESTED_BOX[2])


# the sweep's three failing inputs at ed376bb (Euler 0 for 1, every algorithm): the gap a
# flagged site's empty ring left (2, 2 and 7 sites flagged)
@pytest.mark.parametrize(
    ("centre", "scale", "seed"), [((3e3, -2e3), 1, 2), ((3e3, -2e3), 1, 41), ((-7e4, 5e4), 2, 14)]
)
def test_nested_clusters_flagged_sites_leave_no_gap(centre, scale, seed):
    p = _nested(scale, seed, centre)
    for algorithm in ALGORITHMS:
        d = vf.voronoi(p, NESTED_BOX, algorithm=algorithm)
        assert len(d.unresolved)
        r = d.describe()
        assert r.euler_ok and r.convex_ok, (algorithm, r.euler)
        # exact areas tile the box (rationals)
        want = Fraction(4_000_000) ** 2
        assert sum(_exact_area(c) for c in d.cells if not c.is_empty) == want


def test_a_gap_pinched_at_a_vertex_splits_into_its_loops():
    # the gap of two lost sites side by side touching at one vertex (1.3e13, 10,000 sites:
    # two such gaps stayed holes): its walk passes the vertex twice, each loop is a ring
    a, b, c, e, f = (0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (2.0, 1.0), (1.0, 2.0)
    walk = [a, b, c, e, f, c]
    labels = list("ABCDEF")
    loops = _loops(walk, labels)
    assert sorted(map(tuple, (r for r, _ in loops))) == [(a, b, c), (c, e, f)]
    for r, lab in loops:
        assert len(r) == len(lab) == 3
        assert shapely.Polygon(r).is_valid
    assert sorted(x for _, lab in loops for x in lab) == labels  # every step in one loop
