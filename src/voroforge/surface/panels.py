"""Panels on a surface: polygons in space with planarity, planarisation, solids and openings.

A :class:`Panels` holds shared vertices and, per panel, index rings (the exterior first,
then holes). Morphed panels (:func:`voroforge.surface.morph`) carry UVs and follow the
surface; Voronoi panels (:meth:`SurfaceVoronoi.panels`) are the cells' corner polygons with
straight edges, corners shared between neighbours, so :meth:`Panels.planarize` moves each
corner once for all the panels that meet there.

Planar hexagons exist only where the Gaussian curvature is positive (or zero): in a region
of negative curvature a planar hexagonal panel must be non-convex (Li, Liu & Wang 2015).
:meth:`Panels.planarize` flags those panels and the ones it could not make planar.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import shapely

from ..config import SURFACE_DEGENERATE_NORMAL, SURFACE_NORMAL_NUDGE

__all__ = ["MissingPanelWarning", "Panels", "Planarity", "PlanarizeReport", "PlanarizeWarning"]


class MissingPanelWarning(UserWarning):
    """Cells that have no panel (a boundary of fewer than 3 corners, or several rings)."""


class PlanarizeWarning(UserWarning):
    """:meth:`Panels.planarize` left panels that cross themselves or turned over."""


@dataclass(frozen=True)
class Planarity:
    """Per panel: the largest distance of a vertex from the best-fit plane.

    ``absolute`` in model units, ``relative`` divided by the panel's longest edge.
    """

    absolute: np.ndarray
    relative: np.ndarray

    def __iter__(self):
        return iter((self.absolute, self.relative))


@dataclass(frozen=True)
class PlanarizeReport:
    """What :meth:`Panels.planarize` reached.

    Attributes
    ----------
    tolerance : float
    iterations : int
    planarity : Planarity
        After planarising.
    not_planar : (k,) int
        Panels (positions) still above the tolerance.
    negative_curvature : (m,) int
        Panels over a region of negative Gaussian curvature (no convex planar hexagon fits
        there; a planar panel there is non-convex or stays bent).
    surface_distance : float
        The largest distance of a moved vertex from the surface.
    self_intersecting : (k,) int
        Panels (positions) whose outline, in its best-fit plane, crosses or touches itself
        (a bow-tie), or whose holes leave it (not a valid polygon there).
    flipped : (k,) int
        Panels (positions) whose outline turned over: its orientation in the plane is the
        reverse of the panel's before planarising.
    dropped : int
        Vertices of a single panel left out of its outline because they lay on a straight
        run (a mesh border's facets, see :meth:`Panels.planarize`).
    """

    tolerance: float
    iterations: int
    planarity: Planarity
    not_planar: np.ndarray
    negative_curvature: np.ndarray
    surface_distance: float
    self_intersecting: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    flipped: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    dropped: int = 0

    @property
    def ok(self) -> bool:
        """True when every panel is planar to the tolerance, simple and not turned over."""
        return not (len(self.not_planar) or len(self.self_intersecting) or len(self.flipped))

    @property
    def invalid(self) -> np.ndarray:
        """Panels (positions) that are self-intersecting or flipped."""
        return np.union1d(self.self_intersecting, self.flipped).astype(np.int64)


def _fit_planes(P: np.ndarray):
    """Best-fit planes of ``(m, k, 3)`` point sets: centroids ``(m, 3)``, normals ``(m, 3)``."""
    c = P.mean(axis=1)
    _, _, wt = np.linalg.svd(P - c[:, None, :], full_matrices=False)
    return c, wt[:, 2]


def _plane_frames(P: np.ndarray):
    """Centroid, two in-plane axes and the normal of each ``(m, k, 3)`` point set."""
    c = P.mean(axis=1)
    _, _, wt = np.linalg.svd(P - c[:, None, :], full_matrices=False)
    return c, wt[:, 0], wt[:, 1], wt[:, 2]


@dataclass(eq=False)
class Panels:
    """Polygons in space, each an exterior ring and optional holes over shared vertices.

    Attributes
    ----------
    vertices : (V, 3) float64
    rings : list of list of (k,) int arrays
        Per panel, its rings as indices into ``vertices`` (exterior first).
    ids : (n,) int
        The label of each panel (design cell, Voronoi cell).
    uv : (V, 2) float64 or None
        UV coordinates of the vertices (morphed panels).
    surface : Surface or None
    report : PlanarizeReport or None
        Set by :meth:`planarize`.
    missing : dict
        The cells that have no panel, id -> why (see
        :meth:`voroforge.surface.SurfaceVoronoi.panels`); empty when every cell has one.
    """

    vertices: np.ndarray
    rings: list
    ids: np.ndarray
    uv: np.ndarray | None = None
    surface: object = None
    report: PlanarizeReport | None = None
    missing: dict = field(default_factory=dict)
    _cache: dict = field(default_factory=dict, repr=False)

    # --- construction --------------------------------------------------------------------

    @classmethod
    def from_rings(cls, rings_uv, flat_uv, xyz, *, ids, surface) -> Panels:
        """Panels from per-panel UV rings whose vertices (in order) are ``flat_uv``/``xyz``."""
        rings, k = [], 0
        for panel in rings_uv:
            out = []
            for r in panel:
                out.append(np.arange(k, k + len(r)))
                k += len(r)
            rings.append(out)
        return cls(np.asarray(xyz, float), rings, np.asarray(ids), np.asarray(flat_uv), surface)

    @classmethod
    def from_indexed(cls, vertices, exteriors, *, ids, surface=None) -> Panels:
        """Panels from exterior index rings into ``vertices`` (only used vertices are kept)."""
        used = np.unique(np.concatenate(exteriors)) if exteriors else np.zeros(0, int)
        remap = np.full(len(vertices), -1, np.int64)
        remap[used] = np.arange(len(used))
        rings = [[remap[np.asarray(r)]] for r in exteriors]
        return cls(np.asarray(vertices, float)[used], rings, np.asarray(ids), None, surface)

    def _with(self, vertices=None, rings=None, uv=None, report=None) -> Panels:
        return Panels(
            self.vertices if vertices is None else vertices,
            self.rings if rings is None else rings,
            self.ids,
            self.uv if uv is None and vertices is None else uv,
            self.surface,
            report,
            self.missing,
        )

    def __len__(self) -> int:
        return len(self.rings)

    def polygon(self, i: int) -> list[np.ndarray]:
        """Panel ``i``'s rings as ``(k, 3)`` point arrays (exterior first)."""
        return [self.vertices[r] for r in self.rings[i]]

    # --- measures ------------------------------------------------------------------------

    def _groups(self):
        """Exteriors grouped by vertex count: ``{k: (positions (m,), index (m, k))}``."""
        if "groups" not in self._cache:
            by: dict[int, list] = {}
            for p, rings in enumerate(self.rings):
                by.setdefault(len(rings[0]), []).append(p)
            self._cache["groups"] = {
                k: (np.asarray(ps), np.stack([self.rings[p][0] for p in ps]))
                for k, ps in by.items()
            }
        return self._cache["groups"]

    def _all_index(self, p: int) -> np.ndarray:
        return np.concatenate(self.rings[p])

    def planarity(self) -> Planarity:
        """Per panel, the largest distance of a vertex from its best-fit (least-squares) plane.

        Returns
        -------
        Planarity
            ``absolute (n,)`` in model units and ``relative (n,)`` divided by the longest edge.
        """
        n = len(self)
        ab = np.zeros(n)
        rel = np.zeros(n)
        for pos, idx in self._groups().values():
            P = self.vertices[idx]
            c, nrm = _fit_planes(P)
            d = np.abs(np.einsum("mkj,mj->mk", P - c[:, None, :], nrm)).max(axis=1)
            e = np.linalg.norm(np.roll(P, -1, axis=1) - P, axis=2).max(axis=1)
            ab[pos] = d
            rel[pos] = d / np.maximum(e, 1e-300)
        for p in range(n):  # panels with holes: all their rings in one plane
            if len(self.rings[p]) > 1:
                P = self.vertices[self._all_index(p)][None]
                c, nrm = _fit_planes(P)
                ab[p] = np.abs((P[0] - c[0]) @ nrm[0]).max()
                ext = self.vertices[self.rings[p][0]]
                rel[p] = ab[p] / np.linalg.norm(np.roll(ext, -1, 0) - ext, axis=1).max()
        return Planarity(ab, rel)

    def areas(self) -> np.ndarray:
        """(n,) panel areas.

        On the surface for morphed panels (the UV area element integrated over the UV polygon,
        exact where it is constant), else of the flat polygon.
        """
        out = np.zeros(len(self))
        for p in range(len(self)):
            if self.uv is not None and self.surface is not None:
                tri = _triangles(self.uv, self.rings[p])
                a, b, c = self.uv[tri[:, 0]], self.uv[tri[:, 1]], self.uv[tri[:, 2]]
                d1, d2 = b - a, c - a
                auv = 0.5 * np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
                # degree-2 rule on edge midpoints
                mids = np.stack([(a + b) / 2, (b + c) / 2, (c + a) / 2], axis=1)
                j = self.surface.area_element(mids[..., 0], mids[..., 1]).mean(axis=1)
                out[p] = float(np.sum(auv * j))
            else:
                total = 0.0
                for r, ring in enumerate(self.rings[p]):
                    P = self.vertices[ring] - self.vertices[ring[0]]  # about a ring vertex:
                    vec = 0.5 * np.cross(P, np.roll(P, -1, axis=0)).sum(axis=0)  # no offset^2
                    total += np.linalg.norm(vec) * (1 if r == 0 else -1)
                out[p] = total
        return out

    def centroids(self) -> np.ndarray:
        """(n, 3) vertex centroids of the exteriors."""
        return np.stack([self.vertices[r[0]].mean(axis=0) for r in self.rings])

    def edge_lengths(self, p: int) -> list[np.ndarray]:
        """Panel ``p``'s edge lengths per ring (edge ``k`` from vertex ``k`` to ``k + 1``)."""
        return [np.linalg.norm(np.roll(P, -1, axis=0) - P, axis=1) for P in self.polygon(p)]

    # --- planarize -----------------------------------------------------------------------

    def planarize(
        self,
        tol: float,
        *,
        iterations: int = 2000,
        surface_weight: float = 0.5,
    ) -> Panels:
        """Move vertices so every panel is planar to ``tol``, staying near the surface.

        Alternating projections: each panel's vertices are projected onto its best-fit plane,
        a vertex shared by several panels goes to the mean of its projections, and is pulled
        towards the surface with a weight that fades to zero (so the last steps are planar
        only). Stops when every panel is within ``tol / 2``.

        Parameters
        ----------
        tol : float
            Largest allowed distance from a panel's best-fit plane (model units).
        iterations : int
        surface_weight : float
            Pull towards the surface at the start (0: none).

        Returns
        -------
        Panels
            With ``report`` (:class:`PlanarizeReport`): the panels still above ``tol`` and those
            over negative Gaussian curvature (flagged, not failed silently).
        """
        tol = float(tol)
        if not tol > 0:
            raise ValueError(f"planarize tolerance must be positive; got {tol!r}")
        if int(iterations) != iterations or iterations < 1:
            raise ValueError(f"iterations must be a positive integer; got {iterations!r}")
        import warnings

        from .. import config

        S = self.surface
        V = self.vertices.copy()
        ref = self._vector_areas()
        work, dropped = self._without_straight_runs(config.SURFACE_STRAIGHT_DEG)
        groups = [idx for _, idx in work._groups().values()]
        flat = np.concatenate([idx.ravel() for idx in groups])
        cnt = np.bincount(flat, minlength=len(V)).astype(float)
        # every projected coordinate summed into its vertex by one bincount
        slots = (flat[:, None] * 3 + np.arange(3)).ravel()
        holes = [p for p in range(len(work)) if len(work.rings[p]) > 1]
        it = 0
        for it in range(1, int(iterations) + 1):
            worst = 0.0
            projected = []
            for idx in groups:
                P = V[idx]
                c = P.mean(axis=1)
                Q = P - c[:, None, :]
                # the normal: the covariance's least eigenvector (a batch of 3 x 3 eigh is
                # several times cheaper than the SVD of the points)
                nrm = np.linalg.eigh(np.einsum("mki,mkj->mij", Q, Q))[1][:, :, 0]
                d = np.einsum("mkj,mj->mk", Q, nrm)
                worst = max(worst, float(np.abs(d).max()))
                projected.append((P - d[..., None] * nrm[:, None, :]).ravel())
            acc = np.bincount(slots, np.concatenate(projected), minlength=3 * len(V))
            acc = acc.reshape(-1, 3)
            for p in holes:
                idx = work._all_index(p)
                c, nrm = _fit_planes(V[idx][None])
                d = (V[idx] - c[0]) @ nrm[0]
                worst = max(worst, float(np.abs(d).max()))
            if worst <= tol / 2:
                break
            moved = cnt > 0
            V[moved] = acc[moved] / cnt[moved, None]
            # every few steps (projecting is the costly part), fading out by half-way
            w = surface_weight * max(0.0, 1.0 - 2.0 * it / iterations)
            if S is not None and w > 0 and it % 5 == 1:
                V = V + w * (S.project(V) - V)
        out = work._with(vertices=V)
        plan = out.planarity()
        bad = np.flatnonzero(plan.absolute > tol)
        neg = np.zeros(0, np.int64)
        dist = 0.0
        if S is not None:
            k = S.gaussian_curvature(out.centroids())
            size = np.array([np.max(e) for e in (out.edge_lengths(p)[0] for p in range(len(out)))])
            neg = np.flatnonzero(k * size**2 < -1e-6)
            dist = float(np.linalg.norm(S.project(V) - V, axis=1).max())
        crossed, flipped = out.outline_faults(ref)
        out.report = PlanarizeReport(tol, it, plan, bad, neg, dist, crossed, flipped, dropped)
        if len(crossed) or len(flipped):
            ids = list(map(int, out.ids[np.union1d(crossed, flipped)]))
            warnings.warn(
                f"planarize: {len(crossed)} panels cross themselves and {len(flipped)} turned "
                f"over in their planes (panel ids {ids}); see report.self_intersecting and "
                "report.flipped",
                PlanarizeWarning,
                stacklevel=2,
            )
        return out

    def _vector_areas(self) -> np.ndarray:
        """(n, 3) each exterior's vector area (its normal times its area, for a planar one)."""
        out = np.zeros((len(self), 3))
        for p, rings in enumerate(self.rings):
            P = self.vertices[rings[0]] - self.vertices[rings[0][0]]  # about a ring vertex
            out[p] = 0.5 * np.cross(P, np.roll(P, -1, axis=0)).sum(axis=0)
        return out

    def _without_straight_runs(self, degrees: float) -> tuple[Panels, int]:
        """The panels without their straight runs of unshared vertices, and how many went.

        Left out: exterior vertices that only one panel uses where the outline turns by less
        than ``degrees`` (a mesh border's facets). A run of such vertices is nearly
        collinear: free to move, planarising makes it zigzag and the panel cross itself.
        Panels with holes, and panels that would keep fewer than three vertices, stay whole;
        so do morphed panels (UVs: each has its own densified vertices, which follow the
        surface inside the panel as much as along a border).
        """
        if self.uv is not None:
            return self, 0
        V = self.vertices
        used = np.bincount(
            np.concatenate([np.concatenate(r) for r in self.rings]), minlength=len(V)
        )
        cos_max = np.cos(np.radians(degrees))
        rings, dropped = [], 0
        for panel in self.rings:
            ext = np.asarray(panel[0])
            if len(panel) > 1 or len(ext) < 4:
                rings.append(panel)
                continue
            X = V[ext]
            a = X - np.roll(X, 1, axis=0)
            b = np.roll(X, -1, axis=0) - X
            den = np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1)
            cos = np.einsum("ij,ij->i", a, b) / np.maximum(den, 1e-300)
            drop = (used[ext] == 1) & (cos > cos_max) & (den > 0)
            if (~drop).sum() < 3:
                rings.append(panel)
                continue
            rings.append([ext[~drop]])
            dropped += int(drop.sum())
        if not dropped:
            return self, 0
        return self._with(rings=rings), dropped

    def outline_faults(self, reference=None) -> tuple[np.ndarray, np.ndarray]:
        """Panels whose outline is not a valid polygon in its best-fit plane, or turned over.

        Parameters
        ----------
        reference : (n, 3) array_like, optional
            Per panel the normal it should face (e.g. its vector area before a change); by
            default the panel's own vector area, so nothing counts as turned over.

        Returns
        -------
        self_intersecting : (k,) int
            Panels (positions) whose rings, in the best-fit plane of all their vertices, do
            not make a valid polygon (an outline crossing or touching itself, a hole outside).
        flipped : (m,) int
            Valid panels whose exterior winds against ``reference`` (signed area <= 0).
        """
        ref = self._vector_areas() if reference is None else np.asarray(reference, float)
        crossed, flipped = [], []
        for p, rings in enumerate(self.rings):
            X = self.vertices[np.concatenate(rings)]
            c = X.mean(axis=0)
            _, _, wt = np.linalg.svd(X - c, full_matrices=False)
            e1, nrm = wt[0], wt[2]
            if nrm @ ref[p] < 0:
                nrm = -nrm
            e2 = np.cross(nrm, e1)
            xy = [
                np.stack([(self.vertices[r] - c) @ e1, (self.vertices[r] - c) @ e2], 1)
                for r in rings
            ]
            poly = shapely.Polygon(xy[0], xy[1:]) if len(xy[0]) >= 3 else None
            if poly is None or not poly.is_valid:
                crossed.append(p)
                continue
            x, y = xy[0][:, 0], xy[0][:, 1]
            if np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y) <= 0:
                flipped.append(p)
        return np.asarray(crossed, np.int64), np.asarray(flipped, np.int64)

    # --- openings ------------------------------------------------------------------------

    def openings(self, scale=0.6, *, attractors=None, radius: float | None = None) -> Panels:
        """Cut an opening in every panel: its outline scaled about its centroid.

        Parameters
        ----------
        scale : float or (near, far)
            The opening's size as a fraction of the panel (0..1). ``(near, far)`` grades it by
            distance to the nearest attractor: ``near`` at an attractor, ``far`` at ``radius``
            and beyond (smoothstep in between).
        attractors : (k, 3) array_like, optional
        radius : float, optional

        Returns
        -------
        Panels
            Each panel with one more hole (morphed panels: scaled in UV and mapped, so the
            opening lies on the surface; others in the panel's best-fit plane).
        """
        if np.ndim(scale) == 0:
            s = np.full(len(self), float(scale))
        else:
            near, far = (float(x) for x in scale)
            if attractors is None or radius is None:
                raise ValueError("graded openings (near, far) need attractors and radius")
            pts = np.asarray(attractors, float).reshape(-1, 3)
            d = np.linalg.norm(self.centroids()[:, None, :] - pts[None], axis=2).min(axis=1)
            x = np.clip(1.0 - d / float(radius), 0.0, 1.0)
            s = far + (near - far) * (x * x * (3 - 2 * x))
        if ((s <= 0) | (s >= 1)).any():
            raise ValueError("opening scale must lie strictly between 0 and 1")
        V = [self.vertices]
        UV = [self.uv] if self.uv is not None else None
        rings = []
        k = len(self.vertices)
        for p in range(len(self)):
            ext = self.rings[p][0]
            if UV is not None:
                uv = self.uv[ext]
                c = np.asarray(shapely.Polygon(uv).centroid.coords[0])
                new_uv = c + s[p] * (uv - c)
                xyz = self.surface.evaluate(new_uv[:, 0], new_uv[:, 1])
                UV.append(new_uv)
            else:
                P = self.vertices[ext]
                c, e1, e2, nrm = _plane_frames(P[None])
                xy = np.stack([(P - c[0]) @ e1[0], (P - c[0]) @ e2[0]], axis=1)
                g = np.asarray(shapely.Polygon(xy).centroid.coords[0])
                xy = g + s[p] * (xy - g)
                h = (P - c[0]) @ nrm[0]  # keep each vertex's height over the plane
                xyz = c[0] + xy[:, :1] * e1[0] + xy[:, 1:] * e2[0] + s[p] * h[:, None] * nrm[0]
            V.append(xyz)
            rings.append([*self.rings[p], np.arange(k, k + len(ext))[::-1]])
            k += len(ext)
        uv = np.concatenate(UV) if UV is not None else None
        return Panels(np.concatenate(V), rings, self.ids, uv, self.surface, None, self.missing)

    # --- solids --------------------------------------------------------------------------

    def _normals(self, p: int, idx: np.ndarray) -> np.ndarray:
        """Offset directions of panel ``p``'s vertices ``idx``.

        The surface normal for morphed panels, the panel's plane normal otherwise (the side
        its exterior turns counter-clockwise around).
        """
        P = self.vertices[self.rings[p][0]]
        _, nrm = _fit_planes(P[None])
        nrm = nrm[0]
        if self.uv is not None and self.surface is not None:
            uv = self.uv[idx]
            n = self._surface_normals(uv)
            bad = ~(np.linalg.norm(n, axis=1) > 0.5)
            if bad.any():  # a degenerate point of the map (a pole): the normal next to it,
                c = self.uv[self.rings[p][0]].mean(axis=0)  # a step into the panel
                for step in SURFACE_NORMAL_NUDGE:
                    m = self._surface_normals(uv[bad] + step * (c - uv[bad]))
                    n[np.flatnonzero(bad)] = m
                    bad = ~(np.linalg.norm(n, axis=1) > 0.5)
                    if not bad.any():
                        break
                else:
                    raise ValueError(f"panel {p}: no surface normal at a vertex")
            return n
        # orient like the ring (counter-clockwise seen from the normal's side)
        vec = np.cross(P - P[0], np.roll(P - P[0], -1, axis=0)).sum(axis=0)
        if vec @ nrm < 0:
            nrm = -nrm
        return np.broadcast_to(nrm, (len(idx), 3))

    def _surface_normals(self, uv: np.ndarray) -> np.ndarray:
        """Unit ``f_u x f_v`` at ``uv``; zero rows where it vanishes (a pole of the map)."""
        fu, fv = self.surface.derivatives(uv[:, 0], uv[:, 1])
        n = np.cross(fu, fv)
        size = np.linalg.norm(fu, axis=1) * np.linalg.norm(fv, axis=1)
        ln = np.linalg.norm(n, axis=1)
        ok = (ln > 0) & (ln > SURFACE_DEGENERATE_NORMAL * size)
        out = np.zeros_like(n)
        out[ok] = n[ok] / ln[ok, None]
        return out

    def _panel_solid(self, p: int, t: float):
        """Panel ``p`` offset by ``t`` into a closed solid, as :class:`voroforge.io.mesh.Arrays`.

        ``None`` where the panel's rings, laid flat, cross themselves or each other (its caps
        cannot be triangulated on its own vertices, so no closed solid is made).
        """
        from ..io.mesh import Arrays

        idx = self._all_index(p)
        local = {int(g): q for q, g in enumerate(idx)}

        def plane():
            P = self.vertices[self.rings[p][0]]
            c, e1, e2, _ = _plane_frames(P[None])
            return np.stack([(self.vertices - c[0]) @ e1[0], (self.vertices - c[0]) @ e2[0]], 1)

        base = self.vertices[idx]
        m = len(idx)
        walls = []  # the side walls, the same whichever chart the caps come from
        k = 0
        for ring in self.rings[p]:
            r = np.arange(k, k + len(ring))
            rn = np.roll(r, -1)
            walls.append(np.stack([r, rn, rn + m], 1))
            walls.append(np.stack([r, rn + m, r + m], 1))
            k += len(ring)
        # the plane chart also takes a morphed panel whose UV ring merged a pole's run
        charts = [plane] if self.uv is None else [lambda: self.uv, plane]
        top = None
        for chart in charts:
            tri = _triangles(chart(), self.rings[p])
            if not len(tri):
                continue
            tri = np.vectorize(local.get)(tri)
            if top is None:
                top = base + t * self._normals(p, idx)
            verts, faces = (
                np.concatenate([base, top]),
                np.concatenate([tri[:, ::-1], tri + m, *walls]),
            )
            if _closed(faces):
                break
        else:  # the caps missed triangles: an outline crossing itself
            return None
        a, b, c = (verts[faces[:, k]] - verts[0] for k in range(3))  # about a vertex
        if np.einsum("ij,ij->", a, np.cross(b, c)) < 0:  # 6 x the signed volume (trimesh's
            faces = faces[:, ::-1]  # mass properties cost 20x more)
        return Arrays(verts, faces)

    def thicken(self, t: float, *, arrays: bool = False):
        """Every panel as a solid of thickness ``t`` (offset along its normals).

        Parameters
        ----------
        t : float
            Thickness (> 0).
        arrays : bool
            Return :class:`voroforge.io.mesh.Arrays` instead of Trimeshes (the same vertices
            and faces; :func:`voroforge.io.mesh.write` takes them without importing trimesh).

        Returns
        -------
        list of trimesh.Trimesh
            One watertight solid per panel (holes kept), in panel order.

        Raises
        ------
        ValueError
            Naming the panels whose rings cross themselves or each other in their plane (a
            corner cell of a creased mesh planarized, an opening wider than its panel): no
            closed solid can be made of them. ``planarize`` warns about the same panels.
        """
        t = float(t)
        if not t > 0:
            raise ValueError(f"thickness must be positive; got {t!r}")
        solids = [self._panel_solid(p, t) for p in range(len(self))]
        _refuse_open(solids, self.ids, "thicken")
        return solids if arrays else _trimeshes(solids)

    def frame(self, width: float, *, depth: float | None = None, arrays: bool = False):
        """The frame along the panel edges: each panel's rim of ``width / 2`` as a solid.

        Neighbouring rims meet along the shared edges, so the members are ``width`` wide.

        Parameters
        ----------
        width : float
            Full member width.
        depth : float, optional
            Member depth (default ``width``).
        arrays : bool
            Return :class:`voroforge.io.mesh.Arrays` instead of Trimeshes (as :meth:`thicken`).

        Returns
        -------
        list of trimesh.Trimesh
            One watertight rim per panel.
        """
        width = float(width)
        if not width > 0:
            raise ValueError(f"frame width must be positive; got {width!r}")
        depth = width if depth is None else float(depth)
        rims = []
        for p in range(len(self)):
            ext = self.vertices[self.rings[p][0]]
            c, e1, e2, _ = _plane_frames(ext[None])
            xy = np.stack([(ext - c[0]) @ e1[0], (ext - c[0]) @ e2[0]], 1)
            inner = shapely.Polygon(xy).buffer(-width / 2, join_style="mitre")
            rings = [np.arange(len(ext))]
            verts = [ext]
            if not inner.is_empty and inner.geom_type == "Polygon":
                ixy = np.asarray(shapely.orient_polygons(inner).exterior.coords)[:-1]
                if _signed_area(xy) > 0:  # the hole turns against the exterior
                    ixy = ixy[::-1]
                verts.append(c[0] + ixy[:, :1] * e1[0] + ixy[:, 1:] * e2[0])
                rings.append(np.arange(len(ext), len(ext) + len(ixy)))
            # same exterior ring, same orientation: the rim's normal is the panel's
            rim = Panels(np.concatenate(verts), [rings], self.ids[p : p + 1], None, None)
            rims.append(rim._panel_solid(0, depth))
        _refuse_open(rims, self.ids, "frame")
        return rims if arrays else _trimeshes(rims)

    def to_trimesh(self):
        """All panels triangulated into one mesh; ``face_attributes["panel"]`` the position."""
        import trimesh

        faces, owner = self.triangulate()
        m = trimesh.Trimesh(self.vertices.copy(), faces, process=False)
        m.face_attributes["panel"] = owner
        return m

    def triangulate(self) -> tuple[np.ndarray, np.ndarray]:
        """All panels triangulated: ``(faces (t, 3) into vertices, owner (t,) panel position)``.

        What :meth:`to_trimesh` holds, without importing trimesh.
        """
        faces, owner = [], []
        for p in range(len(self)):
            flat = self.uv
            if flat is None:
                P = self.vertices[self.rings[p][0]]
                c, e1, e2, _ = _plane_frames(P[None])
                idx = self._all_index(p)
                xy = np.zeros((len(self.vertices), 2))
                xy[idx] = np.stack(
                    [(self.vertices[idx] - c[0]) @ e1[0], (self.vertices[idx] - c[0]) @ e2[0]], 1
                )
                flat = xy
            tri = _triangles(flat, self.rings[p])
            faces.append(tri)
            owner.append(np.full(len(tri), p))
        if not faces:
            return np.zeros((0, 3), np.int64), np.zeros(0, np.int64)
        return np.concatenate(faces), np.concatenate(owner)

    # --- flat -------------------------------------------------------------------------------

    def unroll(self, **kwargs):
        """Flatten every panel and lay them out on sheets (see :func:`voroforge.surface.unroll`)."""
        from .unroll import unroll

        return unroll(self, **kwargs)


def _trimeshes(solids: list) -> list:
    """Each :class:`voroforge.io.mesh.Arrays` as a ``trimesh.Trimesh`` (``process=False``)."""
    import trimesh

    return [trimesh.Trimesh(m.vertices, m.faces, process=False) for m in solids]


def _closed(faces: np.ndarray) -> bool:
    """Whether triangles ``faces`` close up: each directed edge once, its reverse once."""
    d = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    if (d[:, 0] == d[:, 1]).any():
        return False
    m = int(faces.max()) + 1
    fwd, back = d[:, 0] * m + d[:, 1], d[:, 1] * m + d[:, 0]
    u, count = np.unique(fwd, return_counts=True)
    return bool((count == 1).all()) and np.array_equal(u, np.unique(back))


def listed(names, most: int = 12) -> str:
    """The first ``most`` of ``names`` joined by commas, ``, ...`` when there are more."""
    names = [str(x) for x in names]
    return ", ".join(names[:most]) + (", ..." if len(names) > most else "")


def _refuse_open(solids: list, ids, what: str) -> None:
    """Raise naming the panels :meth:`Panels._panel_solid` could not close."""
    bad = [p for p, s in enumerate(solids) if s is None]
    if bad:
        shown = listed(int(ids[p]) for p in bad)
        raise ValueError(
            f"{what}: {len(bad)} of {len(solids)} panels (cells {shown}) cross themselves or "
            "their openings in their plane: no closed solid can be made of them (relax the "
            "sites, planarize less, use more cells near sharp creases, or smaller openings)"
        )


def _signed_area(xy: np.ndarray) -> float:
    return 0.5 * float(np.sum(xy[:, 0] * np.roll(xy[:, 1], -1) - np.roll(xy[:, 0], -1) * xy[:, 1]))


def _triangles(flat: np.ndarray, rings: list) -> np.ndarray:
    """A constrained triangulation of a panel's rings in 2D coordinates ``flat[rings]``.

    Returns ``(t, 3)`` indices into ``flat`` (the rings' own vertices only), turning the way
    the exterior ring turns in ``flat`` (so caps and side walls of a solid agree).
    """
    ext = flat[rings[0]]
    turn = np.sign(_signed_area(ext))
    poly = shapely.Polygon(ext, [flat[r] for r in rings[1:]])
    if not poly.is_valid:
        poly = shapely.make_valid(poly)
    tris = shapely.get_parts(shapely.constrained_delaunay_triangles(poly))
    ids = np.concatenate(rings)
    lookup = {(float(x), float(y)): int(i) for i, (x, y) in zip(ids, flat[ids], strict=True)}
    out = []
    for t in tris:
        xy = np.asarray(t.exterior.coords)[:3]
        try:
            tri = [lookup[(float(x), float(y))] for x, y in xy]
        except KeyError:
            continue  # a vertex the repair made: skip that sliver
        a, b, c = flat[tri[0]], flat[tri[1]], flat[tri[2]]
        if ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])) * turn < 0:
            tri = [tri[0], tri[2], tri[1]]
        out.append(tri)
    return np.asarray(out, dtype=np.int64).reshape(-1, 3)
