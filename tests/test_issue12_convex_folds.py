"""Every cell of a ``vf.Convex`` container, interior ones too, checked for folds (issue 12).

docs/exactness.md: "interior cells of a `Convex` are not checked for folds". Here each cell
of diagrams in half-space and hull containers (thin, nearly parallel faces, at UTM-like
offsets) is checked against scipy's ConvexHull of its own vertices: closed (Euler),
outward, every vertex on the inner side of every face of real area (a fold puts a vertex
past one), faces planar, the hull's volume the cell's, and the cells sum to the
container; near the origin, half-space containers' cells against exact Fraction cells.
No fold was found. Two things were wrong and are fixed: ``describe()`` called a cell
non-convex from the rounded normal of a wall's sliver (a hull's nearly coplanar facets at
UTM offsets), and a 1e-9 x 1e-9 x 1e-16 slab at the origin was refused as "0 thick"
(HiGHS's absolute tolerances bounded it; the same slab x 1e3 was built).
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from scipy.spatial import ConvexHull

import voroforge as vf
from reference3d_exact import exact_power_cell

EPS = 2.0**-52
UTM = np.array([500000.0, 4000000.0, 100.0])
CUBE = np.array([[a, b, c] for a in (0, 1) for b in (0, 1) for c in (0, 1)], float) - 0.5


def _cell_problems(d):
    """Cells that are not closed convex outward polyhedra, by their own vertices."""
    cf, lab, area, roff, ring = d.cell_face_table()
    V = np.asarray(d.vertices)
    scale = float(np.abs(V).max())
    probs = []
    for i in range(len(d)):
        f0, f1 = cf[i], cf[i + 1]
        if f0 == f1:
            assert d.volumes[i] == 0
            continue
        rings = [ring[roff[f] : roff[f + 1]] for f in range(f0, f1)]
        edges = {tuple(sorted(e)) for r in rings for e in zip(r, np.roll(r, -1), strict=True)}
        ids = np.unique(np.concatenate(rings))
        if len(ids) - len(edges) + len(rings) != 2:
            probs.append((i, "euler"))
        X = V[ids]
        c0 = X.mean(0)
        size = float(np.ptp(X, 0).max())
        res = 64 * EPS * max(scale, size)  # a few roundings of the coordinates
        for f, r in zip(range(f0, f1), rings, strict=True):
            na = np.linalg.norm(area[f])
            if na <= 1e3 * res * size:
                continue  # a sliver: its normal is rounding
            nrm = area[f] / na
            z = V[r] - c0
            if np.abs((z - z.mean(0)) @ nrm).max() > 4 * res:
                probs.append((i, "face not planar", int(lab[f])))
            if ((X - c0 - z.mean(0)) @ nrm).max() > 4 * res:
                probs.append((i, "a vertex past a face (fold or inward face)", int(lab[f])))
        if size < 1e6 * res:
            continue  # Qhull cannot see a cell a few ulps wide
        Y = (X - c0) / size
        h = ConvexHull(Y)
        rel = res / size
        if abs(h.volume * size**3 - d.volumes[i]) > (1e-9 + 100 * rel) * d.volumes[i]:
            probs.append((i, "volume is not its hull's", d.volumes[i], h.volume * size**3))
        if ((h.equations[:, :3] @ Y.T + h.equations[:, 3:]).max(0) < -4 * rel).any():
            probs.append((i, "a vertex inside its hull (a dent)"))
    return probs


def _sites_in(rows, lo, hi, n, rng):
    """``n`` sites uniform in the half-spaces ``rows`` (rejection in the box ``lo..hi``)."""
    out = np.zeros((0, 3))
    while len(out) < n:
        X = lo + rng.random((8 * n, 3)) * (hi - lo)
        out = np.vstack([out, X[(X @ rows[:, :3].T < rows[:, 3]).all(1)]])
    return out[:n]


def _slab(t, s=1.0):
    """The box ``[0, s]^2 x [0, t]`` as half-spaces."""
    return np.array(
        [[0, 0, 1, t], [0, 0, -1, 0], [1, 0, 0, s], [-1, 0, 0, 0], [0, 1, 0, s], [0, -1, 0, 0]],
        float,
    )


def _container(name, off):
    """``(Convex, lo, hi)``: the container moved by ``off``, and a box around it."""
    rng = np.random.default_rng(11)
    if name == "tangent":  # 20 random tangent planes of the unit sphere
        u = rng.normal(size=(20, 3))
        hs = np.c_[u / np.linalg.norm(u, axis=1)[:, None], np.ones(20)]
        lo, hi = -np.full(3, 3.0), np.full(3, 3.0)
    elif name == "slab":
        hs, lo, hi = _slab(1e-3), np.zeros(3), np.array([1, 1, 1e-3])
    elif name == "wedge":  # two faces 1e-9 rad apart
        a = 1e-9
        hs = _slab(1.0)
        hs[1] = [0, np.sin(a), -np.cos(a), 0]
        lo, hi = np.zeros(3), np.ones(3)
    elif name == "nearly_parallel":  # two oblique faces nearly one plane
        hs = np.array(
            [
                [1, 1, 1, 1.5],
                [1, 1, 1 + 1e-9, 1.5 + 1e-9],
                [-1, 0, 0, 0],
                [0, -1, 0, 0],
                [0, 0, -1, 0],
            ]
        )
        lo, hi = np.zeros(3), np.full(3, 1.5)
    else:  # hulls of points
        pts = rng.normal(size=(60, 3))
        pts /= np.linalg.norm(pts, axis=1)[:, None]
        if name == "thin_hull":
            pts *= [1, 1, 1e-4]
        conv = vf.Convex(points=pts + off)
        return conv, pts.min(0) + off, pts.max(0) + off
    hs = hs.copy()
    hs[:, 3] += hs[:, :3] @ off
    return vf.Convex(halfspaces=hs), lo + off, hi + off


@pytest.mark.parametrize("weighted", [False, True])
@pytest.mark.parametrize("off", [0.0, 1.0])
@pytest.mark.parametrize(
    "name", ["tangent", "slab", "wedge", "nearly_parallel", "hull", "thin_hull"]
)
def test_convex_cells_are_closed_outward_and_convex(name, off, weighted):
    conv, lo, hi = _container(name, off * UTM)
    rng = np.random.default_rng(3)
    P = _sites_in(conv.halfspaces, lo, hi, 100, rng)
    W = rng.random(len(P)) * (conv.volume / len(P)) ** (2 / 3) if weighted else None
    d = vf.voronoi3d(P, conv, weights=W)
    info = d.describe()
    assert info["euler_ok"] and info["convex"] and info["unmatched_vertices"] == 0, info
    assert abs(d.volumes.sum() - conv.volume) <= 1e-12 * conv.volume
    assert _cell_problems(d) == []
    if off == 0 and name in ("tangent", "wedge", "nearly_parallel"):
        # the rows as the cells use them (normalised), exactly
        box = (*(lo - 1), *(hi + 1))
        for i in (0, 1, 2):
            c = exact_power_cell(P, i, box, W, walls=conv.halfspaces)
            assert abs(d.volumes[i] - float(c.volume)) <= 1e-12 * conv.volume / len(P)


def test_thin_slab_at_a_small_scale_is_built():
    """A 1e-9 x 1e-9 x 1e-16 slab at the origin was refused as "0 thick" (HiGHS bounded it
    with absolute tolerances); the same slab x 1e3 was built. Its exact polytope, its cells."""
    hs = _slab(1e-16, 1e-9)
    conv = vf.Convex(halfspaces=hs)
    big = (-1e-8,) * 3 + (1e-8,) * 3
    exact = exact_power_cell(np.zeros((1, 3)), 0, big, walls=hs).volume
    assert exact == Fraction(1e-9) ** 2 * Fraction(1e-16)
    assert abs(conv.volume - float(exact)) <= 4 * EPS * float(exact)
    g = (np.stack(np.meshgrid(*[np.arange(5)] * 2, indexing="ij"), -1).reshape(-1, 2) + 0.5) / 5
    P = np.c_[g * 1e-9, np.full(len(g), 0.5e-16)]
    d = vf.voronoi3d(P, conv)
    info = d.describe()
    assert info["euler_ok"] and info["convex"] and info["cells"] == len(P), info
    assert abs(d.volumes.sum() - conv.volume) <= 1e-12 * conv.volume
    c = exact_power_cell(P, 12, big, walls=hs)
    assert abs(d.volumes[12] - float(c.volume)) <= 1e-12 * float(c.volume)


def test_hull_sliver_wall_is_not_a_fold():
    """A rotated cube's hull at UTM offsets has each face split into two nearly coplanar
    walls; a cell holding a sliver of one (area ~1e-8) was called non-convex from that
    sliver's rounded normal. Its vertices are within ulps of the wall's own row."""
    rng = np.random.default_rng(0)
    R = np.linalg.qr(rng.normal(size=(3, 3)))[0]
    conv = vf.Convex(points=CUBE @ R + UTM)
    g = (np.stack(np.meshgrid(*[np.arange(6)] * 3, indexing="ij"), -1).reshape(-1, 3) + 0.5) / 6
    P = (g - 0.5) @ R + UTM
    W = rng.integers(0, 3, len(P)) / 6**2 / 8
    d = vf.voronoi3d(P, conv, weights=W)
    assert len(conv.halfspaces) > 6  # the faces split
    info = d.describe()
    assert info["euler_ok"] and info["convex"], info["nonconvex_cells"]
    assert _cell_problems(d) == []
    # every cell vertex on the inner side of every wall's row, to ulps of the coordinates
    rows = conv.halfspaces
    V = np.asarray(d.vertices) - UTM
    side = V @ rows[:, :3].T - (rows[:, 3] - rows[:, :3] @ UTM)
    assert side.max() <= 8 * EPS * np.abs(UTM).max()
