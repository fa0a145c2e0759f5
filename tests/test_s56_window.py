"""Float circles far out seen through a small window; tiny boxes (issue 15, checker37 F2).

Sites on a float circle of radius ``R`` seen through a unit window at its centre: the box is
far smaller than the sites' ulp, so the cut's interpolated crossings (rounded at the sites'
magnitude) were a visible part of the box and the next cuts decided on them: at ``R = 1e12``
a cell of exact area 3e-9 was lost (a gap), at 1e16 the areas were 2-5e-2 off. The cut now
names each new vertex right after it is made in such a box (``power.box_cell``), and the
half-plane build leaves such cells to it (at 1e17 one cell got the whole box). In a box
below ~1e-270 a box-side crossing off an exact coordinate is still the nearest double
(``sidecross``: underflowed parts are allowed for with a slack).

Checked against the exact cells (Fraction cuts, ``reference.exact_cell``) for every
algorithm: each cell's area within 1e-12 of the box of the exact one, the areas summing to
the box's exactly (Fractions of the float vertices), valid cells.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

import voroforge as vf

from reference import exact_area, exact_cell

ALGS = ["delaunay", "fortune", "halfplane"]


def _ring_area(ring):
    """Area of an exact ring (Fraction vertices)."""
    k = len(ring)
    s = sum(ring[i][0] * ring[(i + 1) % k][1] - ring[(i + 1) % k][0] * ring[i][1] for i in range(k))
    return abs(s) / 2


def _circle(radius, n):
    t = (np.arange(n) + 0.17) * 2 * np.pi / n
    return np.column_stack((radius * np.cos(t), radius * np.sin(t)))


def _check_exact(d, pts, box):
    """Valid cells tiling the box exactly, each within 1e-12 of the box of its exact area."""
    want = (Fraction(box[2]) - Fraction(box[0])) * (Fraction(box[3]) - Fraction(box[1]))
    cells = list(d.cells)
    assert all(c.is_empty or c.is_valid for c in cells)
    got = [exact_area(c) if not c.is_empty else Fraction(0) for c in cells]
    assert sum(got) == want
    for i in range(len(pts)):
        ref = exact_cell(pts, i, box)
        exact = _ring_area(ref) if len(ref) >= 3 else Fraction(0)
        assert abs(float(got[i] - exact)) <= 1e-12 * float(want), i


@pytest.mark.parametrize("alg", ALGS)
@pytest.mark.parametrize(
    ("radius", "box"),
    [
        (1e12, (0.0, 0.0, 1.0, 1.0)),  # a cell of area 3e-9 was lost: a gap
        (1e17, (-0.5, -0.5, 0.5, 0.5)),  # half-plane gave one cell the whole box
        (1e20, (-0.5, -0.5, 0.5, 0.5)),
    ],
)
def test_far_circle_five(alg, radius, box):
    """Five sites on a float circle of radius ``radius`` through a unit window: the exact cells."""
    pts = _circle(radius, 5)
    _check_exact(vf.voronoi(pts, box, algorithm=alg), pts, box)


@pytest.mark.parametrize("alg", ALGS)
def test_far_circle_64_window(alg):
    """64 sites at radius 1e16, the centred window: areas were 1.8e-2 off, Euler failed."""
    pts = _circle(1e16, 64)
    box = (-0.5, -0.5, 0.5, 0.5)
    d = vf.voronoi(pts, box, algorithm=alg)
    _check_exact(d, pts, box)
    assert d.describe().euler_ok


@pytest.mark.parametrize("alg", ALGS)
@pytest.mark.parametrize("w", [1e-260, 1e-280, 1e-300])
def test_tiny_box_crossing(alg, w):
    """Sites (0, 5), (3, 4) in a box ``w`` wide at the origin: bisector ``y = 3 x``.

    Its crossings of the top and bottom sides, ``x = +-w / 3``, are no exact coordinates;
    their exact parts underflow below ~1e-270 (below ~1e-303 the float formula is kept).
    Each is the double nearest the exact one.
    """
    pts = np.array([(0.0, 5.0), (3.0, 4.0)])
    box = (-w, -w, w, w)
    d = vf.voronoi(pts, box, algorithm=alg)
    third = float(Fraction(w) / 3)
    for cell in d.cells:
        xy = {tuple(v) for v in np.asarray(cell.exterior.coords).tolist()}
        assert (third, w) in xy and (-third, -w) in xy
    _check_exact(d, pts, box)
