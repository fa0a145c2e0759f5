"""``voronoi3d``: 3D Voronoi and power cells in a box, a convex solid or a closed mesh."""

from __future__ import annotations

import itertools

import numpy as np
from numba import njit, prange

from ..config import (
    CONVEX_FOLD_ULPS,
    CONVEX_NEAR_PARALLEL_SIN,
    CONVEX_VERTEX_OUT_ULPS,
    DOOMED_SIDE,
    DOOMED_SPREAD,
    FRAME3D_CAP_EXP,
    NJIT,
    NJIT_PARALLEL,
    OUTSIDE3D_BLOCK,
    VOLUME_RANGE,
    VORONOI3D_INSIDE_BLOCK,
)
from .build3d import build_cells3d, duplicate_owners, release_freed_memory
from .containers import (
    Convex,
    Template,
    as_container,
    box_template,
    check_volume,
)
from .diagram3d import Diagram3D
from .hull3d import hull_cells, takes_hull_path
from .inputs import as_points, as_weights, from_working, working_frame
from .threads import serial_below

__all__ = ["voronoi3d", "Convex", "Diagram3D"]

#: a mesh container's volume range: the boxes' and Convexes' since the mesh cut's areas are
#: taken in the working frame and kernels.meshcut3d scales each cell's moments by a power of
#: two (its centroids overflowed past 2**256); was config.MESH_VOLUME_RANGE (1e-200, 1e200)
MESH_VOLUME_RANGE = VOLUME_RANGE


def duplicate_owner3d(pts: np.ndarray, w: np.ndarray | None) -> np.ndarray:
    """``(n,)``: -1 for a site that owns its cell, else the site that owns it (equal point).

    Among equal points the largest weight owns the cell (the others' power cells are empty),
    ties to the lowest index.
    """
    if len(pts) < 2:
        return np.full(len(pts), -1, np.int64)
    wk = np.zeros(len(pts)) if w is None else np.ascontiguousarray(w, np.float64)
    return duplicate_owners(np.ascontiguousarray(pts, np.float64), wk)


def voronoi3d(points, container=None, *, weights=None, periodic=False, progress=None) -> Diagram3D:
    """3D Voronoi (or power) cells of ``points`` clipped to a container.

    Parameters
    ----------
    points : (n, 3) array_like
        The sites. Cell ``i`` belongs to ``points[i]``, always, in input order.
    container : None, 6-tuple, Convex, trimesh.Trimesh, (vertices, faces) or path, optional
        ``None``: the sites' bounding box padded 10% per side; ``(xmin, ymin, zmin, xmax,
        ymax, zmax)``; :class:`Convex` (half-spaces or hull points); or a closed triangle
        mesh (cells that reach its surface are cut by it).
    weights : (n,) array_like, optional
        Power (radical) diagram weights: cell ``i`` is where ``|x - p_i|^2 - w_i`` is least.
    periodic : bool
        The box is a 3-torus (box containers only; sites must lie in the box). Cells are
        whole polyhedra around their sites and may reach past the box.
    progress : callable, optional
        ``progress(done, total)`` after each chunk of cells.

    Returns
    -------
    Diagram3D

    Examples
    --------
    >>> import numpy as np, voroforge as vf
    >>> d = vf.voronoi3d(np.random.default_rng(0).random((50, 3)), (0, 0, 0, 1, 1, 1))
    >>> round(float(d.volumes.sum()), 12)
    1.0
    """
    pts = as_points(points, dim=3)
    n = len(pts)
    w = None if weights is None else as_weights(weights, n)
    mesh = None
    try:
        t = as_container(container, pts)
    except TypeError:
        from .mesh3d import as_mesh_container

        mesh, t = as_mesh_container(container)
    check_volume(t, VOLUME_RANGE if mesh is None else MESH_VOLUME_RANGE)
    if periodic and (t.kind != "box" or mesh is not None):
        raise ValueError("periodic=True needs a box container (None or a 6-tuple)")
    if n and mesh is not None:
        from .mesh3d import sites_inside

        ins = sites_inside(mesh, pts)
        if not ins.any():
            raise ValueError("the container mesh contains none of the sites")
    if n and mesh is None:
        inside = _in_box(pts, t) if t.kind == "box" else None  # (periodic: a box)
        if not (inside.any() if inside is not None else _convex_holds_any(pts, t)):
            raise ValueError("the container contains none of the sites")
        if periodic and not inside.all():
            bad = int(np.flatnonzero(~inside)[0])
            raise ValueError(f"periodic sites must lie in the box (first outside: row {bad})")
    # the container stays below 2**FRAME3D_CAP_EXP: volumes are cubes of its coordinates
    # (sites 1e-110 apart in a box 10 wide put it near 2**900: volumes inf, at 1e-160 NaN)
    work, k = working_frame(pts, extra=t.bounds, cap=FRAME3D_CAP_EXP)
    # duplicates in the working frame: sites its resolution rounds together are one site
    if periodic and n:
        # on the torus a site on an upper face is the one on the lower face: duplicates are
        # found on the wrapped coordinates
        lo, hi = np.ldexp(np.asarray(t.bounds, dtype=np.float64), k)
        dup = duplicate_owner3d(np.where(work >= hi, lo, work), w)
    else:
        dup = duplicate_owner3d(work, w)
    uniq = np.flatnonzero(dup < 0)
    tw = t.scaled(k)
    wk = None if w is None else np.ldexp(w, 2 * k)
    P = np.ascontiguousarray(work[uniq])
    # equal weights give the unweighted cells (only weight differences enter): built so,
    # they take the Delaunay lists (a vertex of 1,032 owners failed with weights=ones)
    equal = wk is None or not len(wk) or bool((wk == wk[0]).all())
    W = np.zeros(len(uniq)) if equal else np.ascontiguousarray(wk[uniq])
    u = len(uniq)
    if u == 0:
        return _assemble(pts, w, t, k, None, uniq, dup, None, periodic, mesh)
    if periodic:
        res, gmap = _periodic(P, W, tw, progress)
    elif mesh is not None:  # only the cells that can reach the mesh (unweighted: all)
        from .mesh3d import reaching_sites

        build = np.arange(u)
        if w is None:
            build = np.flatnonzero(reaching_sites(mesh, pts, ins)[uniq])
        # (Delaunay lists only for cells with a vertex of more owners than the cell's table
        # holds: the mesh cut's new vertices round by the order of the cell's faces, which a
        # cell built from its list does not keep)
        res = build_cells3d(P, W, tw, cells=build, progress=progress, short=True, lists="owners")
        gmap = None
    else:
        res = _convex_cells(P, W, tw, progress)
        gmap = None
        if tw.float_cut and (
            res.unmatched
            or ((res.status != 0) & (res.status != 1)).any()
            or _leaves_walls(res.vertices, tw)
            or _folded(res, P, W)
        ):
            # a bisector through a hull corner of 4+ walls (containers.exact_twin), nearly
            # coplanar walls that put a vertex outside the hull (checker14 F9), or a folded
            # cell (a vertex past one of its own bisectors): the cells again from the exact
            # polytope of the same walls
            res = _convex_cells(P, W, container._twin().scaled(k), progress)
    d = _assemble(pts, w, t, k, res, uniq, dup, gmap, periodic, mesh)
    if mesh is not None:
        from .mesh3d import cut_by_mesh

        d = cut_by_mesh(d, mesh, short=res.short)
    del res, P, W, uniq, dup, gmap
    release_freed_memory(u)
    return d


def _convex_cells(P, W, tw, progress):
    """The cells of every site in a box or Convex template ``tw`` (working frame)."""
    if takes_hull_path(tw):  # a big Convex: box cells, then those at a wall (engine.hull3d)
        return hull_cells(P, W, tw, progress=progress)
    return build_cells3d(P, W, tw, cells=np.arange(len(P)), progress=progress, outside=True)


def _leaves_walls(V: np.ndarray, tw: Template) -> bool:
    """Whether a vertex of ``V`` (working frame) lies outside a wall of the float-cut ``tw``.

    Checked only where two of its walls are nearly parallel (:data:`CONVEX_NEAR_PARALLEL_SIN`):
    a hull whose facets are coplanar only to rounding (the corners of a cell far out, points
    jittered by 1e-11) gave cells whose vertices, placed by those walls, lay up to 0.15 of
    the solid's extent outside it, non-convex, their volumes still summing right.
    """
    from scipy.spatial import cKDTree

    WP = tw.WP
    n = np.ascontiguousarray(WP[:, :3])
    if not len(V) or not len(cKDTree(n).query_pairs(CONVEX_NEAR_PARALLEL_SIN)):
        return False
    scale = float(np.abs(tw.TV).sum(axis=1).max())  # as kernels.template3d.cut_all
    tol = CONVEX_VERTEX_OUT_ULPS * np.finfo(np.float64).eps * (scale + np.abs(WP[:, 3]))
    o = WP[0, 4:7] if WP.shape[1] > 4 else np.zeros(3)
    for a in range(0, len(V), OUTSIDE3D_BLOCK):
        s = (V[a : a + OUTSIDE3D_BLOCK] - o) @ n.T - WP[:, 3]
        if (s > tol).any():
            return True
    return False


def _folded(res, P: np.ndarray, W: np.ndarray) -> bool:
    """Whether a built cell has a vertex strictly past the bisector of one of its faces.

    A float build in a Convex hull with sites and walls a few ulps apart gave a cell whose
    rings ran through two vertices of other cells, 0.18 nearer their sites than its own
    (solidfix's FOLDED at 1000): volumes right, the mesh folded. Every vertex of cell ``i``
    must be power-nearer its site than each site ``j`` across its faces, within
    :data:`CONVEX_FOLD_ULPS` roundings of the distances (working frame).
    """
    site = np.zeros(len(res.cells), np.int64)
    site[res.pos] = res.cells
    with serial_below(len(site)):
        return bool(
            _fold_flags(
                res.vertices,
                P,
                W,
                site,
                res.cell_faces,
                res.flabel,
                res.voff,
                res.vid,
                CONVEX_FOLD_ULPS * np.finfo(np.float64).eps,
            ).any()
        )


@njit(**NJIT_PARALLEL)
def _fold_flags(V, P, W, site, cf, lab, voff, vid, rel):
    """Per build position: a vertex of the cell past the power bisector of one of its faces.

    ``pw_i(v) - pw_j(v) > rel * ((|v| + |p|) * max |v - p| + |w_i| + |w_j|)`` (max norms):
    the rounding of a vertex placed to a few ulps of its coordinates, moved along
    ``2 (p_j - p_i)``, and of the distances themselves. Only cells with a wall face (the
    folds came from walls ulps apart; the others are built as in a box): a face-by-vertex
    test of every cell cost 13% of a 20,000-site build in a Convex cube.
    """
    nb = site.shape[0]
    bad = np.zeros(nb, np.bool_)
    for b in prange(nb):
        i = site[b]
        wall = False
        for f in range(cf[b], cf[b + 1]):
            if lab[f] < 0:
                wall = True
                break
        if not wall:
            continue
        for t in range(voff[b], voff[b + 1]):
            g = vid[t]
            di = -W[i]
            vm = 0.0
            for a in range(3):
                x = V[g, a]
                vm = max(vm, abs(x))
                e = x - P[i, a]
                di += e * e
            for f in range(cf[b], cf[b + 1]):
                j = lab[f]
                if j < 0:
                    continue
                dj = -W[j]
                for a in range(3):
                    e = V[g, a] - P[j, a]
                    dj += e * e
                if di <= dj:
                    continue
                # past the bisector: beyond the rounding bound? (rarely reached)
                pm = 0.0
                r2 = 0.0
                for a in range(3):
                    pm = max(pm, abs(P[i, a]), abs(P[j, a]))
                    r2 = max(r2, (V[g, a] - P[i, a]) ** 2, (V[g, a] - P[j, a]) ** 2)
                if di - dj > rel * ((vm + pm) * np.sqrt(r2) + abs(W[i]) + abs(W[j])):
                    bad[b] = True
                    break
            if bad[b]:
                break
    return bad


def _walls_frame(pts: np.ndarray, t: Template):
    """``pts`` in the frame of the template's walls, and the inside test's scale per wall."""
    if t.WP.shape[1] > 4:  # walls about an origin near the solid (engine.containers)
        pts = pts - t.origin
    big = max(float(pts.max()), -float(pts.min()))  # np.abs(pts).max(), without its copy
    return pts, np.abs(t.WP[:, 3]) + big + 1e-300


def _in_box(pts: np.ndarray, t: Template) -> np.ndarray:
    """Which sites a box template holds (its walls within 1e-12 of their scale)."""
    pts, scale = _walls_frame(pts, t)
    lo, hi = t.bounds
    return _box_holds(pts, lo - 1e-12 * scale[0::2], hi + 1e-12 * scale[1::2])


@njit(**NJIT)
def _box_holds(pts, lo, hi):
    """``((pts >= lo) & (pts <= hi)).all(axis=1)`` in one pass (no (n, 3) temporaries)."""
    out = np.empty(pts.shape[0], np.bool_)  # noqa: TID251 - every entry written below
    for i in range(pts.shape[0]):
        ok = True
        for q in range(3):
            x = pts[i, q]
            ok = ok and x >= lo[q] and x <= hi[q]
        out[i] = ok
    return out


def _convex_holds_any(pts: np.ndarray, t: Template) -> bool:
    """Whether a Convex template holds any site.

    Blocks of sites until one is held: the (n, W) products of 20,000 sites and a hull of
    4,000 walls took 1.2 s.
    """
    pts, scale = _walls_frame(pts, t)
    WP = t.WP
    for a in range(0, len(pts), VORONOI3D_INSIDE_BLOCK):
        s = pts[a : a + VORONOI3D_INSIDE_BLOCK] @ WP[:, :3].T - WP[:, 3]
        if (s <= 1e-12 * scale).all(axis=1).any():
            return True
    return False


def _periodic(P, W, t, progress):
    """Cells of the torus: the sites plus enough images, then only the sites' cells."""
    lo, hi = t.bounds
    L = hi - lo
    u = len(P)
    # images within this margin (in mean spacings): with 2.5 every uniform input of 1e4-1e5
    # sites needed the doubled second try (twice the time); 5 holds in one
    margin = 5.0 * float(np.prod(L) / u) ** (1.0 / 3.0)
    while True:
        # a torus cell lies within half a period of its site on every axis (its own images a
        # period away bound it), so the image of another site that can bound it is within a
        # period of the site: shifts of -1, 0, 1 suffice, for power cells too (every image
        # has the site's weight). An axis whose margin reaches its period takes all of them
        # and needs no closing test: a thin box's margin grew as its cells (wide across
        # it) did not close, with ~margin / L shifts along it (1 x 1 x 1e-6: no return)
        m = np.minimum(margin, L)
        full = m >= L
        K = [int(np.ceil(m[a] / L[a])) for a in range(3)]
        imgs, origs, shifts = [P], [np.arange(u)], [np.zeros((u, 3), np.int64)]
        # per axis and shift, the sites whose image lies within the margin (the test on
        # P + s * L, one axis at a time); an image needs all three
        near = [
            {
                sa: (P[:, a] + sa * L[a] >= lo[a] - m[a]) & (P[:, a] + sa * L[a] <= hi[a] + m[a])
                for sa in range(-K[a], K[a] + 1)
            }
            for a in range(3)
        ]
        for s in itertools.product(*(range(-K[a], K[a] + 1) for a in range(3))):
            if s == (0, 0, 0):
                continue
            ok = near[0][s[0]] & near[1][s[1]] & near[2][s[2]]
            idx = np.flatnonzero(ok)
            if len(idx):
                imgs.append(P[idx] + np.array(s) * L)
                origs.append(idx)
                shifts.append(np.tile(np.array(s, np.int64), (len(idx), 1)))
        PP = np.ascontiguousarray(np.concatenate(imgs))
        orig = np.concatenate(origs)
        shift = np.concatenate(shifts)
        big = box_template(lo - m, hi + m)
        WO = np.ascontiguousarray(W[orig])
        if not full.all() and _doomed(P, PP, WO, big, lo, hi, m, full):
            margin *= 2.0  # (the cells of a sample already fail the test below)
            continue
        res = build_cells3d(PP, WO, big, cells=np.arange(u), progress=progress)
        r = np.sqrt(res.rad2)[:, None]
        ok = (full | ((P - 2 * r >= lo - m) & (P + 2 * r <= hi + m))).all()
        # status 1: a power cell that no point is nearest to (empty); it had made the loop
        # double the margin until the memory ran out
        if ok and ((res.status == 0) | (res.status == 1)).all():
            return res, (orig, shift)
        if full.all() or margin > 8.0 * L.max():  # every image that can bound a cell is in
            bad = np.flatnonzero((res.status != 0) & (res.status != 1))
            raise RuntimeError(
                "periodic cells did not close within 8 box sizes of images"
                + (f" (site {int(bad[0])}, status {int(res.status[bad[0]])})" if len(bad) else "")
                + "; please report this input"
            )
        margin *= 2.0


def _doomed(P, PP, WO, big, lo, hi, m, full) -> bool:
    """Whether a try of :func:`_periodic` with margins ``m`` fails its closing test for sure.

    Only where a gap between the sites' coordinates along an open axis (circularly, on the
    torus) is wider than its margin (sites on one plane or line: their cells span the period
    across it); then the cells of a sample of the sites (the 8 nearest each open side, 16
    more spread over the input) are built first, and the try is known to fail when one of
    them reaches past the margin by more than rounding. A try that fails this way is skipped,
    so the build that passes is the same call as before, with the same bits: 4,000 sites on
    a plane built three times (2.15 + 1.38 + 1.35 s, the first with its cells spanning the
    margins), on a line 12.0 + 2.1 + 2.3 s.
    """
    L = hi - lo
    u = len(P)
    wide = False
    for a in range(3):
        if full[a]:
            continue
        x = np.unique(P[:, a])
        gaps = np.diff(np.r_[x, x[0] + L[a]])
        wide |= bool(gaps.max() > m[a])
    if not wide:
        return False
    pick = [np.linspace(0, u - 1, min(u, DOOMED_SPREAD)).astype(np.int64)]
    for a in np.flatnonzero(~full):
        o = np.argsort(P[:, a], kind="stable")
        pick += [o[:DOOMED_SIDE], o[-DOOMED_SIDE:]]
    cells = np.unique(np.concatenate(pick))
    res = build_cells3d(PP, WO, big, cells=cells, lists=False)
    r = np.sqrt(res.rad2)[:, None]
    tol = 1e-9 * L  # far above the radius's rounding: a skipped try fails in the real build
    out = (P[cells] - 2 * r < lo - m - tol) | (P[cells] + 2 * r > hi + m + tol)
    return bool((out[:, ~full].any(axis=1) & (res.status == 0)).any())


@njit(**NJIT_PARALLEL)
def _torus_faces(lab, cf, rpos, orig, shift, uniq, cfx, pos):
    """Periodic cells' faces: site labels, which face is listed once, image shifts.

    ``lab``, ``cf`` (build order) label faces by image number; returns the labels as input
    sites, ``keep`` (build order: a wall, a larger site, or the same site across a shift
    that is lexicographically positive) and the shift of the image across each face in the
    caller's order (``pos``, ``cfx``: ``cf`` with an empty slot after the last). Cells in
    parallel (each writes its own faces' rows; the shifts' rows from a prefix sum).
    """
    nfc = lab.shape[0]
    lab2 = lab.copy()
    keep = np.zeros(nfc, np.bool_)
    for c in prange(rpos.shape[0]):
        p = rpos[c]
        owner = uniq[c]
        for f in range(cf[p], cf[p + 1]):
            j = lab[f]
            if j < 0:
                keep[f] = True
                continue
            s0 = shift[j, 0]
            s1 = shift[j, 1]
            s2 = shift[j, 2]
            o = uniq[orig[j]]
            lab2[f] = o
            lexpos = s0 > 0 or (s0 == 0 and (s1 > 0 or (s1 == 0 and s2 > 0)))
            keep[f] = o > owner or (o == owner and lexpos)
    n = pos.shape[0]
    row = np.zeros(n + 1, np.int64)  # the first row of cell i's faces in the shifts
    for i in range(n):
        row[i + 1] = row[i] + cfx[pos[i] + 1] - cfx[pos[i]]
    shifts = np.zeros((row[n], 3), np.int64)
    for i in prange(n):
        p = pos[i]
        r = row[i]
        for f in range(cfx[p], cfx[p + 1]):
            j = lab[f]
            if j >= 0:
                shifts[r, 0] = shift[j, 0]
                shifts[r, 1] = shift[j, 1]
                shifts[r, 2] = shift[j, 2]
            r += 1
    return lab2, keep, shifts


def _assemble(pts, w, t, k, res, uniq, dup, gmap, periodic, mesh):
    n = len(pts)
    if res is None:
        vol = np.zeros(n)
        cen = np.full((n, 3), np.nan)
        z = np.zeros(0, np.int64)
        return Diagram3D(
            sites=pts,
            weights=w,
            periodic=periodic,
            container=t.kind,
            walls=t.absolute_walls(),
            volumes=vol,
            centroids=cen,
            vertices=np.zeros((0, 3)),
            cell_faces=np.zeros(n + 1, np.int64),
            flabel=z,
            roff=np.zeros(1, np.int64),
            ring=z,
            duplicate_of=dup,
            unmatched=0,
            container_volume=t.volume,
        )
    built = uniq[res.cells]  # all unique sites, or (mesh containers) those that reach it
    bad = np.flatnonzero((res.status != 0) & (res.status != 1))
    if len(bad):
        raise RuntimeError(
            f"3D cell builder failed on site {int(built[bad[0]])} "
            f"(status {int(res.status[bad[0]])}); please report this input"
        )
    u = len(uniq)
    vol1 = np.ldexp(res.volume, -3 * k) if k else res.volume
    cen1 = from_working(res.centroid, k)
    if len(built) == n:  # every site built, in order (no duplicates, not a mesh's subset)
        vol, cen, pos = vol1, cen1, res.pos
    else:
        vol = np.zeros(n)
        cen = np.full((n, 3), np.nan)
        vol[built] = vol1
        cen[built] = cen1
        pos = np.full(n, len(built), np.int64)
        pos[built] = res.pos
    # the face table stays in build order; duplicates (and cells not built) point at an
    # empty slot after the last
    cell_faces = np.append(res.cell_faces, res.cell_faces[-1])
    voff = np.append(res.voff, res.voff[-1])
    lab = res.flabel
    face_keep = shifts = None
    if gmap is not None:
        orig, shift = gmap
        with serial_below(n):
            lab, face_keep, shifts = _torus_faces(
                res.flabel, res.cell_faces, res.pos, orig, shift, uniq, cell_faces, pos
            )
    elif u != n:  # site labels from the unique sites' numbers to the input's
        lab = lab.copy()
        site = lab >= 0
        lab[site] = uniq[lab[site]]
    return Diagram3D(
        sites=pts,
        weights=w,
        periodic=periodic,
        container=t.kind,
        walls=t.absolute_walls(),
        volumes=vol,
        centroids=cen,
        vertices=from_working(res.vertices, k),
        cell_faces=cell_faces,
        flabel=lab,
        roff=res.roff,
        ring=res.ring,
        duplicate_of=dup,
        unmatched=res.unmatched,
        box=t.bounds,
        container_volume=t.volume,
        face_keep=face_keep,
        shifts=shifts,
        pos=pos,
        vid=res.vid,
        voff=voff,
        frame=k,
    )
