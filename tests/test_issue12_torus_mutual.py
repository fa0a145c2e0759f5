"""Issue 12, periodic neighbours on lattices degenerate only up to rounding (checker24 F4).

On a torus each cell holds its own copy of a face across the seam (an image's vertices,
shifted by the period, round apart from its twin's), so a face of ~1e-32 of a face's area
was nonzero on one side and zero or absent on the other, and ``d.neighbors`` was one-sided
(FCC copper in metres: 2 entries; FCC shifted by 0.3: 24). Neighbours on a torus are the
cells that see each other across a face of nonzero area.
"""

from __future__ import annotations

import numpy as np
import pytest

import voroforge as vf


def _fcc(k):
    g = np.stack(np.meshgrid(*[np.arange(k)] * 3, indexing="ij"), -1).reshape(-1, 3)
    m = np.array([[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]])
    return (g[:, None, :] + m[None]).reshape(-1, 3)


def _diamond(k):
    f = _fcc(k)
    return np.vstack([f, f + 0.25])


def _rows(d):
    ip, ix = d.neighbors
    return [set(ix[ip[i] : ip[i + 1]].tolist()) for i in range(len(d))]


def _one_sided(d):
    nb = _rows(d)
    return [(i, j) for i in range(len(d)) for j in nb[i] if i not in nb[j]]


@pytest.mark.parametrize(
    "name, pts, period",
    [
        ("fcc copper in metres", _fcc(2) * 3.615e-10, 2 * 3.615e-10),
        ("fcc shifted 0.3", (_fcc(2) + 0.3) % 2, 2.0),
        ("diamond scaled 0.1", (_diamond(2) + 0.3) % 2 * 0.1, 0.2),
    ],
)
def test_lattice_neighbours_on_a_torus_are_mutual(name, pts, period):
    d = vf.voronoi3d(pts, (0.0, 0.0, 0.0) + (period,) * 3, periodic=True)
    assert _one_sided(d) == []
    cell = period**3 / len(pts)
    np.testing.assert_allclose(d.volumes, cell, rtol=1e-12)
    # every face well above rounding (a rhombic dodecahedron's or truncated one's) is kept
    cf, lab, av = d.cell_face_table()[:3]
    area = np.linalg.norm(av, axis=1)
    nb = _rows(d)
    big = area > 1e-6 * cell ** (2 / 3)
    for i in range(len(d)):
        clear = {int(lab[f]) for f in range(cf[i], cf[i + 1]) if big[f] and lab[f] != i}
        assert clear <= nb[i]


def test_random_torus_keeps_every_face_both_cells_see():
    # nothing real is dropped: on random sites each neighbour pair has a face in both
    # cells, and every face of clear area is a neighbour
    pts = np.random.default_rng(3).random((300, 3)) * [2.0, 1.0, 0.5]
    d = vf.voronoi3d(pts, (0, 0, 0, 2.0, 1.0, 0.5), periodic=True)
    cf, lab, av = d.cell_face_table()[:3]
    area = np.linalg.norm(av, axis=1)
    nb = _rows(d)
    assert _one_sided(d) == []
    for i in range(len(d)):
        labels = {int(v) for v in lab[cf[i] : cf[i + 1]]}
        clear = {int(lab[f]) for f in range(cf[i], cf[i + 1]) if area[f] > 1e-9 and lab[f] != i}
        assert clear <= nb[i] <= labels
