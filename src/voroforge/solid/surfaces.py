"""A shell's surface as bare arrays: a revolved profile, even samples, open boundary edges.

What :func:`voroforge.solid.shell` needs of its surface, in numpy: a design's revolved
profile needs neither trimesh (0.3-0.4 s of a first build to import) nor
``scipy.spatial`` (0.28 s). :func:`revolve` gives the vertices and faces trimesh's
``creation.revolve`` gives for a full turn, and :func:`sample_even` the points of
``trimesh.sample.sample_surface_even`` with the same seed (tests compare both).

Examples
--------
>>> m = revolve([[10.0, 0.0], [12.0, 5.0], [10.0, 10.0]], sections=16)
>>> m.vertices.shape, m.faces.shape
((48, 3), (64, 3))
>>> len(boundary_edges(m.faces))  # the two rims
32
>>> sample_even(m, 10, seed=1).shape
(10, 3)
"""

from __future__ import annotations

import numpy as np

from .implicit import Bare

__all__ = ["boundary_edges", "face_areas", "revolve", "sample_even"]

_ALL_PAIRS = 1536  # up to this many candidate points, sample_even compares every pair


def revolve(profile, sections: int) -> Bare:
    """The surface swept by a profile ``[[r, z], ...]`` turned once about the z axis.

    Vertex ``s * len(profile) + p`` is profile point ``p`` at angle ``2 pi s / sections``;
    each section's quads are split into two triangles facing as trimesh's revolve faces
    them. Coincident vertices are one (as trimesh merges them): a profile that ends on the
    axis closes there (its zero-area triangles dropped), a closed profile is a closed
    surface.
    """
    prof = np.asarray(profile, dtype=np.float64)
    if prof.ndim != 2 or prof.shape[1] != 2 or len(prof) < 2:
        raise ValueError(f"profile must be [[r, z], ...] with at least 2 points, got {profile!r}")
    n = int(sections)
    per = len(prof)
    theta = np.linspace(0.0, 2.0 * np.pi, n + 1)[:n]
    v = np.zeros((n, per, 3))
    v[:, :, 0] = np.cos(theta)[:, None] * prof[None, :, 0]
    v[:, :, 1] = np.sin(theta)[:, None] * prof[None, :, 0]
    v[:, :, 2] = prof[None, :, 1]
    s = np.arange(n)[:, None] * per
    nxt = (np.arange(n)[:, None] + 1) % n * per
    p = np.arange(per - 1)[None, :]
    a, b, c, d = s + p, nxt + p, s + p + 1, nxt + p + 1  # (n, per - 1) quad corners
    f = np.stack([np.stack([a, b, c], -1), np.stack([c, b, d], -1)], axis=2).reshape(-1, 3)
    v = v.reshape(-1, 3)
    # coincident vertices as one (the first), as trimesh merges them: points on the axis, a
    # closed profile's ends; their zero-area triangles dropped
    _, first, inverse = np.unique(v + 0.0, axis=0, return_index=True, return_inverse=True)
    same = first[inverse.ravel()]
    if (same != np.arange(len(v))).any():
        f = same[f]
        f = f[(f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 0] != f[:, 2])]
    return Bare(v, f)


def face_areas(vertices, faces) -> np.ndarray:
    """Each triangle's area (half its edges' cross product, as trimesh computes it)."""
    t = np.asarray(vertices, dtype=np.float64)[np.asarray(faces)]
    c = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 1])
    return np.sqrt((c**2).sum(axis=1)) / 2.0


def boundary_edges(faces) -> np.ndarray:
    """``(b, 2)`` vertex pairs (sorted) of the edges only one triangle has."""
    f = np.asarray(faces)
    e = np.sort(f[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    uniq, cnt = np.unique(e, axis=0, return_counts=True)
    return uniq[cnt == 1]


def sample_even(mesh, count: int, *, seed: int = 0) -> np.ndarray:
    """About ``count`` points spread evenly over a surface (fewer where it is too small).

    Three times ``count`` points uniform by area, then the points of every pair closer than
    ``sqrt(area / (3 count))`` thinned: of each such pair, the one in more pairs goes (the
    first on a tie), and the first ``count`` left are kept. The rule and the random draws
    of ``trimesh.sample.sample_surface_even(mesh, count, seed=seed)``: the same points.
    """
    v = np.asarray(mesh.vertices, dtype=np.float64)
    f = np.asarray(mesh.faces)
    area = face_areas(v, f)
    radius = np.sqrt(area.sum() / (3 * count))
    rng = np.random.default_rng(seed)
    cum = np.cumsum(area)
    face = np.searchsorted(cum, rng.random(3 * count) * cum[-1])
    o = v[f[face, 0]]
    e = v[f[face, 1:]] - o[:, None, :]
    uv = rng.random((len(face), 2, 1))
    flip = uv.sum(axis=1).reshape(-1) > 1.0  # outside the triangle: mirrored into it
    uv[flip] -= 1.0
    pts = (e * np.abs(uv)).sum(axis=1) + o
    if len(pts) <= _ALL_PAIRS:  # a few hundred points: every pair at once, no scipy.spatial
        i, j = np.triu_indices(len(pts), k=1)
        d = pts[i] - pts[j]
        close = np.sqrt((d * d).sum(axis=1)) <= radius
        i, j = i[close], j[close]
    else:  # the pairs within the radius from a KD-tree (bounded memory)
        from scipy.spatial import cKDTree

        i, j = cKDTree(pts).query_pairs(radius, output_type="ndarray").T
    times = np.bincount(np.concatenate([i, j]), minlength=len(pts))
    keep = np.ones(len(pts), dtype=bool)
    keep[np.where(times[j] > times[i], j, i)] = False
    return pts[keep][:count]
