"""3D power cells with exact ties: empty cells between coinciding planes (issue 12).

Sites ``(.25, .5, .5), (.5, .5, .5), (.75, .5, .5)`` with weights ``0, -1/16, 0``: both
planes of the middle site are ``x = .5``, its cell is empty and cells 0 and 2 share the face
of area 1. The face was labelled with whichever plane cut first, so ``neighbors`` came out
one-sided (0 -> 1, 1 -> nothing, 2 -> 1) and ``faces`` listed ``(0, 1)`` only (checker20
F2). Each face is checked here against exact powers (fractions): just inside it, the cell's
own site is the strictly nearest in power, and just outside it the labelled site (its
image across the period, on a torus) is; the relation is symmetric, each face is listed
once with both cells and the same area from both sides, empty cells have no faces, the
volumes are the brute-force cells' (every plane intersected, Qhull).
"""

from __future__ import annotations

import itertools
from fractions import Fraction

import numpy as np
import pytest

import voroforge as vf
from reference3d import brute_volumes

BOX = (0.0, 0.0, 0.0, 1.0, 1.0, 1.0)
WALLS = np.array(
    [[-1, 0, 0, 0], [1, 0, 0, 1], [0, -1, 0, 0], [0, 1, 0, 1], [0, 0, -1, 0], [0, 0, 1, 1]],
    np.float64,
)
SHIFTS = np.array(list(itertools.product((-1, 0, 1), repeat=3)), np.int64)


def _grid(k):
    """``k^3`` sites at ``(2 a + 1) / (2 k)``: spacing ``1 / k``, dyadic for ``k = 4``."""
    c = (2 * np.arange(k) + 1) / (2 * k)
    return np.array([[x, y, z] for z in c for y in c for x in c])


def _tie_weights(k, seed):
    """Weights ``0, -s^2, -2 s^2`` (``s = 1 / k``): a light site between two heavier ones on
    an axis (``0, -s^2, 0``) or a diagonal (``0, -2 s^2, 0``) has both planes through it."""
    s2 = 1.0 / k**2
    return -s2 * np.random.default_rng(seed).integers(0, 3, k**3).astype(np.float64)


def _exact_nearest(q, P, W, images):
    """Indices (site, image) of the least power at the rational point ``q``, all ties."""
    pts = P[:, None, :] + images[None, :, :]
    qf = np.array([float(x) for x in q])
    pw = ((pts - qf) ** 2).sum(-1) - W[:, None]
    cand = np.argwhere(pw <= pw.min() + 1e-9 * (1 + np.abs(pw).max()))
    best, out = None, []
    for s, m in cand:
        x = [Fraction(float(v)) for v in pts[s, m]]
        p = sum((q[a] - x[a]) ** 2 for a in range(3)) - Fraction(float(W[s]))
        if best is None or p < best:
            best, out = p, [(int(s), int(m))]
        elif p == best:
            out.append((int(s), int(m)))
    return out


def _faces_of(d, i, centroid=True):
    """Cell ``i``'s faces: ``(label, shift or None, area, centroid (fractions), normal)``.

    ``centroid=False``: ``None`` for the centroid (its rationals are most of the time).
    """
    c = d.cell(i)
    out = []
    for f, ring in enumerate(c.faces):
        v = c.vertices[ring]
        n = np.zeros(3)
        for a in range(len(v)):
            n += np.cross(v[a], v[(a + 1) % len(v)])
        area = 0.5 * np.linalg.norm(n)
        cen = None
        if centroid:
            cen = [sum(Fraction(float(x)) for x in v[:, a]) / len(v) for a in range(3)]
        out.append((int(c.neighbors[f]), None, area, cen, n / np.linalg.norm(n)))
    return out


def _check(P, W, d, periodic=False):
    n = len(P)
    images = SHIFTS.astype(np.float64) if periodic else np.zeros((1, 3))
    own = 13 if periodic else 0  # the (0, 0, 0) image
    row = 0
    indptr, nb = d.neighbors
    pairs = {(i, int(j)) for i in range(n) for j in nb[indptr[i] : indptr[i + 1]]}
    assert all((j, i) in pairs for i, j in pairs), "neighbours not symmetric"
    areas = {}
    for i in range(n):
        faces = _faces_of(d, i)
        if d.volumes[i] == 0.0:
            assert not faces and indptr[i + 1] == indptr[i]
            continue
        for f, (lab, _, area, cen, nrm) in enumerate(faces):
            shift = d.face_shifts[row + f] if periodic else np.zeros(3, np.int64)
            if lab < 0:
                continue
            other = int(np.flatnonzero((SHIFTS == shift).all(1))[0]) if periodic else 0
            delta = Fraction(1, 2**20)
            for sign, want in ((1, (lab, other)), (-1, (i, own))):
                q = [cen[a] + sign * delta * Fraction(float(nrm[a])) for a in range(3)]
                assert _exact_nearest(q, P, W, images) == [want], (i, f, lab, sign)
            assert (i, lab) in pairs
            areas.setdefault((i, lab), []).append(area)
        row += len(faces)
    for (i, j), a in areas.items():
        assert sorted(a) == pytest.approx(sorted(areas[(j, i)]), rel=1e-12, abs=1e-15)
    assert {p for p in areas} == pairs
    # each face between two cells once (a face of a cell with itself across the period:
    # listed once, while the cell has it twice)
    cells = d.faces.cells
    for i, j in {tuple(sorted(p)) for p in pairs}:
        k = int(((cells[:, 0] == i) & (cells[:, 1] == j)).sum())
        assert k == (len(areas[(i, j)]) // 2 if i == j else len(areas[(i, j)])), (i, j)
    assert not ((cells[:, 1] >= 0) & (cells[:, 1] < cells[:, 0])).any()
    if periodic:  # the sites and their 26 images (own first) in the box [-1, 2]^3
        first = SHIFTS[np.argsort((SHIFTS != 0).sum(1), kind="stable")]
        allp = np.vstack([P + s for s in first])
        walls = np.column_stack([WALLS[:, :3], [1, 2, 1, 2, 1, 2]])
        ref = brute_volumes(allp, walls, np.tile(W, 27), range(n))
    else:
        ref = brute_volumes(P, WALLS, W)
    np.testing.assert_allclose(d.volumes, ref, rtol=1e-9, atol=1e-12)
    assert d.volumes.sum() == pytest.approx(1.0, rel=1e-12)


def _pairs(d):
    indptr, nb = d.neighbors
    return {(i, int(j)) for i in range(len(d)) for j in nb[indptr[i] : indptr[i + 1]]}


def test_empty_cell_between_two_on_a_line():
    P = np.array([[0.25, 0.5, 0.5], [0.5, 0.5, 0.5], [0.75, 0.5, 0.5]])
    W = np.array([0.0, -0.0625, 0.0])
    d = vf.voronoi3d(P, BOX, weights=W)
    assert d.volumes[1] == 0.0
    assert _pairs(d) == {(0, 2), (2, 0)}
    assert d.faces.cells[d.faces.cells[:, 1] >= 0].tolist() == [[0, 2]]
    assert d.face_areas[(d.faces.cells[:, 1] >= 0)].tolist() == [1.0]
    _check(P, W, d)


@pytest.mark.parametrize("periodic", [False, True])
def test_empty_middle_layer(periodic):
    g = np.array([[x, y, z] for z in (0.25, 0.5, 0.75) for y in (1, 3, 5) for x in (1, 3, 5)])
    g[:, :2] /= 6
    W = np.where(g[:, 2] == 0.5, -0.0625, 0.0)
    d = vf.voronoi3d(g, BOX, weights=W, periodic=periodic)
    assert (d.volumes[g[:, 2] == 0.5] == 0.0).all()
    bot, top = np.flatnonzero(g[:, 2] == 0.25), np.flatnonzero(g[:, 2] == 0.75)
    assert {(int(b), int(t)) for b, t in zip(bot, top, strict=True)} <= _pairs(d)
    _check(g, W, d, periodic)


@pytest.mark.parametrize("periodic", [False, True])
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_grid_with_exact_tie_weights(seed, periodic):
    P = _grid(4)
    W = _tie_weights(4, seed)
    d = vf.voronoi3d(P, BOX, weights=W, periodic=periodic)
    assert (d.volumes == 0.0).sum() > 5  # many cells squeezed out
    _check(P, W, d, periodic)


# --- unmatched vertices: owners in the diagram's frame (not images, not empty cells) ---------


def _expected_refs(d, P, W, periodic):
    """Per vertex, the sites (no image) whose power at it is least to 1e-9 (float reference)."""
    images = SHIFTS.astype(np.float64) if periodic else np.zeros((1, 3))
    V = np.asarray(d.vertices)
    pts = (P[:, None, :] + images[None, :, :]).reshape(-1, 3)
    pw = ((V[:, None, :] - pts[None, :, :]) ** 2).sum(-1) - np.repeat(W, len(images))[None, :]
    own = pw <= pw.min(1, keepdims=True) + 1e-9
    real = own[:, (13 if periodic else 0) :: len(images)]
    real &= (d.volumes > 0)[None, :]  # empty power cells own no vertex
    return real.sum(1)


def _refs(d):
    cf, _, _, roff, ring = d.cell_face_table()
    out = np.zeros(len(d.vertices), np.int64)
    for i in range(len(d)):
        out[np.unique(ring[roff[cf[i]] : roff[cf[i + 1]]])] += 1
    return out


@pytest.mark.parametrize(
    "case", ["random", "random-periodic", "ties", "ties-periodic", "weights-periodic"]
)
def test_unmatched_vertices_counts_owners_in_the_frame(case):
    rng = np.random.default_rng(3)
    periodic = case.endswith("periodic")
    if case.startswith("ties"):
        P, W = _grid(4), _tie_weights(4, 11)
    else:
        P = rng.random((150, 3))
        W = rng.random(150) * 0.01 if case.startswith("weights") else np.zeros(150)
    d = vf.voronoi3d(P, BOX, weights=W if W.any() else None, periodic=periodic)
    # every vertex is referenced by each of its owner sites' cells: the count is 0
    np.testing.assert_array_equal(_refs(d), _expected_refs(d, P, W, periodic))
    assert d.unmatched_vertices == 0
    assert d.describe()["unmatched_vertices"] == 0


def test_unmatched_vertices_finds_a_vertex_named_twice():
    """The count from the faces is not blind: a cell that holds another record of one of its
    vertices (two cells naming it differently) is counted, on a torus too."""
    from types import SimpleNamespace

    from voroforge.engine.describe3d import unmatched_on_faces

    rng = np.random.default_rng(5)
    d = vf.voronoi3d(rng.random((60, 3)), BOX, periodic=True)
    cf, lab, area, roff, ring = d.cell_face_table()
    assert unmatched_on_faces(d) == 0
    # cell 0's copy of one vertex of a face toward a site (no shift) becomes a new record
    f = next(f for f in range(cf[0], cf[1]) if lab[f] >= 0 and not d.face_shifts[f].any())
    x = ring[roff[f]]
    ring2 = ring.copy()
    for g in range(cf[0], cf[1]):
        r = ring2[roff[g] : roff[g + 1]]
        r[r == x] = len(d.vertices)
    fake = SimpleNamespace(
        cell_face_table=lambda: (cf, lab, area, roff, ring2),
        face_shifts=d.face_shifts,
        vertices=np.vstack([d.vertices, d.vertices[x]]),
    )
    assert unmatched_on_faces(fake) == 2  # both records: each misses the other cells
