"""Periodic diagrams of sites on an axis-parallel line, in one build (issue 15, perlines6).

- Sites on a line across the box make cells half a period across the line: the first try,
  whose margins held only the line, failed on every cell and was a whole build thrown away.
  :func:`voroforge.engine.periodic_lines.line_start` reads the line from the sites'
  extent per axis and starts with the line's copies a period over on both sides and room
  along it for the off sites' cells (their copies to the caps): one build. The proof
  decides as before; the cells are checked against the torus (nearest of the images), the
  plain diagram of 5 x 5 copies, and the box's area.
- The wrapped cells' rings are gathered in one step (``periodic._wrapped_cells``): checked
  bit for bit against the per-ring loop it replaces.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely

import voroforge.engine.periodic as periodic
from test_issue15_periodic import _check_torus
from voroforge.config import PERIODIC_EXTRA_SITES
from voroforge.engine.periodic_lines import line_start

from reference import periodic_reference_areas

BOX = (0.0, 0.0, 3.0, 2.0)
OFF = (1.234375, 1.5625)


def _line(kind: str, n: int, seed: int = 1, off=(OFF,)) -> np.ndarray:
    t = np.random.default_rng(seed).random(n)
    if kind == "v":
        p = np.column_stack((np.full(n, 1.125), t * 2.0))
    elif kind == "h":
        p = np.column_stack((t * 3.0, np.full(n, 0.75)))
    else:  # slope 2, inside the box
        x = t * 0.95
        p = np.column_stack((x, 2.0 * x + 0.1))
    return np.vstack((p, np.array(off, dtype=float).reshape(-1, 2)))


def _start(p):
    margins = periodic._margins(BOX, len(p))
    caps = periodic._caps(BOX)
    return line_start(p, BOX, margins, caps, PERIODIC_EXTRA_SITES), margins


@pytest.mark.parametrize("kind", ["v", "h"])
def test_line_start_reads_an_axis_line(kind):
    p = _line(kind, 500, off=(OFF, (2.5, 0.25)))
    (got, off), plain = _start(p)
    k = 0 if kind == "v" else 1  # the axis across the line
    period = BOX[2 + k] - BOX[k]
    line = p[0, k]
    # the line's copies a period over on both sides are inside the grown box
    assert BOX[k] - got[k] <= line - period and line + period <= BOX[2 + k] + got[k]
    assert got[k] < periodic._caps(BOX)[k]
    # along the line: at least the plain margin, below the cap
    assert plain[1 - k] <= got[1 - k] <= periodic._caps(BOX)[1 - k]
    assert np.flatnonzero(off).tolist() == [500, 501]


def test_line_start_leaves_other_inputs():
    rng = np.random.default_rng(3)
    assert _start(rng.random((500, 2)) * [3.0, 2.0])[0] is None  # uniform
    assert _start(_line("s", 500))[0] is None  # a sloped line
    assert _start(_line("v", 40))[0] is None  # too few to matter
    # more sites off the line than may have their copies to the caps
    p = _line("v", 500, off=rng.random((PERIODIC_EXTRA_SITES + 1, 2)) * [3.0, 2.0])
    assert _start(p)[0] is None


@pytest.mark.parametrize("kind", ["v", "h"])
@pytest.mark.parametrize("wrap", [False, True])
def test_line_and_one_in_one_build(kind, wrap, periodic_builds):
    p = _line(kind, 1000, seed=5)
    d = _check_torus(p, BOX, "delaunay", wrap, samples=200)
    assert len(periodic_builds) == 1, periodic_builds
    # the line and its two copies across it, a few cells' height along it
    assert periodic_builds[0] <= 4 * len(p), periodic_builds
    np.testing.assert_allclose(d.areas, periodic_reference_areas(p, BOX), rtol=0, atol=1e-10)
    assert abs(d.areas.sum() - 6.0) <= 1e-14 * 6.0


def test_two_lines_take_the_plain_tries(periodic_builds):
    # two vertical lines: no band holds all but a few sites, the plain first margins
    p = np.vstack((_line("v", 200, seed=2, off=()), _line("v", 200, seed=3, off=()) + [1.0, 0.0]))
    assert _start(p)[0] is None
    _check_torus(p, BOX, "delaunay", False, samples=200)


def _loop_cells(d, pieces, source, n):
    """The per-ring loop ``_wrapped_cells`` used: the reference of its single-ring path."""
    inside, cross, cut = pieces
    live = ~shapely.is_empty(cut)
    keep = np.sort(np.concatenate((inside, cross[live])))
    coords, (ring, poly, geom) = d.to_geoarrow()
    xy = [None] * len(keep)
    where = np.searchsorted(keep, inside)
    for j, a, b in zip(where, ring[poly[geom[inside]]], ring[poly[geom[inside + 1]]], strict=True):
        xy[j] = coords[a:b]
    for j, c in zip(np.searchsorted(keep, cross[live]), cut[live], strict=True):
        xy[j] = shapely.get_coordinates(shapely.get_exterior_ring(c))
    order = np.argsort(source[keep], kind="stable")
    rings = [xy[j] for j in order]
    counts = np.bincount(source[keep], minlength=n)
    return rings, counts, keep


@pytest.mark.parametrize("kind", ["s", "u"])
def test_wrapped_cells_gather_equals_the_loop(kind, monkeypatch):
    # a sloped line and uniform sites: no cell borders its own image (the one-ring path)
    rng = np.random.default_rng(9)
    p = _line(kind, 300, seed=9) if kind == "s" else rng.random((300, 2)) * [3.0, 2.0]
    seen = []
    real = periodic._wrapped_cells

    def spy(d, pieces, source, n, rounding):
        got = real(d, pieces, source, n, rounding)
        pairs = d.edges.pairs
        assert not (source[pairs[:, 0]] == source[pairs[:, 1]]).any()
        seen.append((got, _loop_cells(d, pieces, source, n)))
        return got

    monkeypatch.setattr(periodic, "_wrapped_cells", spy)
    periodic.periodic_voronoi(p, BOX, wrap=True)
    assert len(seen) == 1
    ((coords, ring, poly, geom), keep), (rings, counts, want_keep) = seen[0]
    assert np.array_equal(keep, want_keep)
    assert np.array_equal(poly, np.arange(len(ring)))
    assert np.array_equal(np.diff(geom), counts)
    assert np.array_equal(np.diff(ring), [len(r) for r in rings])
    assert np.array_equal(coords, np.concatenate(rings))
