"""Inset and fillet of convex cells (design/convexops.py) against shapely.

Two references: the exact one (the intersection of the cell's moved half-planes by GEOS
overlay, grown back by a GEOS round buffer for the fillet), which the direct computation
must match to rounding and to the vertex of each arc sample; and GEOS's own negative
buffers (what cellops used before), which simplify their input by 1% of the distance
(``BufferParameters`` simplify factor 0.01) and so differ by up to about that much.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely

import voroforge as vf
from voroforge.design import cellops, convexops

Q = 16
#: Largest distance of a chord of a round join from its arc, per unit radius.
CHORD = 1.0 - math.cos(math.pi / 4 / Q)
#: GEOS simplifies a buffer's input by this fraction of the distance.
GEOS_SIMPLIFY = 0.01


def _exact_inset(cell: shapely.Polygon, d: float) -> shapely.Geometry:
    """The intersection of the cell's half-planes moved inward by ``d`` (GEOS overlay)."""
    ring = np.asarray(cell.exterior.coords)
    if not cell.exterior.is_ccw:
        ring = ring[::-1]
    big = 4.0 * (np.ptp(ring, axis=0).max() + d + 1.0)
    out = cell
    for a, b in zip(ring[:-1], ring[1:], strict=True):
        if (a == b).all():
            continue
        t = (b - a) / np.hypot(*(b - a))
        n = np.array([-t[1], t[0]])
        p = a + d * n
        half = shapely.Polygon(
            [p - big * t, p + big * t, p + big * t + big * n, p - big * t + big * n]
        )
        out = out.intersection(half)
        if out.is_empty:
            return shapely.Polygon()
    return out if out.area > 0 else shapely.Polygon()


def _exact_fillet(cell, r: float):
    core = _exact_inset(cell, r)
    return shapely.Polygon() if core.is_empty else core.buffer(r, quad_segs=Q)


def _voronoi_cells(n=300, seed=0):
    pts = np.random.default_rng(seed).random((n, 2)) * [100.0, 70.0]
    return np.asarray(vf.voronoi(pts, (0, 0, 100, 70)).cells, dtype=object)


def _random_convex(rng, k, scale=1.0, centre=(0.0, 0.0)):
    ang = np.sort(rng.random(k)) * 2 * math.pi
    ring = np.stack((np.cos(ang), np.sin(ang)), axis=1) * scale * (0.5 + rng.random())
    return shapely.convex_hull(shapely.MultiPoint(ring + centre))


def _degenerate_cells():
    """Named cells that have broken offset code before or could."""
    cells = {
        "square": shapely.box(0, 0, 2, 2),
        "rectangle to a segment": shapely.box(0, 0, 4, 2),
        "tiny": shapely.box(0, 0, 1e-6, 2e-6),
        "acute": shapely.Polygon([(0, 0), (10, 0), (10, 0.002)]),
        "acute both ends": shapely.Polygon([(0, 0), (10, 0.001), (20, 0), (10, -0.001)]),
        "near parallel": shapely.Polygon([(0, 0), (5, -1e-9), (10, 0), (10, 3), (0, 3)]),
        "nearly straight corner": shapely.Polygon([(0, 0), (5, -1e-4), (10, 0), (10, 3), (0, 3)]),
        "short edge": shapely.Polygon([(0, 0), (10, 0), (10.001, 0.0005), (10, 5), (0, 5)]),
        "repeated point": shapely.Polygon([(0, 0), (6, 0), (6, 0), (6, 4), (0, 4)]),
        "straight vertex": shapely.Polygon([(0, 0), (3, 0), (6, 0), (6, 4), (0, 4)]),
        "clockwise": shapely.Polygon([(0, 0), (0, 4), (6, 4), (6, 0)]),
        "far away": shapely.affinity.translate(shapely.box(0, 0, 5, 4), 1e6, -3e6),
        "regular 40-gon": shapely.Point(0, 0).buffer(3.0, quad_segs=10),
        "triangle": shapely.Polygon([(0, 0), (6, 0), (1, 4)]),
    }
    return list(cells), np.asarray(list(cells.values()), dtype=object)


def _check_inset(cells, d, *, geos: bool):
    """Compare cellops.inset on convex cells with the exact reference (and GEOS's buffer)."""
    ours = cellops.inset(cells, d)
    assert shapely.is_valid(ours).all()
    for i, cell in enumerate(cells):
        ref = _exact_inset(cell, d)
        scale = max(1.0, float(np.abs(shapely.get_coordinates(cell)).max()))
        if ref.is_empty or ref.area <= 1e-8 * cell.area:
            assert ours[i].is_empty or ours[i].area <= 1e-9 * cell.area, i
            continue
        assert not ours[i].is_empty, i
        assert shapely.hausdorff_distance(ours[i], ref) <= 1e-9 * scale, i
    if geos:
        old = shapely.buffer(cells, -d, join_style="mitre", mitre_limit=5.0, quad_segs=Q)
        both = ~shapely.is_empty(old) & ~shapely.is_empty(ours)
        gap = shapely.hausdorff_distance(ours[both], old[both])
        assert (gap <= GEOS_SIMPLIFY * d * 1.5 + 1e-9).all()
    return ours


@pytest.mark.parametrize("d", [0.0, 0.3, 1.0, 2.5, 6.0])
def test_inset_of_voronoi_cells_matches_the_half_planes(d):
    cells = _voronoi_cells(120, seed=int(d * 10))
    ours = _check_inset(cells, d, geos=True)
    old = shapely.buffer(cells, -d, join_style="mitre", mitre_limit=5.0, quad_segs=Q)
    # GEOS empties a few tiny insets its 1% input simplification shrinks away
    differ = shapely.is_empty(old) != shapely.is_empty(ours)
    assert differ.sum() <= max(1, len(cells) // 50)
    assert (shapely.area(ours[differ]) <= (0.05 * d) * shapely.length(ours[differ]) + 1e-12).all()


def test_inset_of_random_convex_polygons():
    rng = np.random.default_rng(7)
    cells = np.asarray([_random_convex(rng, int(k)) for k in rng.integers(3, 30, 80)])
    d = rng.random(80) * 0.6
    ours = cellops.inset(cells, d)
    for i in range(len(cells)):
        ref = _exact_inset(cells[i], d[i])
        if ref.is_empty:
            assert ours[i].is_empty or ours[i].area < 1e-12
        else:
            assert shapely.hausdorff_distance(ours[i], ref) <= 1e-9


@pytest.mark.parametrize("d", [0.0, 1e-3, 0.5, 1.0, 1.5, 2.0])
def test_inset_of_degenerate_cells(d):
    names, cells = _degenerate_cells()
    ours = _check_inset(cells, d, geos=False)
    if d == 1.0:
        assert ours[names.index("square")].is_empty
        assert ours[names.index("rectangle to a segment")].is_empty
        assert ours[names.index("tiny")].is_empty
        assert ours[names.index("acute")].is_empty
        assert not ours[names.index("far away")].is_empty


def _check_fillet(cells, r, *, geos: bool):
    ours = cellops.fillet(cells, r)
    assert shapely.is_valid(ours).all()
    for i, cell in enumerate(cells):
        ref = _exact_fillet(cell, r) if r > 0 else cell
        scale = max(1.0, float(np.abs(shapely.get_coordinates(cell)).max()))
        if ref.is_empty or ref.area <= 1e-9 * cell.area:
            assert ours[i].is_empty or ours[i].area <= 4 * r * r, i
            continue
        assert not ours[i].is_empty, i
        # the same arcs, sampled alike: rounding only
        assert shapely.hausdorff_distance(ours[i], ref) <= 1e-9 * scale + 1e-6 * r, i
    if geos:
        old = shapely.buffer(shapely.buffer(cells, -r, quad_segs=Q), r, quad_segs=Q)
        both = ~shapely.is_empty(old) & ~shapely.is_empty(ours)
        gap = shapely.hausdorff_distance(ours[both], old[both], densify=0.25)
        assert (gap <= (GEOS_SIMPLIFY * 1.5 + CHORD) * r + 1e-9).all()
        differ = shapely.is_empty(old) != shapely.is_empty(ours)
        assert differ.sum() <= max(1, len(cells) // 50)
    return ours


@pytest.mark.parametrize(("d", "r"), [(0.0, 0.5), (0.5, 1.0), (1.0, 1.5), (0.2, 4.0)])
def test_fillet_of_inset_voronoi_cells_matches_geos(d, r):
    cells = cellops.inset(_voronoi_cells(120, seed=3), d)
    live = ~shapely.is_empty(cells)
    _check_fillet(cells[live], r, geos=True)


@pytest.mark.parametrize("r", [1e-3, 0.4, 1.0, 1.9])
def test_fillet_of_degenerate_cells(r):
    _, cells = _degenerate_cells()
    _check_fillet(cells, r, geos=False)


def test_fillet_arcs_are_sampled_as_geos_samples_round_joins():
    """Same chord count per corner as GEOS, so io/arcs finds the same arcs."""
    cells = cellops.inset(_voronoi_cells(80, seed=5), 0.5)
    cells = cells[~shapely.is_empty(cells)]
    ours = cellops.fillet(cells, 1.0)
    old = shapely.buffer(shapely.buffer(cells, -1.0, quad_segs=Q), 1.0, quad_segs=Q)
    same = shapely.is_empty(ours) == shapely.is_empty(old)
    n_ours = shapely.get_num_coordinates(ours[same])
    n_old = shapely.get_num_coordinates(old[same])
    assert (n_ours == n_old).mean() > 0.95  # GEOS's simplification drops a corner now and then
    from voroforge.io.arcs import arc_runs

    alike = np.flatnonzero(n_ours == n_old)[:25]
    for g, h in zip(ours[same][alike], old[same][alike], strict=True):
        if g.is_empty:
            continue
        runs = arc_runs(np.asarray(g.exterior.coords)[:-1])
        want = arc_runs(np.asarray(h.exterior.coords)[:-1])
        assert len(runs) >= 3  # a convex cell has at least three rounded corners
        assert sorted(c for _, c, _ in runs) == sorted(c for _, c, _ in want)
        got = np.sort([s for _, _, s in runs])
        assert np.allclose(got, np.sort([s for _, _, s in want]), atol=1e-6)


def test_rings_go_back_clockwise_like_geos_buffers():
    cells = _voronoi_cells(40)
    for g in cellops.fillet(cellops.inset(cells, 0.5), 0.5):
        if not g.is_empty:
            assert not g.exterior.is_ccw
    mask, _, _ = convexops.convex_rings(cells)
    assert mask.all()


def test_non_convex_and_holed_cells_go_to_geos():
    """Cells the boundary cuts (non-convex, holes, several parts) keep GEOS's answer."""
    l_shape = shapely.Polygon([(0, 0), (6, 0), (6, 2), (2, 2), (2, 6), (0, 6)])
    holed = shapely.box(0, 0, 10, 10).difference(shapely.box(4, 4, 6, 6))
    multi = shapely.MultiPolygon([shapely.box(0, 0, 3, 3), shapely.box(5, 0, 8, 3)])
    cells = np.asarray([l_shape, holed, multi, shapely.Polygon()], dtype=object)
    mask, _, start = convexops.convex_rings(cells)
    assert not mask.any() and len(start) == 1
    ours = cellops.inset(cells, 0.5)
    old = shapely.buffer(cells, -0.5, join_style="mitre", mitre_limit=5.0, quad_segs=Q)
    assert shapely.equals_exact(ours[:3], old[:3], 0.0).all()
    assert ours[3].is_empty


def test_per_cell_values_and_zero():
    cells = _voronoi_cells(30)
    r = np.linspace(0.0, 1.5, 30)
    out = cellops.fillet(cells, r)
    assert out[0] is cells[0] or shapely.equals_exact(out[0], cells[0], 0.0)
    for i in range(1, 30, 7):
        ref = _exact_fillet(cells[i], r[i])
        assert shapely.hausdorff_distance(out[i], ref) <= 1e-9 * 100 + 1e-6


def test_a_cell_gets_the_same_bytes_in_any_batch():
    """compute(workers=) splits the cells between threads: each cell's result is its own."""
    cells = _voronoi_cells(90, seed=11)
    whole = cellops.fillet(cellops.inset(cells, 0.4), 0.8)
    for part in (slice(0, 31), slice(31, 90), slice(5, 6)):
        alone = cellops.fillet(cellops.inset(cells[part], 0.4), 0.8)
        assert list(shapely.to_wkb(alone)) == list(shapely.to_wkb(whole[part]))


def _mixed_cells():
    """Voronoi cells in a star (convex and cut ones) and the named degenerate cells."""
    t = np.linspace(0.0, 2.0 * math.pi, 11)[:-1]
    rad = np.where(np.arange(10) % 2, 40.0, 100.0)
    star = shapely.Polygon(np.stack((rad * np.cos(t), rad * np.sin(t)), axis=1))
    pts = np.random.default_rng(5).uniform(-100, 100, (300, 2))
    pts = pts[shapely.contains_xy(star, pts[:, 0], pts[:, 1])]
    cells = np.asarray(vf.voronoi(pts, star).cells, dtype=object)
    return np.concatenate((cells, _degenerate_cells()[1], [shapely.Polygon()]))


@pytest.mark.parametrize("d", [0.0, 0.3, 1.0, 4.0])
def test_reconvex_is_convex_rings_of_the_polygons(d):
    """Flat rings passed on (no polygons in between) are what the shapely round trip gives."""
    _, xy, start = convexops.convex_rings(_mixed_cells())
    xy, start, _, _ = convexops.inset_rings(xy, start, d)
    for rings in ((xy, start), convexops.fillet_rings(xy, start, 1.5, Q)[:2]):
        want = convexops.convex_rings(convexops.polygons(*rings))
        got = convexops.reconvex(*rings)
        assert (got[0] == want[0]).all()
        assert got[1].tobytes() == want[1].tobytes() and (got[2] == want[2]).all()


def test_inset_fillet_is_the_two_calls_byte_for_byte():
    cells = _mixed_cells()
    rng = np.random.default_rng(2)
    n = len(cells)
    per_cell = (rng.uniform(0, 3, n), np.where(rng.random(n) < 0.3, 0.0, rng.uniform(0.2, 2, n)))
    for d, r in [(1.0, 1.5), (0.0, 1.5), (1.0, 0.0), (6.0, 3.0), per_cell]:
        for join in ("mitre", "round"):
            two = cellops.fillet(cellops.inset(cells, d, join=join), r)
            one = cellops.inset_fillet(cells, d, r, join=join)
            assert list(shapely.to_wkb(one)) == list(shapely.to_wkb(two)), (d, r, join)


def _needle_inset(P, d):
    """The inset of triangle ``P`` by ``d`` in 60-digit decimals: the triangle scaled about
    its incentre by ``1 - d / inradius`` (None when it empties)."""
    from decimal import Decimal, localcontext

    with localcontext() as ctx:
        ctx.prec = 60
        Q = [(Decimal(float(x)), Decimal(float(y))) for x, y in P]
        side = []
        for i in range(3):
            (ax, ay), (bx, by) = Q[(i + 1) % 3], Q[(i + 2) % 3]
            side.append(((ax - bx) ** 2 + (ay - by) ** 2).sqrt())
        s = sum(side)
        ix = sum(side[i] * Q[i][0] for i in range(3)) / s
        iy = sum(side[i] * Q[i][1] for i in range(3)) / s
        (ax, ay), (bx, by), (cx, cy) = Q
        k = 1 - Decimal(d) * s / abs((bx - ax) * (cy - ay) - (by - ay) * (cx - ax))
        if k <= 0:
            return None
        return np.array([[float(ix + (x - ix) * k), float(iy + (y - iy) * k)] for x, y in Q])


@pytest.mark.parametrize("h", [1e-4, 1e-8, 1e-12])
def test_inset_of_needles_is_accurate(h):
    # corners of 2h radians: the first crossing divided by 1 + cos(pi - 2h), which cancels
    # (NaN vertices at h = 1e-9, a vertex 1.9e-4 off at 1e-7); the error allowed is the
    # conditioning of float edge directions, ~eps (1 + d / theta^2)
    worst = 0.0
    for apex in (0.5, 0.9, 0.01):
        for turn in (0, 1, 2, 3, 0.3, 1.1):
            P = np.array([[0.0, 0.0], [1.0, 0.0], [apex, h]])
            if turn in (0, 1, 2, 3):  # quarter turns: exact
                for _ in range(turn):
                    P = np.column_stack([-P[:, 1], P[:, 0]])
            else:
                c, s = math.cos(turn), math.sin(turn)
                P = P @ np.array([[c, s], [-s, c]])
            e = np.roll(P, -1, axis=0) - P
            ang = [
                abs(math.atan2(e[i, 0] * e[i - 1, 1] - e[i, 1] * e[i - 1, 0], -e[i] @ e[i - 1]))
                for i in range(3)
            ]
            inr = abs(e[0, 0] * e[2, 1] - e[0, 1] * e[2, 0]) / np.hypot(e[:, 0], e[:, 1]).sum()
            for f in (0.01, 0.25, 0.45):
                d = f * inr
                ref = shapely.Polygon(_needle_inset(P, d))
                cell = shapely.Polygon(P)
                ours = cellops.inset([cell], d)[0]
                assert ours.is_valid and not ours.is_empty, (apex, turn, f)
                err = shapely.hausdorff_distance(ours, ref)
                worst = max(worst, err / (1e-16 * (1.0 + d / min(ang) ** 2)))
                filleted = cellops.inset_fillet([cell], d, d)[0]
                assert filleted.is_valid and filleted.within(cell.buffer(1e-12))
    assert worst <= 2000.0
