"""``Diagram3D.describe``: counts and checks of a 3D diagram."""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import CONVEX3D_RTOL, CONVEX3D_ULPS, NJIT

EPS = float(np.finfo(np.float64).eps)


def _norm(a: np.ndarray) -> float:
    """``|a|``, computed on ``a`` scaled by a power of two.

    Its square neither overflows nor underflows; the same bits as ``np.linalg.norm(a)``
    wherever that does not.
    """
    big = float(np.abs(a).max())
    if big == 0.0 or not np.isfinite(big):
        return big
    e = int(np.frexp(big)[1])
    return float(np.ldexp(np.linalg.norm(np.ldexp(a, -e)), e))


def _perimeter(r: np.ndarray) -> float:
    """The perimeter of the ring of points ``r (k, 3)`` (scaled as :func:`_norm`)."""
    e = r - np.roll(r, 1, axis=0)
    big = float(np.abs(e).max())
    if big == 0.0 or not np.isfinite(big):
        return big
    k = int(np.frexp(big)[1])
    return float(np.ldexp(np.linalg.norm(np.ldexp(e, -k), axis=1).sum(), k))


def unmatched_on_faces(d) -> int:
    """Vertices of a face between two cells that the cell across does not reference.

    The count behind ``Diagram3D.unmatched_vertices`` on a torus and for power cells with
    empty ones: a vertex's owner sites there include images (whose cells are other sites'
    cells, holding the vertex as another record, shifted) and sites whose cells are empty
    (no faces, no vertices), which the cell builder's count of references against owners
    took as missing. Here each cell face toward a site in the same frame (no shift) names
    the owners that must reference each of its vertices: the cell across, which owns them
    whenever it shares a face of positive area (a vertex named differently by two cells is
    counted, as before).
    """
    cf, lab, _, roff, ring = d.cell_face_table()
    shifted = np.zeros(len(lab), np.bool_)
    if d.face_shifts is not None:
        shifted = np.ascontiguousarray((d.face_shifts != 0).any(axis=1))
    order = np.argsort(lab, kind="stable")
    return int(_unmatched(cf, lab, roff, ring, shifted, order, len(d.vertices)))


@njit(**NJIT)
def _unmatched(cf, lab, roff, ring, shifted, order, nv):
    """Count of the vertices of unshifted site faces missing from the cell across.

    ``order`` sorts the faces by label: cell ``t``'s vertices are stamped, then every face
    labelled ``t`` is checked against the stamps.
    """
    stamp = np.full(nv, -1, np.int64)
    bad = np.zeros(nv, np.bool_)
    owner = np.zeros(lab.shape[0], np.int64)  # the cell of each face
    for i in range(cf.shape[0] - 1):
        for f in range(cf[i], cf[i + 1]):
            owner[f] = i
    q = 0
    while q < order.shape[0]:
        t = lab[order[q]]
        e = q
        while e < order.shape[0] and lab[order[e]] == t:
            e += 1
        if t >= 0:
            for f in range(cf[t], cf[t + 1]):
                for r in range(roff[f], roff[f + 1]):
                    stamp[ring[r]] = t
            for k in range(q, e):
                f = order[k]
                if shifted[f] or owner[f] == t:
                    continue
                for r in range(roff[f], roff[f + 1]):
                    if stamp[ring[r]] != t:
                        bad[ring[r]] = True
        q = e
    return np.count_nonzero(bad)


def _pieces(ring, roff, f0, f1) -> int:
    """Connected pieces of the faces ``f0:f1`` (faces sharing a vertex are connected)."""
    parent: dict = {}

    def root(v):
        while parent.setdefault(v, v) != v:
            parent[v] = parent[parent[v]]
            v = parent[v]
        return v

    for f in range(f0, f1):
        r = ring[roff[f] : roff[f + 1]].tolist()
        a = root(r[0])
        for v in r[1:]:
            b = root(v)
            if a != b:
                parent[b] = a
    return len({root(v) for v in list(parent)})


def describe3d(d) -> dict:
    """V, E, F, C; the Euler check per cell; convexity; cells cut by a non-convex container.

    Returns a dict: ``vertices``, ``edges`` (unique undirected edges), ``faces`` (unique),
    ``cells`` (non-empty), ``euler_ok`` (every non-empty cell has ``V - E + F = 2``; one a
    mesh container cuts, an even ``V - E + F`` of at most 2 per connected piece: it may be
    split into pieces, and a piece may have handles),
    ``euler_failures`` (cell numbers), ``convex`` (every face's vertices on the inner side of
    every other face of its cell, to ``CONVEX3D_RTOL`` of the cell's size or
    ``CONVEX3D_ULPS`` ulps of its coordinates, whichever is coarser, plus the error that
    resolution makes in the face's normal (times the cell's size and the face's perimeter
    over its area); faces thinner than that are left out; cells a mesh container cuts are
    tested too, so a torus's cut cells make it ``False``: ``nonconvex_cells`` lists them),
    ``cut_cells`` (cells cut by a mesh container, else 0), ``unmatched_vertices``,
    ``volume`` and ``container_volume``.
    """
    cf, lab, farea, roff, ring = d.cell_face_table()
    n = len(d)
    fails = []
    nonconvex = []
    edges = set()
    for i in range(n):
        f0, f1 = cf[i], cf[i + 1]
        if f1 == f0:
            continue
        cell_edges = set()
        verts = set()
        for f in range(f0, f1):
            r = ring[roff[f] : roff[f + 1]]
            for a, b in zip(r, np.roll(r, -1), strict=False):
                e = (min(a, b), max(a, b))
                cell_edges.add(e)
                edges.add(e)
            verts.update(r.tolist())
        chi = len(verts) - len(cell_edges) + (f1 - f0)
        cut = d.container == "mesh" and d.cut_cells is not None and bool(d.cut_cells[i])
        if cut:
            # a cell the mesh cuts may be several closed pieces, each with handles (a piece
            # of a torus): every closed orientable surface has an even chi <= 2
            pieces = _pieces(ring, roff, f0, f1)
            if chi % 2 or chi > 2 * pieces:
                fails.append(i)
        elif chi != 2:
            fails.append(i)
        # convexity of cut cells too: a non-convex container's cut cells are not convex
        V = d.vertices[list(verts)]
        size = float(np.ptp(V, axis=0).max()) if len(V) else 0.0
        # the resolution: a fraction of the cell, or a few ulps of its coordinates where
        # those are coarser (a cell 4 wide at 7e13 has vertices an ulp, 0.0078, apart)
        res = max(CONVEX3D_RTOL * size, CONVEX3D_ULPS * EPS * float(np.abs(V).max(initial=0)))
        for f in range(f0, f1):
            a = farea[f]
            na = _norm(a)
            if na <= res * size:
                continue  # a face thinner than the resolution has no normal to test
            r = d.vertices[ring[roff[f] : roff[f + 1]]]
            p0 = r[0]
            # the normal of vertices each within res is good to res * perimeter / area (a
            # wall's sliver beside a nearly coplanar wall of a hull at UTM offsets: 1.1e-8
            # of area, its rounded normal put the cell's far vertices 4e-8 past it)
            tol = res * (1.0 + size * _perimeter(r) / na)
            if ((V - p0) @ (a / na)).max() > tol:
                nonconvex.append(i)
                break
    return {
        "vertices": len(d.vertices),
        "edges": len(edges),
        "faces": len(d.faces),
        "cells": int((np.diff(cf) > 0).sum()),
        "euler_ok": not fails,
        "euler_failures": fails,
        "convex": not nonconvex,
        "nonconvex_cells": nonconvex,
        "cut_cells": 0 if d.cut_cells is None else int(np.count_nonzero(d.cut_cells)),
        "unmatched_vertices": d.unmatched_vertices,
        "volume": float(np.sum(d.volumes)),
        "container_volume": d.container_volume,
    }
