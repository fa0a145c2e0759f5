"""Mesh containers: cells built in the mesh's (padded) bounding box, then cut by the mesh.

Only cells that can reach the surface are cut: a cell whose ball around its site (radius: its
farthest vertex) holds no point of any triangle is wholly inside or wholly outside, decided
by exact ray parity at its centroid (:mod:`kernels.inside3d`), and kept untouched (convex,
named vertices) or emptied. A cell that may reach the surface is intersected with the mesh by
manifold3d (double precision); its faces become the result's triangles, labelled with the
cell face they came from (a site or a box wall) or ``-1 - t`` for container triangle ``t``,
and its new vertices are its own (not shared with the neighbour across a cut face). Cells
that the container splits report their number of pieces.
"""

from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np

from .containers import box_template
from .csr import unique


@dataclass(frozen=True)
class MeshContainer:
    """A validated closed, consistently oriented triangle mesh (outward)."""

    vertices: np.ndarray
    faces: np.ndarray
    volume: float


def _edge_report(F: np.ndarray) -> str | None:
    """None for a closed 2-manifold with consistent orientation, else what is wrong."""
    e = np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
    key = np.sort(e, axis=1)
    uniq, inv, cnt = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    bad = uniq[cnt != 2]
    if len(bad):
        kinds = cnt[cnt != 2]
        show = ", ".join(f"({a}, {b}) x{k}" for (a, b), k in zip(bad[:5], kinds[:5], strict=True))
        what = "open" if (kinds == 1).any() else "non-manifold"
        return (
            f"the container mesh is {what}: {len(bad)} edges not shared by exactly two "
            f"faces ({show})"
        )
    d, dc = np.unique(e, axis=0, return_counts=True)
    if (dc > 1).any():
        a, b = d[dc > 1][0]
        return (
            "the container mesh is not consistently oriented "
            f"(edge ({a}, {b}) runs the same way twice)"
        )
    return None


def as_mesh_container(container):
    """``(MeshContainer, Template)`` from a trimesh, ``(vertices, faces)`` or a mesh file."""
    import trimesh

    if isinstance(container, (str, os.PathLike)):
        path = os.fspath(container)
        if not os.path.exists(path):
            raise ValueError(f"container file not found: {path}")
        try:
            mesh = trimesh.load(path, force="mesh")
        except Exception as exc:  # noqa: BLE001 - trimesh raises many kinds
            raise ValueError(f"could not read the container mesh {path}: {exc}") from None
        V, F = np.asarray(mesh.vertices, np.float64), np.asarray(mesh.faces, np.int64)
    elif isinstance(container, trimesh.Trimesh):
        V, F = np.array(container.vertices, np.float64), np.array(container.faces, np.int64)
    elif isinstance(container, (tuple, list)) and len(container) == 2:
        try:
            V = np.array(container[0], np.float64)
            F = np.array(container[1], np.int64)
        except (TypeError, ValueError) as exc:
            raise ValueError(
                f"a mesh container is (vertices (k, 3), faces (m, 3)) ({exc})"
            ) from None
    else:
        raise ValueError(
            "container must be None, (xmin, ymin, zmin, xmax, ymax, zmax), vf.Convex, a closed "
            "triangle mesh (trimesh, (vertices, faces)) or a mesh file; "
            f"got {type(container).__name__}"
        )
    if V.ndim != 2 or V.shape[1] != 3 or F.ndim != 2 or F.shape[1] != 3 or len(F) < 4:
        raise ValueError(
            "a mesh container needs vertices (k, 3) and faces (m >= 4, 3); "
            f"got {V.shape}, {F.shape}"
        )
    if not np.isfinite(V).all():
        raise ValueError("the container mesh has NaN or infinite vertices")
    if F.min() < 0 or F.max() >= len(V):
        raise ValueError("the container mesh's faces index vertices that do not exist")
    # merge exactly equal vertices (STL-style soups), drop unused ones
    V, inv = np.unique(V, axis=0, return_inverse=True)
    F = inv.reshape(-1)[F]
    if ((F[:, 0] == F[:, 1]) | (F[:, 1] == F[:, 2]) | (F[:, 2] == F[:, 0])).any():
        raise ValueError("the container mesh has degenerate triangles (a repeated vertex)")
    msg = _edge_report(F)
    if msg:
        raise ValueError(msg)
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    vol = float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)
    if vol == 0.0:
        raise ValueError("the container mesh encloses no volume")
    if vol < 0:  # inside out: turn it
        F = F[:, ::-1].copy()
        vol = -vol
    lo, hi = V.min(axis=0), V.max(axis=0)
    pad = 0.01 * float((hi - lo).max())
    t = box_template(lo - pad, hi + pad)
    t = type(t)(t.TV, t.TF, t.TR, t.WP, "mesh", vol, t.bounds)
    return MeshContainer(np.ascontiguousarray(V), np.ascontiguousarray(F), vol), t


def _manifold(V, F, face_id):
    import manifold3d as m3

    mesh = m3.Mesh64(
        vert_properties=np.ascontiguousarray(V, np.float64),
        tri_verts=np.ascontiguousarray(F, np.uint64),
        face_id=np.ascontiguousarray(face_id, np.uint64),
    )
    return m3.Manifold(mesh)


def _seg_dist(p, a, b):
    ab = b - a
    t = np.clip(((p - a) * ab).sum(1) / np.maximum((ab * ab).sum(1), 1e-300), 0.0, 1.0)
    return np.linalg.norm(p - (a + t[:, None] * ab), axis=1)


def _point_triangle_distance(p, tri):
    """Distance from point ``p (3,)`` to each triangle ``tri (m, 3, 3)``."""
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    n = np.cross(b - a, c - a)
    nn = np.maximum((n * n).sum(1), 1e-300)
    h = ((p - a) * n).sum(1) / nn
    q = p - h[:, None] * n  # projection onto the plane
    inside = np.ones(len(tri), bool)
    for u, v in ((a, b), (b, c), (c, a)):
        inside &= (np.cross(v - u, q - u) * n).sum(1) >= 0
    d = np.minimum(np.minimum(_seg_dist(p, a, b), _seg_dist(p, b, c)), _seg_dist(p, c, a))
    return np.where(inside, np.abs(h) * np.sqrt(nn), d)


def sites_inside(mesh: MeshContainer, pts: np.ndarray) -> np.ndarray:
    """``(n,) bool``: which points lie inside the mesh (exact ray parity)."""
    from ..kernels.inside3d import inside_mesh, yz_grid

    V, F = mesh.vertices, mesh.faces
    g, start, items = yz_grid(V, F, int(max(1, min(512, np.sqrt(len(F) / 4)))))
    return inside_mesh(np.ascontiguousarray(pts, np.float64), V, F, g, start, items)


def cut_by_mesh(d, mesh: MeshContainer, progress=None):
    """Cut a box diagram ``d`` (Diagram3D in the mesh's box) by ``mesh``; a new Diagram3D."""
    from scipy.spatial import cKDTree

    from ..kernels.inside3d import inside_mesh, yz_grid
    from .diagram3d import Diagram3D

    n = len(d)
    V, F = mesh.vertices, mesh.faces
    cf, lab, farea, roff, ring = d.cell_face_table()
    tri = V[F]
    cen_t = tri.mean(axis=1)
    rt = float(np.linalg.norm(tri - cen_t[:, None], axis=2).max())
    tree = cKDTree(cen_t)
    sites = np.asarray(d.sites)
    verts = np.asarray(d.vertices)
    live = np.diff(cf) > 0
    # reach of each cell from its site
    reach = np.zeros(n)
    owner_r = np.repeat(np.repeat(np.arange(n), np.diff(cf)), np.diff(roff))
    if len(ring):
        dist = np.linalg.norm(verts[ring] - sites[owner_r], axis=1)
        np.maximum.at(reach, owner_r, dist)
    # triangles whose centroid is within reach + rt, then their true distance to the site
    slack = 1e-9 * float(np.abs(V).max())
    cand = np.zeros(n, bool)
    idx = np.flatnonzero(live)
    lists = tree.query_ball_point(sites[idx], reach[idx] * (1 + 1e-9) + rt + slack)
    for i, lst in zip(idx, lists, strict=True):
        if lst:
            ts = np.asarray(lst)
            pd = _point_triangle_distance(sites[i], tri[ts])
            cand[i] = bool((pd <= reach[i] * (1 + 1e-9) + slack).any())
    g, start, items = yz_grid(V, F, int(max(1, min(512, np.sqrt(len(F) / 4)))))
    q = np.nan_to_num(np.asarray(d.centroids))
    ins = inside_mesh(np.ascontiguousarray(q), V, F, g, start, items)
    keep = live & ~cand & ins
    contM = _manifold(V, F, np.arange(len(F)))
    vol = np.where(keep, d.volumes, 0.0)
    cen = np.where(keep[:, None], d.centroids, np.nan)
    pieces = np.where(keep, 1, 0).astype(np.int64)
    cut = np.zeros(n, bool)
    # new per-cell face table
    new_lab, new_rings, counts = [], [], np.zeros(n, np.int64)
    extra_v = [verts]
    nvert = len(verts)
    todo = np.flatnonzero(cand)
    for k, i in enumerate(range(n)):
        f0, f1 = cf[i], cf[i + 1]
        if keep[i]:
            for f in range(f0, f1):
                new_rings.append(ring[roff[f] : roff[f + 1]])
            new_lab.append(lab[f0:f1])
            counts[i] = f1 - f0
            continue
        if not cand[i]:
            continue
        rings = [ring[roff[f] : roff[f + 1]] for f in range(f0, f1)]
        ids = unique(np.concatenate(rings))
        loc = np.searchsorted(ids, np.concatenate(rings))
        tris, fid = [], []
        pos = 0
        for fi, r in enumerate(rings):
            lr = loc[pos : pos + len(r)]
            pos += len(r)
            for t in range(1, len(r) - 1):
                tris.append((lr[0], lr[t], lr[t + 1]))
                fid.append(fi)
        cellM = _manifold(verts[ids], np.array(tris), np.array(fid) + len(F))
        res = cellM ^ contM
        v = res.volume()
        if v <= 0.0:
            continue
        out = res.to_mesh64()
        ov = np.asarray(out.vert_properties)[:, :3]
        ot = np.asarray(out.tri_verts, np.int64)
        ofid = np.asarray(out.face_id, np.int64)
        # face ids: container triangle t is t, cell face f is len(F) + f
        fromcell = ofid >= len(F)
        labels = np.where(fromcell, lab[f0 + np.where(fromcell, ofid - len(F), 0)], -1 - ofid)
        a, b, c = ov[ot[:, 0]], ov[ot[:, 1]], ov[ot[:, 2]]
        det = np.einsum("ij,ij->i", a, np.cross(b, c))
        cut[i] = True
        vol[i] = det.sum() / 6.0
        cen[i] = (det[:, None] * (a + b + c)).sum(axis=0) / 24.0 / vol[i]
        pieces[i] = len(res.decompose())
        for t in ot:
            new_rings.append(t + nvert)
        new_lab.append(labels)
        counts[i] = len(ot)
        extra_v.append(ov)
        nvert += len(ov)
        if progress is not None and k % 256 == 0:
            progress(int(np.searchsorted(todo, i)), len(todo))
    cell_faces = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    lens = np.array([len(r) for r in new_rings], np.int64)
    roff2 = np.concatenate([[0], np.cumsum(lens)]).astype(np.int64)
    ring2 = np.concatenate(new_rings).astype(np.int64) if new_rings else np.zeros(0, np.int64)
    lab2 = np.concatenate(new_lab).astype(np.int64) if new_lab else np.zeros(0, np.int64)
    allv = np.vstack(extra_v)
    used = np.zeros(len(allv), bool)
    used[ring2] = True
    remap = np.cumsum(used) - 1
    return Diagram3D(
        sites=d.sites,
        weights=d.weights,
        periodic=False,
        container="mesh",
        walls=np.zeros((0, 4)),
        volumes=vol,
        centroids=cen,
        vertices=allv[used],
        cell_faces=cell_faces,
        flabel=lab2,
        roff=roff2,
        ring=remap[ring2],
        duplicate_of=d.duplicate_of,
        unmatched=d.unmatched_vertices,
        box=d.box,
        pieces=pieces,
        cut_cells=cut,
        container_volume=mesh.volume,
    )
