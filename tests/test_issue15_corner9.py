"""A bisector passing within an ulp of a box corner (issue 15, checker27 F9).

Sites ``(5e5, 4e6 + 0.003)`` and ``(5e5 + 0.003, 4e6)`` in the box ``(5e5 - 0.0005,
4e6 - 0.0005, 5e5 + 0.0035, 4e6 + 0.0035)``: their bisector crosses the right side 2 ulps
below the top right corner and the left side an eighth of an ulp above the bottom left one.
The cut's crossings rounded onto the corners and merged with them; one cell then named the
top side's crossing (an ulp left of the corner: the top side is crossed only past it) and
left a gap of 7e-8 of the box that nothing flagged. Checked against exact geometry
(Fractions): the rings' areas sum to the box's, every vertex off a corner is shared bit for
bit by another ring, and every box corner lies in the ring of an exactly nearest site. The
family: 2-3 sites symmetric about a box diagonal, far from the origin.
"""

from __future__ import annotations

from collections import Counter
from fractions import Fraction

import numpy as np
import pytest

import voroforge as vf

ALGS = ("delaunay", "fortune", "halfplane", "power")


def _area(ring):
    c = [(Fraction(x), Fraction(y)) for x, y in ring]
    return sum(a[0] * b[1] - a[1] * b[0] for a, b in zip(c, c[1:], strict=False)) / 2


def _diagram(alg, pts, box):
    if alg == "power":
        return vf.power(pts, np.full(len(pts), 0.25), box)
    return vf.voronoi(pts, box, algorithm=alg)


def _family():
    """The repro, and inputs of its family (a fixed sample of checker27's scan)."""
    out = [((5e5, 4e6), 0.003, 0.0005, False, False)]
    rng = np.random.default_rng(7)
    for _ in range(14):
        off = tuple(
            float(
                rng.choice([1e3, 5e5, 1e6, 4e6, 1e7]) * rng.choice([1, -1]) + rng.integers(-50, 50)
            )
            for _ in range(2)
        )
        s = 10.0 ** int(rng.integers(-4, 1))
        out.append(
            (
                off,
                int(rng.integers(1, 9)) * s,
                int(rng.integers(1, 5)) * s,
                bool(rng.random() < 0.5),
                bool(rng.random() < 0.5),
            )
        )
    return out


def _input(off, a, h, third, flip):
    box = (off[0] - h, off[1] - h, off[0] + a + h, off[1] + a + h)
    pts = np.array([[off[0], off[1] + a], [off[0] + a, off[1]]])
    if third:
        pts = np.r_[pts, [[off[0] + 0.1 * a, off[1] + 0.1 * a]]]
    if flip:  # the other diagonal
        pts = np.c_[pts[:, 0], box[1] + box[3] - pts[:, 1]]
    return pts, box


def _rings(d):
    out = {}
    for i, c in enumerate(d.cells):
        if not c.is_empty:
            out[i] = [(float(x), float(y)) for x, y in c.exterior.coords]
    return out


@pytest.mark.parametrize("case", range(15))
def test_corner_family_tiles_exactly(case):
    pts, box = _input(*_family()[case])
    corners = [(box[0], box[1]), (box[2], box[1]), (box[2], box[3]), (box[0], box[3])]
    whole = (Fraction(box[2]) - Fraction(box[0])) * (Fraction(box[3]) - Fraction(box[1]))
    exact = [[Fraction(v) for v in p] for p in pts]
    for alg in ALGS:
        rings = _rings(_diagram(alg, pts, box))
        assert all(_area(r) > 0 for r in rings.values()), alg
        assert sum(_area(r) for r in rings.values()) == whole, alg
        seen = Counter(v for r in rings.values() for v in set(r[:-1]))
        lone = [v for v, k in seen.items() if k < 2 and v not in corners]
        assert not lone, (alg, lone)
        for c in corners:
            d2 = [(Fraction(c[0]) - p[0]) ** 2 + (Fraction(c[1]) - p[1]) ** 2 for p in exact]
            near = {i for i, d in enumerate(d2) if d == min(d2)}
            holders = {i for i, r in rings.items() if c in r}
            assert holders & near, (alg, c, holders, near)
