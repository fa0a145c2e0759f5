"""Named degenerate 3D inputs every 3D test runs on: ``CATALOGUE3D[name] = (points, box)``.

``box`` is a 6-tuple or ``None`` (the default padded bounding box).
"""

from __future__ import annotations

import numpy as np


def _grid(k):
    g = np.stack(np.meshgrid(*[np.arange(k)] * 3, indexing="ij"), -1).reshape(-1, 3)
    return g.astype(np.float64)


def _sphere(n, seed=3):
    v = np.random.default_rng(seed).normal(size=(n, 3))
    return v / np.linalg.norm(v, axis=1)[:, None]


def _bcc(k):
    g = _grid(k)
    return np.vstack([g, g[(g < k - 1).all(axis=1)] + 0.5])


def _fcc(k):
    g = _grid(k)
    out = [g]
    for off in ((0.5, 0.5, 0), (0.5, 0, 0.5), (0, 0.5, 0.5)):
        out.append(g + np.array(off))
    return np.vstack(out)


_rng = np.random.default_rng(12)
_rand = _rng.random((40, 3))

CATALOGUE3D = {
    "cubic_grid": (_grid(4), None),  # 8 co-spherical sites at every interior vertex
    "cubic_grid_tight": (_grid(3) + 0.5, (0, 0, 0, 3, 3, 3)),  # vertices on the walls
    "bcc": (_bcc(3), (-0.25, -0.25, -0.25, 2.25, 2.25, 2.25)),
    "fcc": (_fcc(2), None),
    "sphere": (_sphere(30), (-1.5, -1.5, -1.5, 1.5, 1.5, 1.5)),
    "sphere_centre": (np.vstack([_sphere(30), [[0, 0, 0]]]), (-1.5, -1.5, -1.5, 1.5, 1.5, 1.5)),
    "coplanar": (np.column_stack([_rand[:, :2], np.zeros(40)]), None),
    "collinear": (np.column_stack([np.linspace(0, 1, 7), np.zeros(7), np.zeros(7)]), None),
    "duplicates": (np.vstack([_rand[:20], _rand[:5], _rand[3:4]]), (0, 0, 0, 1, 1, 1)),
    "one": (np.array([[0.2, 0.3, 0.4]]), (0, 0, 0, 1, 1, 1)),
    "two": (np.array([[0.2, 0.3, 0.4], [0.7, 0.6, 0.5]]), (0, 0, 0, 1, 1, 1)),
    "three": (_rand[:3], (0, 0, 0, 1, 1, 1)),
    "four": (_rand[:4], (0, 0, 0, 1, 1, 1)),
    "outside_and_on": (
        np.vstack([_rand[:20], [[1.5, 0.5, 0.5], [1.0, 0.3, 0.3], [0, 0, 0], [0.5, 0.5, 1.0]]]),
        (0, 0, 0, 1, 1, 1),
    ),
    "utm": (_rand * [100, 100, 10] + [500000, 4000000, 100], None),
    "tiny": (_rand * 1e-9, None),
    "huge": (_rand * 1e9, None),
}
