"""Voronoi diagrams restricted to a surface mesh, and centroidal ones (surface CVT).

:func:`voronoi` cuts every triangle of the surface's mesh by the bisector planes of nearby
sites (:func:`voroforge.kernels.surface.rvd`): cell ``i`` is the part of the surface nearer to
site ``i`` than to any other in 3D distance (geogram's restricted Voronoi diagram). With
``relax > 0`` the sites move to a centroidal Voronoi tessellation on the surface: Lloyd steps
(cell centroid projected back onto the mesh) or L-BFGS on the CVT energy (Liu et al. 2009),
which converges in far fewer steps and leaves fewer defects.

Examples
--------
>>> from voroforge import surface
>>> S = surface.sphere(1.0, subdivisions=3)
>>> vd = surface.voronoi(S, 50, relax=10)
>>> bool(abs(vd.areas.sum() - S.area) < 1e-9 * S.area)
True
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction

import numpy as np

from .. import config
from ..engine.readonly import readonly
from .shapes import Surface, as_points3, check_surface_range

__all__ = ["SurfaceVoronoi", "voronoi"]


def _box(S: Surface, sites: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The box of the mesh and the sites."""
    lo, hi = S.bounds
    return np.minimum(lo, sites.min(axis=0)), np.maximum(hi, sites.max(axis=0))


def bucket_side(S: Surface, sites: np.ndarray) -> float:
    """Side of the sites' bucket grid: their mean spacing on the surface.

    Widened so the grid holds at most ``SURFACE_BUCKETS_PER_SITE`` buckets per site.
    """
    lo, hi = _box(S, sites)
    ext = np.maximum(hi - lo, 1e-300)
    h = math.sqrt(S.area / len(sites))
    limit = config.SURFACE_BUCKETS_PER_SITE * len(sites) + 64
    while np.prod(np.floor(ext / h) + 1) > limit:
        h *= 1.25
    return h


def _run(S: Surface, sites: np.ndarray, mode: int, hint: np.ndarray | None = None):
    """:func:`voroforge.kernels.surface.rvd` of ``sites`` on ``S`` (``mode``: what to return).

    ``hint``: each mesh vertex's nearest site from a previous call (the last item returned),
    the start of this call's nearest-site search.
    """
    from ..engine.build3d import bucket_sort3d
    from ..kernels.surface import rvd

    h = bucket_side(S, sites)
    lo, hi = _box(S, sites)
    dims = np.floor(np.maximum(hi - lo, 0.0) / h) + 1
    g = np.concatenate([lo, [h, h, h], dims])
    start, _, sidx = bucket_sort3d(sites, g)
    if hint is None or len(hint) != len(S.vertices) or (hint >= len(sites)).any():
        hint = np.full(len(S.vertices), -1, np.int64)
    return rvd(
        S.vertices,
        S.faces,
        S.face_frames,
        sites,
        start,
        sidx,
        g,
        hint,
        mode,
        config.SURFACE_KNN,
    )


@dataclass(eq=False)
class SurfaceVoronoi:
    """A Voronoi diagram restricted to a surface mesh.

    Attributes
    ----------
    surface : Surface
    sites : (n, 3) float64
        The sites (after relaxation).
    areas : (n,) float64
        Cell areas on the mesh (they sum to the mesh's area).
    centroids : (n, 3) float64
        Area centroids of the cells (in space, not projected; NaN for empty cells).
    energy : float
        The CVT energy ``sum_i ∫_{cell i} |x - s_i|^2 dA``.
    history : list of float
        The energy before each relaxation step (empty without ``relax``).
    piece_cell, piece_tri, piece_area : (p,) arrays
        Every piece of a triangle that lies in one cell: its cell, triangle and area.
    """

    surface: Surface
    sites: np.ndarray
    areas: np.ndarray
    centroids: np.ndarray
    energy: float
    piece_cell: np.ndarray
    piece_tri: np.ndarray
    piece_area: np.ndarray
    piece_offsets: np.ndarray
    piece_coords: np.ndarray
    piece_owners: np.ndarray
    history: list = field(default_factory=list)
    _cache: dict = field(default_factory=dict, repr=False)

    def __len__(self) -> int:
        return len(self.sites)

    # --- topology ------------------------------------------------------------------------

    def _keys(self):
        """Names of every piece vertex, and each cell's boundary segments.

        A piece vertex is named from its two edges' owners: a mesh vertex (a triangle corner,
        recognised exactly), a mesh edge and a site pair (a bisector crossing an edge), or a
        triangle and a site triple (three cells meet); neighbouring pieces name a shared
        vertex alike. A piece edge is on its cell's boundary when no piece of the same cell
        has it reversed (that covers bisector edges, the mesh's border, and bisectors lying
        exactly along a mesh edge).
        """
        if "keys" in self._cache:
            return self._cache["keys"]
        S = self.surface
        n = len(self.sites)
        _, face_edges, _ = S.edges
        off = self.piece_offsets
        code = self.piece_owners
        own = code >> 2
        corner = (code & 3) - 1
        nq = len(own)
        piece_of = np.repeat(np.arange(len(self.piece_cell)), np.diff(off))
        cell = self.piece_cell[piece_of]
        tri = self.piece_tri[piece_of]
        pos = np.arange(nq)
        starts = off[:-1][piece_of]
        ends = off[1:][piece_of]
        prev = np.where(pos - 1 < starts, ends - 1, pos - 1)
        nxt = np.where(pos + 1 >= ends, starts, pos + 1)
        a = own[prev]
        b = own[pos]
        c0 = np.zeros(nq, np.int64)  # kind + 4 * (vertex, edge, triangle or position)
        c1 = np.zeros(nq, np.int64)  # the sites, packed
        one = (a < 0) ^ (b < 0)
        e_local = np.where(a < 0, -1 - a, -1 - b) % 3
        j = np.where(a < 0, b, a)
        lo, hi = np.minimum(cell, j), np.maximum(cell, j)
        c0[one] = 1 + 4 * face_edges[tri[one], e_local[one]]
        c1[one] = lo[one] * n + hi[one]
        three = (a >= 0) & (b >= 0)
        trip = np.sort(np.stack([cell, a, b], axis=1), axis=1)
        c0[three] = 2 + 4 * tri[three]
        c1[three] = (trip[three, 0] * n + trip[three, 1]) * n + trip[three, 2]
        odd = three & ((trip[:, 0] == trip[:, 1]) | (trip[:, 1] == trip[:, 2]))
        c0[odd] = 3 + 4 * pos[odd]  # a vertex inside one edge: its piece's own
        c1[odd] = 0
        at = corner >= 0
        c0[at] = 4 * S.faces[tri[at], corner[at]]
        c1[at] = 0
        order = np.lexsort((c1, c0))
        new = np.ones(nq, bool)
        new[1:] = (np.diff(c0[order]) != 0) | (np.diff(c1[order]) != 0)
        vid = np.zeros(nq, np.int64)
        vid[order] = np.cumsum(new) - 1
        kind = np.zeros(new.sum(), np.int64)
        first = np.zeros(new.sum(), np.int64)
        kind[vid[order][new]] = c0[order][new] & 3
        first[vid[order][new]] = order[new]
        self._cache["prim"] = c0[first] >> 2
        # directed piece edges; those not cancelled by a reversed copy in the same cell bound it
        va, vb = vid[pos], vid[nxt]
        real = va != vb
        m = int(vid.max()) + 1 if nq else 1
        fwd = (cell * m + va) * m + vb
        rev = (cell * m + vb) * m + va
        fr = np.sort(fwd[real])
        k = np.searchsorted(fr, rev)
        k = np.minimum(k, max(len(fr) - 1, 0))
        seg = real & ~((fr[k] == rev) if len(fr) else np.zeros(nq, bool))
        self._cache["keys"] = (kind, vid, first, cell, seg, nxt, m)
        return self._cache["keys"]

    @property
    def vertices(self) -> np.ndarray:
        """(m, 3) float64: every distinct piece vertex (first occurrence's coordinates)."""
        _, _, first, *_ = self._keys()
        return self.piece_coords[first]

    @property
    def neighbors(self) -> tuple[np.ndarray, np.ndarray]:
        """CSR ``(indptr, indices)``: the cells sharing a boundary of positive length."""
        if "neighbors" not in self._cache:
            from ..engine.csr import csr_from_pairs

            kind, vid, first, cell, seg, nxt, m = self._keys()
            s = np.flatnonzero(seg)
            p = self.piece_coords
            length = np.linalg.norm(p[first[vid[nxt[s]]]] - p[first[vid[s]]], axis=1)
            s = s[length > config.SURFACE_EDGE_RTOL * self.surface.scale]
            # the cell on the other side has the same edge reversed
            fwd = vid[s] * m + vid[nxt[s]]
            rev = vid[nxt[s]] * m + vid[s]
            order = np.argsort(fwd, kind="stable")
            k = np.searchsorted(fwd[order], rev)
            k = np.minimum(k, max(len(s) - 1, 0))
            hit = fwd[order][k] == rev if len(s) else np.zeros(0, bool)
            i, j = cell[s][hit], cell[s][order][k][hit]
            keep = i != j
            self._cache["neighbors"] = csr_from_pairs(len(self.sites), i[keep], j[keep])
        return self._cache["neighbors"]

    def degree(self) -> np.ndarray:
        """(n,) int: neighbours per cell (6 for a hexagon)."""
        indptr, _ = self.neighbors
        return np.diff(indptr)

    def hexagon_fraction(self) -> float:
        """The share of non-empty cells with exactly six neighbours."""
        live = self.areas > 0
        return float((self.degree()[live] == 6).mean())

    @property
    def cells(self) -> list[list[np.ndarray]]:
        """Per cell, its boundary rings as ``(k, 3)`` arrays of points on the surface.

        A cell that is a disc has one ring (counter-clockwise seen from the normals' side); a
        cell around a handle or touching the mesh's border in two places has more.
        """
        if "cells" not in self._cache:
            from ..kernels.surface import chain_rings

            kind, vid, first, cell, seg, nxt, _ = self._keys()
            s = np.flatnonzero(seg)
            c, st, en = cell[s], vid[s], vid[nxt[s]]
            order = np.lexsort((st, c))
            rv, roff, coff = chain_rings(c[order], st[order], en[order], len(self.sites))
            pts = self.piece_coords[first[rv]]
            # a ring that encloses nothing (edges there and back, left where rounding put a
            # vertex next to a bisector a hair off it) bounds nothing: drop it
            lens = np.diff(roff)
            keep = np.zeros(len(lens), bool)
            if len(pts):
                nxt_pt = np.arange(len(pts)) + 1
                nxt_pt[roff[1:] - 1] = roff[:-1]
                rel = pts - np.repeat(pts[roff[:-1]], lens, axis=0)  # about each ring's start
                vec = np.add.reduceat(np.cross(rel, rel[nxt_pt]), roff[:-1], axis=0)
                per = np.add.reduceat(np.linalg.norm(pts[nxt_pt] - pts, axis=1), roff[:-1])
                keep = np.linalg.norm(vec, axis=1) > config.SURFACE_EDGE_RTOL * per * per
            if not keep.all():
                owner = np.repeat(np.arange(len(self.sites)), np.diff(coff))
                rv = rv[np.repeat(keep, lens)]
                roff = np.concatenate([[0], np.cumsum(lens[keep])])
                coff = np.concatenate(
                    [[0], np.cumsum(np.bincount(owner[keep], minlength=len(self.sites)))]
                )
                pts = self.piece_coords[first[rv]]
            self._cache["ring_ids"] = (rv, roff, coff)
            out = []
            for i in range(len(self.sites)):
                out.append([pts[roff[r] : roff[r + 1]] for r in range(coff[i], coff[i + 1])])
            self._cache["cells"] = out
        return self._cache["cells"]

    def corners(self) -> list[np.ndarray]:
        """Per cell, the ids (into :attr:`vertices`) of its corners in ring order.

        Corners are where three cells meet, and on an open surface where a cell boundary meets
        the border and the border's own vertices: the cell as a polygon of straight edges
        (what a panel is made of).
        """
        self.cells  # noqa: B018 - builds the rings
        kind, *_ = self._keys()
        rv, roff, coff = self._cache["ring_ids"]
        # a corner: three or more cells meet there, or it lies on the mesh's border
        _, vid, first, cell, seg, nxt, _ = self._keys()
        prim = self._cache["prim"]
        sg = np.flatnonzero(seg)
        pairs = np.unique(np.stack([vid[sg], cell[sg]], axis=1), axis=0)
        cells_at = np.bincount(pairs[:, 0], minlength=len(kind))
        e, _, border = self.surface.edges
        bverts = np.zeros(len(self.surface.vertices), bool)
        bverts[e[border].ravel()] = True
        on_border = np.zeros(len(kind), bool)
        on_border[kind == 0] = bverts[prim[kind == 0]]
        on_border[kind == 1] = border[prim[kind == 1]]
        keep = (cells_at >= 3) | on_border
        out = []
        for i in range(len(self.sites)):
            if coff[i + 1] == coff[i]:
                out.append(np.zeros(0, np.int64))
                continue
            # the longest ring is the outer one
            r = max(range(coff[i], coff[i + 1]), key=lambda r: roff[r + 1] - roff[r])
            ids = rv[roff[r] : roff[r + 1]]
            out.append(ids[keep[ids]])
        return out

    def to_trimesh(self):
        """The surface split into cells: a mesh whose ``face_attributes["cell"]`` is the cell id.

        Each piece is fanned into triangles over its shared (named) vertices, so the cells join
        without cracks.
        """
        import trimesh

        uniq, vid, first, *_ = self._keys()
        off = self.piece_offsets
        tris, cells = [], []
        for k in range(3, int(np.diff(off).max()) + 1):
            sel = np.flatnonzero(np.diff(off) == k)
            if not len(sel):
                continue
            base = off[sel]
            for q in range(1, k - 1):
                tris.append(np.stack([vid[base], vid[base + q], vid[base + q + 1]], axis=1))
                cells.append(self.piece_cell[sel])
        faces = np.concatenate(tris)
        cell = np.concatenate(cells)
        good = (
            (faces[:, 0] != faces[:, 1])
            & (faces[:, 1] != faces[:, 2])
            & (faces[:, 0] != faces[:, 2])
        )
        m = trimesh.Trimesh(self.piece_coords[first], faces[good], process=False)
        m.face_attributes["cell"] = cell[good]
        return m

    def panels(self):
        """The cells as panels: polygons through their corners (see :meth:`corners`).

        A panel is one flat polygon, so a cell whose boundary has fewer than 3 corners (a
        smooth curve where only two cells meet: each half of a 2-site sphere, a band around
        a torus's tube) or several rings (a band has two, a cell around another cell has a
        hole) gets none: such cells are listed in the result's ``missing`` (id -> why) and a
        :class:`voroforge.surface.MissingPanelWarning` names them. Empty cells (no area) get
        none and are not listed.
        """
        from .panels import MissingPanelWarning, Panels

        verts = self.vertices
        rings = self.corners()
        _, _, coff = self._cache["ring_ids"]
        n_rings = np.diff(coff)
        ids, missing = [], {}
        for i, r in enumerate(rings):
            if n_rings[i] > 1:
                missing[i] = (
                    f"{int(n_rings[i])} boundary rings (a band or a cell with a hole); "
                    "a panel is one flat polygon"
                )
            elif n_rings[i] == 1 and len(r) < 3:
                missing[i] = (
                    f"{len(r)} corners (a boundary where only two cells meet); "
                    "a panel is a polygon of at least 3 corners"
                )
            elif len(r) >= 3:
                ids.append(i)
        if missing:
            import warnings

            shown = sorted(missing)[:10]
            more = f" and {len(missing) - 10} more" if len(missing) > 10 else ""
            warnings.warn(
                f"panels: {len(missing)} of {len(rings)} cells have no panel (cells "
                f"{', '.join(map(str, shown))}{more}): {missing[shown[0]]}; see Panels.missing",
                MissingPanelWarning,
                stacklevel=2,
            )
        out = Panels.from_indexed(
            verts,
            [rings[i] for i in ids],
            ids=np.asarray(ids, dtype=np.int64),
            surface=self.surface,
        )
        out.missing = missing
        return out

    def sample_check(self, count: int = 2000, *, seed: int = 0) -> float:
        """Share of random surface points whose nearest site owns the piece they fall in.

        A diagnostic for tests and users: 1.0 for a correct diagram (ties aside) at any
        scale and distance from the origin. Distances are measured in a frame centred on the
        surface, and a point counts as its owner's when it is no farther from it than from
        the nearest site by ``1e-12`` of the surface's size plus ``config.SURFACE_SAMPLE_ULPS`` unit
        roundoffs of its largest coordinate (where the pieces' vertices were rounded); when
        the nearest distances tie to within their own rounding (sites far from the surface),
        the point's exact squared distances decide.
        """
        from scipy.spatial import cKDTree

        S = self.surface
        V = np.asarray(S.vertices, dtype=np.float64)
        centre = 0.5 * (V.min(axis=0) + V.max(axis=0))
        sites = self.sites - centre
        rng = np.random.default_rng(seed)
        k = rng.choice(len(self.piece_area), size=count, p=self.piece_area / self.piece_area.sum())
        d_owner = np.zeros(count)
        pts = np.zeros((count, 3))
        for q, p in enumerate(k):
            ring = self.piece_coords[self.piece_offsets[p] : self.piece_offsets[p + 1]] - centre
            w = rng.random(len(ring)) ** 4
            pts[q] = (w / w.sum()) @ ring
            d_owner[q] = np.linalg.norm(pts[q] - sites[self.piece_cell[p]])
        tree = cKDTree(sites)
        dk, _ = tree.query(pts, k=min(2, len(sites)))
        dk = dk.reshape(count, -1)
        d = dk[:, 0]
        d2 = dk[:, -1] if dk.shape[1] > 1 else np.full(count, np.inf)
        eps = np.finfo(np.float64).eps
        slack = 1e-12 * S.scale + config.SURFACE_SAMPLE_ULPS * eps * np.abs(V).max()
        # distances round to ulps of their length (the KD tree and numpy disagree by an ulp
        # of ``d``; checker14 F6): the owner within that of the nearest distance is the
        # nearest site when no other is as near, else exact squares decide
        # (one site: no second distance; its own bounds the rounding)
        tol = slack + 4.0 * eps * (np.where(np.isfinite(d2), d2, d) + d_owner)
        ok = np.abs(d_owner - d) <= tol
        for q in np.flatnonzero(ok & (d2 - d <= 2.0 * tol)):
            x = [Fraction(float(a)) + Fraction(float(c)) for a, c in zip(pts[q], centre)]  # noqa: B905
            do2 = _dist2(x, self.sites[self.piece_cell[k[q]]])
            rhs = Fraction(slack * 2.0 * (d[q] + tol[q]) * (1.0 + 1e-9))
            near = tree.query_ball_point(pts[q], d[q] + 2.0 * tol[q])
            ok[q] = all(do2 - _dist2(x, self.sites[j]) <= rhs for j in near)
        return float(ok.mean())


def _dist2(x, s) -> Fraction:
    """Exact squared distance from rational ``x`` to float point ``s``."""
    return sum((a - Fraction(float(b))) ** 2 for a, b in zip(x, s))  # noqa: B905


def _result(S: Surface, sites: np.ndarray, history: list, store: bool = True) -> SurfaceVoronoi:
    """The diagram of ``sites`` (with the piece vertices when ``store``)."""
    mass, first, energy, pc, pt, pa, off, xyz, own, _ = _run(S, sites, 2 if store else 1)
    with np.errstate(invalid="ignore", divide="ignore"):
        cen = first / mass[:, None]
    cen[mass == 0] = np.nan
    return SurfaceVoronoi(
        S, sites, mass, cen, math.fsum(energy), pc, pt, pa, off, xyz, own, history
    )


def _project_cells(S: Surface, points: np.ndarray, pc: np.ndarray, pt: np.ndarray) -> np.ndarray:
    """Each cell's centroid to the nearest point of the triangles its cell covers."""
    from ..kernels.surface import project_pieces

    out = np.zeros_like(points)
    # read-only views of what it does not write, on every path (engine.readonly): numba
    # types the flag (a container mesh's writeable vertices compiled it twice)
    v, f = readonly(S.vertices), readonly(S.faces)
    project_pieces(v, f, readonly(points), readonly(pc), readonly(pt), out)
    return out


def _lloyd(S: Surface, sites: np.ndarray, steps: int, history: list, progress) -> np.ndarray:
    hint = None
    for k in range(steps):
        mass, first, energy, pc, pt, pa, *_, hint = _run(S, sites, 1, hint)
        history.append(float(energy.sum()))
        live = mass > 0
        cen = sites.copy()
        cen[live] = first[live] / mass[live, None]
        sites = _project_cells(S, cen, pc, pt)
        if progress is not None:
            progress(k + 1, steps)
    return sites


def _lbfgs(S: Surface, sites: np.ndarray, steps: int, history: list, progress) -> np.ndarray:
    """L-BFGS on the CVT energy with sites free in space, projected onto the mesh at the end.

    ``F(s) = sum_i ∫_{V_i} |x - s_i|^2 dA`` is C^2 where the diagram changes smoothly and its
    gradient is ``2 (m_i s_i - ∫_{V_i} x dA)``; a minimum has every site at its cell's centroid.
    The two-loop recursion keeps the last ``SURFACE_LBFGS_MEMORY`` steps (scaled by the
    newest pair's ``s.y / y.y``); the first step, and every step after a reset, uses the
    diagonal ``1 / (2 m_i)`` instead (the energy's Hessian without the cells' coupling): a
    Lloyd step. A backtracking (Armijo) line search tries the full step first, which is taken
    nearly always: about one diagram per step. The nearest-site answers of each diagram start
    the next one's search.
    """
    hint = None

    def evaluate(s):
        nonlocal hint
        mass, first, energy, *_, hint = _run(S, s, 0, hint)
        return float(energy.sum()), 2.0 * (mass[:, None] * s - first), mass

    x = np.array(sites, dtype=np.float64)
    fx, g, mass = evaluate(x)
    mem: list = []
    for k in range(steps):
        history.append(fx)
        diag = 1.0 / (2.0 * np.maximum(mass, np.finfo(float).tiny))[:, None]
        q = g.copy()
        alphas = []
        for sk, yk, rho in reversed(mem):
            a = rho * np.vdot(sk, q)
            alphas.append(a)
            q -= a * yk
        if mem:  # the usual scale of the newest pair
            sk, yk, rho = mem[-1]
            r = q / (rho * float(np.vdot(yk, yk)))
        else:  # a Lloyd step
            r = diag * q
        for (sk, yk, rho), a in zip(mem, reversed(alphas), strict=True):
            r += sk * (a - rho * np.vdot(yk, r))
        p = -r
        slope = float(np.vdot(g, p))
        if not slope < 0.0:  # not a descent direction: forget and take a Lloyd step
            mem.clear()
            p = -diag * g
            slope = float(np.vdot(g, p))
            if not slope < 0.0:
                break  # a stationary point
        step = 1.0
        for _ in range(config.SURFACE_LBFGS_BACKTRACK):
            xn = x + step * p
            fn, gn, mn = evaluate(xn)
            if fn <= fx + 1e-4 * step * slope:
                break
            step *= 0.5
        else:
            mem.clear()  # no decrease along it: a Lloyd step, taken as it is
            xn = x - diag * g
            fn, gn, mn = evaluate(xn)
        sk, yk = xn - x, gn - g
        sy = float(np.vdot(sk, yk))
        if sy > 1e-12 * float(np.linalg.norm(sk) * np.linalg.norm(yk)):
            mem.append((sk, yk, 1.0 / sy))
            if len(mem) > config.SURFACE_LBFGS_MEMORY:
                mem.pop(0)
        x, fx, g, mass = xn, fn, gn, mn
        if progress is not None:
            progress(k + 1, steps)
    # onto the surface: each site to the nearest point of the triangles its cell covers
    _, _, _, pc, pt, *_ = _run(S, x, 1, hint)
    return _project_cells(S, x, pc, pt)


def voronoi(
    S: Surface,
    points_or_count,
    *,
    relax: int = 0,
    method: str = "lbfgs",
    init: str = "multilevel",
    seed: int = 0,
    progress=None,
) -> SurfaceVoronoi:
    """The Voronoi diagram of sites restricted to a surface, optionally relaxed to a CVT.

    Parameters
    ----------
    S : Surface
    points_or_count : (n, 3) array_like or int
        Sites in space (used as given: restricted cells are defined for any point; relaxing
        moves them onto the surface), or a count of random sites on the surface.
    relax : int
        Relaxation iterations (0: the diagram of the given sites).
    method : {"lbfgs", "lloyd"}
        ``"lloyd"``: each site to its cell's centroid projected back onto the surface.
        ``"lbfgs"``: quasi-Newton on the CVT energy (same fixed points, far fewer defects per
        iteration), sites projected onto the surface at the end.
    init : {"multilevel", "random"}
        For a site count with ``relax >= 10``: ``"multilevel"`` relaxes a quarter of the
        sites first (40% of the steps), adds the midpoints of their neighbour pairs and
        relaxes all (the rest): 94% hexagons for 1,000 cells on a sphere in 100 steps, against
        86% from random sites. ``"random"``: random sites, all steps at full size.
    seed : int
        Random seed for a site count.
    progress : callable, optional
        Called as ``progress(done, total)`` after each iteration.

    Returns
    -------
    SurfaceVoronoi
    """
    if not isinstance(S, Surface):
        raise ValueError(
            f"voronoi needs a Surface (surface.cylinder(...), ...); got {type(S).__name__}"
        )
    if method not in ("lbfgs", "lloyd"):
        raise ValueError(f"method must be 'lbfgs' or 'lloyd'; got {method!r}")
    if int(relax) != relax or relax < 0:
        raise ValueError(f"relax must be a non-negative integer; got {relax!r}")
    if np.isscalar(points_or_count):
        n = points_or_count
        if isinstance(n, bool) or int(n) != n or n < 1:
            raise ValueError(f"site count must be a positive integer; got {n!r}")
        if n > config.SEEDS_MAX_POINTS:
            raise ValueError(
                f"site count {int(n):,} is past the most sites a surface may be sampled with "
                f"({config.SEEDS_MAX_POINTS:,}, config.SEEDS_MAX_POINTS)"
            )
        sites = S.sample(int(n), seed=seed)
    else:
        sites = as_points3(points_or_count, "points")
        check_surface_range(sites, "points")
        if len(sites) < 1:
            raise ValueError("voronoi needs at least one site")
        V = np.asarray(S.vertices, dtype=np.float64)
        far = float(np.abs(sites - 0.5 * (V.min(axis=0) + V.max(axis=0))).max()) / S.scale
        if far > config.SURFACE_FAR_SITES:
            raise ValueError(
                f"a site lies {far:.3g} times the surface's size from it; the cells are "
                f"computed for sites within {config.SURFACE_FAR_SITES:g} times (squared "
                "distances to farther sites no longer tell which is nearest)"
            )
        if len(np.unique(sites, axis=0)) < len(sites):
            raise ValueError("sites contain exact duplicates (their cells would coincide)")
    history: list = []
    if init not in ("multilevel", "random"):
        raise ValueError(f"init must be 'multilevel' or 'random'; got {init!r}")
    if relax:
        if len(sites) < 2:
            raise ValueError("relaxing needs at least two sites")
        run = _lbfgs if method == "lbfgs" else _lloyd
        steps = int(relax)
        if (
            np.isscalar(points_or_count)
            and init == "multilevel"
            and steps >= 10
            and len(sites) >= 40
        ):
            # a quarter of the sites relaxed first, then each Delaunay edge's midpoint added:
            # the fine sites inherit the coarse order (far fewer defects; measured in docs)
            coarse = max(1, round(config.SURFACE_COARSE_SHARE * steps))
            few = S.sample(max(4, (len(sites) + 6) // 4), seed=seed)
            few = run(S, few, coarse, history, progress)
            sites = _refine(S, _result(S, np.ascontiguousarray(few), []), len(sites), seed)
            done = coarse
            fine = (lambda k, total: progress(done + k, steps)) if progress else None
            sites = run(S, sites, steps - coarse, history, fine)
        else:
            sites = run(S, sites, steps, history, progress)
    return _result(S, np.ascontiguousarray(sites), history)


def _refine(S: Surface, vd: SurfaceVoronoi, n: int, seed: int) -> np.ndarray:
    """``n`` sites: ``vd``'s sites plus its neighbour pairs' midpoints projected onto ``S``.

    On a hexagonal layout of ``N`` sites there are about ``3 N`` pairs: ``4 N`` sites in a
    hexagonal layout of half the spacing. Extra sites are dropped at random, missing ones
    sampled at random.
    """
    indptr, idx = vd.neighbors
    i = np.repeat(np.arange(len(vd.sites)), np.diff(indptr))
    keep = i < idx
    mids = 0.5 * (vd.sites[i[keep]] + vd.sites[idx[keep]])
    pts = np.concatenate([vd.sites, S.project(mids)])
    pts = np.unique(pts, axis=0)
    rng = np.random.default_rng(seed)
    if len(pts) > n:
        pts = pts[np.sort(rng.choice(len(pts), n, replace=False))]
    elif len(pts) < n:
        pts = np.concatenate([pts, S.sample(n - len(pts), seed=seed + 1)])
    return pts
