"""Issue 15, the half-plane algorithm on long lines: the k-d search's stop test.

A cell of a site on a long line is a strip to the box: its far vertices are far from the
site, and the line's sites at distance ``s`` along it pass within ``s^2 / 2`` of those
vertices' circles. The stop test per k-d bucket (``halfplane._node_clear``) now has an
absolute margin (the float cut's vertex error) instead of one relative to the cell, which
kept sites in proportion to ``n``. These inputs check that no bucket holding a site that
cuts (or that the exact finishing needs) is cleared: every algorithm passes the invariants
and the half-plane cells are the default's.

Every check is an invariant (valid cells, tiling, clear samples in their nearest site's
cell, Euler and convexity, the three algorithms agreeing), never a snapshot.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely

import voroforge as vf
from test_issue15_halfplane import _check
from voroforge.kernels import halfplane as hp

ALGS = ["delaunay", "fortune", "halfplane"]


def _agree(pts, boundary):
    """Every algorithm passes the invariants; each half-plane cell is the default's (their
    symmetric difference is below 1e-9 of its area: the strips' vertices may differ in bits)."""
    ds = {alg: vf.voronoi(pts, boundary, algorithm=alg) for alg in ALGS}
    for d in ds.values():
        _check(d, pts)
    a = ds["delaunay"]
    for alg in ("fortune", "halfplane"):
        d = ds[alg]
        assert set(d.unresolved.tolist()) == set(a.unresolved.tolist())
        ea = shapely.is_empty(np.asarray(a.cells, dtype=object))
        ed = shapely.is_empty(np.asarray(d.cells, dtype=object))
        assert (ea == ed).all(), (alg, np.flatnonzero(ea != ed)[:10])
        both = np.flatnonzero(~ea)
        sd = shapely.area(
            shapely.symmetric_difference(
                np.asarray(a.cells, dtype=object)[both], np.asarray(d.cells, dtype=object)[both]
            )
        )
        bad = sd > 1e-9 * a.areas[both]
        assert not bad.any(), (alg, both[bad][:10], sd[bad][:10])
    return ds


def _uses_tree(pts):
    return len(hp._search_grid(pts[:, 0].copy(), pts[:, 1].copy())[2][0]) > 1


def _line(n, slope, off=(0.0, 0.0), length=1.0):
    t = np.linspace(0.0, length, n)
    return np.column_stack((t, slope * t)) + np.asarray(off)


@pytest.mark.parametrize(
    ("slope", "n", "other", "box"),
    [
        (0.0, 10000, (0.5, 0.1), (-0.5, -0.5, 1.5, 1.5)),  # bench_growth's collinear
        (1e-3, 3000, (0.2, 0.9), (-1.0, -1.0, 2.0, 2.0)),
        (0.5, 4000, (0.2, 0.9), (-1.0, -1.0, 2.0, 2.0)),  # bench_growth's sloped
        (-0.25, 3000, (0.7, -0.9), (-1.0, -1.0, 2.0, 1.0)),
        (0.5, 3000, (0.2, 0.9), (-3.0, -0.2, 5.0, 1.2)),  # a wide, low box
    ],
)
def test_line_plus_one(slope, n, other, box):
    """A line (k-d buckets) and one site off it: every cell is the default's."""
    pts = np.concatenate((_line(n, slope), [other]))
    assert _uses_tree(pts)
    _agree(pts, box)


@pytest.mark.parametrize(("slope", "n", "seed"), [(0.0, 3000, 1), (0.5, 3000, 2), (1e-3, 4000, 3)])
def test_line_plus_others(slope, n, seed):
    """A line across the unit box and 1% random sites (the README's 100,000 on a line plus
    1,000 others, smaller): the strips end at the other sites' cells."""
    pts = _line(n, slope, (0.0, 0.5 - 0.5 * slope))
    others = np.random.default_rng(seed).random((n // 100, 2))
    pts = np.concatenate((pts, others))
    assert _uses_tree(pts)
    _agree(pts, (0.0, 0.0, 1.0, 1.0))


@pytest.mark.parametrize(
    ("off", "length", "box"),
    [
        # far from the origin: the margin grows with the coordinates (the named vertices'
        # rounding), the strips are long against the spacing
        ((5e5, 4e6), 1.0, (5e5 - 1.0, 4e6 - 1.0, 5e5 + 2.0, 4e6 + 2.0)),
        # a short line in a big box: strips 3e-10 wide and 1 long
        ((0.3, 0.4), 1e-6, (0.0, 0.0, 1.0, 1.0)),
    ],
)
def test_line_far_and_short(off, length, box):
    """Coordinates large against the line, or a line tiny against the box."""
    pts = np.concatenate((_line(3000, 0.5, off, length), [[off[0], off[1] + 0.5 * length]]))
    assert _uses_tree(pts)
    _agree(pts, box)


def test_line_with_ulp_jitter():
    """Sites a few ulps off the line (alternately above and below): the bisectors of
    neighbours are nearly parallel to each other's, their crossings far out ill-conditioned."""
    pts = _line(3000, 0.5)
    pts[:, 1] = np.nextafter(pts[:, 1], np.where(np.arange(3000) % 2, 1.0, -1.0))
    pts = np.concatenate((pts, [[0.2, 0.9]]))
    assert _uses_tree(pts)
    _agree(pts, (-1.0, -1.0, 2.0, 2.0))


def test_crossing_lines():
    """Two lines crossing (an X): strips of both meet near the crossing."""
    a = _line(2000, 0.5, (0.0, 0.25))
    b = _line(2000, -2.0, (0.3, 1.0), 0.5)
    pts = np.unique(np.concatenate((a, b)), axis=0)
    assert _uses_tree(pts)
    _agree(pts, (-1.0, -1.0, 2.0, 2.0))
