"""Issue 12 (3D exactness): vertices near the origin solved exactly, locate far out."""

from __future__ import annotations

import itertools
import warnings
from fractions import Fraction

import numpy as np
import pytest
from scipy.spatial import cKDTree

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


def _key(*cols, sizes):
    """Rows of small non-negative ints as one int64 each (mixed radix ``sizes``): equal
    rows, equal keys, and the keys sort as the rows do."""
    assert np.prod(np.array(sizes, dtype=float)) < 2.0**62
    out = np.zeros(len(cols[0]), np.int64)
    for c, m in zip(cols, sizes, strict=True):
        assert len(c) == 0 or 0 <= c.min() <= c.max() < m
        out = out * m + c
    return out


def _check_cells(d, box):
    """Euler and closure per cell (by vertex numbers), faces matched from both sides,
    volumes tiling the box, vertices equidistant from their cells, samples in the nearest
    site's cell, describe() clean. Vertices may share coordinates (distinct exact vertices
    closer than the doubles can tell). Every cell, face and ring entry at once (numpy): the
    same checks as one cell at a time."""
    cf, lab, farea, roff, ring = d.cell_face_table()
    cf, roff = np.asarray(cf, np.int64), np.asarray(roff, np.int64)
    lab, ring = np.asarray(lab, np.int64), np.asarray(ring, np.int64)
    V = np.asarray(d.vertices)
    S = np.asarray(d.sites)
    n = len(d)
    lo, hi = np.array(box[:3]), np.array(box[3:])
    size = float((hi - lo).max())
    assert abs(d.volumes.sum() - np.prod(hi - lo)) <= 1e-12 * np.prod(hi - lo)
    # the faces of cells 0..n-1 and their ring entries: cell, face, place in the ring
    fcell = np.repeat(np.arange(n), np.diff(cf))
    face = np.arange(cf[0], cf[n])
    flen = roff[face + 1] - roff[face]
    assert (flen >= 3).all(), (fcell[flen < 3][:3], face[flen < 3][:3])
    efac = np.repeat(np.arange(len(face)), flen)  # face (as a row of `face`) per entry
    k = np.arange(len(efac)) - np.repeat(np.cumsum(flen) - flen, flen)  # place in its ring
    a = ring[roff[face][efac] + k]
    b = ring[roff[face][efac] + (k + 1) % flen[efac]]  # the next vertex round the ring
    ecell = fcell[efac]
    m = len(V)
    assert len(np.unique(_key(efac, a, sizes=(len(face), m)))) == len(a), "a ring repeats a vertex"
    # per cell: its directed edges (a set, as before) closed, and V - E + F = 2
    directed = np.unique(_key(ecell, a, b, sizes=(n, m, m)))
    dc, rest = np.divmod(directed, m * m)
    da, db = np.divmod(rest, m)
    twin = np.isin(_key(dc, db, da, sizes=(n, m, m)), directed)
    assert twin.all(), f"cell {dc[~twin][0]} not closed"
    vc, vv = np.divmod(np.unique(_key(ecell, a, sizes=(n, m))), m)  # each cell's vertices
    nv = np.bincount(vc, minlength=n)
    ne = np.bincount(dc, minlength=n) // 2
    euler = nv - ne + np.diff(cf) == 2
    assert euler.all(), f"cell {np.flatnonzero(~euler)[0]} Euler"
    # each cell's vertices are no farther from its site than from the nearest site (the
    # nearest from a k-d tree, its distance in the same float formula; the tolerance is
    # 1e-9 of the size squared, far above their rounding)
    own = ((V[vv] - S[vc]) ** 2).sum(-1)
    used = np.unique(vv)
    _, near = cKDTree(S).query(V[used], k=min(4, n))
    near = near.reshape(len(used), -1)
    nearest = np.full(len(V), np.inf)
    nearest[used] = ((V[used][:, None, :] - S[near]) ** 2).sum(-1).min(1)
    # the vertices are doubles: an ulp of their coordinates moves them that far
    tol = 1e-9 * size**2 + 8 * size * np.spacing(np.abs(V).max())
    far = ~(own - nearest[vv] <= tol)
    assert not far.any(), f"cell {vc[far][0]} vertex not nearest"
    # faces matched from both sides: (i, j, its vertex set) has (j, i, the same set)
    order = np.lexsort((a, efac))
    keys = [tuple(r.tolist()) for r in np.split(a[order], np.cumsum(flen)[:-1])]
    faces = set(zip(fcell.tolist(), lab[face].tolist(), keys, strict=True))
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
    # every face fanned from its first vertex, the triangles in cell and face order
    fan = np.repeat(np.arange(len(face)), flen - 2)
    t = np.arange(len(fan)) - np.repeat(np.cumsum(flen - 2) - (flen - 2), flen - 2) + 1
    r0 = roff[face][fan]
    tris = np.column_stack((ring[r0], ring[r0 + t], ring[r0 + t + 1]))
    tstart = np.searchsorted(fcell[fan], np.arange(n + 1))
    for q, c in zip(x[clear], d2[clear].argmin(1), strict=True):
        tri = tris[tstart[c] : tstart[c + 1]]
        a_, b_, c_ = ((V[tri[:, m]] - S[c]) - (q - S[c]) for m in range(3))
        la, lb, lc = (np.linalg.norm(e, axis=1) for e in (a_, b_, c_))
        num = (a_ * np.cross(b_, c_)).sum(1)
        den = la * lb * lc + (a_ * b_).sum(1) * lc + (a_ * c_).sum(1) * lb + (b_ * c_).sum(1) * la
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
