"""Cut cells by a closed mesh with manifold3d: the boolean path of :func:`mesh3d.cut_by_mesh`.

Cells the exact convex path (``mesh3d._convex_part``) leaves are intersected with the
container in batches of cells that share no vertex; the result's connected components are
given back to their cells by the face ids manifold3d keeps.
"""

from __future__ import annotations

import numpy as np

from .csr import unique, used_only

__all__ = ["cut_split", "manifold_of", "ranks"]


def manifold_of(V, F, face_id):
    """A manifold3d ``Manifold`` of triangles ``F`` on ``V``, each keeping ``face_id``."""
    import manifold3d as m3

    mesh = m3.Mesh64(
        vert_properties=np.ascontiguousarray(V, np.float64),
        tri_verts=np.ascontiguousarray(F, np.uint64),
        face_id=np.ascontiguousarray(face_id, np.uint64),
    )
    return m3.Manifold(mesh)


def _drop_flat(ov, ot, ofid, tol):
    """The result without components thinner than ``tol`` on average (|volume| <= tol area).

    Where a container wall lies exactly in a cell's face plane (the bisector of two sites
    on a notch's wall), manifold3d can return a closed sheet of zero volume between the
    coincident faces: a third "piece" of the cell with wall and neighbour faces of area
    but no volume (checker29 F4). ``(ov, ot, ofid)`` unchanged where there is none.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    e = np.concatenate([ot[:, [0, 1]], ot[:, [1, 2]]])
    g = coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(len(ov), len(ov)))
    ncomp, comp = connected_components(g, directed=False)
    tcomp = comp[ot[:, 0]]
    a, b, c = ov[ot[:, 0]], ov[ot[:, 1]], ov[ot[:, 2]]
    comps, first = np.unique(tcomp, return_index=True)
    o = np.zeros((ncomp, 3))
    o[comps] = ov[ot[first, 0]]  # about a vertex of each component
    a, b, c = a - o[tcomp], b - o[tcomp], c - o[tcomp]
    vol = np.bincount(tcomp, np.einsum("ij,ij->i", a, np.cross(b, c)), ncomp) / 6.0
    area = np.bincount(tcomp, 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1), ncomp)
    flat = np.abs(vol) <= tol * area
    if not flat[tcomp].any():
        return ov, ot, ofid
    keep = ~flat[tcomp]
    ov, ot = used_only(ov, ot[keep])
    return ov, ot, ofid[keep]


def _cut_batch(batch, cf, roff, ring, verts, lab, nF, container, tol):
    """Cells ``batch`` (no two touching) ∩ ``container`` (a Manifold), in one boolean.

    ``(vertices, cells, ntri, triangles, labels, volumes, centroids, pieces)`` for the cells
    that keep some volume (``cells`` ascending, their ``ntri`` triangles one cell after
    another), or None when a connected component of the result cannot be given to one
    cell: a closed part of the container inside a cell that touches none of its faces, or
    faces of two cells in one component (cells that touch without sharing a named vertex);
    the caller then halves the batch. Components thinner than ``tol`` are left out
    (:func:`_drop_flat`).
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    nf = cf[batch + 1] - cf[batch]
    fidx = np.repeat(cf[batch], nf) + ranks(nf)  # the batch's faces
    lens = roff[fidx + 1] - roff[fidx]
    flat = ring[np.repeat(roff[fidx], lens) + ranks(lens)]
    ids = unique(flat)  # the cells share no vertex: one vertex list for the batch
    loc = np.searchsorted(ids, flat)
    first = np.repeat(np.cumsum(lens) - lens, lens - 2)  # fans from each face's first vertex
    step = ranks(lens - 2) + 1
    ts = np.stack([loc[first], loc[first + step], loc[first + step + 1]], 1)
    fs = np.repeat(fidx, lens - 2) + nF
    face_owner = np.repeat(batch, nf)  # the owner of each batch face, by position
    out = (manifold_of(verts[ids], ts, fs) ^ container).to_mesh64()
    ofid = np.asarray(out.face_id, np.int64)
    ov = np.array(np.asarray(out.vert_properties)[:, :3], np.float64)
    ot = np.asarray(out.tri_verts, np.int64).reshape(-1, 3)
    if len(ot):
        ov, ot, ofid = _drop_flat(ov, ot, ofid, tol)
    empty = np.zeros(0, np.int64)
    if not len(ot):
        return ov, empty, empty, ot, empty, np.zeros(0), np.zeros((0, 3)), empty
    fromcell = ofid >= nF
    gface = np.where(fromcell, ofid - nF, 0)
    tcell = np.where(fromcell, face_owner[np.searchsorted(fidx, gface)], -1)
    # connected components of the result: each lies in one cell
    e = np.concatenate([ot[:, [0, 1]], ot[:, [1, 2]]])
    g = coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(len(ov), len(ov)))
    ncomp, comp = connected_components(g, directed=False)
    tcomp = comp[ot[:, 0]]
    ccell = np.full(ncomp, batch[0] if len(batch) == 1 else -1, np.int64)
    ccell[tcomp[fromcell]] = tcell[fromcell]
    if (ccell[tcomp] < 0).any() or (ccell[tcomp[fromcell]] != tcell[fromcell]).any():
        return None
    tcell = ccell[tcomp]
    labels = np.where(fromcell, lab[gface], -1 - ofid)
    a, b, c = ov[ot[:, 0]], ov[ot[:, 1]], ov[ot[:, 2]]
    det = np.einsum("ij,ij->i", a, np.cross(b, c))
    order = np.argsort(tcell, kind="stable")
    cs = tcell[order]
    starts = np.flatnonzero(np.r_[True, cs[1:] != cs[:-1]])
    cells = cs[starts]
    ntri = np.diff(np.r_[starts, len(order)])
    v = np.add.reduceat(det[order], starts) / 6.0
    # the moments in units of the largest determinant (a power of two, exact: the same bits
    # as unscaled where that does not overflow; det times a coordinate overflowed at 2**300)
    e = int(np.frexp(np.abs(det).max())[1])
    ds = np.ldexp(det[order], -e)
    mom = np.add.reduceat(ds[:, None] * (a + b + c)[order], starts) / 24.0
    vs = np.add.reduceat(ds, starts) / 6.0
    # pieces: distinct components per cell (components are sorted by cell with it)
    pc = unique(cs * ncomp + tcomp[order]) // ncomp
    npc = np.diff(np.searchsorted(pc, np.r_[cells, cells[-1] + 1]))
    ok = v > 0.0
    with np.errstate(invalid="ignore", divide="ignore"):
        ce = mom / vs[:, None]
    tok = np.repeat(ok, ntri)
    sel = order[tok]
    return ov, cells[ok], ntri[ok], ot[sel], labels[sel], v[ok], ce[ok], npc[ok]


def cut_split(batch, args):
    """``_cut_batch``, halving the batch where a result cannot be told apart by cells."""
    got = _cut_batch(batch, *args)
    if got is not None:
        return got
    if len(batch) == 1:  # unreachable: a lone cell owns every component
        raise RuntimeError("manifold3d's result could not be assigned to the cell")
    h = len(batch) // 2
    return _merge([cut_split(batch[:h], args), cut_split(batch[h:], args)])


def _merge(got):
    """One result of ``_cut_batch`` from several, triangle indices shifted."""
    base = np.cumsum([0] + [len(r[0]) for r in got])
    ov = np.vstack([r[0] for r in got])
    ot = np.concatenate([r[3] + b for r, b in zip(got, base, strict=False)])
    return (
        ov,
        np.concatenate([r[1] for r in got]),
        np.concatenate([r[2] for r in got]),
        ot,
    ) + tuple(np.concatenate([r[k] for r in got]) for k in range(4, 8))


def ranks(lens):
    """``0 .. len - 1`` for each run length in ``lens``, concatenated."""
    total = int(lens.sum())
    return np.arange(total) - np.repeat(np.cumsum(lens) - lens, lens)
