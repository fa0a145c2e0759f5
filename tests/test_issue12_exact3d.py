"""Issue 12 (3D exactness): vertices near the origin solved exactly, locate far out."""

from __future__ import annotations

import itertools
import warnings
from fractions import Fraction

import numpy as np
import pytest

import voroforge as vf
from voroforge.kernels.predicates3d import exact_point, scratch


def _sphere(n, seed, r=1.0, off=0.0):
    u = np.random.default_rng(seed).normal(size=(n, 3))
    return off + r * (u / np.linalg.norm(u, axis=1)[:, None])


def _exact_vertex(P, q):
    """The exact circumcentre of sites ``q`` (4 indices) as Fractions, or None (flat)."""
    a = [Fraction(float(c)) for c in P[q[0]]]
    A = [[Fraction(float(P[j][k])) - a[k] for k in range(3)] for j in q[1:]]
    b = [sum(x * x for x in r) / 2 for r in A]

    def det(M):
        return (
            M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1])
            - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0])
            + M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0])
        )

    D = det(A)
    if D == 0:
        return None
    out = []
    for k in range(3):
        M = [row[:] for row in A]
        for r in range(3):
            M[r][k] = b[r]
        out.append(a[k] + det(M) / D)
    return out


def test_exact_point_is_right_to_a_few_ulps_of_itself():
    # 8 float points on the unit sphere: every quadruple's centre lies within ~1e-15 of the
    # origin, where the float solve p0 + y (sites of size 1) keeps none of its digits
    P = _sphere(8, 8)
    W = np.zeros(8)
    WP = np.zeros((0, 4))
    buf = scratch()
    x = np.zeros(3)
    for q in itertools.combinations(range(8), 4):
        e = _exact_vertex(P, q)
        assert exact_point(q[0], q[1], q[2], q[3], P, W, WP, 8, buf, x) == (e is not None)
        if e is None:
            continue
        for k in range(3):
            err = abs(Fraction(float(x[k])) - e[k])
            assert err <= 4 * 2.0**-52 * abs(e[k]), (q, k, float(e[k]), x[k])


def test_exact_point_with_walls_and_weights():
    # a power vertex with one wall row, checked against the float solve where it is exact
    P = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    W = np.array([0.0, 0.25, -0.25])
    WP = np.array([[0.0, 0.0, 1.0, 0.5]])  # z <= 0.5
    x = np.zeros(3)
    assert exact_point(0, 1, 2, 3, P, W, WP, 3, scratch(), x)
    # 2 x . (p_k - p_0) = |p_k|^2 + w_0 - w_k: x = (1 - 0.25) / 2, y = (1 + 0.25) / 2
    assert x.tolist() == [0.375, 0.625, 0.5]


def _exact_nearest(S, q):
    d2 = [sum((Fraction(float(q[k])) - Fraction(float(s[k]))) ** 2 for k in range(3)) for s in S]
    m = min(d2)
    return min(i for i in range(len(S)) if d2[i] == m)


@pytest.mark.parametrize("n", [20, 200])  # the full scan and the k-d tree path
def test_locate_far_queries_no_overflow(n):
    # queries at 1e200 squared to inf: every site was a near tie, with an overflow warning
    g = np.random.default_rng(1)
    S = g.random((n, 3))
    d = vf.voronoi3d(S)
    Q = np.array(
        [[1e200, 0.5, 0.5], [-1e200, 1e200, 0.0], [1e308, 1e308, 1e308], [1e-300, 0.0, 0.7]]
    )
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = d.locate(Q)
    assert got.tolist() == [_exact_nearest(S, q) for q in Q]


def test_locate_far_queries_weighted():
    g = np.random.default_rng(2)
    S = g.random((30, 3))
    W = 0.01 * g.random(30)
    d = vf.voronoi3d(S, weights=W)
    q = np.array([1e250, -3e249, 0.5])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = d.locate(q)
    d2 = [
        sum((Fraction(float(q[k])) - Fraction(float(s[k]))) ** 2 for k in range(3))
        - Fraction(float(w))
        for s, w in zip(S, W, strict=True)
    ]
    assert got == min(range(30), key=lambda i: (d2[i], i))


def _check_cells(d, box):
    """Euler and closure per cell (by vertex numbers), faces matched from both sides,
    volumes tiling the box, vertices equidistant from their cells, samples in the nearest
    site's cell, describe() clean. Vertices may share coordinates (distinct exact vertices
    closer than the doubles can tell)."""
    cf, lab, farea, roff, ring = d.cell_face_table()
    V = np.asarray(d.vertices)
    S = np.asarray(d.sites)
    lo, hi = np.array(box[:3]), np.array(box[3:])
    size = float((hi - lo).max())
    assert abs(d.volumes.sum() - np.prod(hi - lo)) <= 1e-12 * np.prod(hi - lo)
    faces = {}
    for i in range(len(d)):
        f0, f1 = cf[i], cf[i + 1]
        directed, verts = set(), set()
        for f in range(f0, f1):
            r = ring[roff[f] : roff[f + 1]].tolist()
            assert len(r) >= 3 and len(set(r)) == len(r), (i, r)
            directed.update(zip(r, r[1:] + r[:1], strict=True))
            verts.update(r)
            faces[(i, int(lab[f]), tuple(sorted(r)))] = r
        assert all((b, a) in directed for a, b in directed), f"cell {i} not closed"
        assert len(verts) - len(directed) // 2 + (f1 - f0) == 2, f"cell {i} Euler"
        if verts:
            dd = ((V[sorted(verts)][:, None, :] - S[None, :, :]) ** 2).sum(-1)
            own = ((V[sorted(verts)] - S[i]) ** 2).sum(-1)
            # the vertices are doubles: an ulp of their coordinates moves them that far
            tol = 1e-9 * size**2 + 8 * size * np.spacing(np.abs(V).max())
            assert (own - dd.min(1) <= tol).all(), f"cell {i} vertex not nearest"
    for i, j, key in faces:
        if j >= 0:
            assert (j, i, key) in faces, f"face {i}-{j} has no twin"
    # samples whose nearest site is clear lie in its cell: winding number of the cell's
    # surface (faces fanned into triangles, relative to the site), not face planes, whose
    # normals are meaningless on faces thinner than the coordinates' ulps
    x = lo + (hi - lo) * np.random.default_rng(0).random((300, 3))
    d2 = ((x[:, None, :] - S[None, :, :]) ** 2).sum(-1)
    srt = np.sort(d2, axis=1)
    # clear: nearer by 1e-6 of the distance and by more than the vertices' rounding (an
    # ulp of their coordinates: cells 67 ulps wide at 1e8 are drawn to 1.5%)
    ulps = 64 * np.spacing(np.abs(V).max())
    clear = np.sqrt(srt[:, 1]) - np.sqrt(srt[:, 0]) > 1e-6 * np.sqrt(srt[:, 0]) + ulps
    for q, k in zip(x[clear], d2[clear].argmin(1), strict=True):
        tri = [
            (ring[roff[f]], ring[roff[f] + t], ring[roff[f] + t + 1])
            for f in range(cf[k], cf[k + 1])
            for t in range(1, roff[f + 1] - roff[f] - 1)
        ]
        a, b, c = ((V[np.array(tri)[:, m]] - S[k]) - (q - S[k]) for m in range(3))
        la, lb, lc = (np.linalg.norm(e, axis=1) for e in (a, b, c))
        num = (a * np.cross(b, c)).sum(1)
        den = la * lb * lc + (a * b).sum(1) * lc + (a * c).sum(1) * lb + (b * c).sum(1) * la
        wind = 2 * np.arctan2(num, den).sum() / (4 * np.pi)
        assert abs(wind - 1) < 1e-6, f"a sample lies outside its nearest site's cell ({wind})"
    r = d.describe()
    assert r["euler_ok"] and r["convex"] and r["unmatched_vertices"] == 0, r


@pytest.mark.parametrize(
    ("n", "seed", "r", "off", "centre"),
    [
        (8, 8, 1.0, 0.0, False),  # docs/exactness.md: faces pinched at a vertex
        (50, 50000, 1e-3, 0.0, False),
        (50, 50000, 1e-3, 100.0, False),
        (50, 50000, 1.0, 100.0, False),
        (50, 3, 1e-3, 1e4, True),
        (20, 4, 1.0, 1e8, True),
    ],
)
def test_float_sphere_cells_are_valid(n, seed, r, off, centre):
    # float points on a sphere are only nearly co-spherical: the exact diagram has several
    # vertices within rounding of the centre; near the origin the float solve scrambled
    # them (solved exactly now), far from it they round to the same doubles (kept apart by
    # their names now); merging them pinched the cells' faces (Euler per cell failed)
    S = _sphere(n, seed, r, off)
    if centre:
        S = np.vstack([S, [[off, off, off]]])
    box = (off - 2 * r,) * 3 + (off + 2 * r,) * 3
    _check_cells(vf.voronoi3d(S, box), box)


def test_fcc_lattice_at_1e8_volumes_and_euler():
    # FCC of step 4/3 at 1e8: its octahedral holes are co-spherical only to rounding, four
    # exact vertices 1e-8 apart where an ulp is 1.5e-8; the coordinate merge moved one onto
    # another (volumes off by 1.06e-8) and repeated it in rings
    def lattice(k, step):
        a = np.arange(k) * step
        return np.stack(np.meshgrid(a, a, a, indexing="ij"), -1).reshape(-1, 3)

    st, off = 4 / 3, 1e8
    shifts = ([0, 0, 0], [st / 2, st / 2, 0], [st / 2, 0, st / 2], [0, st / 2, st / 2])
    P = np.concatenate([lattice(3, st) + off + np.array(s) for s in shifts]) + 0.3
    box = (off,) * 3 + (off + 4,) * 3
    d = vf.voronoi3d(P, box)
    _check_cells(d, box)
    # the same sites moved exactly to the origin: the same cells
    d0 = vf.voronoi3d(P - off, (0, 0, 0, 4, 4, 4))
    assert np.allclose(d.volumes, d0.volumes, rtol=0, atol=1e-12)
