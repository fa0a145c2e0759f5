"""Float circles far out whose fold rounds named a joined class at its edge (issue 15).

The exact Voronoi vertices of n float sites on a circle far from the origin scatter near its
centre over ~``ulp * n**2 / 20`` (the sites' rounding). The fold rounds
(``kernels.folds.unfold_cells``) join classes of triangles there, and a joined class was
named near its best-conditioned member, wherever that lay in the class: at its edge, so the
next rings folded and the next rounds joined more. 1000 sites of radius 1e-3 at (3e4, 1e4),
phase 0.65, ended with one class of 997 of its 998 triangles named 22,000 ulps from the
circle's centre: every cell a triangle with that apex, clear samples 6,231 ulps from their
bisector outside their cells. In the fold rounds' first try a class whose members' own
centres spread far is now named from its middle member (``kernels.refit.middle_member``);
where rings still fold, the rounds run again with the usual names and the better stands
(``kernels.folds.unfold_cells``).

Checked against exact references: every cell vertex lies within a bound of its site's exact
cell (the largest distance past a bisector of the site and any other, exact rationals),
clear samples in their nearest site's cell (brute force), valid, Euler, convex.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import shapely

import voroforge as vf
from test_issue15_neighbours import ALGS, _check, _samples
from voroforge.kernels.delaunay import triangulate_sorted
from voroforge.kernels.refit import middle_member

#: (n, radius, centre, phase): before, the largest vertex distance past its site's exact cell
#: and the clear samples outside (ulps of the centre's largest coordinate)
CASES = {
    # 22,189 ulps (every cell's apex at one vertex), 3 samples up to 6,231 ulps -> 50
    "1000_r1e-3_at_3e4_p0.65": (1000, 1e-3, (3e4, 1e4), 0.65),
    # 1 sample 1,575 ulps from its bisector -> 24
    "1000_r1e-3_at_5e4_p0.35": (1000, 1e-3, (-5e4, 2e4), 0.35),
    # 3 samples up to 376 ulps -> 38
    "257_r1e-5_at_5e4_p0.45": (257, 1e-5, (-5e4, 2e4), 0.45),
}
#: what the cells may reach past their exact cells, in ulps (50 at most in these cases)
BOUND_ULPS = 128.0


def _circle(n, r, centre, phase):
    t = np.arange(n) * (2.0 * np.pi / n) + phase
    return np.column_stack((r * np.cos(t), r * np.sin(t))) + centre


def _past(v, a, i):
    """Float screen: how far each vertex ``v`` lies past a bisector of site ``i`` (local frame)."""
    dj = a - a[i]
    nj = np.sqrt((dj**2).sum(1))
    nj[i] = np.inf
    m = (a + a[i]) / 2
    return (((v[:, None, :] - m[None]) * dj[None]).sum(-1) / nj[None]).max(1)


def _past_exact(v, pts, i):
    """Exact: the largest signed distance of point ``v`` past a bisector of site ``i``.

    ``(|v - p_i|^2 - |v - p_j|^2) / (2 |p_i - p_j|)``, the square root taken in floats of an
    exact rational (a relative error of an ulp of the distance, not of the coordinates).
    """
    vx, vy = Fraction(v[0]), Fraction(v[1])
    px, py = Fraction(pts[i, 0]), Fraction(pts[i, 1])
    best = -np.inf
    for j in range(len(pts)):
        if j == i:
            continue
        qx, qy = Fraction(pts[j, 0]), Fraction(pts[j, 1])
        num = (vx - px) ** 2 + (vy - py) ** 2 - (vx - qx) ** 2 - (vy - qy) ** 2
        if num <= 0 and best >= 0:
            continue
        den2 = 4 * ((px - qx) ** 2 + (py - qy) ** 2)
        best = max(best, float(num) / float(den2) ** 0.5)
    return best


def _largest_past(d, pts, centre):
    """The largest distance (ulps of the centre) of a cell vertex past its exact cell."""
    c = np.asarray(centre, dtype=float)
    a = pts - c  # exact: each coordinate within a factor 2 of the centre's (Sterbenz)
    ulp = np.spacing(np.abs(c).max())
    worst = []
    for i, cell in enumerate(d.cells):
        if cell is None or cell.is_empty:
            continue
        v = shapely.get_coordinates(cell)[:-1]
        s = _past(v - c, a, i)
        k = int(s.argmax())
        worst.append((s[k], i, v[k]))
    worst.sort(key=lambda w: -w[0])
    # the float screen's few largest, exactly (its error is far below an ulp of the centre)
    return max(_past_exact(v, pts, i) for _, i, v in worst[:6]) / ulp


@pytest.mark.parametrize(("n", "r", "centre", "phase"), list(CASES.values()), ids=list(CASES))
def test_far_circle_cells_near_exact(n, r, centre, phase):
    """Every algorithm: valid, tiling, sites and clear samples in their cells, Euler, convex
    (``_check``); every vertex within ``BOUND_ULPS`` of its site's exact cell; the sweep's
    and the half-plane's cells have the default's vertices, bit for bit."""
    pts = _circle(n, r, centre, phase)
    ds = [vf.voronoi(pts, None, algorithm=alg) for alg in ALGS]
    q = _samples(pts, ds[0].boundary, 0)
    for d in ds:
        _check(d, pts, q)
    assert _largest_past(ds[0], pts, centre) <= BOUND_ULPS
    ref = [set(map(tuple, shapely.get_coordinates(c).tolist())) for c in ds[0].cells]
    for d in ds[1:]:
        got = [set(map(tuple, shapely.get_coordinates(c).tolist())) for c in d.cells]
        assert got == ref  # the same vertices, bit for bit (a ring may start elsewhere)


def test_middle_member_names_a_spread_class_from_its_middle():
    """A class of a float circle's triangles spread over many ulps: the member nearest the
    median of the members' own centres (brute force over exact-rational centres); a class
    of one exactly cocircular square (centres equal to rounding) is left to the usual name."""
    pts = _circle(64, 1e-7, (3e4, 1e4), 0.1)
    order, xs, ys, tri, he, _, ok = triangulate_sorted(pts[:, 0].copy(), pts[:, 1].copy())
    assert ok
    rank = np.arange(len(xs))
    mem = np.arange(len(tri) // 3, dtype=np.int64)
    t, x, y = middle_member(xs, ys, tri, mem, rank)
    assert t >= 0

    def centre(k):
        a, b, c = (tri[3 * k + j] for j in range(3))
        ax, ay = Fraction(xs[a]), Fraction(ys[a])
        bx, by = Fraction(xs[b]) - ax, Fraction(ys[b]) - ay
        qx, qy = Fraction(xs[c]) - ax, Fraction(ys[c]) - ay
        den = 2 * (bx * qy - by * qx)
        ux = (qy * (bx * bx + by * by) - by * (qx * qx + qy * qy)) / den
        uy = (bx * (qx * qx + qy * qy) - qx * (bx * bx + by * by)) / den
        return float(ux + ax), float(uy + ay)

    own = np.array([centre(k) for k in mem])
    spread = np.ptp(own[:, 0]) + np.ptp(own[:, 1])
    ulp = np.spacing(3e4)
    assert spread > 64 * ulp
    mid = np.median(own, axis=0)
    dist = np.abs(own - mid).sum(1)
    # its own centre is within rounding (a few ulps) of the exact one, and as near the
    # middle as any member's, to rounding
    assert abs(x - own[t, 0]) + abs(y - own[t, 1]) <= 4 * ulp
    assert dist[t] <= dist.min() + 8 * ulp

    sq = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 3.0]]) + 1e4
    order, xs, ys, tri, he, _, ok = triangulate_sorted(sq[:, 0].copy(), sq[:, 1].copy())
    mem = np.arange(len(tri) // 3, dtype=np.int64)
    two = np.array(
        [
            k
            for k in mem
            if max(xs[tri[3 * k + j]] for j in range(3)) <= 1e4 + 1.0
            and max(ys[tri[3 * k + j]] for j in range(3)) <= 1e4 + 1.0
        ],
        dtype=np.int64,
    )
    assert len(two) == 2
    assert middle_member(xs, ys, tri, two, np.arange(len(xs)))[0] == -1
