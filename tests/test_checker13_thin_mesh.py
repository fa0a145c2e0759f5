"""Thin and far box-shaped mesh containers (checker13 F1): rods and plates against exact references.

A closed 12-triangle box mesh (corners written exactly) and the same box's cells: each cell's
volume against scipy's half-space intersection of its bisectors (sites about the box's corner,
exact there, scaled by a power of two), the volumes' sum against the box's exact volume.
Before: a rod 1 x 1e-6 x 1e-6 had cells 1.9e-8 off (moments about a cell vertex 1e4 times the
rod's thickness away), rods 1e-7 thick were refused, and far out (1e15, 1e-3) the mesh's own
signed volume was 1.4e-5 off and the mesh refused.
"""

from fractions import Fraction

import numpy as np
import pytest
from scipy.spatial import ConvexHull, HalfspaceIntersection

import voroforge as vf
from voroforge.engine.mesh3d import as_mesh_container

_CORNERS = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)])
_FACES = np.array(
    [
        [0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
        [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3],
    ]
)  # fmt: skip


def _box_mesh(lo, hi):
    """The box ``[lo, hi]`` as 12 outward triangles, its corners ``lo``/``hi`` exactly."""
    return np.where(_CORNERS > 0, hi, lo), _FACES


def _exact_volume(lo, hi):
    return float(
        np.prod([Fraction(float(b)) - Fraction(float(a)) for a, b in zip(lo, hi, strict=True)])
    )


def _reference(q, ext):
    """Voronoi cell volumes of sites ``q`` in the box ``[0, ext]`` (scipy, scaled by 2**-k)."""
    k = int(np.frexp(ext.max())[1])
    q, e = np.ldexp(q, -k), np.ldexp(ext, -k)
    walls = [[-1, 0, 0, 0], [1, 0, 0, -e[0]], [0, -1, 0, 0], [0, 1, 0, -e[1]]]
    walls += [[0, 0, -1, 0], [0, 0, 1, -e[2]]]
    out = []
    for i in range(len(q)):
        n = np.delete(q, i, axis=0) - q[i]
        mid = 0.5 * (np.delete(q, i, axis=0) + q[i])
        rows = np.vstack([walls, np.c_[n, -np.einsum("ij,ij->i", n, mid)]])
        # the site nudged towards the box's centre (off a wall it lies on): the nudge with the
        # most room to the cell's planes (qhull wants the point clearly inside)
        pts = q[i] + (0.5 * e - q[i]) * np.array([1e-2, 1e-3, 1e-6])[:, None]
        room = (-(pts @ rows[:, :3].T + rows[:, 3]) / np.linalg.norm(rows[:, :3], axis=1)).min(1)
        inner = pts[np.argmax(room)]
        out.append(ConvexHull(HalfspaceIntersection(rows, inner).intersections).volume)
    return np.ldexp(np.array(out), 3 * k)


CASES = [
    (scale, off, t, shape)
    for scale, off in [(1.0, 0.0), (1.0, 1e6), (1e9, 1e15), (1e-9, 1e-3)]
    for t in (1e-4, 1e-6, 1e-8)
    for shape in ("rod", "plate")
]


@pytest.mark.parametrize("scale, off, t, shape", CASES)
def test_thin_box_mesh_cells_match_the_exact_box(scale, off, t, shape):
    rng = np.random.default_rng(int(-np.log10(t)) + 10 * (shape == "rod"))
    lo = np.full(3, off)
    hi = lo + scale * np.array([1.0, t, t] if shape == "rod" else [1.0, 1.0, t])
    ext = hi - lo  # exact (Sterbenz): the corners are what the mesh holds
    p = np.clip(lo + rng.random((40, 3)) * ext, lo, hi)
    ref = _reference(p - lo, ext)  # p - lo exact too
    vol = _exact_volume(lo, hi)
    d = vf.voronoi3d(p, _box_mesh(lo, hi))  # not refused
    assert d.container_volume == pytest.approx(vol, rel=1e-13, abs=0)
    assert abs(d.volumes.sum() - vol) <= 1e-9 * vol
    assert np.abs(d.volumes / ref - 1).max() <= 1e-9
    db = vf.voronoi3d(p, (*lo, *hi))
    assert np.abs(d.volumes / db.volumes - 1).max() <= 1e-9


@pytest.mark.parametrize(
    "scale, off", [(1e9, 1e15), (1e-9, 1e-3), (1.0, 1e6), (2.0**-300, 2.0**-290), (2.0**300, 0.0)]
)
def test_far_thin_mesh_signed_volume_is_exact(scale, off):
    # far_origin's step follows the largest extent: y and z differences 5e5 times the rod's
    # thickness cancelled in the triple products (1.4e-5 off at 1e15)
    lo = np.full(3, off)
    hi = lo + scale * np.array([1.0, 1e-6, 1e-6])
    mc, _ = as_mesh_container(_box_mesh(lo, hi))
    assert mc.volume == pytest.approx(_exact_volume(lo, hi), rel=1e-14, abs=0)
