"""A float circle's wedge that crossed itself keeps its site, edge to edge (issue 15, s57).

1025 sites on a circle of radius 1e-7 at (5e5, 4e6), phase 0.90: the Delaunay dual merges
the Voronoi vertices within ~150 ulps of the circle's centre into one, so site 477's wedge
runs its edges with 482 and 475 to that point. Moving the end of the edge with 475 from
its exact vertex (-148.07, -13.0 y-ulps) to the centre turned it across the wedge's other
side (the vertex of 477, 481 and 482, exact y -19.30 ulps, rounds to -19 where the moved
edge passes at -20.25): the ring crossed itself, was emptied as folded, and its gap (the
same bow-tie) stayed open; Euler's count failed and 7 edge ends had no partner. Now the
ring is cut at the crossing and the thin loop goes to 475 (``engine.uncross``). Checked in
the circle's integer frame with exact rationals (no engine code).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import shapely

import voroforge as vf

from reference import holds_exactly

CENTRE = (5e5, 4e6)
UNIT = 2.0**-34  # an x-ulp at 5e5; a y-ulp at 4e6 is 8 units
R = 1e-7
ALGORITHMS = ("delaunay", "fortune", "halfplane")


def _circle(n, phase):
    t = np.arange(n) * (2.0 * np.pi / n) + phase
    return np.column_stack((R * np.cos(t), R * np.sin(t))) + CENTRE


def _local(xy):
    out = (np.asarray(xy, dtype=np.float64) - CENTRE) / UNIT
    assert (out == np.round(out)).all()  # exact: every float here is on the unit grid
    return out.astype(np.int64)


def _area2(ring):
    """Twice the signed area of a closed ring of integer points, exactly."""
    return sum(
        int(a[0]) * int(b[1]) - int(b[0]) * int(a[1])
        for a, b in zip(ring[:-1], ring[1:], strict=True)
    )


@pytest.fixture(scope="module")
def diagrams():
    pts = _circle(1025, 0.90)
    out = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for alg in ALGORITHMS:
            out[alg] = vf.voronoi(pts, None, algorithm=alg)
    return pts, out


@pytest.mark.parametrize("alg", ALGORITHMS)
def test_crossed_wedge_cut_and_cells_edge_to_edge(diagrams, alg):
    pts, ds = diagrams
    d = ds[alg]
    p = _local(pts)
    cells = np.asarray(d.cells, dtype=object)
    nonempty = np.array([c is not None and not c.is_empty for c in cells])
    assert shapely.is_valid(cells[nonempty]).all()
    assert d.describe().euler_ok
    # the wedge's ring holds its site, and it is not flagged
    ring = _local(shapely.get_coordinates(cells[477]))
    assert len(ring) >= 4 and holds_exactly(ring, p[477])
    assert 477 not in set(d.unresolved.tolist())
    # the rings tile the box exactly (integer areas, every ring counter-clockwise) and
    # every edge inside the box is its neighbour's reversed
    lo, hi = _local([d.boundary.bounds[:2], d.boundary.bounds[2:]])
    total = 0
    edges = set()
    for c in cells[nonempty]:
        for part in shapely.get_parts(c):
            r = _local(shapely.get_coordinates(part.exterior))
            if not part.exterior.is_ccw:
                r = r[::-1]
            a2 = _area2(r)
            assert a2 > 0
            total += a2
            edges.update(zip(map(tuple, r[:-1].tolist()), map(tuple, r[1:].tolist()), strict=True))
    assert total == 2 * int(hi[0] - lo[0]) * int(hi[1] - lo[1])

    def on_side(a, b):
        return (a[0] == b[0] and a[0] in (lo[0], hi[0])) or (
            a[1] == b[1] and a[1] in (lo[1], hi[1])
        )

    assert [e for e in edges if not on_side(*e) and e[::-1] not in edges] == []


def test_crossed_wedge_same_cells_every_algorithm(diagrams):
    _, ds = diagrams
    ref = np.asarray(ds["delaunay"].cells, dtype=object)
    for alg in ALGORITHMS[1:]:
        got = np.asarray(ds[alg].cells, dtype=object)
        assert all(
            (a is None or a.is_empty) == (b is None or b.is_empty)
            and (a is None or a.is_empty or a.equals_exact(b, 0.0, normalize=True))
            for a, b in zip(ref, got, strict=True)
        )
