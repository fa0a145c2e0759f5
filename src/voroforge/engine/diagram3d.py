"""``Diagram3D``: the result of :func:`voroforge.voronoi3d`.

Layout (all arrays read-only):

- ``vertices (V, 3)``: every Voronoi vertex once; cells that meet at a vertex share its bits.
- per cell ``i``: faces ``cell_faces[i]:cell_faces[i + 1]`` of the per-cell face table, each
  with a ring of vertex numbers (outward, counter-clockwise seen from outside), the
  neighbour across it (a site, or ``-1 - w`` for container wall ``w``) and its area vector.
- ``faces``: each face once (:class:`Faces3D`): a cell face of ``i`` with site ``j > i``, and
  every wall face; its ring as seen from ``cells[:, 0]`` and its normal pointing to
  ``cells[:, 1]``.

Example: walk the faces of cell 0::

    p = d.cell(0)
    for ring, nb in zip(p.faces, p.neighbors):
        print(nb, p.vertices[ring])
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .csr import unique


def _ro(a):
    a = np.asarray(a)
    a.flags.writeable = False
    return a


@dataclass(frozen=True)
class Faces3D:
    """Unique faces: ``ring(k) = indices[indptr[k]:indptr[k + 1]]``, ``cells (m, 2)``.

    ``cells[k] = (i, j)`` with ``j`` a site (``j > i``) or ``-1 - w`` for a wall face.
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
    neighbors : tuple of (n + 1,) and (k,) int64
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
        farea,
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
    ):
        self.sites = _ro(sites)
        self.weights = None if weights is None else _ro(weights)
        self.periodic = bool(periodic)
        self.container = container
        self.walls = _ro(walls)
        self.volumes = _ro(volumes)
        self.centroids = _ro(centroids)
        self.vertices = _ro(vertices)
        self._cell_faces = _ro(cell_faces)
        self._flabel = _ro(flabel)
        self._farea = _ro(farea)
        self._roff = _ro(roff)
        self._ring = _ro(ring)
        self.duplicate_of = _ro(duplicate_of)
        self.unmatched_vertices = int(unmatched)
        self.box = box
        self.pieces = None if pieces is None else _ro(pieces)
        self.cut_cells = None if cut_cells is None else _ro(cut_cells)
        self.container_volume = container_volume
        self._face_keep = face_keep
        self.face_shifts = None if shifts is None else _ro(shifts)
        self._cache: dict = {}

    # --- per cell -------------------------------------------------------------------------
    def __len__(self) -> int:
        return len(self.sites)

    def __repr__(self) -> str:
        return (
            f"Diagram3D({len(self)} cells, {len(self.vertices)} vertices, "
            f"{len(self.faces)} faces, container={self.container}, periodic={self.periodic})"
        )

    def cell_face_table(self):
        """Per-cell faces: ``(cell_faces (n + 1,), labels, area_vectors, ring_offsets, rings)``.

        Faces of cell ``i`` are ``cell_faces[i]:cell_faces[i + 1]``; face ``f``'s ring is
        ``rings[ring_offsets[f]:ring_offsets[f + 1]]`` (outward). The internal layout other
        modules (solids, surfaces) use instead of private attributes.
        """
        return self._cell_faces, self._flabel, self._farea, self._roff, self._ring

    def cell(self, i: int) -> Polyhedron:
        """Cell ``i`` as a :class:`Polyhedron` (outward faces, neighbours per face)."""
        i = int(i)
        if not -len(self) <= i < len(self):
            raise IndexError(f"cell {i} out of range for {len(self)} cells")
        i %= len(self)
        f0, f1 = self._cell_faces[i], self._cell_faces[i + 1]
        rings = [self._ring[self._roff[f] : self._roff[f + 1]] for f in range(f0, f1)]
        ids = unique(np.concatenate(rings)) if rings else np.zeros(0, np.int64)
        local = {int(v): k for k, v in enumerate(ids)}
        faces = [np.array([local[int(v)] for v in r], np.int64) for r in rings]
        return Polyhedron(
            self.vertices[ids],
            faces,
            np.array(self._flabel[f0:f1]),
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

    # --- unique faces ---------------------------------------------------------------------
    def _unique(self):
        if "unique" not in self._cache:
            n = len(self)
            cf = self._cell_faces
            owner = np.repeat(np.arange(n), np.diff(cf))
            lab = self._flabel
            keep = (lab < 0) | (lab > owner) if self._face_keep is None else self._face_keep
            sel = np.flatnonzero(keep)
            lens = np.diff(self._roff)[sel]
            indptr = np.concatenate([[0], np.cumsum(lens)]).astype(np.int64)
            idx = (
                (
                    np.repeat(self._roff[sel], lens)
                    + np.arange(int(indptr[-1]))
                    - np.repeat(indptr[:-1], lens)
                )
                if len(sel)
                else np.zeros(0, np.int64)
            )
            faces = Faces3D(
                _ro(indptr),
                _ro(self._ring[idx]),
                _ro(np.column_stack([owner[sel], lab[sel]]).astype(np.int64)),
            )
            av = self._farea[sel]
            area = np.linalg.norm(av, axis=1) if len(sel) else np.zeros(0)
            with np.errstate(invalid="ignore", divide="ignore"):
                normals = av / area[:, None]
            self._cache["unique"] = (faces, _ro(area), _ro(normals))
        return self._cache["unique"]

    @property
    def faces(self) -> Faces3D:
        """Each face once: CSR rings into ``vertices`` and ``cells (m, 2)``."""
        return self._unique()[0]

    @property
    def face_areas(self) -> np.ndarray:
        """Areas of the unique faces, ``(m,)``."""
        return self._unique()[1]

    @property
    def face_normals(self) -> np.ndarray:
        """Unit normals of the unique faces, from ``faces.cells[:, 0]`` to ``[:, 1]``."""
        return self._unique()[2]

    @property
    def neighbors(self):
        """CSR ``(indptr, indices)``: the cells sharing a face of positive area, sorted."""
        if "nb" not in self._cache:
            n = len(self)
            owner = np.repeat(np.arange(n), np.diff(self._cell_faces))
            lab = self._flabel
            area = np.linalg.norm(self._farea, axis=1) if len(lab) else np.zeros(0)
            ok = (lab >= 0) & (area > 0) & (lab != owner)
            key = unique(owner[ok].astype(np.int64) * max(n, 1) + lab[ok])
            pairs = np.column_stack([key // max(n, 1), key % max(n, 1)])
            indptr = np.zeros(n + 1, np.int64)
            np.add.at(indptr, pairs[:, 0] + 1, 1)
            self._cache["nb"] = (_ro(np.cumsum(indptr)), _ro(pairs[:, 1].astype(np.int64)))
        return self._cache["nb"]

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
