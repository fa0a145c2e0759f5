"""Whether a power cell is empty, decided exactly (integers), for sites float64 lost.

In a cluster a few ulps of its coordinates wide a power cell can be narrower than an ulp:
the checked path's rings then come out empty, whether or not the site has a cell. A site
has a cell in the box exactly when the box cut by its power bisectors keeps some area.
:func:`lost_sites` decides that in integer arithmetic (every float is a dyadic rational:
scaled by one power of two, coordinates and weights are integers), with the bisectors of
the sites nearest in power first: a cut by fewer bisectors is a superset of the cell, so
an empty one proves the cell empty; a non-empty one gives an interior point, and the cell
is non-empty when no site beats the cell's own there (every site is checked, in floats
with a bound, exactly where the bound cannot decide). A site that beats it joins the cut.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
from scipy.spatial import cKDTree

from ..config import POWER_EXACT_FILTER_ULPS, POWER_EXACT_FIRST, POWER_EXACT_ROUNDS
from ..kernels.predicates import orient2d

_EPS = float(np.finfo(float).eps)


def _scale(values, squared) -> int:
    """An exponent ``s`` that makes ``values * 2**s`` and ``squared * 4**s`` integers.

    A nonzero float ``m 2**e`` (``0.5 <= |m| < 1``, 53 bits) has at most ``53 - e`` binary
    digits after the point.
    """
    v = np.asarray(values, dtype=np.float64)
    q = np.asarray(squared, dtype=np.float64)
    s = int((53 - np.frexp(v[v != 0.0])[1]).max(initial=0))
    return max(s, int(((54 - np.frexp(q[q != 0.0])[1]) // 2).max(initial=0)))


def _int(v: float, s: int) -> int:
    """``v * 2**s`` as an integer (exact: ``s`` is large enough)."""
    num, den = float(v).as_integer_ratio()
    return (num << s) // den


def _line(xi, yi, wi, xj, yj, wj):
    """Integer half-plane ``a X + b Y <= c`` of cell ``i`` against site ``j`` (scaled)."""
    return (2 * (xj - xi), 2 * (yj - yi), xj * xj + yj * yj - xi * xi - yi * yi + wi - wj)


def _vertex(l1, l2):
    """Homogeneous ``(X, Y, D)``, ``D > 0``, of the crossing of two lines (not parallel)."""
    a1, b1, c1 = l1
    a2, b2, c2 = l2
    d = a1 * b2 - a2 * b1
    x = c1 * b2 - c2 * b1
    y = a1 * c2 - a2 * c1
    return (x, y, d) if d > 0 else (-x, -y, -d)


def _cut(lines, line):
    """Convex polygon (its edges' lines, counter-clockwise) cut by ``line``; [] if no area.

    A line every vertex satisfies changes nothing; one no vertex is strictly inside of
    leaves no area.
    """
    m = len(lines)
    a, b, c = line
    val = []
    for k in range(m):
        x, y, d = _vertex(lines[k - 1], lines[k])  # vertex k starts edge k
        val.append(a * x + b * y - c * d)
    if all(v <= 0 for v in val):
        return lines
    if all(v >= 0 for v in val):
        return []
    # edge k (vertex k to k + 1) keeps a part when one of its ends is strictly inside;
    # the new line follows the kept edge that leaves the half-plane (one, by convexity)
    keep = [min(val[k], val[(k + 1) % m]) < 0 for k in range(m)]
    out = []
    for k in range(m):
        if keep[k]:
            out.append(lines[k])
            if val[(k + 1) % m] > 0 or not keep[(k + 1) % m]:
                out.append(line)
    return out


class _Exact:
    """The sites scaled to integers (as needed), and the cut of one site's box."""

    def __init__(self, x, y, w, box, ids):
        self.s = _scale(np.concatenate((x[ids], y[ids], box)), w[ids])
        self.xs, self.ys, self.ws = x, y, w
        self.x, self.y, self.w = {}, {}, {}
        x0, y0, x1, y1 = (_int(v, self.s) for v in box)
        self.box = [(0, -1, -y0), (1, 0, x1), (0, 1, y1), (-1, 0, -x0)]

    def site(self, i):
        """Scaled integer coordinates and weight of site ``i``."""
        if i not in self.x:
            self.x[i] = _int(self.xs[i], self.s)
            self.y[i] = _int(self.ys[i], self.s)
            self.w[i] = _int(self.ws[i], 2 * self.s)
        return self.x[i], self.y[i], self.w[i]

    def cell(self, i, others):
        """Lines of cell ``i`` cut by ``others`` (empty list: no area)."""
        lines = self.box
        xi, yi, wi = self.site(i)
        for j in others:
            j = int(j)
            if j == i:
                continue
            lines = _cut(lines, _line(xi, yi, wi, *self.site(j)))
            if not lines:
                return lines
        return lines

    def inside(self, lines):
        """An interior point of the polygon, unscaled (the mean of its vertices)."""
        sx = sy = Fraction(0)
        for k in range(len(lines)):
            x, y, d = _vertex(lines[k - 1], lines[k])
            sx += Fraction(x, d)
            sy += Fraction(y, d)
        m = len(lines) * 2**self.s
        return sx / m, sy / m

    def beats(self, i, j, q):
        """Whether site ``j``'s power distance at ``q`` is at most site ``i``'s (exactly)."""
        s = 2**self.s
        a, b, c = _line(*self.site(i), *self.site(j))
        return a * q[0] * s + b * q[1] * s - c >= 0


def _rivals(x, y, w, ids, i, q):
    """Sites of ``ids`` that beat or tie site ``i`` at ``q`` (floats with a bound, then exact).

    Returns the sites that surely beat it and those the bound cannot decide.
    """
    ux = float(q[0] - Fraction(float(x[i])))
    uy = float(q[1] - Fraction(float(y[i])))
    dx = x[ids] - x[i]
    dy = y[ids] - y[i]
    d2 = dx * dx + dy * dy
    # power distance of j minus that of i at q: -2 d.u + |d|^2 + w_i - w_j
    val = -2.0 * (dx * ux + dy * uy) + d2 + (w[i] - w[ids])
    mag = 2.0 * np.sqrt(d2) * np.hypot(ux, uy) + d2 + abs(w[i]) + np.abs(w[ids])
    bound = POWER_EXACT_FILTER_ULPS * _EPS * mag
    other = ids != i
    # not finite (squares overflowed): the exact test decides
    return ids[other & (val < -bound)], ids[other & ~(np.abs(val) > bound)]


def has_cell(i, x, y, w, exact, ids, tree, top):
    """Whether site ``i`` has a power cell of positive area in ``box`` (exact).

    ``ids`` are the sites that may have a cell, ``exact`` their integers (and the box's),
    ``tree`` a KD-tree of them lifted to ``(x, y, sqrt(top - w))`` (power distances are its
    squared distances).
    """
    k = min(len(ids), POWER_EXACT_FIRST + 1)
    near = tree.query((x[i], y[i], np.sqrt(top - w[i])), k=k)[1]
    cand = list(dict.fromkeys(int(j) for j in ids[np.atleast_1d(near)]))
    for _ in range(POWER_EXACT_ROUNDS):
        lines = exact.cell(i, cand)
        if not lines:
            return False
        q = exact.inside(lines)
        sure, unsure = _rivals(x, y, w, ids, i, q)
        more = [int(j) for j in sure] + [int(j) for j in unsure if exact.beats(i, int(j), q)]
        if not more:
            return True
        cand += [j for j in more if j not in cand]
    return bool(exact.cell(i, ids.tolist()))


def lost_sites(x, y, w, box, active, rows):
    """The sites of ``rows`` (their rings came out empty) that have a cell in ``box``.

    ``active`` are the sites that may have a cell at all (duplicates and sites hidden by
    :func:`~voroforge.engine.power._may_win` have none).
    """
    rows = np.asarray(rows, dtype=np.int64)
    if not len(rows):
        return rows
    ids = np.flatnonzero(active)
    top = float(w[ids].max())
    tree = cKDTree(np.column_stack((x[ids], y[ids], np.sqrt(top - w[ids]))))
    exact = _Exact(x, y, w, np.asarray(box, dtype=np.float64), ids)
    keep = [has_cell(int(i), x, y, w, exact, ids, tree, top) for i in rows.tolist()]
    return rows[np.array(keep, dtype=bool)]


def on_one_line(px, py, far):
    """Whether every site lies on the line through sites ``0`` and ``far`` (exact).

    The frame's ``(u, v)`` can round distinct sites onto one point (a cluster 1e-12 wide
    at the origin in a frame 1e6 wide): their exact turn decides.
    """
    ax, ay, bx, by = px[0], py[0], px[far], py[far]
    c = (px - ax) * (by - ay) - (py - ay) * (bx - ax)
    return all(orient2d(ax, ay, bx, by, px[k], py[k]) == 0.0 for k in np.flatnonzero(c != 0.0))


# the integer machinery, public for :mod:`voroforge.engine.restore` (exact Voronoi cells of
# the sites every construction lost); unchanged here
Exact = _Exact
line = _line
vertex = _vertex
