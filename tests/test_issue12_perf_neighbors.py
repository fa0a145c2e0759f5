"""Issue 12: ``Diagram3D.neighbors`` built in one pass over the face table in build order.

Each cell's sorted row is written into a buffer at its first face's place, then the rows are
copied out in the caller's order (``engine.diagram3d._neighbors``). Checked against what
the rows must be: the unique faces of positive area (another pass over the table, and the
fan areas), symmetric, sorted, the same under a permutation of the input, and the six
axis neighbours of a cubic grid (whose edge and corner contacts have zero area).
"""

from __future__ import annotations

import numpy as np
import pytest

import voroforge as vf

BOX = (0.0, 0.0, 0.0, 1.0, 1.0, 1.0)


def _rows(indptr, indices):
    return [indices[indptr[i] : indptr[i + 1]].tolist() for i in range(len(indptr) - 1)]


def _from_faces(d):
    """Neighbour rows from the unique faces of positive area (both directions)."""
    cells = np.asarray(d.faces.cells, np.int64)
    keep = (cells[:, 1] >= 0) & (cells[:, 0] != cells[:, 1]) & (d.face_areas > 0)
    rows = [set() for _ in range(len(d))]
    for i, j in cells[keep]:
        rows[i].add(int(j))
        rows[j].add(int(i))
    return [sorted(r) for r in rows]


@pytest.mark.parametrize("n", [1, 7, 600, 3000])
def test_rows_are_the_faces_of_positive_area(n):
    p = np.random.default_rng(n).random((n, 3))
    d = vf.voronoi3d(p, BOX)
    indptr, indices = d.neighbors
    assert indptr.dtype == np.int64 and indptr[0] == 0 and indptr[-1] == len(indices)
    rows = _rows(indptr, indices)
    assert rows == _from_faces(d)
    for i, r in enumerate(rows):
        assert r == sorted(set(r)) and i not in r
        assert all(i in rows[j] for j in r)


def test_rows_follow_a_permutation_of_the_input():
    rng = np.random.default_rng(12)
    p = rng.random((2500, 3))
    perm = rng.permutation(len(p))
    a = _rows(*vf.voronoi3d(p, BOX).neighbors)
    b = _rows(*vf.voronoi3d(p[perm], BOX).neighbors)
    inv = np.argsort(perm)
    assert [sorted(int(perm[j]) for j in b[k]) for k in inv] == a


def test_cubic_grid_has_six_axis_neighbours():
    m = 6
    ax = (np.arange(m) + 0.5) / m
    p = np.stack(np.meshgrid(ax, ax, ax, indexing="ij"), axis=-1).reshape(-1, 3)
    d = vf.voronoi3d(p, BOX)
    want = []
    for x in range(m):
        for y in range(m):
            for z in range(m):
                r = []
                for dx, dy, dz in ((1, 0, 0), (0, 1, 0), (0, 0, 1)):
                    for s in (-1, 1):
                        u, v, w = x + s * dx, y + s * dy, z + s * dz
                        if 0 <= u < m and 0 <= v < m and 0 <= w < m:
                            r.append((u * m + v) * m + w)
                want.append(sorted(r))
    assert _rows(*d.neighbors) == want


def test_duplicates_have_empty_rows():
    p = np.random.default_rng(3).random((400, 3))
    p = np.vstack([p, p[:50]])
    d = vf.voronoi3d(p, BOX)
    rows = _rows(*d.neighbors)
    assert all(rows[i] == [] for i in range(400, 450))
    assert rows == _from_faces(d)
