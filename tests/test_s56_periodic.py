"""Periodic diagrams of sites on lines, faster passes (issue 15, perlines5).

- The exact pass (:mod:`voroforge.engine.periodic_exact`) finds the ring points and edge
  ends equal to a moved vertex by a table of ``(x bits, y bits, cell)`` rows keyed by a
  64-bit mix (it numbered the bits with ``np.unique``, 0.83 s of 1.6 s on 1e4 sites on a
  slope-2 line). Checked against a dictionary, where the cells asked for are fewer than the
  table's (the old packed key aliased there: an edge end near the grown box's corner kept
  its rounded value while its rings took the exact one).
- Wrapped cells whose pieces touch (a vertical line: every cell as wide as the box) are
  united in one vectorised GEOS call (:mod:`voroforge.engine.periodic_union`): the same
  geometries as one union per cell, and the wrapped cells tile the box.
"""

from __future__ import annotations

import numpy as np
import shapely

import voroforge as vf
import voroforge.engine.periodic as periodic
import voroforge.engine.periodic_exact as pexact
import voroforge.engine.periodic_union as punion

BOX = (0.0, 0.0, 3.0, 2.0)


def _brute(points, cell, old, cells):
    rows = {}
    for i, (p, c) in enumerate(zip(old.tolist(), cells.tolist(), strict=True)):
        for k in c:
            rows[(np.float64(p[0]).tobytes(), np.float64(p[1]).tobytes(), k)] = i
    return np.array(
        [
            rows.get((np.float64(p[0]).tobytes(), np.float64(p[1]).tobytes(), c), -1)
            for p, c in zip(points.tolist(), cell.tolist(), strict=True)
        ],
        dtype=np.int64,
    )


def test_matches_table_against_a_dictionary():
    rng = np.random.default_rng(7)
    old = rng.random((300, 2)) * 3.0
    old[::7, 1] = old[1::7, 1][: len(old[::7])]  # shared y bits
    old[::11, 0] = -0.0  # signed zeros differ from 0.0 in bits
    old = np.unique(old, axis=0)
    m = len(old)
    cells = np.stack([rng.choice(10_000, 3, replace=False) for _ in range(m)])
    cells[::5, 2] = -1  # side points: two cells
    # ring points: some equal to a vertex in one of its cells, some in another cell, others
    pick = rng.integers(0, m, 2000)
    which = rng.integers(0, 3, 2000)
    pts = old[pick].copy()
    cell = cells[pick, which]
    cell[::3] = rng.integers(0, 40, len(cell[::3]))  # fewer cells asked than the table holds
    pts[::13] = rng.random((len(pts[::13]), 2))
    pts[::17, 0] = 0.0
    cell = cell.astype(np.int64)
    want = _brute(pts, cell, old, cells)
    assert (want >= 0).sum() > 500
    table = pexact._table(old, cells)
    assert np.array_equal(pexact._matches(pts, cell, old, cells, table), want)
    assert np.array_equal(pexact._matches(pts, cell, old, cells), want)
    assert np.array_equal(pexact._matches(pts[:0], cell[:0], old, cells), want[:0])
    # only low cells asked (the edges' first cells), the table's reaching 10,000
    cells[:, 0] = rng.integers(0, 40, m)
    low = cells[pick, 0].astype(np.int64)
    want = _brute(old[pick], low, old, cells)
    assert (want >= 0).all()
    assert np.array_equal(pexact._matches(old[pick], low, old, cells), want)


def _line(kind: str, n: int, seed: int = 1) -> np.ndarray:
    t = np.random.default_rng(seed).random(n)
    if kind == "v":
        p = np.column_stack((np.full(n, 1.125), t * 2.0))
    else:
        p = np.column_stack((t * 3.0, np.full(n, 0.75)))
    return np.vstack((p, [[1.234375, 1.5625]]))


def test_united_pieces_as_one_union_per_cell(monkeypatch):
    seen = []

    def checked(merged, rounding):
        out = punion.united_pieces(merged, rounding)
        ref = [punion.one_united(g, rounding) for g in merged]
        for a, b in zip(out, ref, strict=True):
            assert a.geom_type == b.geom_type
            assert np.array_equal(shapely.get_coordinates(a), shapely.get_coordinates(b))
        seen.append(len(merged))
        return out

    monkeypatch.setattr(periodic, "united_pieces", checked)
    for kind in ("v", "h"):
        p = _line(kind, 400)
        d = vf.voronoi(p, BOX, periodic=True, wrap=True)
        assert shapely.is_valid(d.cells).all()
        assert abs(d.areas.sum() - 6.0) <= 1e-14 * 6.0
        # each cell holds its site (the pieces of a strip as wide as the box, united)
        assert shapely.covers(d.cells, shapely.points(p)).all()
    assert sum(seen) > 300


def test_united_pieces_drops_slivers_and_keeps_parts():
    a = shapely.box(0.0, 0.0, 1.0, 1.0)
    b = shapely.box(1.0, 0.0, 2.0, 1.0)
    far = shapely.box(3.0, 0.0, 3.5, 1.0)
    thin = shapely.box(5.0, 0.0, 5.0 + 1e-17, 1.0)
    merged = np.array(
        [
            shapely.MultiPolygon([a, b]),
            shapely.MultiPolygon([a, b, far]),
            shapely.MultiPolygon([a, b, thin]),
        ],
        dtype=object,
    )
    out = punion.united_pieces(merged, 1e-15)
    ref = [punion.one_united(g, 1e-15) for g in merged]
    for got, want in zip(out, ref, strict=True):
        assert shapely.equals(got, want)
    assert out[0].geom_type == "Polygon" and out[0].area == 2.0
    assert out[1].geom_type == "MultiPolygon" and out[1].area == 2.5
    assert out[2].geom_type == "Polygon" and out[2].area == 2.0
