"""The face planes that the mesh cut clips by: thin faces take their normals from the sites.

:func:`mesh3d.cut_by_mesh` clips container triangles by each cell's face planes (normal: the
face's area vector, through its first vertex). A face that is a sliver or a segment (cells
meeting along one edge: k >= 5 sites on a circle around it, e.g. on a torus's centre circle,
give faces between sites that are not neighbours, rings of near-equal vertices along the
circle's axis) has an area vector made of rounding: its direction is noise, and the plane
through the axis that it gives cut away the part of a triangle inside the cell (a cell the
torus crossed counted as untouched and kept whole: the cells filled 2.75 of a 1.68 torus).
The plane of a face between sites ``i`` and ``j`` is normal to ``p_j - p_i`` (a power
bisector too), a box wall's normal is its axis: :func:`steady_normals` uses those where the
area vector is too small to carry a direction.
"""

from __future__ import annotations

import numpy as np

from ..config import FACE_NOISE_ULPS, FACE_THIN_RTOL

#: outward normals of the box walls, label ``-1 - w`` (:func:`containers.box_template`)
_WALLS = np.array([[-1, 0, 0], [1, 0, 0], [0, -1, 0], [0, 1, 0], [0, 0, -1], [0, 0, 1]], float)


def steady_normals(farea, cf, lab, roff, ring, verts, sites):
    """``farea`` with each thin face's row replaced by its exact plane's normal.

    ``farea (f, 3)``: the faces' area vectors (:meth:`Diagram3D.cell_face_table`, cell ``i``'s
    faces ``cf[i]:cf[i + 1]``, labels ``lab``: a neighbour site ``>= 0`` or box wall
    ``-1 - w``); ``verts``: the vertices the rings ``roff``/``ring`` index; ``sites (n, 3)``
    in the same cell order. A thin face's new row points from its cell's site to the
    neighbour's (or along the wall's axis), scaled to its largest component in ``[0.5, 1)``.
    Other rows are returned as they were (the same bits; ``farea`` itself, as a contiguous
    float64 array, when no face is thin; else a copy).
    """
    from ..kernels.meshclip3d import thin_faces

    farea = np.ascontiguousarray(farea, np.float64)
    if not len(farea):
        return farea.copy()
    eps = np.finfo(np.float64).eps
    thin = thin_faces(
        farea,
        np.ascontiguousarray(roff, np.int64),
        np.ascontiguousarray(ring, np.int64),
        np.ascontiguousarray(verts, np.float64),
        FACE_THIN_RTOL,
        FACE_NOISE_ULPS * eps,
    )
    if not thin.any():
        return farea
    farea = farea.copy()
    f = np.flatnonzero(thin)
    owner = np.repeat(np.arange(len(cf) - 1), np.diff(cf))[f]
    lf = np.asarray(lab)[f]
    nrm = np.zeros((len(f), 3))
    site = lf >= 0
    nrm[site] = sites[lf[site]] - sites[owner[site]]
    wall = (lf < 0) & (lf >= -6)
    nrm[wall] = _WALLS[-1 - lf[wall]]
    big = np.abs(nrm).max(axis=1)
    ok = big > 0
    nrm[ok] = np.ldexp(nrm[ok], -np.frexp(big[ok])[1][:, None])
    # a face of unknown kind or between equal sites keeps its row (no better plane)
    farea[f[ok]] = nrm[ok]
    return farea
