"""Named degenerate 3D inputs every 3D test runs on: ``CATALOGUE3D[name] = (points, box)``.

``box`` is a 6-tuple or ``None`` (the default padded bounding box).
"""

from __future__ import annotations

import numpy as np


def helix(n, turns=10, r=0.3):
    """``n`` points on a helix of ``turns`` turns and radius ``r`` in the unit box (cells of
    hundreds of nearly parallel faces)."""
    a = np.linspace(0, 2 * np.pi * turns, n)
    return np.c_[0.5 + r * np.cos(a), 0.5 + r * np.sin(a), np.linspace(0.05, 0.95, n)]


def three_lines(n):
    """``n`` sites on three orthogonal lines through the unit box (ill-conditioned vertices)."""
    rng = np.random.default_rng(0)
    k = n // 3
    return np.r_[
        np.c_[rng.random(k), np.full(k, 0.2), np.full(k, 0.2)],
        np.c_[np.full(k, 0.8), rng.random(k), np.full(k, 0.5)],
        np.c_[np.full(k, 0.5), np.full(k, 0.5), rng.random(k)],
    ]


def _grid(k):
    g = np.stack(np.meshgrid(*[np.arange(k)] * 3, indexing="ij"), -1).reshape(-1, 3)
    return g.astype(np.float64)


def _sphere(n, seed=3):
    v = np.random.default_rng(seed).normal(size=(n, 3))
    return v / np.linalg.norm(v, axis=1)[:, None]


def _sphere_exact(n, seed=3):
    """``n`` points exactly on one sphere: integer solutions of x^2 + y^2 + z^2 = 693^2,
    scaled by 2^-9 (exact), so every vertex at the centre is exactly co-spherical."""
    r = 693
    x, y = np.meshgrid(np.arange(-r, r + 1), np.arange(-r, r + 1), indexing="ij")
    z2 = r * r - x * x - y * y
    ok = z2 >= 0
    z = np.sqrt(np.where(ok, z2, 0)).round().astype(np.int64)
    ok &= z * z == z2
    pts = np.column_stack([x[ok], y[ok], z[ok]])
    pts = np.vstack([pts, pts * [1, 1, -1]])
    pts = np.unique(pts, axis=0)
    pick = np.random.default_rng(seed).choice(len(pts), n, replace=False)
    return pts[pick] / 512.0


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

#: inputs whose exact diagram has distinct vertices closer than 1e-9 of its size
NEAR = {"sphere_rounded"}

CATALOGUE3D = {
    "cubic_grid": (_grid(4), None),  # 8 co-spherical sites at every interior vertex
    "cubic_grid_tight": (_grid(3) + 0.5, (0, 0, 0, 3, 3, 3)),  # vertices on the walls
    "bcc": (_bcc(3), (-0.25, -0.25, -0.25, 2.25, 2.25, 2.25)),
    "fcc": (_fcc(2), None),
    # exactly co-spherical (integer points of one sphere), with and without the centre
    "sphere": (_sphere_exact(30), (-2, -2, -2, 2, 2, 2)),
    "sphere_centre": (np.vstack([_sphere_exact(30), [[0, 0, 0]]]), (-2, -2, -2, 2, 2, 2)),
    # rounded onto the unit sphere: distinct vertices ~1e-16 apart near the centre (NEAR)
    "sphere_rounded": (_sphere(30), (-1.5, -1.5, -1.5, 1.5, 1.5, 1.5)),
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
