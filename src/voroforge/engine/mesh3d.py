"""Mesh containers: cells built in the mesh's (padded) bounding box, then cut by the mesh.

Only the cells that can reach the mesh are built (:func:`reaching_sites`: sites inside, and
sites outside that are not provably farther from every container triangle than another
site). Only cells that the surface meets are cut: a cell that no triangle meets (each
triangle clipped by the cell's face planes moved out by a 1e-9 slack,
:mod:`kernels.meshclip3d`) is wholly inside or wholly outside, decided by exact ray parity
at its centroid (:mod:`kernels.inside3d`), and kept untouched (convex, named vertices) or
emptied. A cell the surface meets only where it is convex from the cell's side is cut by
the triangles' planes (:func:`kernels.meshcut3d.convex_cells`, checked there). The other
cells are intersected with the mesh by manifold3d (double precision) in a few batches of
cells that share no vertex (a greedy colouring), one boolean per batch: each boolean costs
about the batch's size, so cutting cells one at a time would pay the overhead per cell.
The result's triangles are labelled with the cell face they came from (a site or a box
wall) or ``-1 - t`` for container triangle ``t``; its connected components tell the cells
apart (a component without a cell face, a closed part of the container inside a cell, makes
the batch split in halves). A cut cell's new vertices are its own (not shared with the
neighbour across a cut face). Cells that the container splits report their number of pieces.
The cut works relative to an origin whose subtraction is exact (:func:`_exact_origin`).
"""

from __future__ import annotations

import itertools
import os
from dataclasses import dataclass

import numpy as np

from ..config import (
    MANIFOLD_SAFE,
    MESH_COORD_RTOL,
    VORONOI3D_MESH_FACING,
    VORONOI3D_MESH_SLACK_RTOL,
    VORONOI3D_MESH_VOLUME_RTOL,
)
from .containers import box_template, far_origin
from .meshbool3d import cut_split, manifold_of, ranks
from .meshcheck3d import crossing_report, nesting_report
from .readonly import readonly


@dataclass(frozen=True)
class MeshContainer:
    """A validated closed, consistently oriented triangle mesh (outward)."""

    vertices: np.ndarray
    faces: np.ndarray
    volume: float


def _edge_report(F: np.ndarray, V: np.ndarray) -> str | None:
    """None for a closed 2-manifold with consistent orientation, else what is wrong."""
    e = np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
    nv = int(F.max()) + 1  # edges as one integer each (a 1-D unique: ~5x faster than rows)
    lo, hi = e.min(axis=1), e.max(axis=1)
    uniq, cnt = np.unique(lo * nv + hi, return_counts=True)
    if (cnt != 2).any():
        kinds = cnt[cnt != 2]
        bad = uniq[cnt != 2]
        show = ", ".join(
            f"({a}, {b}) x{k}"
            for a, b, k in zip(bad[:5] // nv, bad[:5] % nv, kinds[:5], strict=True)
        )
        what = "open" if (kinds == 1).any() else "non-manifold"
        # even counts, each edge run both ways alike: closed shells that share an edge or a
        # face's vertices (two boxes side by side); shells that only touch without sharing
        # vertices are cut as their union
        touch = (kinds % 2 == 0).all()
        a, b = (", ".join(f"{x:.17g}" for x in V[k]) for k in (bad[0] // nv, bad[0] % nv))
        return (
            f"the container mesh is {what}: {len(bad)} edges not shared by exactly two "
            f"faces ({show}; the first from ({a}) to ({b}))"
            + (
                "; closed shells that touch along an edge or a face with shared vertices, "
                "or one solid pinched along an edge (its surface meets itself there; "
                "vertices at equal positions are merged), are not a surface bounding a "
                "solid: union them (e.g. with manifold3d) or thicken the pinch"
                if touch
                else ""
            )
        )
    d, dc = np.unique(e[:, 0] * nv + e[:, 1], return_counts=True)
    if (dc > 1).any():
        k = int(d[dc > 1][0])
        return (
            "the container mesh is not consistently oriented "
            f"(edge ({k // nv}, {k % nv}) runs the same way twice)"
        )
    return None


def _read_mesh_file(path: str):
    """The mesh in ``path``: the project's reader for 3MF and ``.3dm``, trimesh for the rest.

    :func:`voroforge.io.mesh.read` reads 3MF without lxml (``trimesh.load`` needed it) and
    ``.3dm`` through rhino3dm (``trimesh.load`` cannot); every other suffix (STL, OBJ, PLY,
    GLB, OFF ...) loads through ``trimesh.load`` as before (the same vertices and faces as
    ``read`` for the formats both know, and an empty file still reads as no triangles).
    """
    import trimesh

    if os.path.splitext(path)[1].lower() in (".3mf", ".3dm"):
        from ..io.mesh import read

        return read(path)
    # unprocessed: trimesh's processing drops faces of NaN vertices (the file was then called
    # "open") and merges vertices within 1e-8; exactly equal ones are merged below
    return trimesh.load(path, force="mesh", process=False)


def as_mesh_container(container):
    """``(MeshContainer, Template)`` from a trimesh, ``(vertices, faces)`` or a mesh file."""
    import trimesh

    if isinstance(container, (str, os.PathLike)):
        path = os.fspath(container)
        if not os.path.exists(path):
            raise ValueError(f"container file not found: {path}")
        try:
            mesh = _read_mesh_file(path)
        except Exception as exc:  # noqa: BLE001 - the readers raise many kinds
            raise ValueError(f"could not read the container mesh {path}: {exc}") from None
        V, F = np.asarray(mesh.vertices, np.float64), np.asarray(mesh.faces, np.int64)
        if F.ndim != 2 or len(F) < 4:  # an empty or garbage file reads as no triangles
            raise ValueError(
                f"the container mesh file {path} holds {len(F)} triangles (a closed mesh "
                "needs at least 4): empty, or not a mesh file trimesh can read"
            )
    elif isinstance(container, trimesh.Trimesh):
        V, F = np.array(container.vertices, np.float64), np.array(container.faces, np.int64)
    elif isinstance(container, (tuple, list)) and len(container) == 2:
        try:
            V = np.array(container[0], np.float64)
            raw = np.asarray(container[1])
            F = np.array(raw, np.int64)
        except (TypeError, ValueError) as exc:
            raise ValueError(
                f"a mesh container is (vertices (k, 3), faces (m, 3)) ({exc})"
            ) from None
        if raw.dtype.kind not in "iu" and (raw.dtype.kind != "f" or (F != raw).any()):
            raise ValueError(
                f"the container mesh's faces must be integer vertex indices; got {raw.dtype} "
                "values that are not whole numbers"
                if raw.dtype.kind == "f"
                else f"the container mesh's faces must be integer vertex indices; got {raw.dtype}"
            )
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
    msg = _edge_report(F, V)
    if msg:
        raise ValueError(msg)
    # signed volume about the mesh's centre: about the origin it cancels far out (a torus of
    # volume 2.98 at (5e5, 4e6, 100) measured 2.87)
    centre = 0.5 * (V.min(axis=0) + V.max(axis=0))
    if far_origin(V.min(axis=0), V.max(axis=0)) is not None:
        # far out: about an origin whose differences are exact, per axis (far_origin's
        # steps follow the largest extent: a rod 1e3 thick 1e9 long at 1e15 had y and z
        # differences up to ~5e8 there, and its volume came out 1.4e-5 short)
        centre = _exact_origin(V)
    a, b, c = (V[F[:, k]] - centre for k in range(3))
    with np.errstate(over="ignore", invalid="ignore"):  # past the range: inf, refused below
        vol = float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)
    if vol == 0.0:
        raise ValueError("the container mesh encloses no volume")
    if vol < 0:  # inside out: turn it
        F = F[:, ::-1].copy()
        vol = -vol
    msg = crossing_report(V, F) or nesting_report(V, F)
    if msg:
        raise ValueError(msg)
    lo, hi = V.min(axis=0), V.max(axis=0)
    pad = 0.01 * float((hi - lo).max())
    t = box_template(lo - pad, hi + pad)
    t = type(t)(t.TV, t.TF, t.TR, t.WP, "mesh", vol, t.bounds)
    return MeshContainer(np.ascontiguousarray(V), np.ascontiguousarray(F), vol), t


def sites_inside(mesh: MeshContainer, pts: np.ndarray) -> np.ndarray:
    """``(n,) bool``: which points lie in the closed solid (exact ray parity, or on a triangle).

    A point on the surface (exactly, :func:`kernels.inside3d.on_mesh`) counts as inside and
    gets its cell, as a site on a box's wall does.
    """
    from ..kernels.inside3d import inside_mesh, on_mesh, yz_grid
    from .threads import serial_below

    V, F = mesh.vertices, mesh.faces
    g, start, items = yz_grid(V, F, int(max(1, min(512, np.sqrt(len(F) / 4)))))
    q = np.ascontiguousarray(pts, np.float64)
    if not q.flags.writeable:  # (a frozen Diagram3D's sites): numba types the flag, so a
        q = q.copy()  # read-only array compiled inside_mesh a second time
    with serial_below(len(pts)):
        out = inside_mesh(q, V, F, g, start, items)
    rest = np.flatnonzero(~out)
    if len(rest):  # on the surface: the triangles of each point's 3D bucket
        _, lo, h, dims, start, items = _tri_buckets(V[F], 0.0)
        with serial_below(len(rest)):
            out[rest] = on_mesh(np.ascontiguousarray(q[rest]), V, F, lo, h, dims, start, items)
    return out


#: :func:`reaching_sites` splits a triangle in four while its size (largest distance of a
#: corner from its centroid) exceeds this many times the distance of its centroid to the
#: nearest site (large flat triangles otherwise keep every site near them), up to
#: ``REACH_SPLIT_CAP`` triangles per container triangle and site
REACH_SPLIT_RATIO = 4.0
REACH_SPLIT_CAP = 4


def reaching_sites(mesh: MeshContainer, pts: np.ndarray, inside: np.ndarray) -> np.ndarray:
    """``(n,) bool``: sites whose Voronoi cells may meet the mesh; every other cell is empty.

    A site inside keeps its cell. A site ``p`` outside lies in its own (convex, unclipped)
    Voronoi cell, so the cell meets the closed solid only if it meets the surface. For each
    triangle ``T`` of the surface take the site ``q`` nearest its centroid: where every
    corner ``v`` of ``T`` is strictly nearer ``q`` than ``p``, so is all of ``T`` (the
    half-space nearer ``q`` is convex) and ``p``'s cell misses ``T``. So ``p`` is kept when
    some corner has ``|v - p| <= |v - q|``: per vertex, a ball of radius the largest
    ``|v - q|`` over its triangles, grown by ``VORONOI3D_MESH_SLACK_RTOL`` of the largest
    coordinate (far above the rounding of the distances); one ball query. Triangles much
    larger than their distance to the sites are split first (``REACH_SPLIT_RATIO``; they
    still cover the surface). Conservative: it keeps cells that miss the surface (10,287 of
    the 52,544 outside sites on the bench's torus, where 6,135 reach inside), never drops
    one that meets it. Unweighted cells only (a power cell need not hold its site).
    """
    from scipy.spatial import cKDTree

    out = np.asarray(inside, bool).copy()
    far = np.flatnonzero(~out)
    if not len(far):
        return out
    tree = cKDTree(pts)
    V, F = mesh.vertices, mesh.faces
    room = REACH_SPLIT_CAP * (len(F) + len(pts))
    leaves, lq = [], []
    while len(F):
        T = V[F]
        c = T.mean(axis=1)
        dist, q = tree.query(c)
        size = np.sqrt(((T - c[:, None, :]) ** 2).sum(axis=2)).max(axis=1)
        split = size > REACH_SPLIT_RATIO * dist
        room -= len(F)
        if 4 * np.count_nonzero(split) > room:
            split[:] = False
        leaves.append(F[~split])
        lq.append(q[~split])
        V, F = _split4(V, F[split])
    F = np.concatenate(leaves)
    q = np.concatenate(lq)
    r = np.sqrt(((V[F] - pts[q][:, None, :]) ** 2).sum(axis=2))  # (m, 3): |v - q| per corner
    R = np.full(len(V), -1.0)
    np.maximum.at(R, F.reshape(-1), r.reshape(-1))
    at = np.flatnonzero(R >= 0)
    scale = max(float(np.abs(V).max()), float(np.abs(pts[far]).max()))
    R = R[at] * (1.0 + 1e-12) + VORONOI3D_MESH_SLACK_RTOL * scale
    # which far sites some ball holds (a set: the tree's shape does not matter, and an
    # unbalanced one builds faster); its lists flattened in one pass (~5x faster than
    # concatenating an array per list)
    tree = cKDTree(pts[far], balanced_tree=False)
    near = tree.query_ball_point(V[at], R, return_sorted=False)
    hit = np.fromiter(itertools.chain.from_iterable(near), np.int64)
    out[far[hit]] = True
    return out


def _split4(V, F):
    """Triangles ``F`` each split in four at their edges' midpoints (shared between them)."""
    if not len(F):
        return V, F
    a, b, c = F[:, 0], F[:, 1], F[:, 2]
    e = np.sort(np.concatenate([np.stack([a, b], 1), np.stack([b, c], 1), np.stack([c, a], 1)]), 1)
    u, inv = np.unique(e, axis=0, return_inverse=True)
    m = len(V) + np.arange(len(u))
    ab, bc, ca = m[inv.reshape(3, -1)]
    V = np.vstack([V, 0.5 * (V[u[:, 0]] + V[u[:, 1]])])
    F = np.concatenate(
        [np.stack(t, 1) for t in ((a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca))]
    )
    return V, F


def _tri_buckets(tri, tol):
    """Triangles ``tri (m, 3, 3)`` on a bucket grid: ``(T, lo, h, dims, start, items)``."""
    from ..kernels.meshclip3d import tri_grid

    lo = tri.min(axis=(0, 1)) - tol
    hi = tri.max(axis=(0, 1)) + tol
    # buckets about the size of a triangle's box, at most ~8 per triangle
    ext = (tri.max(axis=1) - tri.min(axis=1)).max(axis=1)
    h = max(float(np.median(ext)), float((np.prod(hi - lo) / (8.0 * len(tri))) ** (1 / 3)))
    dims = np.maximum(1, np.ceil((hi - lo) / h)).astype(np.int64)
    T = np.ascontiguousarray(tri, np.float64)
    start, items = tri_grid(T, lo, h, dims)
    return T, lo, h, dims, start, items


def _touching(cf, roff, ring, verts, farea, live, tri, tol, grid=None, fpt=None):
    """``(n,) bool``: cells that some triangle of ``tri`` meets (each grown by ``tol``).

    ``fpt``: a point of each face (:func:`_face_points`), computed here if not given.
    """
    from ..kernels.meshclip3d import touching_cells
    from .threads import serial_below

    T, lo, h, dims, start, items = _tri_buckets(tri, tol) if grid is None else grid
    if fpt is None:
        fpt = _face_points(roff, ring, verts, len(cf) - 1)
    # the cells in space order (by buckets of twice the triangles' grid, at a vertex of
    # each): the input's order reads the vertices at random (bench: 0.30-0.42 -> 0.17-0.29
    # s on one thread)
    cells = np.flatnonzero(live)
    if len(cells):
        at = verts[ring[roff[cf[cells]]]]
        key = np.zeros(len(cells), np.int64)
        for c in range(3):
            g = np.floor((at[:, c] - lo[c]) / (2.0 * h)).astype(np.int64)
            g -= g.min()
            key = key * (int(g.max()) + 1) + g
        cells = cells[np.argsort(key, kind="stable")]
    with serial_below(len(cells)):
        return touching_cells(
            cf,
            roff,
            ring,
            verts,
            np.ascontiguousarray(farea),
            fpt,
            cells,
            T,
            lo,
            h,
            dims,
            start,
            items,
            tol,
        )


def _face_points(roff, ring, verts, n):
    """``(f, 3)``: each face's first vertex (the face table of ``n`` cells)."""
    from ..kernels.meshclip3d import face_points
    from .threads import serial_below

    with serial_below(n):
        return face_points(roff, ring, np.ascontiguousarray(verts, np.float64))


def _convex_part(todo, cf, lab, farea, roff, ring, verts, grid, tol, fpt):
    """The cells of ``todo`` that :func:`kernels.meshcut3d.convex_cells` cuts itself.

    ``(part, volumes, centroids, pieces)`` for those cells (a part as :func:`cut_by_mesh` collects
    them: vertices, cells, faces per cell, flat rings into the vertices, ring lengths,
    labels), or None when it cut none. ``fpt``: a point of each face (:func:`_face_points`
    of ``verts``).
    """
    import numba

    from ..kernels import meshcut3d as mc

    T, lo, h, dims, start, items = grid
    k = len(todo)
    if not k:
        return None
    tn, ok = unit_normals(T[:, 1] - T[:, 0], T[:, 2] - T[:, 0])
    with np.errstate(invalid="ignore"):  # a needle: no plane, NaN offset
        to = np.where(ok, np.einsum("ij,ij->i", tn, T[:, 0]), np.nan)
    oV = np.zeros((k * mc.CC_OUT_V, 3))
    oF = np.zeros((k * mc.CC_OUT_F, 2), np.int64)
    oR = np.zeros(k * mc.CC_OUT_R, np.int64)
    counts = np.zeros((k, 3), np.int64)
    vol = np.zeros(k)
    cen = np.zeros((k, 3))
    npc = np.zeros(k, np.int64)
    lab = np.asarray(lab, np.int64)
    farea = np.ascontiguousarray(farea)
    cells = np.asarray(todo, np.int64)

    def part(a, b):  # the kernel releases the GIL: threads take slices of the cells
        mc.convex_cells(
            cells[a:b],
            cf,
            roff,
            ring,
            verts,
            lab,
            farea,
            fpt,
            T,
            tn,
            to,
            lo,
            h,
            dims,
            start,
            items,
            tol,
            oV[a * mc.CC_OUT_V : b * mc.CC_OUT_V],
            oF[a * mc.CC_OUT_F : b * mc.CC_OUT_F],
            oR[a * mc.CC_OUT_R : b * mc.CC_OUT_R],
            counts[a:b],
            vol[a:b],
            cen[a:b],
            npc[a:b],
        )

    nth = max(1, min(numba.get_num_threads(), k // 256))  # ~40 us a cell: threads from 256
    bounds = np.array([0, k])
    if nth == 1:
        part(0, k)
    else:  # 8 slices a thread, taken as threads come free (a loaded machine)
        from concurrent.futures import ThreadPoolExecutor

        bounds = np.linspace(0, k, 8 * nth + 1).astype(int)
        with ThreadPoolExecutor(nth) as pool:
            list(pool.map(part, bounds[:-1], bounds[1:]))
    ok = np.flatnonzero(counts[:, 0] > 0)
    if not len(ok):
        return None
    # each slice's cells wrote their rows one after another from the slice's start
    used = np.add.reduceat(counts, bounds[:-1], axis=0)  # slices are not empty
    runs = [
        (a * mc.CC_OUT_V, a * mc.CC_OUT_F, a * mc.CC_OUT_R, u)
        for a, u in zip(bounds[:-1], used, strict=True)
    ]
    pv = np.concatenate([oV[v : v + u[0]] for v, _, _, u in runs])
    pf = np.concatenate([oF[f : f + u[1]] for _, f, _, u in runs])
    pr = np.concatenate([oR[r : r + u[2]] for _, _, r, u in runs])
    nv, nf, nr = counts[ok, 0], counts[ok, 1], counts[ok, 2]
    vbase = np.repeat(np.cumsum(nv) - nv, nr)  # each cell's first row in the vertices
    part = (pv, todo[ok], nf, pr + vbase, pf[:, 1], pf[:, 0])
    return part, vol[ok], cen[ok], npc[ok]


def cut_by_mesh(d, mesh: MeshContainer, progress=None, short=None):
    """Cut a box diagram ``d`` (Diagram3D in the mesh's box) by ``mesh``; a new Diagram3D.

    ``d`` may hold only the cells that can reach the mesh (:func:`reaching_sites`; the
    others have no faces). ``short``: ``(V,) bool`` over ``d.vertices``, the vertices its
    build found fewer cells at than they have owners (``Cells3D.short``); the result's
    ``unmatched_vertices`` counts those its untouched cells keep (without it, ``d``'s count).
    """
    from ..kernels.inside3d import inside_mesh, yz_grid
    from ..kernels.meshclip3d import map_runs, mark_runs
    from .diagram3d import Diagram3D
    from .meshplanes3d import cut_planes, local_vertices, plane_rows
    from .threads import serial_below

    n = len(d)
    V, F = mesh.vertices, mesh.faces
    cf, lab, farea, roff, ring = d.cell_face_table()
    verts = np.asarray(d.vertices)
    # slivers' area vectors are rounding: their planes from the sites (meshplanes3d)
    # each row scaled by a power of two (exact): the kernels square these normals
    farea = cut_planes(farea, cf, lab, roff, ring, verts, np.asarray(d.sites))
    nface = np.diff(cf)
    live = nface > 0
    # the cut works relative to an origin that the subtraction moves exactly (Sterbenz):
    # far from the origin (UTM-like), manifold3d in absolute coordinates lost up to a
    # quarter of the volume
    # A mesh far from its size (containers.far_origin) is cut about that origin, with the
    # cut cells' vertices and face planes recomputed about it (meshplanes3d.local_vertices):
    # in absolute doubles a 1e-3 cube at 4e6 summed 2.2e-8 off its volume
    fo = far_origin(V.min(axis=0), V.max(axis=0))
    o = _exact_origin(V, verts) if fo is None else fo
    Vl, vl = V - o, verts - o
    big = MESH_COORD_RTOL * float(np.abs(V).max())  # the rounding of coordinates, with room
    slack = VORONOI3D_MESH_SLACK_RTOL * float(np.abs(Vl).max()) + big
    grid = _tri_buckets(Vl[F], slack)
    fpt = _face_points(roff, ring, vl, n)
    cand = _touching(cf, roff, ring, vl, farea, live, Vl[F], slack, grid, fpt)
    if fo is not None and cand.any():
        c = np.flatnonzero(cand)
        vl = local_vertices(c, cf, lab, roff, ring, verts, d.sites, d.weights, d.box, o)
        nf = cf[c + 1] - cf[c]
        f = np.repeat(cf[c], nf) + ranks(nf)
        farea = plane_rows(farea.copy(), f, cf, lab, np.asarray(d.sites))
        fpt = _face_points(roff, ring, vl, n)  # of the recomputed vertices
    g, start, items = yz_grid(V, F, int(max(1, min(512, np.sqrt(len(F) / 4)))))
    test = np.flatnonzero(live & ~cand)  # the others: no parity needed
    ins = np.zeros(n, bool)
    q = np.ascontiguousarray(np.asarray(d.centroids)[test])
    with serial_below(len(test)):
        ins[test] = inside_mesh(q, V, F, g, start, items)
    keep = live & ~cand & ins
    vol = np.where(keep, d.volumes, 0.0)
    cen = np.where(keep[:, None], d.centroids, np.nan)
    pieces = np.where(keep, 1, 0).astype(np.int64)
    cut = np.zeros(n, bool)
    counts = np.where(keep, nface, 0).astype(np.int64)
    nvert = len(verts)
    todo = np.flatnonzero(cand)
    # (vertices, cells, faces per cell, flat rings (global vertex numbers), ring lengths,
    # labels) per part: the cells cut here, then manifold3d's batches
    parts = []
    # its decisions (coplanar, inside a half-space) within 1e-9 of the mesh's least extent
    # (its largest gave a rod 1e-7 thick 1% of its thickness), above the rounding of the
    # coordinates (``big``). The bench torus: the same cells, bit for bit
    ext = float((V.max(axis=0) - V.min(axis=0)).min())
    if fo is not None:  # the cut cells' coordinates about o carry the rounding of those
        big = MESH_COORD_RTOL * float(np.abs(Vl).max())
    tol = VORONOI3D_MESH_SLACK_RTOL * ext + big
    got = _convex_part(todo, cf, lab, farea, roff, ring, vl, grid, tol, fpt)
    if got is not None:
        part, v, ce, npc = got
        cells = part[1]
        cut[cells] = True
        vol[cells], cen[cells], pieces[cells], counts[cells] = v, ce + o, npc, part[2]
        parts.append((part[0] + o,) + part[1:3] + (part[3] + nvert,) + part[4:])
        nvert += len(part[0])
        todo = np.setdiff1d(todo, cells, assume_unique=True)
    done = 0
    # manifold3d sees coordinates scaled by a power of two near 1 when they lie past
    # 2**200 or below 2**-200 (exact; at 2**260 and 2**-260 a torus's cut cells came back
    # short: "not a valid solid"); nearer 1 it sees them as they are
    ms = 0
    top = float(np.abs(Vl).max())
    if top > MANIFOLD_SAFE or top < 1.0 / MANIFOLD_SAFE:
        ms = int(np.frexp(top)[1])
    Vm, vm = (Vl, vl) if ms == 0 else (np.ldexp(Vl, -ms), np.ldexp(vl, -ms))
    for batch in _apart(todo, cf, roff, ring, len(verts)):
        if done == 0:  # the container for manifold3d, only when some cell needs it
            whole = manifold_of(Vm, F, np.arange(len(F)))
        r = cut_split(batch, (cf, roff, ring, vm, lab, len(F), whole, np.ldexp(tol, -ms)))
        ov, cells, ntri, ot, labels, v, ce, npc = r
        if ms:
            ov, v, ce = np.ldexp(ov, ms), np.ldexp(v, 3 * ms), np.ldexp(ce, ms)
        cut[cells] = True
        vol[cells], cen[cells], pieces[cells], counts[cells] = v, ce + o, npc, ntri
        parts.append((ov + o, cells, ntri, ot.reshape(-1) + nvert, np.full(len(ot), 3), labels))
        nvert += len(ov)
        done += len(batch)
        if progress is not None:
            progress(done, len(todo))
    # the new face table, in cell order: kept cells' faces as they were, cut cells' faces
    cell_faces = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    lens = np.zeros(int(cell_faces[-1]), np.int64)
    lab2 = np.zeros(len(lens), np.int64)
    kept = np.flatnonzero(np.repeat(keep, nface))  # old faces kept, in cell order
    kown = np.repeat(np.arange(n), nface)[kept]
    dest = cell_faces[kown] + (kept - cf[kown])
    klen = np.diff(roff)[kept]
    lens[dest] = klen
    lab2[dest] = lab[kept]
    if parts:  # cut cells: their faces, in the order their part lists them
        cells = np.concatenate([p[1] for p in parts])
        nfc = np.concatenate([p[2] for p in parts])
        tdest = np.repeat(cell_faces[cells], nfc) + ranks(nfc)
        flens = np.concatenate([p[4] for p in parts])
        lens[tdest] = flens
        lab2[tdest] = np.concatenate([p[5] for p in parts])
    roff2 = np.concatenate([[0], np.cumsum(lens)]).astype(np.int64)
    # the vertices in use (the kept cells' and the cut cells' new ones), renumbered in
    # order, and the rings written once with the new numbers: each kept cell's rings one
    # block (two passes over the 4.5M ring entries of the bench's 100,000 cells, not five)
    kc = np.flatnonzero(keep)
    s0, s1 = roff[cf[kc]], roff[cf[kc + 1]]
    nv0 = len(verts)
    used = np.zeros(nvert, bool)
    mark_runs(ring, s0, s1, used)
    pring = np.concatenate([p[3] for p in parts]) if parts else np.zeros(0, np.int64)
    used[pring] = True
    if nvert <= np.iinfo(ring.dtype).max:
        # the cut cells' rings in the table's type and flag (a frozen int32 table from the
        # box cells): map_runs compiled once for both calls, not for int64 too
        pring = readonly(pring, ring.dtype)
    remap = np.cumsum(used) - 1
    ring2 = np.zeros(int(roff2[-1]), np.int64)
    map_runs(ring, s0, s1, ring2, roff2[cell_faces[kc]], remap)
    if parts:  # each cut cell's rings: one block of pring, one block of ring2
        fs = np.concatenate([[0], np.cumsum(nfc)])
        rs = np.concatenate([[0], np.cumsum(flens)])
        map_runs(pring, rs[fs[:-1]], rs[fs[1:]], ring2, roff2[cell_faces[cells]], remap)
    newv = np.vstack(
        [verts[used[:nv0]]] + [p[0][used[b : b + len(p[0])]] for p, b in _bases(parts, nv0)]
    )
    if parts:  # cut cells' triangles facing an emptied cell: walls the boolean mislabelled
        tl = lab2[tdest]
        nb = np.maximum(tl, 0)
        odd = (tl >= 0) & ~keep[nb] & ~cut[nb]
        if odd.any():
            _coplanar_walls(mesh, newv, ring2, roff2, tdest[odd], lab2, slack)
    total = float(np.sum(vol))
    if abs(total - mesh.volume) > VORONOI3D_MESH_VOLUME_RTOL * mesh.volume:
        # A closed, consistently oriented mesh whose shells overlap or nest the same way
        # (two boxes as one mesh, a cavity facing outwards) passes the edge checks, but its
        # signed volume counts the overlap twice while the cut sees it once.
        raise ValueError(
            "the container mesh is not a valid solid: its cells fill "
            f"{total:.9g} but its signed volume is {mesh.volume:.9g} (shells that overlap "
            "or intersect, or an inner shell facing outwards; union them, e.g. with "
            "manifold3d, and face cavities inwards)"
        )
    unmatched = d.unmatched_vertices
    if short is not None:  # of the vertices kept as they were (the untouched cells')
        unmatched = int(np.count_nonzero(short & used[:nv0]))
    return Diagram3D(
        sites=d.sites,
        weights=d.weights,
        periodic=False,
        container="mesh",
        walls=np.zeros((0, 4)),
        volumes=vol,
        centroids=cen,
        vertices=newv,
        cell_faces=cell_faces,
        flabel=lab2,
        roff=roff2,
        ring=ring2,
        duplicate_of=d.duplicate_of,
        unmatched=unmatched,
        box=d.box,
        pieces=pieces,
        cut_cells=cut,
        container_volume=mesh.volume,
        frame=_vertex_frame(newv),
    )


def _bases(parts, nv0):
    """``(part, its first vertex number)`` for each part, numbered after ``nv0`` vertices."""
    b = nv0
    for p in parts:
        yield p, b
        b += len(p[0])


def _vertex_frame(V):
    """:class:`Diagram3D`'s working-frame exponent of its vertices ``V`` (the same rule).

    Taken per column: numpy's axis-0 reduction of an ``(n, 3)`` array is many times slower.
    """
    from .inputs import working_frame

    if not len(V):
        return 0
    return working_frame(np.array([[np.abs(V[:, c]).max() for c in range(3)]]))[1]


def _exact_origin(*arrays):
    """``(3,)``: per axis, a value whose subtraction from every coordinate is exact.

    The least coordinate where all lie in ``[a, 2a]`` (``a > 0``), the greatest where all
    lie in ``[2b, b]`` (``b < 0``), else 0 (Sterbenz: ``x - y`` is exact for ``y / 2 <= x
    <= 2 y``).
    """
    # per column: numpy's axis-0 reduction of an (n, 3) array is ~20x slower (412k
    # vertices: 12-27 ms against 1 ms)
    lo = np.array([min(a[:, c].min() for a in arrays) for c in range(3)])
    hi = np.array([max(a[:, c].max() for a in arrays) for c in range(3)])
    return np.where((lo > 0) & (hi <= 2 * lo), lo, np.where((hi < 0) & (lo >= 2 * hi), hi, 0.0))


def _coplanar_walls(mesh, verts, ring, roff, faces, lab, tol):
    """Walls that the boolean labelled as cell faces: ``lab`` corrected in place.

    Where a cell's face lies in the plane of a container triangle (sites mirrored exactly
    across a flat side of the container), manifold3d keeps the cell's face there, labelled
    with the neighbour across it, although that neighbour's cell is wholly outside the
    container. ``faces`` are the cut cells' triangles labelled with such an emptied cell:
    each lies on the container's surface, and becomes a wall of the container triangle it
    lies on (in its plane within ``tol``, facing the same way, its centroid inside it).
    Not covered: a face in a container triangle's plane whose neighbour keeps volume
    elsewhere (a container with a step in that plane); telling those apart would take an
    area comparison over every cut face, about a tenth of a mesh run. Returns how many
    triangles were relabelled.
    """
    from scipy.spatial import cKDTree

    t3 = verts[ring[roff[faces][:, None] + np.arange(3)]]
    nrm, ok = unit_normals(t3[:, 1] - t3[:, 0], t3[:, 2] - t3[:, 0])
    faces, t3, nrm = faces[ok], t3[ok], nrm[ok]
    tri = mesh.vertices[mesh.faces]
    tn, _ = unit_normals(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    tc = tri.mean(axis=1)
    reach = float(np.sqrt(((tri - tc[:, None]) ** 2).sum(-1)).max())
    cen = t3.mean(axis=1)
    moved = 0
    for k, near in enumerate(cKDTree(tc).query_ball_point(cen, reach + tol)):
        for t in near:
            a, b, c = tri[t]
            if abs(tn[t] @ (cen[k] - a)) > tol or tn[t] @ nrm[k] < 1.0 - VORONOI3D_MESH_FACING:
                continue
            inside = all(
                np.cross(q - p, cen[k] - p) @ tn[t] >= -tol * np.linalg.norm(q - p)
                for p, q in ((a, b), (b, c), (c, a))
            )
            if inside:
                lab[faces[k]] = -1 - t
                moved += 1
                break
    return moved


def unit_normals(e1: np.ndarray, e2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unit normals of ``e1 x e2`` (rows, (m, 3)) and ``(m,) bool``: the cross is not zero.

    Each row pair is scaled by a power of two (exact) to its largest component first: the
    cross product squares the units and its norm squares them again, which overflowed at
    sides ~1e77 (triangles of a mesh at 2**300) and underflowed at ~1e-77. The same bits
    as the unscaled formula wherever that neither overflows nor underflows (a normal is
    invariant under the scaling, its norm scales exactly). A zero row (a needle) has
    normal 0.
    """
    m = np.maximum(np.abs(e1).max(axis=1), np.abs(e2).max(axis=1))
    k = np.frexp(m)[1][:, None]  # m < 2**k (0 for m == 0)
    c = np.cross(np.ldexp(e1, -k), np.ldexp(e2, -k))
    size = np.linalg.norm(c, axis=1)
    ok = size > 0
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(ok[:, None], c / size[:, None], 0.0), ok


def _apart(cells, cf, roff, ring, nvert):
    """Split ``cells`` into batches of cells that share no vertex (greedy, in order)."""
    from ..kernels.meshclip3d import colour_cells

    col = colour_cells(np.asarray(cells, np.int64), cf, roff, ring, nvert)
    order = np.argsort(col, kind="stable")
    cuts = np.flatnonzero(np.diff(col[order])) + 1
    return np.split(cells[order], cuts) if len(cells) else []
