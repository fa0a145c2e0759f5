"""Float circles far out: side crossings in order (issue 15), and thin pieces at a reflex vertex.

1,000 float sites on a circle of radius 1e-7 at (5e5, 4e6) (neighbours 1.3 ulps apart):
the bisectors of 421-425 and 425-426 (phase 0.05) cross the left side 118.79 and 118.25
ulps above the centre; the float formula gave 118 and 119, so 425's side edge ran
backwards, its ring folded and was dropped, and every algorithm left a hole (Euler -1; so
did phase 0.80). For sites a few ulps apart (``config.SIDE_NEAREST_ULPS``) the crossing
is now the double nearest the exact one (``kernels.sidecross``), which keeps crossings in
order; farther pairs keep the float formula's bits (every catalogue diagram unchanged).

Those nearest crossings had made three sites an ulp apart at a polygon's reflex vertex
lose the middle site's cell (tests/test_issue15_polygon_domains.py, tooth and notch): its
strip, clipped in the vertex's frame, is two pieces an ulp or two wide either side of the
vertex, and GEOS's union of them (in that frame, and again once rounded back, where they
touch along a segment) came back empty, which the area check let through (its slack, ulps
times the perimeter, exceeds the strip's whole area). Such a union is now checked against
the parts' exact area and redone by a buffer of 0 (``engine.assemble._union_kept``).

Sites exactly on one line (an ulp apart on a diagonal) have parallel bisectors, whose
crossings of a side come half an ulp apart: the float cut lost the side edge between them
and wrote a vertex of the two parallel lines (the collinear dual cells: in the middle of
the box; the half-plane settling refused the ring and wrote the float cut, its side points
off the crossings its neighbours name). With the nearest crossings that broke
tests/test_issue15_ulps_box.py's diagonal strips; the side is now put back by name before
the vertices are named (``kernels.sidegap``).

Checked against exact references: crossings against Fractions, the cells against the
exact cells (the largest distance of a vertex past a bisector, exact integers), Euler,
validity, the box; the union against the exact shoelace area.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import shapely

import voroforge as vf
from test_issue15_circle_sides import _circle, _local, _past
from test_issue15_polygon_domains import _ulps_from
from test_issue15_ulpid import _edge_to_edge, _rings
from voroforge.config import SIDE_NEAREST_ULPS
from voroforge.engine.assemble import _union_kept
from voroforge.kernels.sidecross import nearest_crossing
from voroforge.kernels.sidegap import parallel_between, restore_side_vertices, restore_sides
from voroforge.kernels.vertex import box_crossing

from reference import exact_area

ALGS = ["delaunay", "fortune", "halfplane"]


def _exact(ax, ay, bx, by, side, box):
    """The exact crossing's coordinate along ``side`` (Fractions)."""
    ax, ay, bx, by = map(Fraction, (ax, ay, bx, by))
    if side in (-1, -3):
        x = Fraction(box[0] if side == -1 else box[2])
        return ((ax - bx) * (2 * x - ax - bx) + (by - ay) * (by + ay)) / (2 * (by - ay))
    y = Fraction(box[1] if side == -2 else box[3])
    return ((ay - by) * (2 * y - ay - by) + (bx - ax) * (bx + ax)) / (2 * (bx - ax))


def test_crossing_of_sites_ulps_apart_is_the_nearest_double():
    """Random pairs (offsets 1e-3..1e12, spreads 1e-8..1e8; a third of them a few ulps
    apart, some bisectors nearly parallel to the side): a pair within
    ``SIDE_NEAREST_ULPS`` gets Fraction's float() of the exact crossing, any pair one
    within a few ulps of it, the same bits either way round."""
    g = np.random.default_rng(5)
    near = 0
    far = 0
    for k in range(600):
        sc = 10.0 ** g.uniform(-8, 8)
        off = 10.0 ** g.uniform(-3, 12) * g.choice([-1.0, 1.0], 2)
        a = off + g.normal(size=2) * sc
        b = off + g.normal(size=2) * sc
        if k % 3 == 0:
            b = a + g.integers(-8, 8, 2) * np.spacing(np.abs(a))
        lo = np.minimum(a, b) - sc
        hi = np.maximum(a, b) + sc
        box = np.array([lo[0], lo[1], hi[0], hi[1]])
        xs = np.array([a[0], b[0]])
        ys = np.array([a[1], b[1]])
        ulps = (np.abs(b - a).sum()) / np.spacing(np.abs(np.concatenate((a, b))).max())
        for side in (-1, -2, -3, -4):
            x, y = box_crossing(0, 1, xs, ys, side, box)
            if x != x:
                assert (side in (-1, -3) and a[1] == b[1]) or (side in (-2, -4) and a[0] == b[0])
                continue
            assert (x, y) == tuple(box_crossing(1, 0, xs, ys, side, box))
            got = y if side in (-1, -3) else x
            ex = _exact(a[0], a[1], b[0], b[1], side, box)
            if ulps <= SIDE_NEAREST_ULPS:
                assert got == float(ex), (k, side)
                near += 1
            else:
                # the float formula: its error grows with the bisector's slope to the side
                da, db = (b - a) if side in (-1, -3) else (b - a)[::-1]
                slope = abs(da / db)
                mag = max(np.abs(box).max(), np.abs(a).max(), np.abs(b).max())
                err = abs(Fraction(got) - ex) / Fraction(np.spacing(mag))
                assert err <= 4 * (1 + slope), (k, side, float(err))
                far += 1
    assert near > 500 and far > 1200


def test_crossings_of_a_float_circle_stay_in_order():
    """The left side's crossings of 421-425 and 425-426 (phase 0.05), 0.54 ulp apart."""
    pts = _circle(1000, 0.05)
    xs = np.ascontiguousarray(pts[:, 0])
    ys = np.ascontiguousarray(pts[:, 1])
    u = np.spacing(4e6)  # the box of these sites: 257.75 x 258 ulps about the centre
    box = np.array([5e5 - 257.75 * u, 4e6 - 258 * u, 5e5 + 257.75 * u, 4e6 + 258 * u])
    at = []
    for a, b in ((421, 425), (425, 426)):
        x, y = box_crossing(a, b, xs, ys, -1, box)
        assert x == box[0]
        e = _exact(xs[a], ys[a], xs[b], ys[b], -1, box)
        assert y == float(e)
        at.append((y, e))
    assert at[0][1] > at[1][1] and at[0][0] > at[1][0]
    # the float formula's NaN (a bisector parallel to the side) is passed through
    assert np.isnan(nearest_crossing(0.0, 0.0, 1.0, 0.0, -1, box, np.nan, np.nan)[1])


def _unmatched(d):
    """Edges of one cell that no other cell has reversed, off the box's sides."""
    x0, y0, x1, y1 = d.boundary.bounds
    edges = set()
    for c in d.cells:
        if c is None or c.is_empty:
            continue
        v = [tuple(q) for q in shapely.get_coordinates(c)]
        edges.update(zip(v[:-1], v[1:], strict=True))
    bad = []
    for a, b in edges:
        on = (a[0] == b[0] and a[0] in (x0, x1)) or (a[1] == b[1] and a[1] in (y0, y1))
        if not on and (b, a) not in edges:
            bad.append((a, b))
    return bad


@pytest.mark.parametrize("phase", [0.05, 0.80, 0.95])
def test_far_circle_of_1000_tiles_the_box(phase):
    """Every algorithm: Euler, valid cells in the box, no hole (phases 0.05 and 0.95: edge
    to edge, the cells' exact areas sum to the box's), within 8 ulps of the exact cells
    (distance past a bisector, exact integers), one diagram.

    Phase 0.95 had two holes Euler did not see (a side vertex rounded to 95 ulps in one
    cell and 96 in the next hid them until the crossings were the nearest doubles): hull
    site 293 lost the centre (-255, 95) ulps of its triangle with 290 and 292, 2.75 ulps
    inside the left side and never put on it (its sites an ulp apart), because the run of
    lost centres took no such centre (``cellcut._inside_box``); hull site 352 kept its
    edge with 355, a ray from a centre 5 ulps left of the side running left, in place of
    its 1-ulp neighbour 354's (``cellcut._end_past``)."""
    pts = _circle(1000, phase)
    p = _local(pts)
    first = None
    for alg in ALGS:
        d = vf.voronoi(pts, None, algorithm=alg)
        rep = d.describe()
        assert rep.euler_ok, f"{alg}: {rep}"
        assert shapely.is_valid(np.asarray(d.cells, dtype=object)).all()
        if phase != 0.80:  # (0.80: flagged site 258's sliver is left out, a hole)
            assert not _unmatched(d), alg
            total = sum(exact_area(c) for c in d.cells if c is not None)
            assert total == exact_area(d.boundary), alg
        x0, y0, x1, y1 = d.boundary.bounds
        worst = 0.0
        for i, c in enumerate(d.cells):
            if c is None or c.is_empty:
                continue
            v = shapely.get_coordinates(c)
            assert ((v[:, 0] >= x0) & (v[:, 0] <= x1) & (v[:, 1] >= y0) & (v[:, 1] <= y1)).all()
            if i not in d.unresolved:
                worst = max(worst, _past(_local(v), p, i))
        assert worst <= 8.0, f"{alg}: a vertex {worst:.2f} ulps past its exact cell"
        got = sorted(shapely.get_coordinates(c).tobytes() for c in d.cells if c is not None)
        if first is None:
            first = got
        assert got == first, f"{alg} differs from {ALGS[0]}"


def test_thin_pieces_at_a_reflex_vertex_keep_their_union():
    """The middle strip of three sites an ulp apart at the reflex vertex (1.5, 0.5) of a
    notch, clipped in the vertex's frame: two faces an ulp or two wide either side of it
    (disjoint), and the same rounded back to the plane (touching along a segment). Their
    union keeps the parts' exact area (to rounding) and is valid."""
    faces = shapely.from_wkt(
        [
            "POLYGON ((0.2500000000000002 -0.5, 5.329070518200751e-17 3.375077994860476e-16, "
            "1.0658141036401502e-16 6.750155989720952e-16, 0.2500000000000004 -0.5, "
            "0.2500000000000002 -0.5))",
            "POLYGON ((-1.0248212535001446e-16 6.490534605500915e-16, -1.5 3.0000000000000004, "
            "-1.5 3.000000000000001, -2.049642507000289e-16 1.298106921100183e-15, "
            "-1.0248212535001446e-16 6.490534605500915e-16))",
        ]
    )
    back = shapely.transform(faces, lambda p: p + np.array([1.5, 0.5]))
    site = (1.5 + 2.0**-52, 0.5 + 2.0**-53)  # the middle site
    for parts in (faces, back):
        got = _union_kept(parts)
        assert shapely.is_valid(got) and not got.is_empty
        want = sum(exact_area(p) for p in parts)
        # rounding moves each vertex by at most half an ulp of 4: a small part of the area
        assert abs(exact_area(got) - want) <= want / 4
    assert shapely.intersects_xy(_union_kept(back), *site)


def _strip_sites(start, step, count):
    """``start`` and the points 1, 2, ... ulps from it along ``step`` (one line, exactly)."""
    return _ulps_from(start, step, count)


def test_a_side_lost_between_parallel_bisectors_is_put_back():
    """Five sites an ulp apart on the diagonal (1, -1) at (2.25, 3.7): the middle site's
    bisectors are parallel and cross the top side half an ulp apart, so the float cut's
    ring is [1, left, 3] (a vertex of two parallel lines). The top side goes back between
    them; a ring whose neighbours are not on one line with its site is left alone."""
    pts = _strip_sites((2.25, 3.7), (1, -1), 5)
    xs = np.ascontiguousarray(pts[:, 0])
    ys = np.ascontiguousarray(pts[:, 1])
    box = np.array([0.0, 0.0, 10.0, 10.0])
    assert parallel_between(2, 1, 3, xs, ys) and not parallel_between(2, 1, 0, xs, ys)
    lab = np.zeros(8, np.int64)
    sure = np.ones(8)
    lab[:3] = (1, -1, 3)
    m = restore_sides(2, lab, sure, 3, xs, ys, box)
    assert lab[:m].tolist() == [-4, 1, -1, 3]  # (between 3 and 1)
    assert sure[:m].tolist() == [0.0, 0.0, 1.0, 0.0]  # the side and the two edges at it
    # with its vertices: the crossings named by the pairs (the nearest doubles)
    px = np.zeros(8)
    py = np.zeros(8)
    pw = np.zeros(8, np.int64)
    px[:3] = (4.0, 0.0, 0.0)  # the cut's vertex of the parallel lines, then the left side
    py[:3] = (5.0, 1.4499999999999988, 1.449999999999998)
    pw[:3] = (1, -1, 3)
    nbrs = np.array([1, 3], np.int64)
    tris = np.array([-1, -1], np.int64)
    m = restore_side_vertices(2, px, py, pw, 3, nbrs, tris, 2, xs, ys, box)
    assert pw[:m].tolist() == [-4, 1, -1, 3]
    assert (px[0], py[0]) == tuple(box_crossing(2, 3, xs, ys, -4, box))
    assert (px[1], py[1]) == tuple(box_crossing(2, 1, xs, ys, -4, box))
    assert (px[2], py[3]) == (0.0, 1.449999999999998)
    # a site off the line: its neighbours' bisectors meet, nothing changes
    xs2 = xs.copy()
    xs2[2] = np.nextafter(xs2[2], np.inf)
    lab[:3] = (1, -1, 3)
    assert restore_sides(2, lab, sure, 3, xs2, ys, box) == 3


_STRIPS = [
    ((2.25, 3.7), (1, -1), 5, 0.0),  # (failed with the nearest crossings alone)
    ((2.25, 3.7), (1, -1), 4, 0.0),
    ((2.25, 3.7), (-1, 1), 7, 0.0),
    ((1.0, 9.0), (1, -1), 5, 0.0),
    ((2.25, 3.7), (1, -1), 5, 5e5),
    ((2.25, 3.7), (-1, 1), 5, 1e15),
]


@pytest.mark.parametrize(("start", "step", "count", "off"), _STRIPS)
def test_strips_on_a_diagonal_meet_edge_to_edge(start, step, count, off):
    """Sites an ulp apart on one line (offsets 0, 5e5, 1e15): every algorithm's cells are
    valid, Euler holds, every edge off the box is its neighbour's reversed bit for bit and
    the rings' areas sum exactly to the box's (Fractions); each side point at the end of a
    bisector edge is the nearest double of the exact crossing; every site not flagged is in
    its cell; one diagram."""
    scale = 64.0 if off >= 1e15 else 1.0
    box = (off, off, off + 10.0 * scale, off + 10.0 * scale)
    pts = _strip_sites((off + start[0] * scale, off + start[1] * scale), step, count)
    exact = [(Fraction(x), Fraction(y)) for x, y in pts]
    first = None
    for alg in ALGS:
        d = vf.voronoi(pts, box, algorithm=alg)
        rep = d.describe()
        assert rep.euler_ok, (alg, str(rep))
        cells = np.asarray(d.cells, dtype=object)
        assert shapely.is_valid(cells).all(), alg
        rings = _rings(d)
        lone, tiles = _edge_to_edge(rings, box)
        assert lone == [] and tiles, (alg, lone)
        held = shapely.intersects(cells, shapely.points(pts))
        flagged = set(d.unresolved.tolist())
        assert all(held[i] or i in flagged for i in range(count)), alg
        for i, c in enumerate(d.cells):
            if c is None or c.is_empty:
                continue
            for x, y in shapely.get_coordinates(c)[:-1]:
                side = _side_of(x, y, box)
                if side is None:
                    continue
                # a point on a side: some pair's crossing (the nearest double), or a corner
                q = Fraction(x), Fraction(y)
                d2 = [(sx - q[0]) ** 2 + (sy - q[1]) ** 2 for sx, sy in exact]
                near = sorted(range(count), key=lambda k: d2[k])
                if (x, y) in {
                    (box[0], box[1]),
                    (box[0], box[3]),
                    (box[2], box[1]),
                    (box[2], box[3]),
                }:
                    continue
                a, b = sorted(near[:2])
                e = _exact(*pts[a], *pts[b], side, box)
                assert (y if side in (-1, -3) else x) == float(e), (alg, i, x, y)
        if first is None:
            first = rings
        assert rings == first, f"{alg} differs from {ALGS[0]}"


def _side_of(x, y, box):
    """The box side code (-1..-4) a point lies on, or None."""
    if x == box[0]:
        return -1
    if x == box[2]:
        return -3
    if y == box[1]:
        return -2
    if y == box[3]:
        return -4
    return None
