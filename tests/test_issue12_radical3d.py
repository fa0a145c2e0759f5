"""Power (radical) cells in 3D against exact Fraction cells and voro++ -r (issue 12).

docs/exactness.md listed "a light weight among heavy ones: voro++ -r disagrees with our
volumes there by up to 0.975, not checked which is right". Neither was wrong: with ``-r``
and no custom format voro++ writes ``id x y z volume radius``, and the benchmark read the
last column (the radius, ``sqrt(0.95) = 0.9747`` less a cell's volume). Read as volumes
(``-c "%i %v"``, ``reference3d.voropp_volumes``) the two agree to voro++'s six printed
digits, and sampled cells of that 20,000-site case agree with exact cells to 7e-16
(worst 4.9e-6 for voro++'s printing). Here the same case, smaller, and weights fuzzed
against :func:`reference3d_exact.exact_power_cell` (every radical plane cut exactly).
"""

from __future__ import annotations

import os
import subprocess
import tempfile
from fractions import Fraction

import numpy as np
import pytest

import voroforge as vf
from reference3d import VOROPP, voropp_volumes
from reference3d_exact import area_vector, exact_power_cell

BOX = (0.0, 0.0, 0.0, 1.0, 1.0, 1.0)
EPS = 2.0**-52


def _light(n, many, seed=7):
    rng = np.random.default_rng(seed)
    w = np.ones(n)
    w[: max(1, n // 100) if many else 1] = 0.05
    return rng.random((n, 3)), w


def _width(ring) -> float:
    """Twice the area over the diameter: how thin an exact face is."""
    a = float(sum(x * x for x in area_vector(ring))) ** 0.5 / 2
    R = np.array([[float(x) for x in v] for v in ring])
    dia = float(np.linalg.norm(R[:, None] - R[None], axis=2).max())
    return 0.0 if dia == 0 else a / dia


def _check_cells(P, W, box, cells=None):
    """Cells ``cells`` (default all) of ``voronoi3d(P, box, weights=W)`` against exact ones.

    Empty exactly where the exact cell is; volumes within 1e-12 of the larger of the cell
    and the mean cell (rounded vertices: a sliver's own volume is only good to its
    vertices' ulps); neighbours: each one a site whose exact face has positive area (or a
    site whose plane coincides with it), and every exact face wider than a few ulps of the
    coordinates among them. Returns the exact cells.
    """
    d = vf.voronoi3d(P, box, weights=W)
    ip, ix = d.neighbors
    box = tuple(float(x) for x in box)
    vol = (box[3] - box[0]) * (box[4] - box[1]) * (box[5] - box[2])
    res = 16 * EPS * max(np.abs(box).max(), np.abs(P).max())
    out = []
    for i in range(len(P)) if cells is None else cells:
        c = exact_power_cell(P, i, box, W)
        ours = set(ix[ip[i] : ip[i + 1]].tolist())
        assert (c.volume == 0) == (d.volumes[i] == 0), (i, float(c.volume), d.volumes[i])
        tol = 1e-12 * max(float(c.volume), vol / len(P))
        assert abs(d.volumes[i] - float(c.volume)) <= tol, (i, float(c.volume), d.volumes[i])
        sets = [s for s in c.neighbour_sets() if min(s) >= 0]
        assert all(any(j in s for s in sets) for j in ours), (i, ours, sets)
        need = [lab for lab, ring in c.faces if min(lab) >= 0 and _width(ring) > res]
        assert all(lab & ours for lab in need), (i, ours, need)
        out.append(c)
    return d, out


@pytest.mark.skipif(VOROPP is None, reason="voro++ not installed")
def test_voropp_radical_default_output_ends_with_the_radius():
    """The benchmark's 0.975: voro++ -r's default line is ``id x y z volume radius``."""
    P, W = _light(40, many=False)
    rad = np.sqrt(W - W.min())
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "pts")
        with open(path, "w") as fh:
            for k, (x, y, z) in enumerate(P):
                fh.write(f"{k} {float(x)!r} {float(y)!r} {float(z)!r} {float(rad[k])!r}\n")
        subprocess.run([VOROPP, "-o", "-r", "0", "1", "0", "1", "0", "1", path], check=True)
        rows = np.loadtxt(path + ".vol")
    # one row per non-empty cell (the light site's cell is empty, and has no row)
    assert rows.shape == (39, 6) and 0 not in rows[:, 0]
    k = rows[:, 0].astype(int)
    np.testing.assert_allclose(rows[:, 5], rad[k], rtol=1e-5)  # the radius, last
    vol = vf.voronoi3d(P, BOX, weights=W).volumes
    np.testing.assert_allclose(rows[:, 4], vol[k], rtol=1e-5, atol=1e-12)  # then the volume
    assert np.abs(rows[:, 5] - vol[k]).max() > 0.9  # the reported disagreement, rebuilt


@pytest.mark.parametrize("many", [False, True])
def test_light_among_heavy_exact_and_voropp(many):
    """One (or 1%) of weight 0.05 among weight 1: the light cells are empty, the rest are
    the heavy sites' Voronoi cells; sampled cells exact, all cells as voro++ -r prints."""
    P, W = _light(400, many)
    rng = np.random.default_rng(1)
    near = np.argsort(((P - P[0]) ** 2).sum(1))[:4]  # the light site and its nearest
    cells = sorted({*near.tolist(), *rng.choice(len(P), 4, replace=False).tolist()})
    d, ex = _check_cells(P, W, BOX, cells)
    assert ex[cells.index(0)].empty
    assert (d.volumes[W < 1] == 0).all() and (d.volumes[W == 1] > 0).all()
    assert d.volumes.sum() == pytest.approx(1.0, rel=1e-13)
    if VOROPP is not None:
        v = voropp_volumes(P, BOX, weights=W)
        np.testing.assert_allclose(v, d.volumes, rtol=5e-6, atol=1e-12)


def _slabs(k):
    """Lines of three sites along x; the middle weight makes its cell the plane x = 1/2
    (zero volume, ``w = -1/16``) or empty (a little lighter)."""
    yz = (np.stack(np.meshgrid(np.arange(k), np.arange(k), indexing="ij"), -1).reshape(-1, 2)) / k
    yz = yz + 0.5 / k
    P = np.vstack([np.c_[np.full(len(yz), x), yz] for x in (0.25, 0.5, 0.75)])
    W = np.zeros(len(P))
    return P, W, slice(len(yz), 2 * len(yz))


def _family(name, n, rng):
    s2 = n ** (-2 / 3)  # the squared spacing
    P = rng.random((n, 3))
    if name == "equal":
        return P, np.full(n, 0.3)
    if name == "dominant":
        W = np.zeros(n)
        W[rng.integers(n)] = 1.0
        return P, W
    if name == "big_spread":  # weights 1e-12..1e12 of the squared spacing in one diagram
        return P, s2 * 10.0 ** rng.uniform(-12, 12, n)
    if name == "small_spread":
        return P, s2 * 10.0 ** rng.uniform(-12, 0, n)
    if name == "negative":
        return P, -rng.random(n) * s2 * 2
    if name == "offset_1e12":  # exact differences of weights near 1e12
        return P, 1e12 + rng.random(n) * s2
    if name in ("zero_slab", "empty_slab"):
        P, W, mid = _slabs(2)
        W[mid] = -0.0625 if name == "zero_slab" else -0.0625 - 2.0**-30
        return P, W
    if name == "grid_ulps":  # a cubic grid (8 sites on each sphere) with weights ulps apart
        g = (np.stack(np.meshgrid(*[np.arange(2)] * 3, indexing="ij"), -1).reshape(-1, 3) + 0.5) / 2
        return g, 0.25 + rng.integers(-2, 3, len(g)) * 2.0**-54
    if name == "on_faces":  # sites on the box's faces, edges and corners
        F = rng.random((n, 3))
        F[np.arange(n), rng.integers(0, 3, n)] = rng.integers(0, 2, n)
        F[: n // 4] = rng.integers(0, 2, (n // 4, 3))
        F = np.unique(F, axis=0)
        return F, rng.random(len(F)) * s2
    if name == "duplicates":  # a heavier and an equal duplicate: one of each pair is empty
        P[1] = P[0]
        P[3] = P[2]
        W = np.zeros(n)
        W[1] = 0.01
        return P, W
    if name == "ray":  # sites on one line, planes that may coincide
        return np.c_[np.linspace(0.1, 0.9, n), np.full(n, 0.5), np.full(n, 0.5)], rng.random(n) * (
            3.2 / n**2
        )
    raise ValueError(name)


FAMILIES = [
    "equal",
    "dominant",
    "big_spread",
    "small_spread",
    "negative",
    "offset_1e12",
    "zero_slab",
    "empty_slab",
    "grid_ulps",
    "on_faces",
    "duplicates",
    "ray",
]


@pytest.mark.parametrize("name", FAMILIES)
def test_weight_families_exact(name):
    P, W = _family(name, 12, np.random.default_rng(FAMILIES.index(name)))
    _, ex = _check_cells(P, W, BOX)
    assert sum(c.volume for c in ex) == 1  # the exact cells tile the box
    if name == "zero_slab":
        _, _, mid = _slabs(2)
        assert all(c.empty for c in ex[mid])


@pytest.mark.parametrize(
    ("name", "scale", "offset"),
    [
        ("small_spread", 2.0**-30, 0.0),
        ("negative", 1e9, 0.0),
        ("grid_ulps", 1.0, 1.0),
        ("on_faces", 1.0, 1.0),
        ("zero_slab", 1e-9, 1.0),
    ],
)
def test_weight_families_moved_exact(name, scale, offset):
    """The same at other scales and at a UTM-like offset (weights times the scale squared;
    the sites and box rounded there, the exact cells of the rounded input)."""
    P, W = _family(name, 12, np.random.default_rng(FAMILIES.index(name)))
    o = offset * np.array([500000.0, 4000000.0, 100.0])
    lo, hi = o, o + scale
    _, ex = _check_cells(P * scale + o, W * scale**2, (*lo, *hi))
    total = sum(c.volume for c in ex)
    assert total == np.prod(
        [Fraction(float(b)) - Fraction(float(a)) for a, b in zip(lo, hi, strict=True)]
    )
