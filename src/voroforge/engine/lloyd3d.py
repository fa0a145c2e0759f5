"""``lloyd3d``: centroidal Voronoi tessellations in 3D (Lloyd's iteration on voronoi3d)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..config import LLOYD3D_INTO_MESH_FRACTIONS, LLOYD3D_INTO_MESH_PUSH
from .inputs import as_points
from .readonly import readonly
from .voronoi3d import voronoi3d

__all__ = ["Relaxation3D", "lloyd3d"]

# degree-2 tetrahedron rule (Keast/Stroud, 4 points, weights 1/4): barycentric (A, B, B, B)
# with A = (5 + 3 sqrt 5) / 20, B = (5 - sqrt 5) / 20. Lead: move to config.py.
_KEAST_A = (5.0 + 3.0 * np.sqrt(5.0)) / 20.0
_KEAST_B = (5.0 - np.sqrt(5.0)) / 20.0


@dataclass(frozen=True)
class Relaxation3D:
    """Result of :func:`lloyd3d`: final ``points``, their ``diagram``, per-step ``moves``."""

    points: np.ndarray
    diagram: object
    moves: np.ndarray
    iterations: int


def _density_centroids(d, density):
    """Density-weighted cell centroids: a degree-2 rule on each face-fan tetrahedron.

    Four points per tetrahedron, equal weights, at barycentric (a, b, b, b) and its
    permutations (:data:`_KEAST_A`, :data:`_KEAST_B`): exact for quadratics, so mass and
    first moments are exact for linear densities (to rounding).
    """
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
    corners = np.stack([a, b, c, apex])  # (4, m, 3)
    base = _KEAST_B * corners.sum(axis=0)
    pts = base[None] + (_KEAST_A - _KEAST_B) * corners  # (4, m, 3): one point per corner
    rho = np.asarray(density(pts.reshape(-1, 3)), np.float64).reshape(-1)
    if rho.shape != (pts.shape[0] * pts.shape[1],) or not np.isfinite(rho).all() or (rho < 0).any():
        raise ValueError("density must return one finite, non-negative value per point")
    w = rho.reshape(4, -1) * (vol / 4.0)  # (4, m)
    mass = np.bincount(cell, weights=w.sum(axis=0), minlength=n)
    for ax in range(3):
        m = np.bincount(cell, weights=(w * pts[:, :, ax]).sum(axis=0), minlength=n)
        with np.errstate(invalid="ignore", divide="ignore"):
            out[:, ax] = np.where(mass > 0, m / np.where(mass > 0, mass, 1), out[:, ax])
    return out


def _check(iterations, tol, density):
    """ValueErrors for options :func:`lloyd3d` cannot use (as :func:`voroforge.lloyd`'s)."""
    if isinstance(iterations, bool) or not isinstance(iterations, (int, np.integer)):
        raise ValueError(f"iterations must be an integer; got {iterations!r}")
    if iterations < 0:
        raise ValueError(f"iterations must be >= 0; got {iterations}")
    if tol is not None and (
        isinstance(tol, bool)
        or not isinstance(tol, (int, float, np.number))
        or not (np.isfinite(tol) and tol >= 0)
    ):
        raise ValueError(f"tol must be None or a finite number >= 0; got {tol!r}")
    if density is not None and not callable(density):
        raise ValueError(f"density must be None or a callable; got {type(density).__name__}")


def _nearest_on_mesh(mesh, q):
    """The point of the mesh's surface nearest to each row of ``q`` (to rounding)."""
    from itertools import chain

    from scipy.spatial import cKDTree

    from ..kernels.surface import project_pieces

    T = mesh.vertices[mesh.faces]
    cen = T.mean(axis=1)
    rad = float(np.sqrt(((T - cen[:, None, :]) ** 2).sum(axis=2)).max())
    tree = cKDTree(cen)
    d, _ = tree.query(q)
    # every triangle with a point within d of q has its centroid within d + rad
    lists = tree.query_ball_point(q, d + rad * (1.0 + 1e-9))
    lens = np.fromiter(map(len, lists), np.int64, count=len(lists))
    owner = np.repeat(np.arange(len(q), dtype=np.int64), lens)
    tris = np.fromiter(chain.from_iterable(lists), np.int64, count=len(owner))
    out = np.zeros_like(q)
    # its inputs as read-only views, as the surfaces hand theirs (engine.readonly)
    v, f, q = readonly(mesh.vertices), readonly(mesh.faces), readonly(q)
    project_pieces(v, f, q, readonly(owner), readonly(tris), out)
    return out


def _into_mesh(mesh, c, old):
    """``c`` with its points outside the mesh solid moved to the nearest point of its surface.

    That point is at least as near the centroid as any point of the solid, the previous
    site ``old`` included, so the step does not raise the energy. Rounding can leave it
    just outside: :func:`_push_inside` then moves it in by a few units of rounding.
    """
    from .mesh3d import sites_inside

    q = c.copy()
    out = np.flatnonzero(~sites_inside(mesh, q))
    if len(out):
        q[out] = _nearest_on_mesh(mesh, q[out])
        _push_inside(mesh, q, c, old, out)
    return q


def _push_inside(mesh, q, c, old, rows):
    """Rows ``rows`` of ``q`` (on the surface to rounding) moved inside the exact test, in place.

    First along the ray from the centroid ``c`` through ``q`` by
    :data:`~voroforge.config.LLOYD3D_INTO_MESH_PUSH` (farther from ``c`` by at most ``2**-30``
    of the mesh's size), else towards ``old`` where that is inside, by
    :data:`~voroforge.config.LLOYD3D_INTO_MESH_FRACTIONS`: a point between ``q`` and ``old``
    is no farther from ``c`` than ``old`` (the distance is convex). A row neither moves in
    stays on the surface, just outside (its cell still reaches the solid).
    """
    from .mesh3d import sites_inside

    rows = rows[~sites_inside(mesh, q[rows])]
    if not len(rows):
        return
    scale = float(np.abs(mesh.vertices).max())
    u = q[rows] - c[rows]
    norm = np.sqrt((u * u).sum(axis=1))[:, None]
    u = np.divide(u, norm, out=np.zeros_like(u), where=norm > 0)
    start = q[rows]
    tries = [(start, u * (h * scale)) for h in LLOYD3D_INTO_MESH_PUSH]
    for t in LLOYD3D_INTO_MESH_FRACTIONS:
        tries.append((start, t * (old[rows] - start)))
    keep = np.ones(len(rows), bool)
    for base, delta in tries:
        live = np.flatnonzero(keep)
        if not len(live):
            break
        trial = base[live] + delta[live]
        ok = sites_inside(mesh, trial)
        q[rows[live[ok]]] = trial[ok]
        keep[live[ok]] = False


def lloyd3d(points, container=None, *, iterations=20, tol=1e-9, density=None) -> Relaxation3D:
    """Move 3D sites to their cells' centroids until they stop moving (3D CVT).

    Parameters
    ----------
    points : (n, 3) array_like
        Starting sites.
    container : as :func:`voroforge.voronoi3d` (box, Convex or closed mesh)
    iterations : int
        Most Lloyd steps.
    tol : float or None
        Stop when no site moves more than ``tol`` times the container's size (None: run
        every step).
    density : callable, optional
        ``density(xyz (m, 3)) -> (m,)`` non-negative: density-weighted centroids (a 4-point
        degree-2 rule per tetrahedron of each cell's face fans: exact for linear densities).

    Returns
    -------
    Relaxation3D

    Raises
    ------
    ValueError
        Malformed points, container, options or density values.

    Notes
    -----
    In a mesh container a cell's centroid can lie outside the solid (a cell of a torus's
    tube curves around the hole): the site moves to the nearest point of the surface
    instead, kept inside the exact inside test, so sites stay in the container and the
    energy ``sum_i int_{V_i} rho |x - z_i|^2`` does not increase from sites inside (as the
    2D :func:`voroforge.lloyd` does with ``areas=``). Box and Convex cells are convex:
    their centroids are inside. No points: an empty result.
    """
    p = as_points(points, dim=3)
    _check(iterations, tol, density)
    d = voronoi3d(p, container)
    if container is None:  # keep the first box: the sites' padded box would drift
        container = None if d.box is None else tuple(np.asarray(d.box).ravel())
    mesh = None
    if d.container == "mesh":
        from .mesh3d import as_mesh_container

        mesh = as_mesh_container(container)[0]
    box = np.asarray(d.box) if d.box is not None else np.zeros((2, 3))
    if d.box is None and len(p):
        box = np.array([p.min(0), p.max(0)])
    size = float((box[1] - box[0]).max()) or 1.0
    moves = []
    it = 0
    for it in range(1, iterations + 1):  # noqa: B007 - reported
        c = np.asarray(d.centroids) if density is None else _density_centroids(d, density)
        live = np.isfinite(c).all(axis=1)
        q = np.where(live[:, None], c, p)
        if mesh is not None and live.any():  # a site without a cell stays where it is
            q[live] = _into_mesh(mesh, q[live], p[live])
        step = float(np.abs(q - p).max()) if len(p) else 0.0
        moves.append(step)
        p = q
        d = voronoi3d(p, container)
        if tol is not None and step <= tol * size:
            break
    return Relaxation3D(p, d, np.array(moves), it)
