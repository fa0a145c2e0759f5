"""``Diagram3D``: the result of :func:`voroforge.voronoi3d`.

Layout (all arrays read-only):

- ``vertices (V, 3)``: every Voronoi vertex once; cells that meet at a vertex share its bits.
- per cell ``i``: faces ``cell_faces[i]:cell_faces[i + 1]`` of the per-cell face table
  (:meth:`Diagram3D.cell_face_table`), each with a ring of vertex numbers (outward,
  counter-clockwise seen from outside), the neighbour across it (a site, or ``-1 - w`` for
  container wall ``w``) and its area vector.
- ``faces``: each face once (:class:`Faces3D`): a cell face of ``i`` with site ``j > i``, and
  every wall face; its ring as seen from ``cells[:, 0]`` and its normal pointing to
  ``cells[:, 1]``.

Storage: the per-cell face table is kept in the order the cells were built (bucket order):
``int32`` labels and ring offsets, rings of ``uint8`` indices into the cell's own list of
vertex numbers; area vectors are computed when asked for, never stored with the table.
Everything public is in the caller's order.

Example: walk the faces of cell 0::

    p = d.cell(0)
    for ring, nb in zip(p.faces, p.neighbors):
        print(nb, p.vertices[ring])
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit, prange

from ..config import FAN_D2_MAX as _FAN_D2_MAX
from ..config import FAN_D2_MIN as _FAN_D2_MIN
from ..config import FAN_ERR as _FAN_ERR
from ..config import NJIT, NJIT_PARALLEL
from .csr import unique
from .readonly import readonly
from .threads import serial_below

# :func:`_flat`'s shortcut (:func:`_clearly_not_flat`): a fan sum over a ring of ``n``
# vertices whose offsets from its apex are at most ``M`` long is within ``1.01 u n^2 M^2``
# of the exact area vector (``u = 2**-53``: ~4 roundings in each cross product, each
# component at most ``|u||w|``, and ``n`` in the sum). The first entry's fan has ``M = D``
# (its longest offset), any other's ``M <= 2 D``, so two fans' sums differ by less than
# ``5.05 u n^2 D^2 = 5.6e-16 n^2 D^2``: a component above ``FAN_ERR n^2 D^2`` (config) is
# nonzero in every fan. ``D^2`` in ``(FAN_D2_MIN, FAN_D2_MAX)`` keeps the products clear of
# under- and overflow (else the canonical fan decides)


def _ro(a):
    a = np.asarray(a)
    a.flags.writeable = False
    return a


@dataclass(frozen=True)
class Faces3D:
    """Unique faces: ``ring(k) = indices[indptr[k]:indptr[k + 1]]``, ``cells (m, 2)``.

    ``cells[k] = (i, j)`` with ``j`` a site (``j > i``) or ``-1 - w`` for a wall face; on a
    torus, ``(i, i)`` for a face between a cell and its own image (``neighbors`` leaves
    those out).
    """

    indptr: np.ndarray
    indices: np.ndarray
    cells: np.ndarray

    def __len__(self) -> int:
        return len(self.cells)

    def ring(self, k: int) -> np.ndarray:
        """Vertex numbers of face ``k``, counter-clockwise seen from outside ``cells[k, 0]``."""
        return self.indices[self.indptr[k] : self.indptr[k + 1]]


@dataclass(frozen=True)
class Polyhedron:
    """One cell: ``vertices (k, 3)``, ``faces`` (rings into them, outward), ``neighbors``.

    ``vertex_ids`` are the rows of ``Diagram3D.vertices``; ``neighbors[f]`` is the site across
    face ``f`` or ``-1 - w`` for wall ``w``; ``volume`` and ``centroid`` as in the diagram.
    """

    vertices: np.ndarray
    faces: list
    neighbors: np.ndarray
    vertex_ids: np.ndarray
    volume: float
    centroid: np.ndarray


class Diagram3D:
    """3D Voronoi (or power) cells of sites in a container; see :func:`voroforge.voronoi3d`.

    Attributes
    ----------
    sites : (n, 3) float64
        The input points, in input order; cell ``i`` belongs to ``sites[i]``.
    volumes : (n,) float64
    centroids : (n, 3) float64
        NaN for empty cells.
    neighbors : tuple of (n + 1,) int64 and (k,) int32
        CSR ``(indptr, indices)`` of the cells sharing a face of positive area, sorted.
    vertices : (V, 3) float64
    faces : Faces3D
    face_areas : (m,) float64
    face_normals : (m, 3) float64
        Unit normals of the unique faces, from ``faces.cells[:, 0]`` towards ``[:, 1]``.
    duplicate_of : (n,) int64
        -1, or the site that owns this site's (empty) cell because they coincide.
    weights : (n,) float64 or None
    periodic : bool
    container : str
        ``"box"``, ``"convex"`` or ``"mesh"``.
    walls : (W, 4) float64
        The container's planes ``a x + b y + c z <= d`` (box and convex).
    """

    def __init__(
        self,
        *,
        sites,
        weights,
        periodic,
        container,
        walls,
        volumes,
        centroids,
        vertices,
        cell_faces,
        flabel,
        roff,
        ring,
        duplicate_of,
        unmatched,
        box=None,
        pieces=None,
        cut_cells=None,
        container_volume=None,
        face_keep=None,
        shifts=None,
        pos=None,
        vid=None,
        voff=None,
        frame=None,
    ):
        self.sites = _ro(sites)
        self.weights = None if weights is None else _ro(weights)
        self.periodic = bool(periodic)
        self.container = container
        # a copy: ``walls`` may be the container template's own rows (Template.absolute_walls),
        # which frozen in place made the next call on the same Convex pass the kernels a
        # read-only array, a second numba type: every 3D cell kernel compiled twice
        self.walls = _ro(np.array(walls, dtype=np.float64))
        self.volumes = _ro(volumes)
        self.centroids = _ro(centroids)
        self.vertices = _ro(vertices)
        # the per-cell face table, in build order: cell i's faces are
        # cell_faces[pos[i]]:cell_faces[pos[i] + 1] (pos None: the caller's order)
        # (pos None: the caller's order); ring entries are local to the cell: cell position p's
        # vertex r is vid[voff[p] + r] (without vid: rings hold vertex numbers)
        self._cell_faces = _ro(cell_faces)
        self._flabel = _ro(flabel)
        self._roff = _ro(roff)
        self._ring = _ro(ring)
        self._pos = None if pos is None else _ro(np.asarray(pos, np.int64))
        if vid is None:
            vid = np.arange(len(vertices), dtype=np.int64)
            voff = np.zeros(len(cell_faces), np.int64)
        self._vid = _ro(vid)
        self._voff = _ro(voff)
        self.duplicate_of = _ro(duplicate_of)
        self._unmatched = int(unmatched)
        self.box = box
        self.pieces = None if pieces is None else _ro(pieces)
        self.cut_cells = None if cut_cells is None else _ro(cut_cells)
        self.container_volume = container_volume
        self._face_keep = face_keep
        self.face_shifts = None if shifts is None else _ro(shifts)
        # the working frame's exponent (engine.inputs.working_frame): area vectors and the
        # flatness test are computed on vertices times 2**frame (exact), where squares of
        # areas and products of coordinates neither overflow nor underflow; 0 for ordinary
        # input (the same bits); None (mesh containers): the same rule on the vertices
        if frame is None:
            frame = _vertex_frame(self.vertices)
        self._frame = int(frame)
        self._cache: dict = {}

    # --- per cell -------------------------------------------------------------------------
    def __len__(self) -> int:
        return len(self.sites)

    def __repr__(self) -> str:
        return (
            f"Diagram3D({len(self)} cells, {len(self.vertices)} vertices, "
            f"{len(self.faces)} faces, container={self.container}, periodic={self.periodic})"
        )

    def _positions(self):
        # read-only either way (a frozen order or a fresh arange): numba types the flag, and
        # the face kernels' callees (_cells_at) compiled twice
        return readonly(np.arange(len(self), dtype=np.int64) if self._pos is None else self._pos)

    def cell_face_table(self):
        """Per-cell faces: ``(cell_faces (n + 1,), labels, area_vectors, ring_offsets, rings)``.

        Faces of cell ``i`` are ``cell_faces[i]:cell_faces[i + 1]``; face ``f``'s ring is
        ``rings[ring_offsets[f]:ring_offsets[f + 1]]`` (outward), its area vector (outward,
        length = area) ``area_vectors[f]``. The internal layout other modules (solids,
        surfaces) use instead of private attributes; built on first use (a copy in the
        caller's order, with the area vectors).
        """
        if "table" not in self._cache:
            cf, lab, roff, ring = _in_caller_order(
                self._positions(),
                self._cell_faces,
                self._flabel,
                self._roff,
                self._ring,
                self._voff,
                self._vid,
            )
            area = np.zeros((len(lab), 3))
            # read-only views, as _areas passes its frozen faces: one compile (numba types
            # the flag)
            ro, rg = readonly(roff), readonly(ring)
            _face_vectors(readonly(self.vertices), ro, rg, area, self._scale())
            if self._frame:
                area = np.ldexp(area, -2 * self._frame)
            self._cache["table"] = tuple(_ro(a) for a in (cf, lab, area, roff, ring))
        return self._cache["table"]

    def cell(self, i: int) -> Polyhedron:
        """Cell ``i`` as a :class:`Polyhedron` (outward faces, neighbours per face)."""
        i = int(i)
        if not -len(self) <= i < len(self):
            raise IndexError(f"cell {i} out of range for {len(self)} cells")
        i %= len(self)
        p = i if self._pos is None else int(self._pos[i])
        f0, f1 = self._cell_faces[p], self._cell_faces[p + 1]
        rings = [
            self._vid[
                self._voff[p] + np.asarray(self._ring[self._roff[f] : self._roff[f + 1]], np.int64)
            ]
            for f in range(f0, f1)
        ]
        ids = unique(np.concatenate(rings)) if rings else np.zeros(0, np.int64)
        local = {int(v): k for k, v in enumerate(ids)}
        faces = [np.array([local[int(v)] for v in r], np.int64) for r in rings]
        return Polyhedron(
            self.vertices[ids],
            faces,
            np.array(self._flabel[f0:f1], np.int64),
            ids,
            float(self.volumes[i]),
            np.array(self.centroids[i]),
        )

    def to_trimesh(self, i=None):
        """Cell ``i`` as a closed ``trimesh.Trimesh``, or a list with one mesh per cell.

        Rings are fanned into triangles (outward); empty cells give empty meshes.
        """
        import trimesh

        def one(k):
            p = self.cell(k)
            tris = [(r[0], r[t], r[t + 1]) for r in p.faces for t in range(1, len(r) - 1)]
            return trimesh.Trimesh(
                p.vertices, np.array(tris, np.int64).reshape(-1, 3), process=False
            )

        if i is not None:
            return one(i)
        return [one(k) for k in range(len(self))]

    def triangles(self):
        """Every cell as one triangle mesh: ``(vertices (m, 3), faces (t, 3), cell (t,))``.

        The same triangles, vertices and order as concatenating :meth:`to_trimesh`'s meshes
        (each cell its own copy of its vertices, rings fanned outward, cells in input order,
        empty cells left out), built at once: 100,000 cells one by one took ~40 s.
        """
        cf, _, _, roff, ring = self.cell_face_table()
        flen = np.diff(roff)
        ntri = np.maximum(flen - 2, 0)
        tri_face = np.repeat(np.arange(len(flen)), ntri)
        first = np.cumsum(ntri) - ntri  # each face's first triangle
        t = np.arange(len(tri_face)) - first[tri_face] + 1  # fan step 1 .. len - 2
        start = roff[:-1][tri_face]
        cell = np.repeat(np.arange(len(self), dtype=np.int64), np.diff(cf))[tri_face]
        nv = max(len(self.vertices), 1)
        corners = [ring[start], ring[start + t], ring[start + t + 1]]
        keys = np.concatenate([cell * nv + np.asarray(c, np.int64) for c in corners])
        uk, inv = np.unique(keys, return_inverse=True)
        verts = np.asarray(self.vertices)[uk % nv]
        return verts, inv.reshape(3, -1).T.copy(), cell

    # --- unique faces ---------------------------------------------------------------------
    def _unique(self):
        if "unique" not in self._cache:
            keep = self._face_keep
            use = keep is not None
            with serial_below(len(self)):
                indptr, indices, cells = _unique_faces(
                    self._positions(),
                    self._cell_faces,
                    self._flabel,
                    self._roff,
                    self._ring,
                    self._voff,
                    self._vid,
                    np.asarray(keep if use else np.zeros(0, bool)),
                    use,
                )
            self._cache["unique"] = Faces3D(_ro(indptr), _ro(indices), _ro(cells))
        return self._cache["unique"]

    def _scale(self):
        """``2**frame``: the factor of the working frame's coordinates (1.0: none)."""
        return float(np.ldexp(1.0, self._frame))

    def _areas(self):
        """Areas and unit normals of the unique faces (computed on first use).

        Both in the working frame (a power-of-two scaling: the normals are the same bits,
        the areas scale back exactly), where the squared areas neither overflow nor
        underflow.
        """
        if "areas" not in self._cache:
            faces = self.faces
            av = np.zeros((len(faces), 3))
            V, fp, fi = readonly(self.vertices), readonly(faces.indptr), readonly(faces.indices)
            _face_vectors(V, fp, fi, av, self._scale())
            area = np.sqrt((av * av).sum(axis=1))
            with np.errstate(invalid="ignore", divide="ignore"):
                av /= area[:, None]
            if self._frame:
                area = np.ldexp(area, -2 * self._frame)
            self._cache["areas"] = (_ro(area), _ro(av))
        return self._cache["areas"]

    @property
    def faces(self) -> Faces3D:
        """Each face once: CSR rings into ``vertices`` and ``cells (m, 2)``."""
        return self._unique()

    @property
    def face_areas(self) -> np.ndarray:
        """Areas of the unique faces, ``(m,)`` (computed on first use)."""
        return self._areas()[0]

    @property
    def face_normals(self) -> np.ndarray:
        """Unit normals of the unique faces, from ``faces.cells[:, 0]`` to ``[:, 1]``."""
        return self._areas()[1]

    @property
    def neighbors(self):
        """CSR ``(indptr, indices)``: the cells sharing a face of positive area, sorted.

        On a torus, where each cell holds its own copy of a face across the seam (an image's
        vertices, shifted by the period, round apart from its twin's), two cells are
        neighbours where both see the face with nonzero area (:func:`_mutual`).
        """
        if "nb" not in self._cache:
            with serial_below(len(self)):
                indptr, indices = _neighbors(
                    self._positions(),
                    self._cell_faces,
                    self._flabel,
                    self._roff,
                    self._ring,
                    self._voff,
                    self._vid,
                    np.asarray(self.vertices),
                    self._scale(),
                )
            if self.periodic:
                indptr, indices = _mutual(indptr, indices)
            self._cache["nb"] = (_ro(indptr), _ro(indices))
        return self._cache["nb"]

    @property
    def unmatched_vertices(self) -> int:
        """Vertices referenced by fewer cells than they have owner sites (0 when healthy).

        Owner sites are those whose cells are not empty, in the diagram's frame: on a torus
        not the images (their cells hold the vertex as another record, shifted), and with
        weights not the sites of empty power cells; there the count is taken from the faces
        (:func:`.describe3d.unmatched_on_faces`), on first use.
        """
        if "unmatched" not in self._cache:
            u = self._unmatched
            if self.periodic or (u and self.weights is not None and self.container != "mesh"):
                from .describe3d import unmatched_on_faces

                u = unmatched_on_faces(self)
            self._cache["unmatched"] = u
        return self._cache["unmatched"]

    # --- queries --------------------------------------------------------------------------
    def locate(self, xyz):
        """Nearest site (power distance with weights) of each query; exact ties -> lowest.

        Parameters
        ----------
        xyz : (3,) or (m, 3) array_like

        Returns
        -------
        int or (m,) int64
        """
        from .locate3d import locate3d

        return locate3d(self, xyz)

    def describe(self):
        """Counts and checks: V, E, F, C, Euler per cell, convexity, cut cells (a dict)."""
        from .describe3d import describe3d

        return describe3d(self)


def _vertex_frame(V) -> int:
    """The working frame's exponent of vertices ``V`` (:func:`.inputs.working_frame`'s rule)."""
    from .inputs import working_frame

    return working_frame(np.abs(V).max(axis=0, keepdims=True))[1] if len(V) else 0


# --- kernels over the face table (private) ------------------------------------------------


@njit(**{**NJIT, "inline": "always"})
def _fan_cross(V, v0, u, w, s):
    """``(u - v0) x (w - v0)`` of vertices ``V[u]``, ``V[w]``, ``V[v0]``, the offsets times ``s``.

    Twice the area vector of one triangle of a face's fan (:func:`_face_vectors`, :func:`_flat`).
    """
    ux = (V[u, 0] - V[v0, 0]) * s
    uy = (V[u, 1] - V[v0, 1]) * s
    uz = (V[u, 2] - V[v0, 2]) * s
    wx = (V[w, 0] - V[v0, 0]) * s
    wy = (V[w, 1] - V[v0, 1]) * s
    wz = (V[w, 2] - V[v0, 2]) * s
    return uy * wz - uz * wy, uz * wx - ux * wz, ux * wy - uy * wx


@njit(**NJIT)
def _face_vectors(V, roff, ring, out, s):
    """Area vectors of the rings ``ring[roff[f]:roff[f + 1]]`` (outward: length = area).

    Fanned from each ring's first vertex, in coordinates relative to it (far from the
    origin, e.g. UTM, the products stay accurate), times ``s`` (a power of two: the area
    vectors times ``s**2``, exactly, where they are representable).
    """
    for f in range(out.shape[0]):
        a = roff[f]
        b = roff[f + 1]
        v0 = ring[a]
        ax = 0.0
        ay = 0.0
        az = 0.0
        for q in range(a + 1, b - 1):
            u = ring[q]
            w = ring[q + 1]
            cx, cy, cz = _fan_cross(V, v0, u, w, s)
            ax += cx
            ay += cy
            az += cz
        out[f, 0] = 0.5 * ax
        out[f, 1] = 0.5 * ay
        out[f, 2] = 0.5 * az


@njit(**NJIT)
def _in_caller_order(pos, cf, lab, roff, ring, voff, vid):
    """The face table with cell ``i``'s faces at ``i`` and rings of vertex numbers (a copy)."""
    n = pos.shape[0]
    cf2 = np.zeros(n + 1, np.int64)
    for i in range(n):
        cf2[i + 1] = cf2[i] + cf[pos[i] + 1] - cf[pos[i]]
    lab2 = np.zeros(cf2[n], lab.dtype)
    roff2 = np.zeros(cf2[n] + 1, np.int64)
    nr = 0
    for i in range(n):
        p = pos[i]
        nr += roff[cf[p + 1]] - roff[cf[p]]
    ring2 = np.zeros(nr, vid.dtype)
    f2 = 0
    for i in range(n):
        p = pos[i]
        base = voff[p]
        for f in range(cf[p], cf[p + 1]):
            lab2[f2] = lab[f]
            r0 = roff2[f2]
            for q in range(roff[f], roff[f + 1]):
                ring2[r0 + q - roff[f]] = vid[base + ring[q]]
            roff2[f2 + 1] = r0 + roff[f + 1] - roff[f]
            f2 += 1
    return cf2, lab2, roff2, ring2


@njit(**NJIT)
def _cells_at(pos, npos):
    """The cell built at each of ``npos`` positions (``pos``'s inverse; unused: -1)."""
    at = np.full(npos, -1, np.int64)
    for i in range(pos.shape[0]):
        at[pos[i]] = i
    return at


@njit(**NJIT)
def _kept(use_keep, keep, lab, f, i):
    """Whether face ``f`` of cell ``i`` is one of the unique faces (:func:`_unique_faces`)."""
    if use_keep:
        return keep[f]
    return lab[f] < 0 or lab[f] > i


@njit(**NJIT)
def _runs(npos):
    """Runs of build positions that a parallel pass over the face table takes one at a time."""
    nrun = max(1, min(256, npos // 512))
    return nrun, (npos + nrun - 1) // nrun


@njit(**NJIT_PARALLEL)
def _unique_faces(pos, cf, lab, roff, ring, voff, vid, keep, use_keep):
    """Each face once, in the caller's cell order: ``(indptr, indices, cells (m, 2))``.

    A face of cell ``i`` is kept when its label is a wall or a site ``> i`` (or, with
    ``use_keep``, where ``keep`` (build order) says so: periodic images). The table is read
    in build order (neighbouring cells, near vertices) and written in the caller's; runs of
    build positions in parallel, each cell's counts then its rows (disjoint).
    """
    n = pos.shape[0]
    npos = cf.shape[0] - 1
    at = _cells_at(pos, npos)
    nf = np.zeros(n + 1, np.int64)  # kept faces of cell i, then their offsets
    nr = np.zeros(n + 1, np.int64)  # their ring entries
    nrun, step = _runs(npos)
    for run in prange(nrun):
        for p in range(run * step, min(npos, (run + 1) * step)):
            i = at[p]
            if i < 0:
                continue
            a = 0
            b = 0
            for f in range(cf[p], cf[p + 1]):
                if _kept(use_keep, keep, lab, f, i):
                    a += 1
                    b += roff[f + 1] - roff[f]
            nf[i + 1] = a
            nr[i + 1] = b
    for i in range(n):
        nf[i + 1] += nf[i]
        nr[i + 1] += nr[i]
    m = nf[n]
    indptr = np.zeros(m + 1, roff.dtype)  # unique rings are half of the per-cell ones
    indices = np.empty(nr[n], vid.dtype)  # noqa: TID251 - every entry written below
    cells = np.empty((m, 2), lab.dtype)  # noqa: TID251 - every row written below
    for run in prange(nrun):
        for p in range(run * step, min(npos, (run + 1) * step)):
            i = at[p]
            if i < 0:
                continue
            k = nf[i]
            r = nr[i]
            base = voff[p]
            for f in range(cf[p], cf[p + 1]):
                if _kept(use_keep, keep, lab, f, i):
                    cells[k, 0] = i
                    cells[k, 1] = lab[f]
                    for q in range(roff[f], roff[f + 1]):
                        indices[r] = vid[base + ring[q]]
                        r += 1
                    k += 1
                    indptr[k] = r
    return indptr, indices, cells


@njit(**{**NJIT, "inline": "always"})
def _clearly_not_flat(V, roff, ring, base, vid, f, s):
    """Whether face ``f``'s area vector, fanned from any vertex, cannot sum to exactly zero.

    Fanned from the ring's first entry, in order (:func:`_face_vectors`' sum, times
    ``s``): a component larger than :data:`_FAN_ERR` ``n^2 D^2`` (``D`` the largest offset
    from that entry) leaves the exact area, hence every other fan's float sum, nonzero.
    """
    a = roff[f]
    b = roff[f + 1]
    if b - a < 3:
        return False
    v0 = vid[base + ring[a]]
    x0 = V[v0, 0]
    y0 = V[v0, 1]
    z0 = V[v0, 2]
    u = vid[base + ring[a + 1]]
    ux = (V[u, 0] - x0) * s
    uy = (V[u, 1] - y0) * s
    uz = (V[u, 2] - z0) * s
    d2 = ux * ux + uy * uy + uz * uz
    ax = 0.0
    ay = 0.0
    az = 0.0
    for q in range(a + 2, b):  # (the products of _fan_cross)
        w = vid[base + ring[q]]
        wx = (V[w, 0] - x0) * s
        wy = (V[w, 1] - y0) * s
        wz = (V[w, 2] - z0) * s
        ax += uy * wz - uz * wy
        ay += uz * wx - ux * wz
        az += ux * wy - uy * wx
        d2 = max(d2, wx * wx + wy * wy + wz * wz)
        ux = wx
        uy = wy
        uz = wz
    if not _FAN_D2_MIN < d2 < _FAN_D2_MAX:
        return False
    n = b - a
    lim = _FAN_ERR * (n * n) * d2
    return abs(ax) > lim or abs(ay) > lim or abs(az) > lim


@njit(**{**NJIT, "_nrt": False})
def _flat(V, roff, ring, base, vid, f, s):
    """Whether face ``f``'s area vector is exactly zero (the fan of :func:`_face_vectors`).

    On coordinates times ``s`` (the working frame: products of tiny differences do not
    underflow to zero). The fan starts at the ring's lowest vertex number and runs towards
    its lower-numbered neighbour, so both cells of a face (the same vertices, rings
    reversed) sum the same products and agree: a face a few ulps wide (a lattice moved by
    ulps) was flat on one side only, and ``neighbors`` was not symmetric.

    That fan is summed only where the ring's own fan (from its first entry, no search) is
    too small to prove it nonzero (:func:`_clearly_not_flat`): both sums are within a few
    roundings of the exact area vector, so an area well above those roundings is not zero.
    Compiled without reference counting (it allocates nothing): a call per face otherwise
    paid atomic count updates on four arrays, as much as the face's fan.
    """
    return not _clearly_not_flat(V, roff, ring, base, vid, f, s) and _flat_fan(
        V, roff, ring, base, vid, f, s
    )


@njit(**{**NJIT, "inline": "always"})
def _flat_fan(V, roff, ring, base, vid, f, s):
    """:func:`_flat`'s canonical fan: whether its sum is exactly zero."""
    a = roff[f]
    n = roff[f + 1] - a
    q0 = 0
    for q in range(1, n):
        if vid[base + ring[a + q]] < vid[base + ring[a + q0]]:
            q0 = q
    nxt = q0 + 1 if q0 + 1 < n else 0
    prv = q0 - 1 if q0 > 0 else n - 1
    d = -1 if vid[base + ring[a + prv]] < vid[base + ring[a + nxt]] else 1
    v0 = vid[base + ring[a + q0]]
    ax = 0.0
    ay = 0.0
    az = 0.0
    j = prv if d < 0 else nxt  # (ring positions wrapped by hand: no division per step)
    for _ in range(1, n - 1):
        j2 = j + d
        if j2 == n:
            j2 = 0
        elif j2 < 0:
            j2 = n - 1
        u = vid[base + ring[a + j]]
        w = vid[base + ring[a + j2]]
        j = j2
        cx, cy, cz = _fan_cross(V, v0, u, w, s)
        ax += cx
        ay += cy
        az += cz
    return ax == 0.0 and ay == 0.0 and az == 0.0


@njit(**NJIT)
def _sorted_nb(cf, lab, roff, ring, voff, vid, V, s, p, i, out, o):
    """Cell ``i``'s (build position ``p``) neighbours across faces of nonzero area, sorted.

    Into ``out[o:]`` (no more than the cell's faces); returns their count.
    """
    c = 0
    for f in range(cf[p], cf[p + 1]):
        j = lab[f]
        if j < 0 or j == i or _flat(V, roff, ring, voff[p], vid, f, s):
            continue
        b = o + c - 1  # insertion sort, dropping repeats
        while b >= o and out[b] > j:
            b -= 1
        if b >= o and out[b] == j:
            continue
        for q in range(o + c, b + 1, -1):
            out[q] = out[q - 1]
        out[b + 1] = j
        c += 1
    return c


@njit(**NJIT_PARALLEL)
def _neighbors(pos, cf, lab, roff, ring, voff, vid, V, s):
    """CSR of each cell's neighbours across faces of nonzero area (sorted, once each).

    One pass in build order (runs of positions in parallel) writes each cell's row at its
    first face's place of a buffer as long as the face table; the caller's rows are then
    copied from it, written in order. Two passes in build order, the second writing each
    row at the caller's place (random writes, missing the caches at 1e6), took 1.35-1.42 us
    a cell at 1e5 and 1.58-1.97 at 1e6 (one and two threads); this, 0.89-0.90 and 1.05-1.25.
    """
    n = pos.shape[0]
    npos = cf.shape[0] - 1
    at = _cells_at(pos, npos)
    cnt = np.zeros(npos, np.int32)
    rows = np.empty(lab.shape[0], lab.dtype)  # noqa: TID251 - read only up to cnt, written
    nrun, step = _runs(npos)
    for run in prange(nrun):
        for p in range(run * step, min(npos, (run + 1) * step)):
            i = at[p]
            if i >= 0:
                cnt[p] = _sorted_nb(cf, lab, roff, ring, voff, vid, V, s, p, i, rows, cf[p])
    indptr = np.zeros(n + 1, np.int64)
    for i in range(n):
        indptr[i + 1] = indptr[i] + cnt[pos[i]]
    indices = np.empty(indptr[n], lab.dtype)  # noqa: TID251 - every entry written below
    for i in prange(n):
        p = pos[i]
        a = cf[p]
        r = indptr[i]
        for q in range(cnt[p]):
            indices[r + q] = rows[a + q]
    return indptr, indices


@njit(**NJIT_PARALLEL)
def _mutual(indptr, indices):
    """Sorted CSR rows keeping ``j`` in row ``i`` only where row ``j`` holds ``i``.

    A periodic cell decides a face's flatness from its own copy of it: on a lattice that is
    degenerate only up to rounding (FCC in metres, 3.615e-10) a face of 1e-32 of a face's
    area was nonzero on one side and exactly zero, or absent, on the other, and the
    neighbour lists were one-sided (checker24 F4). Rows sorted, each looked up by bisection.
    """
    n = indptr.shape[0] - 1
    keep = np.zeros(indices.shape[0], np.bool_)
    cnt = np.zeros(n + 1, np.int64)
    for i in prange(n):
        c = 0
        for q in range(indptr[i], indptr[i + 1]):
            j = indices[q]
            lo = indptr[j]
            hi = indptr[j + 1]
            while lo < hi:
                m = (lo + hi) >> 1
                if indices[m] < i:
                    lo = m + 1
                else:
                    hi = m
            if lo < indptr[j + 1] and indices[lo] == i:
                keep[q] = True
                c += 1
        cnt[i + 1] = c
    for i in range(n):
        cnt[i + 1] += cnt[i]
    out = np.empty(cnt[n], indices.dtype)  # noqa: TID251 - every entry written below
    for i in prange(n):
        r = cnt[i]
        for q in range(indptr[i], indptr[i + 1]):
            if keep[q]:
                out[r] = indices[q]
                r += 1
    return cnt, out
