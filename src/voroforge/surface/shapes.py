"""Surfaces: a triangle mesh, its UVs per corner, and (for the built-in shapes) the map f(u, v).

Every surface is a triangle mesh (``vertices (V, 3)``, ``faces (F, 3)``) with UVs per face
corner (``uv (F, 3, 2)``, so a seam keeps both sides' coordinates while its vertices are
shared). Analytic surfaces (cylinder, sphere patch, saddle, torus, height field, any
``parametric(f)``) also keep ``f(u, v) -> xyz`` on ``[0, 1]^2``: Surface Morph evaluates it
directly, so morphed vertices lie on the true surface. A mesh surface maps UV points through
its UV triangles (barycentric), so they lie on the mesh.

The restricted Voronoi diagram is always computed on the mesh; choose the resolution so the
facets are small against the cells (the default gives edges of about 1/100 of the span).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from itertools import chain

import numpy as np

from ..config import SURFACE_COORD_RANGE, SURFACE_DEFAULT_MAX_CELLS, SURFACE_MAX_CELLS
from ..engine.readonly import readonly

__all__ = [
    "Surface",
    "cylinder",
    "heightfield",
    "mesh",
    "parametric",
    "saddle",
    "sphere",
    "sphere_patch",
    "torus",
]


@dataclass(eq=False)
class Surface:
    """A triangle mesh with UVs per corner and, for analytic surfaces, the map ``f(u, v)``.

    Attributes
    ----------
    vertices : (V, 3) float64
    faces : (F, 3) int64
        Counter-clockwise seen from the outside (the normals' side).
    uv : (F, 3, 2) float64 or None
        UV coordinates of each face corner.
    fn : callable or None
        ``fn(u, v) -> (..., 3)``, vectorised, on ``[0, 1]^2``.
    jacobian : callable or None
        ``jacobian(u, v) -> (f_u, f_v)``, each ``(..., 3)``; finite differences when absent.
    name : str
    """

    vertices: np.ndarray
    faces: np.ndarray
    uv: np.ndarray | None = None
    fn: Callable | None = None
    jacobian: Callable | None = None
    name: str = "surface"
    _cache: dict = field(default_factory=dict, repr=False)

    def __post_init__(self):
        v = np.ascontiguousarray(self.vertices, dtype=np.float64)
        f = np.ascontiguousarray(self.faces, dtype=np.int64)
        if v.ndim != 2 or v.shape[1] != 3 or len(v) < 3:
            raise ValueError(f"surface vertices must be (V, 3) with V >= 3; got {v.shape}")
        if f.ndim != 2 or f.shape[1] != 3 or len(f) == 0:
            raise ValueError(f"surface faces must be (F, 3) with F >= 1; got {f.shape}")
        if not np.isfinite(v).all():
            raise ValueError("surface vertices must be finite")
        if f.min() < 0 or f.max() >= len(v):
            raise ValueError("surface faces index vertices that do not exist")
        check_surface_range(v, "surface vertices", extent=True)
        v.flags.writeable = False
        f.flags.writeable = False
        self.vertices, self.faces = v, f
        if self.uv is not None:
            uv = np.ascontiguousarray(self.uv, dtype=np.float64)
            if uv.shape != (len(f), 3, 2):
                raise ValueError(f"surface uv must be (F, 3, 2) = {(len(f), 3, 2)}; got {uv.shape}")
            uv.flags.writeable = False
            self.uv = uv

    # --- derived data --------------------------------------------------------------------

    @property
    def face_areas(self) -> np.ndarray:
        """(F,) area of each triangle."""
        if "areas" not in self._cache:
            v, f = self.vertices, self.faces
            cr = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
            self._cache["areas"] = 0.5 * np.sqrt(np.einsum("ij,ij->i", cr, cr))
        return self._cache["areas"]

    @property
    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """``(lo, hi)``, each (3,): the corners of the vertices' bounding box."""
        if "box" not in self._cache:
            self._cache["box"] = (self.vertices.min(axis=0), self.vertices.max(axis=0))
        return self._cache["box"]

    @property
    def face_frames(self) -> np.ndarray:
        """Per triangle, what the surface kernels need of it (``kernels.surface.tri_frames``)."""
        if "frames" not in self._cache:
            from ..kernels.surface import tri_frames

            self._cache["frames"] = tri_frames(self.vertices, self.faces)
        return self._cache["frames"]

    @property
    def area(self) -> float:
        """Total mesh area (exactly summed: ``math.fsum``)."""
        if "area" not in self._cache:
            self._cache["area"] = math.fsum(self.face_areas)
        return self._cache["area"]

    @property
    def scale(self) -> float:
        """The bounding box's diagonal."""
        return float(np.linalg.norm(np.ptp(self.vertices, axis=0)))

    @property
    def edges(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(edges (E, 2), face_edges (F, 3), border (E,) bool)``.

        ``face_edges[t, k]`` is the edge from corner ``k`` to ``k + 1`` of triangle ``t``;
        ``border`` marks edges with one triangle.
        """
        if "edges" not in self._cache:
            f = self.faces
            pairs = np.stack([f, np.roll(f, -1, axis=1)], axis=2).reshape(-1, 2)
            key = np.sort(pairs, axis=1)
            uniq, inv, count = np.unique(key, axis=0, return_inverse=True, return_counts=True)
            self._cache["edges"] = (uniq, inv.reshape(-1, 3), count == 1)
        return self._cache["edges"]

    @property
    def closed(self) -> bool:
        """True when every edge has two triangles."""
        return not self.edges[2].any()

    def to_trimesh(self):
        """The mesh as a ``trimesh.Trimesh`` (no processing)."""
        import trimesh

        return trimesh.Trimesh(self.vertices.copy(), self.faces.copy(), process=False)

    def _centroid_tree(self):
        if "ctree" not in self._cache:
            from scipy.spatial import cKDTree

            v, f = self.vertices, self.faces
            cen = v[f].mean(axis=1)
            rad = np.sqrt(((v[f] - cen[:, None, :]) ** 2).sum(axis=2)).max()
            self._cache["ctree"] = (cKDTree(cen), float(rad))
        return self._cache["ctree"]

    def project(self, points) -> np.ndarray:
        """The nearest point of the mesh to each point.

        Parameters
        ----------
        points : (n, 3) float64

        Returns
        -------
        (n, 3) float64
        """
        from ..kernels.surface import project_pieces

        p = as_points3(points, "points")
        tree, rad = self._centroid_tree()
        d, _ = tree.query(p)
        lists = tree.query_ball_point(p, d + rad + 1e-12 * self.scale)
        # flattened at C level (map, chain): a Python loop over the lists cost more than
        # the query on planarize's 200 projections
        lens = np.fromiter(map(len, lists), np.int64, count=len(lists))
        owner = np.repeat(np.arange(len(p), dtype=np.int64), lens)
        tris = np.fromiter(chain.from_iterable(lists), np.int64, count=len(owner))
        out = np.zeros_like(p)
        # read-only views of what it does not write, on every path (engine.readonly)
        v, f = readonly(self.vertices), readonly(self.faces)
        project_pieces(v, f, readonly(p), readonly(owner), readonly(tris), out)
        return out

    def sample(self, n: int, *, seed: int = 0) -> np.ndarray:
        """``n`` points uniformly distributed over the mesh area (seeded)."""
        if int(n) != n or n < 1:
            raise ValueError(f"sample count must be a positive integer; got {n!r}")
        rng = np.random.default_rng(seed)
        w = self.face_areas / self.face_areas.sum()
        t = rng.choice(len(w), size=int(n), p=w)
        r1 = np.sqrt(rng.random(int(n)))
        r2 = rng.random(int(n))
        v = self.vertices[self.faces[t]]
        return (
            (1 - r1)[:, None] * v[:, 0]
            + (r1 * (1 - r2))[:, None] * v[:, 1]
            + (r1 * r2)[:, None] * v[:, 2]
        )

    # --- the UV map ----------------------------------------------------------------------

    def evaluate(self, u, v) -> np.ndarray:
        """Points of the surface at UV coordinates (arrays of one shape) -> ``(..., 3)``.

        Analytic surfaces evaluate ``f``; mesh surfaces locate each UV point in a UV triangle.
        """
        u = np.asarray(u, dtype=np.float64)
        v = np.asarray(v, dtype=np.float64)
        if self.fn is not None:
            return np.asarray(self.fn(u, v), dtype=np.float64)
        if self.uv is None:
            raise ValueError(f"{self.name}: this mesh has no UV coordinates to map a design with")
        flat = self._uv_locate(np.stack([u.ravel(), v.ravel()], axis=1))
        return flat.reshape(u.shape + (3,))

    def _uv_locate(self, q: np.ndarray) -> np.ndarray:
        from scipy.spatial import cKDTree

        if "uvtree" not in self._cache:
            c = self.uv.mean(axis=1)
            r = np.sqrt(((self.uv - c[:, None, :]) ** 2).sum(axis=2)).max()
            self._cache["uvtree"] = (cKDTree(c), float(r))
        tree, rad = self._cache["uvtree"]
        d, _ = tree.query(q)
        out = np.full((len(q), 3), np.nan)
        best = np.full(len(q), np.inf)
        for k, cands in enumerate(tree.query_ball_point(q, d + rad + 1e-12)):
            t = np.asarray(cands)
            a, b, c = self.uv[t, 0], self.uv[t, 1], self.uv[t, 2]
            m = np.stack([b - a, c - a], axis=2)
            det = np.linalg.det(m)
            ok = np.abs(det) > 0
            lam = np.zeros((len(t), 2))
            lam[ok] = np.linalg.solve(m[ok], (q[k] - a[ok])[..., None])[..., 0]
            bary = np.stack([1 - lam.sum(axis=1), lam[:, 0], lam[:, 1]], axis=1)
            outside = np.where(ok, -bary.min(axis=1), np.inf)
            j = int(np.argmin(outside))
            if outside[j] < best[k]:
                best[k] = outside[j]
                w = np.clip(bary[j], 0, None)
                w /= w.sum()
                out[k] = w @ self.vertices[self.faces[t[j]]]
        if np.isnan(out).any() or (best > 1e-9).any():
            raise ValueError(f"{self.name}: UV points outside the mesh's UV layout")
        return out

    def derivatives(self, u, v) -> tuple[np.ndarray, np.ndarray]:
        """``(f_u, f_v)`` at UV points: analytic when known, else central differences."""
        u = np.asarray(u, dtype=np.float64)
        v = np.asarray(v, dtype=np.float64)
        if self.jacobian is not None:
            fu, fv = self.jacobian(u, v)
            return np.asarray(fu, dtype=np.float64), np.asarray(fv, dtype=np.float64)
        h = 1e-6
        ua, ub = np.clip(u - h, 0, 1), np.clip(u + h, 0, 1)
        va, vb = np.clip(v - h, 0, 1), np.clip(v + h, 0, 1)
        fu = (self.evaluate(ub, v) - self.evaluate(ua, v)) / (ub - ua)[..., None]
        fv = (self.evaluate(u, vb) - self.evaluate(u, va)) / (vb - va)[..., None]
        return fu, fv

    def area_element(self, u, v) -> np.ndarray:
        """``|f_u x f_v|``: surface area per unit UV area."""
        fu, fv = self.derivatives(u, v)
        return np.linalg.norm(np.cross(fu, fv), axis=-1)

    def gaussian_curvature(self, points) -> np.ndarray:
        """Gaussian curvature of the mesh near each point (angle defect over the vertex area).

        Parameters
        ----------
        points : (n, 3) float64

        Returns
        -------
        (n,) float64
            ``(2 pi - sum of angles) / (area / 3)`` at the nearest interior mesh vertex; 0 at
            border vertices (no defect is defined there).
        """
        from scipy.spatial import cKDTree

        if "gauss" not in self._cache:
            v, f = self.vertices, self.faces
            ang = np.zeros(len(v))
            area = np.zeros(len(v))
            for k in range(3):
                a = v[f[:, k]]
                b = v[f[:, (k + 1) % 3]] - a
                c = v[f[:, (k + 2) % 3]] - a
                cos = np.einsum("ij,ij->i", b, c) / (
                    np.linalg.norm(b, axis=1) * np.linalg.norm(c, axis=1) + 1e-300
                )
                np.add.at(ang, f[:, k], np.arccos(np.clip(cos, -1, 1)))
                np.add.at(area, f[:, k], self.face_areas / 3)
            border = np.zeros(len(v), bool)
            e, _, b = self.edges
            border[e[b].ravel()] = True
            k = np.where(border | (area == 0), 0.0, (2 * np.pi - ang) / np.maximum(area, 1e-300))
            self._cache["gauss"] = (cKDTree(v), k)
        tree, k = self._cache["gauss"]
        _, idx = tree.query(as_points3(points, "points"))
        return k[idx]


def as_points3(points, name: str) -> np.ndarray:
    """A float64 copy of ``points`` checked to be finite ``(n, 3)`` (``name`` for the error)."""
    p = np.array(points, dtype=np.float64, copy=True)
    if p.ndim != 2 or p.shape[1] != 3:
        raise ValueError(f"{name} must be (n, 3); got shape {p.shape}")
    if not np.isfinite(p).all():
        raise ValueError(f"{name} must be finite")
    return p


def check_surface_range(p: np.ndarray, name: str, *, extent: bool = False) -> None:
    """Raise ``ValueError`` where ``p`` lies outside :data:`SURFACE_COORD_RANGE`.

    Every coordinate's magnitude must be at most its upper end and, with ``extent``, the
    largest side of the points' bounding box at least its lower end (areas are squared in
    the kernels: past ~1e+-77 they vanish or overflow).
    """
    lo, hi = SURFACE_COORD_RANGE
    big = float(np.abs(p).max(initial=0.0))
    if big > hi:
        raise ValueError(
            f"{name} reach {big:.3g}; surfaces work with coordinates up to {hi:g} "
            "(scale them by a power of ten, and the results back)"
        )
    if extent and len(p):
        side = float(np.ptp(p, axis=0).max())
        if side < lo:
            raise ValueError(
                f"{name} span {side:.3g}; surfaces work with an extent of at least {lo:g} "
                "(scale them by a power of ten, and the results back)"
            )


def _positive(value, name: str) -> float:
    x = float(value)
    if not math.isfinite(x) or x <= 0:
        raise ValueError(f"{name} must be a positive number; got {value!r}")
    return x


def _resolution(res, default: tuple[int, int]) -> tuple[int, int]:
    """``(nu, nv)`` grid cells: ``res`` checked, or ``default`` capped (with a warning)."""
    if res is None:
        nu, nv = default
        if nu * nv > SURFACE_DEFAULT_MAX_CELLS:
            fit = max(1, SURFACE_DEFAULT_MAX_CELLS // nu)
            warnings.warn(
                f"near-square facets would need {nu} x {nv} grid cells; using {nu} x {fit} "
                "(elongated facets: pass resolution=(nu, nv) to choose)",
                stacklevel=3,
            )
            nv = fit
        return nu, nv
    nu, nv = (res, res) if np.isscalar(res) else res
    if int(nu) != nu or int(nv) != nv or nu < 1 or nv < 1:
        raise ValueError(f"resolution must be positive integers (nu, nv); got {res!r}")
    if int(nu) * int(nv) > SURFACE_MAX_CELLS:
        raise ValueError(
            f"resolution {int(nu)} x {int(nv)} is {int(nu) * int(nv):,} grid cells; at most "
            f"{SURFACE_MAX_CELLS:,} (two triangles each)"
        )
    return int(nu), int(nv)


def _grid_mesh(fn, nu: int, nv: int, *, merge_tol: float):
    """Tessellate ``fn`` on a ``(nu + 1) x (nv + 1)`` UV grid; coincident vertices merged."""
    from ..io.snap import close_pairs  # numpy: no scipy.spatial import (0.2-0.4 s) for this

    us, vs = np.meshgrid(np.linspace(0, 1, nu + 1), np.linspace(0, 1, nv + 1), indexing="ij")
    uvg = np.stack([us.ravel(), vs.ravel()], axis=1)
    xyz = np.asarray(fn(uvg[:, 0], uvg[:, 1]), dtype=np.float64)
    if xyz.shape != (len(uvg), 3):
        raise ValueError(f"f(u, v) must return (n, 3) points for n UV pairs; got {xyz.shape}")
    if not np.isfinite(xyz).all():
        raise ValueError("f(u, v) returned non-finite points")
    idx = np.arange((nu + 1) * (nv + 1)).reshape(nu + 1, nv + 1)
    a, b = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel()
    c, d = idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()
    # alternate the diagonal so the mesh has no preferred direction
    flip = ((np.arange(nu)[:, None] + np.arange(nv)[None, :]) % 2).ravel().astype(bool)
    t1 = np.where(flip[:, None], np.stack([a, b, d], 1), np.stack([a, b, c], 1))
    t2 = np.where(flip[:, None], np.stack([b, c, d], 1), np.stack([a, c, d], 1))
    corners = np.concatenate([t1, t2])
    uv = uvg[corners]
    # merge coincident points (seams, poles), keeping UVs per corner
    span = float(np.linalg.norm(np.ptp(xyz, axis=0)))
    pairs = close_pairs(xyz, merge_tol * span)
    parent = np.arange(len(xyz))
    for i, j in sorted(map(tuple, pairs)):
        ri, rj = parent[i], parent[j]
        while parent[ri] != ri:
            ri = parent[ri]
        while parent[rj] != rj:
            rj = parent[rj]
        if ri != rj:
            parent[max(ri, rj)] = min(ri, rj)
    for i in range(len(parent)):
        r = parent[i]
        while parent[r] != r:
            r = parent[r]
        parent[i] = r
    keep, inv = np.unique(parent, return_inverse=True)
    faces = inv[corners]
    good = (
        (faces[:, 0] != faces[:, 1]) & (faces[:, 1] != faces[:, 2]) & (faces[:, 0] != faces[:, 2])
    )
    if not good.any():
        raise ValueError(
            f"the surface collapses at {nu} x {nv} grid cells: every facet has corners closer "
            f"than {merge_tol:g} x the surface's size ({span:.3g}), which are merged (too thin "
            "to tessellate)"
        )
    verts = xyz[keep]
    faces, uv = faces[good], uv[good]
    return verts, faces, uv


def _orient_outward(verts, faces, fn_normal):
    """Flip all triangles when their normals point against ``fn_normal`` on average."""
    v = verts[faces]
    n = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0])
    if np.einsum("ij,ij->", n, fn_normal(v.mean(axis=1))) < 0:
        return faces[:, ::-1].copy(), True
    return faces, False


def parametric(
    f: Callable,
    *,
    resolution=None,
    jacobian: Callable | None = None,
    name: str = "parametric",
) -> Surface:
    """A surface from a vectorised map ``f(u, v) -> (n, 3)`` on ``[0, 1]^2``.

    Parameters
    ----------
    f : callable
        Takes two float arrays of one shape, returns points with a last axis of 3.
    resolution : int or (int, int), optional
        Grid cells along u and v (default 64 x 64); points that coincide (a seam, a pole) are
        merged, so a closed surface gives a closed mesh.
    jacobian : callable, optional
        ``jacobian(u, v) -> (f_u, f_v)``; central differences otherwise.
    name : str

    Returns
    -------
    Surface

    Examples
    --------
    >>> import numpy as np
    >>> s = parametric(lambda u, v: np.stack([u, v, u * v], axis=-1), resolution=8)
    >>> s.faces.shape
    (128, 3)
    """
    if not callable(f):
        raise ValueError(f"parametric needs a callable f(u, v); got {type(f).__name__}")
    nu, nv = _resolution(resolution, (64, 64))
    verts, faces, uv = _grid_mesh(f, nu, nv, merge_tol=1e-10)
    return Surface(verts, faces, uv, fn=f, jacobian=jacobian, name=name)


def cylinder(radius: float, height: float, *, resolution=None) -> Surface:
    """An open cylinder around the z axis, ``u`` the angle (one turn), ``v`` the height.

    ``f(u, v) = (r cos 2 pi u, r sin 2 pi u, h v)``: isometric up to scale, so UV areas times
    ``2 pi r h`` are areas on the surface.

    Parameters
    ----------
    radius, height : float
    resolution : int or (int, int), optional
        Segments around and rows up (default 96 around, rows to make near-square facets).
    """
    r = _positive(radius, "radius")
    h = _positive(height, "height")
    tau = 2 * np.pi
    nu = 96
    default = (nu, max(1, round(h / (tau * r / nu))))
    nu, nv = _resolution(resolution, default)

    def fn(u, v):
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        return np.stack([r * np.cos(tau * u), r * np.sin(tau * u), h * v], axis=-1)

    def jac(u, v):
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        fu = np.stack([-tau * r * np.sin(tau * u), tau * r * np.cos(tau * u), 0 * u], axis=-1)
        fv = np.stack([0 * u, 0 * u, h + 0 * u], axis=-1)
        return fu, fv

    verts, faces, uv = _grid_mesh(fn, nu, nv, merge_tol=1e-10)
    faces, flipped = _orient_outward(verts, faces, lambda p: p * [1, 1, 0])
    if flipped:
        uv = uv[:, ::-1].copy()
    return Surface(verts, faces, uv, fn=fn, jacobian=jac, name="cylinder")


def sphere_patch(
    radius: float,
    *,
    polar: tuple[float, float] = (0.0, np.pi / 2),
    azimuth: tuple[float, float] = (0.0, 2 * np.pi),
    resolution=None,
) -> Surface:
    """A part of a sphere about the origin: ``u`` the azimuth, ``v`` the polar angle.

    The default is the upper hemisphere (a dome); ``polar=(0, pi)`` is the whole sphere (the
    poles are merged), ``polar=(0, 0.6)`` a shallow cap.

    Parameters
    ----------
    radius : float
    polar : (float, float)
        Polar angles from the +z axis, radians, ``0 <= start < stop <= pi``.
    azimuth : (float, float)
        Azimuths, radians (at most one turn).
    resolution : int or (int, int), optional
    """
    r = _positive(radius, "radius")
    t0, t1 = map(float, polar)
    p0, p1 = map(float, azimuth)
    if not (0 <= t0 < t1 <= np.pi):
        raise ValueError(f"polar must satisfy 0 <= start < stop <= pi; got {polar!r}")
    if not (p0 < p1 <= p0 + 2 * np.pi + 1e-12):
        raise ValueError(f"azimuth must be an increasing range of at most 2 pi; got {azimuth!r}")
    arc_u = (p1 - p0) * math.sin(max(min(t1, np.pi / 2), t0))
    nv = 48
    default = (max(3, round(nv * arc_u / (t1 - t0))), nv)
    nu, nv = _resolution(resolution, default)

    def fn(u, v):
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        ph = p0 + (p1 - p0) * u
        th = t0 + (t1 - t0) * v
        return np.stack(
            [r * np.sin(th) * np.cos(ph), r * np.sin(th) * np.sin(ph), r * np.cos(th)], axis=-1
        )

    def jac(u, v):
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        ph = p0 + (p1 - p0) * u
        th = t0 + (t1 - t0) * v
        du = (
            (p1 - p0)
            * r
            * np.stack([-np.sin(th) * np.sin(ph), np.sin(th) * np.cos(ph), 0 * u], axis=-1)
        )
        dv = (
            (t1 - t0)
            * r
            * np.stack([np.cos(th) * np.cos(ph), np.cos(th) * np.sin(ph), -np.sin(th)], axis=-1)
        )
        return du, dv

    verts, faces, uv = _grid_mesh(fn, nu, nv, merge_tol=1e-10)
    faces, flipped = _orient_outward(verts, faces, lambda p: p)
    if flipped:
        uv = uv[:, ::-1].copy()
    return Surface(verts, faces, uv, fn=fn, jacobian=jac, name="sphere_patch")


def sphere(radius: float = 1.0, *, subdivisions: int = 4) -> Surface:
    """A closed icosphere (near-uniform triangles; ``20 * 4**subdivisions`` of them).

    No UV map (use :func:`sphere_patch` to morph a design onto a sphere).
    """
    import trimesh

    r = _positive(radius, "radius")
    if int(subdivisions) != subdivisions or not 0 <= subdivisions <= 8:
        raise ValueError(f"subdivisions must be an integer 0..8; got {subdivisions!r}")
    m = trimesh.creation.icosphere(subdivisions=int(subdivisions), radius=1.0)
    v = np.asarray(m.vertices, dtype=np.float64)
    v = r * v / np.linalg.norm(v, axis=1, keepdims=True)
    return Surface(v, np.asarray(m.faces), name="sphere")


def torus(major: float = 1.0, minor: float = 0.4, *, resolution=None) -> Surface:
    """A closed torus about the z axis: ``u`` around the axis, ``v`` around the tube.

    Parameters
    ----------
    major, minor : float
        Distance from the axis to the tube's centre, and the tube's radius
        (``0 < minor < major``).
    resolution : int or (int, int), optional
        Segments around the axis and around the tube (default in the ratio of the radii).
    """
    big = _positive(major, "major")
    small = _positive(minor, "minor")
    if small >= big:
        raise ValueError(f"torus minor radius must be below the major one; got {minor} >= {major}")
    tau = 2 * np.pi
    nv = 48
    default = (max(3, round(nv * big / small)), nv)
    nu, nv = _resolution(resolution, default)

    def fn(u, v):
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        rr = big + small * np.cos(tau * v)
        return np.stack(
            [rr * np.cos(tau * u), rr * np.sin(tau * u), small * np.sin(tau * v)], axis=-1
        )

    verts, faces, uv = _grid_mesh(fn, nu, nv, merge_tol=1e-10)

    def outward(p):
        ring = p * [1, 1, 0]
        ring = big * ring / np.linalg.norm(ring, axis=1, keepdims=True)
        return p - ring

    faces, flipped = _orient_outward(verts, faces, outward)
    if flipped:
        uv = uv[:, ::-1].copy()
    return Surface(verts, faces, uv, fn=fn, name="torus")


def saddle(
    width: float = 4.0, depth: float | None = None, rise: float = 0.8, *, resolution=None
) -> Surface:
    """A hyperbolic paraboloid ``z = rise * (X^2 - Y^2)`` over a ``width x depth`` rectangle.

    ``X, Y`` run over ``[-1, 1]`` across the rectangle (centred on the origin), so the corners
    rise and fall by ``rise``; Gaussian curvature is negative everywhere.
    """
    w = _positive(width, "width")
    d = _positive(depth if depth is not None else width, "depth")
    k = float(rise)
    if not math.isfinite(k):
        raise ValueError(f"rise must be finite; got {rise!r}")
    n = 64
    default = (max(1, round(n * w / max(w, d))), max(1, round(n * d / max(w, d))))
    nu, nv = _resolution(resolution, default)

    def fn(u, v):
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        x, y = 2 * u - 1, 2 * v - 1
        return np.stack([0.5 * w * x, 0.5 * d * y, k * (x * x - y * y)], axis=-1)

    def jac(u, v):
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        x, y = 2 * u - 1, 2 * v - 1
        z = 0 * u
        return (
            np.stack([w + z, z, 4 * k * x], axis=-1),
            np.stack([z, d + z, -4 * k * y], axis=-1),
        )

    verts, faces, uv = _grid_mesh(fn, nu, nv, merge_tol=1e-10)
    return Surface(verts, faces, uv, fn=fn, jacobian=jac, name="saddle")


def heightfield(array, bounds) -> Surface:
    """A height field: ``z`` sampled on a regular grid over ``bounds``, bilinear in between.

    Parameters
    ----------
    array : (ny, nx) array_like
        Heights; row ``j`` is at ``y = ymin + j * dy``, column ``i`` at ``x = xmin + i * dx``.
    bounds : (xmin, ymin, xmax, ymax)
        The rectangle the grid spans.

    Returns
    -------
    Surface
        One mesh vertex per sample (two triangles per grid cell), ``u`` along x, ``v`` along y.
    """
    z = np.array(array, dtype=np.float64, copy=True)
    if z.ndim != 2 or min(z.shape) < 2:
        raise ValueError(f"heightfield needs a 2D array of at least 2 x 2 samples; got {z.shape}")
    if not np.isfinite(z).all():
        raise ValueError("heightfield samples must be finite")
    try:
        x0, y0, x1, y1 = (float(b) for b in bounds)
    except (TypeError, ValueError):
        raise ValueError(f"bounds must be (xmin, ymin, xmax, ymax); got {bounds!r}") from None
    if not (x1 > x0 and y1 > y0):
        raise ValueError(f"bounds must have xmax > xmin and ymax > ymin; got {bounds!r}")
    ny, nx = z.shape

    def fn(u, v):
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        gx = np.clip(u, 0, 1) * (nx - 1)
        gy = np.clip(v, 0, 1) * (ny - 1)
        i = np.minimum(gx.astype(int), nx - 2)
        j = np.minimum(gy.astype(int), ny - 2)
        fx, fy = gx - i, gy - j
        h = (
            z[j, i] * (1 - fx) * (1 - fy)
            + z[j, i + 1] * fx * (1 - fy)
            + z[j + 1, i] * (1 - fx) * fy
            + z[j + 1, i + 1] * fx * fy
        )
        return np.stack([x0 + u * (x1 - x0), y0 + v * (y1 - y0), h], axis=-1)

    verts, faces, uv = _grid_mesh(fn, nx - 1, ny - 1, merge_tol=0.0)
    # grid vertices are the samples themselves
    return Surface(verts, faces, uv, fn=fn, name="heightfield")


def mesh(trimesh_or_path, *, name: str | None = None) -> Surface:
    """A surface from a triangle mesh (a ``trimesh.Trimesh`` or a mesh file), with its UVs.

    Parameters
    ----------
    trimesh_or_path : trimesh.Trimesh or str or Path
        Files load through :func:`voroforge.io.mesh.read` (STL, OBJ, 3MF, GLB, PLY, 3dm).
        Per-vertex UVs (``mesh.visual.uv``) become per-corner UVs.
    """
    import trimesh

    m = trimesh_or_path
    label = name
    if not isinstance(m, trimesh.Trimesh):
        from pathlib import Path

        path = Path(m)
        if not path.exists():
            raise ValueError(f"{path}: no such mesh file")
        try:
            from ..io.mesh import read

            m = read(path)
        except ImportError:  # pragma: no cover - io.mesh ships with the mesh extra
            m = trimesh.load(path, force="mesh")
        label = label or path.stem
    faces = np.asarray(m.faces, dtype=np.int64)
    uv = None
    vis = getattr(m, "visual", None)
    vuv = getattr(vis, "uv", None) if vis is not None else None
    if vuv is not None and len(vuv) == len(m.vertices):
        uv = np.asarray(vuv, dtype=np.float64)[faces]
    return Surface(np.asarray(m.vertices, dtype=np.float64), faces, uv, name=label or "mesh")
