"""Issue 15, periodic sites on one line with one site off it: copies and the chord test.

The margin's proof clears a vertex on an axis where no site's other coordinate falls in the
chord of its empty disk at the margin. A site off a line of sites lies in the chords of the
line's long disks, so it failed every vertex near the box's sides, and its cell, reaching
across the box before the line's copies were in, asked for 1.4 periods along the line: 5.9 n
copies where 3 n are proved. Those few sites' copies past the margin are now measured one
by one (:func:`voroforge.engine.periodic_chord.chord_clear`), and a vertex failing on both
axes while cells are cut off by the grown box waits for the next try.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from test_issue15_periodic import _check_torus
from voroforge.engine.periodic_chord import chord_clear

BOX = (0.0, 0.0, 3.0, 2.0)


def _line_and_one(kind: str, n: int, seed: int):
    rng = np.random.default_rng(seed)
    # dyadic: every copy is an exact shift
    t = np.unique(np.floor(rng.random(n) * 2.0**20) / 2.0**20)
    if kind == "h":
        p = np.column_stack((t * 3.0, np.full(len(t), 0.75)))
    else:
        p = np.column_stack((np.full(len(t), 1.125), t * 2.0))
    return np.vstack((p, [[1.234375, 1.5625]]))


@pytest.mark.parametrize("kind", ["h", "v"])
def test_line_and_one_site_three_copies_and_torus_cells(kind, periodic_builds):
    p = _line_and_one(kind, 300, 3)
    sizes = periodic_builds
    d = _check_torus(p, BOX, "delaunay", False, samples=300)
    # the line and its two copies across it (was 5.9 n: 1.4 periods along the line too),
    # in one build: the line's margins are set up front (periodic_lines; was the line
    # alone first); along the line the plain first margin, 0.48 of the period at 300 sites
    assert len(sizes) == 1 and sizes[0] <= 5 * len(p), sizes
    pairs = {tuple(e) for e in np.asarray(d.edges.pairs).tolist()}
    indptr, idx = d.neighbors
    for i in range(len(p)):
        for j in idx[indptr[i] : indptr[i + 1]].tolist():
            assert i in idx[indptr[j] : indptr[j + 1]].tolist()
            assert (min(i, j), max(i, j)) in pairs
    # the line's cells away from the off site are exact strips a period across the line
    ax = 0 if kind == "h" else 1
    line = np.sort(p[:-1, ax])
    period = BOX[2 + ax] - BOX[ax]
    gap = np.diff(np.r_[line, line[0] + period])
    apart = np.abs(p[:-1, ax] - p[-1, ax])
    far = np.minimum(apart, period - apart) > 0.45 * period  # clear of the off site's cell
    at = np.searchsorted(line, p[:-1, ax])
    width = (gap[at] + np.r_[gap[-1], gap[:-1]][at]) / 2
    across = BOX[3 - ax] - BOX[1 - ax]
    got = d.areas[:-1]
    # exact: the strips' sides are dyadic midpoints, the area one product
    want = np.array([float(Fraction(w) * Fraction(across)) for w in width])
    assert far.sum() > 20
    np.testing.assert_array_equal(got[far], want[far])


def test_chord_clear_measures_the_copies_past_the_margin():
    # box 3 x 2, margin 0.04 on x; a vertex at (0.05, 1.0) whose empty disk has radius 0.5
    side = 3.0
    v = np.array([[0.05, 1.0]])
    r2 = np.array([(0.5 / side) ** 2])
    room = np.array([(0.05 + 0.04) / side])
    slack = 1e-15
    which = np.array([True])

    def clear(site):
        s = np.array([site])
        return bool(chord_clear(v, r2, room, s, BOX, 0, 0.04, side, slack, which)[0])

    # the site's copy at -0.01 is inside the margin (in the diagram); the next, -3.01, is far
    assert clear((2.99, 1.0))
    # the copy at -0.1 is past the margin and 0.15 from the vertex: inside the disk
    assert not clear((2.9, 1.0))
    # past the margin but 0.6 away across the chord: outside (sqrt(0.15^2 + 0.6^2) > 0.5)
    assert clear((2.9, 1.6))
    # no site's y in the chord at all
    assert clear((1.0, 0.2))
