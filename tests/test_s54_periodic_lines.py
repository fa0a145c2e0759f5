"""Periodic diagrams of sites on one line and one off it (issue 15, perlines3).

A site off a vertical line cuts the line's cells from its copies a period along the line:
the margin's proof found them past a narrow margin and asked for the margin along the
whole line to grow by 1.6 periods (10 n copies at n = 2,000). Those few sites' copies are
now taken to the caps instead (:func:`voroforge.engine.periodic_chord.shortfall`), and a
cell cut off by the grown box on both axes waits while the line's copies across it come
in. The cells are checked against the torus: areas tile it, clear samples lie in the cell
of their nearest site over the images, neighbours are symmetric, and the areas equal
those of the plain diagram of 5 x 5 copies (a reference that needs no margin).
"""

from __future__ import annotations

import numpy as np
import pytest

from test_issue15_periodic import _check_torus
from voroforge.engine.periodic_chord import chord_clear

from reference import periodic_reference_areas

BOX = (0.0, 0.0, 3.0, 2.0)
OFF = (1.234375, 1.5625)


def _line(kind: str, n: int, seed: int = 1) -> np.ndarray:
    t = np.random.default_rng(seed).random(n)
    if kind == "v":
        p = np.column_stack((np.full(n, 1.125), t * 2.0))
    elif kind == "h":
        p = np.column_stack((t * 3.0, np.full(n, 0.75)))
    else:  # slope 3, inside the box
        x = t * (1.9 / 3.0)
        p = np.column_stack((x, 3.0 * x + 0.05))
    return np.vstack((p, [OFF]))


def _symmetric(d) -> None:
    indptr, idx = d.neighbors
    pairs = set()
    for i in range(len(indptr) - 1):
        for j in idx[indptr[i] : indptr[i + 1]].tolist():
            pairs.add((i, j))
    assert all((j, i) in pairs for i, j in pairs)


@pytest.mark.parametrize("kind", ["v", "h", "s"])
@pytest.mark.parametrize("wrap", [False, True])
def test_line_and_one_torus_cells(kind, wrap):
    p = _line(kind, 300, seed=7)
    d = _check_torus(p, BOX, "delaunay", wrap, samples=200)
    _symmetric(d)
    # the copies here are rounded sums (0.9 + 3.0), and the periodic cells' vertices are
    # tied to their images' (periodic_ties): a long thin cell's area moves by ~1e-11
    np.testing.assert_allclose(d.areas, periodic_reference_areas(p, BOX), rtol=0, atol=1e-10)


def test_vertical_line_and_one_few_copies(periodic_builds):
    # 2,000 random floats on x = 1.125 and one site off it: the line's copies across it
    # and a few cells' height along it (was 10 n copies: 2.3 periods along the line)
    p = _line("v", 2000, seed=1)
    d = _check_torus(p, BOX, "delaunay", False, samples=300)
    _symmetric(d)
    assert max(periodic_builds) <= 4 * len(p), periodic_builds


def test_chord_clear_measures_extra_sites_past_the_cap():
    # the vertex of test_issue15_periodic_lines' chord test: a copy at -0.1 is past the
    # margin 0.04 and inside the disk; with the site's copies in to a cap of 0.5 it is in
    # the diagram, and the next copy past the cap (-3.1) is far
    side = 3.0
    v = np.array([[0.05, 1.0]])
    r2 = np.array([(0.5 / side) ** 2])
    room = np.array([(0.05 + 0.04) / side])
    which = np.array([True])
    s = np.array([[2.9, 1.0]])
    got = []
    assert not chord_clear(v, r2, room, s, BOX, 0, 0.04, side, 1e-15, which, None, got)[0]
    assert got[0].tolist() == [0]
    extra = (np.array([True]), 0.5)
    assert chord_clear(v, r2, room, s, BOX, 0, 0.04, side, 1e-15, which, extra)[0]
    # a cap that does not reach the copy: still measured, still inside
    extra = (np.array([True]), 0.05)
    assert not chord_clear(v, r2, room, s, BOX, 0, 0.04, side, 1e-15, which, extra)[0]
