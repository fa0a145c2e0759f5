"""``lloyd3d``: centroidal Voronoi tessellations in 3D (Lloyd's iteration on voronoi3d)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .inputs import as_points
from .voronoi3d import voronoi3d

__all__ = ["Relaxation3D", "lloyd3d"]


@dataclass(frozen=True)
class Relaxation3D:
    """Result of :func:`lloyd3d`: final ``points``, their ``diagram``, per-step ``moves``."""

    points: np.ndarray
    diagram: object
    moves: np.ndarray
    iterations: int


def _density_centroids(d, density):
    """Density-weighted cell centroids by one-point quadrature on each face-fan tetrahedron."""
    cf, lab, farea, roff, ring = d.cell_face_table()
    V = np.asarray(d.vertices)
    sites = np.asarray(d.sites)
    n = len(d)
    out = np.array(d.centroids, copy=True)
    owner_f = np.repeat(np.arange(n), np.diff(cf))
    lens = np.diff(roff)
    # fan of each face from its first vertex, apex at the cell's (uniform) centroid
    tri_f = np.repeat(np.arange(len(lab)), np.maximum(lens - 2, 0))
    k = np.arange(len(tri_f)) - np.repeat(
        np.cumsum(np.maximum(lens - 2, 0)) - np.maximum(lens - 2, 0), np.maximum(lens - 2, 0)
    )
    a = V[ring[roff[tri_f]]]
    b = V[ring[roff[tri_f] + k + 1]]
    c = V[ring[roff[tri_f] + k + 2]]
    cell = owner_f[tri_f]
    apex = np.where(np.isfinite(d.centroids[cell]), d.centroids[cell], sites[cell])
    vol = np.einsum("ij,ij->i", a - apex, np.cross(b - apex, c - apex)) / 6.0
    mid = (a + b + c + apex) / 4.0
    rho = np.asarray(density(mid), np.float64).reshape(-1)
    if rho.shape != (len(mid),) or not np.isfinite(rho).all() or (rho < 0).any():
        raise ValueError("density must return one finite, non-negative value per point")
    mass = np.bincount(cell, weights=vol * rho, minlength=n)
    for ax in range(3):
        m = np.bincount(cell, weights=vol * rho * mid[:, ax], minlength=n)
        with np.errstate(invalid="ignore", divide="ignore"):
            out[:, ax] = np.where(mass > 0, m / np.where(mass > 0, mass, 1), out[:, ax])
    return out


def lloyd3d(points, container=None, *, iterations=20, tol=1e-9, density=None) -> Relaxation3D:
    """Move 3D sites to their cells' centroids until they stop moving (3D CVT).

    Parameters
    ----------
    points : (n, 3) array_like
        Starting sites.
    container : as :func:`voroforge.voronoi3d` (box, Convex or closed mesh)
    iterations : int
        Most Lloyd steps.
    tol : float
        Stop when no site moves more than ``tol`` times the container's size.
    density : callable, optional
        ``density(xyz (m, 3)) -> (m,)`` non-negative: density-weighted centroids (one-point
        quadrature per tetrahedron of each cell's face fans).

    Returns
    -------
    Relaxation3D
    """
    p = as_points(points, dim=3)
    if iterations < 0:
        raise ValueError(f"iterations must be >= 0; got {iterations}")
    d = voronoi3d(p, container)
    if container is None:  # keep the first box: the sites' padded box would drift
        container = tuple(np.asarray(d.box).ravel())
    box = np.asarray(d.box) if d.box is not None else np.array([p.min(0), p.max(0)])
    size = float((box[1] - box[0]).max()) or 1.0
    moves = []
    it = 0
    for it in range(1, iterations + 1):  # noqa: B007 - reported
        c = np.asarray(d.centroids) if density is None else _density_centroids(d, density)
        live = np.isfinite(c).all(axis=1)
        q = np.where(live[:, None], c, p)
        step = float(np.abs(q - p).max()) if len(p) else 0.0
        moves.append(step)
        p = q
        d = voronoi3d(p, container)
        if step <= tol * size:
            break
    return Relaxation3D(p, d, np.array(moves), it)
