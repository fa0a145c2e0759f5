"""The vertex rule in 3D: a vertex is named by its owner quadruple, computed from that name.

Owners are keys: a site ``j`` is key ``j``, wall ``w`` of the container is key ``nsites + w``
(so sites sort first). A vertex's owners are *every* site and wall it is equidistant from /
lies on (the cell builder collects them: the faces around the vertex and the planes that only
touch it), so every cell meeting at the vertex sees the same set. Its name is the first
quadruple of that sorted set, in lexicographic order, whose planes are independent: for a
cubic grid's 8 co-spherical sites the first four are coplanar and are skipped. The
coordinates are solved from the name alone (relative to the name's lowest site), so every
cell gets the same bits.

The linear system: for the lowest site ``p0`` and each other owner a row ``r . y = t``,
``r = p_j - p0``, ``t = (|r|^2 + w0 - w_j) / 2`` for a site (its power bisector), ``r = n``,
``t = d - n . p0`` for a wall ``n . x <= d`` (``d - n . (p0 - o)`` for a wall about an origin
``o``, :func:`kernels.predicates3d.wall_lift`); ``x = p0 + y`` by Cramer's rule. A coordinate on
an axis-aligned wall is set to the wall's value exactly.

Where ``p0 + y`` cancels (the vertex lies much nearer the origin than its sites: points on a
float sphere around the origin, whose exact diagram has several vertices within 1e-16 of
the centre) the float solve's error, a few ulps of the sites, is as large as the vertex
itself, and distinct exact vertices came out in arbitrary order or as one (a cell's faces
pinched at the merged vertex). Such a vertex is solved again from exact expansions
(:func:`place`, :func:`kernels.predicates3d.exact_point`), right to a few ulps of itself;
still from the name alone, so every cell gets the same bits.

The exact solves about a site (a cut's ill-conditioned vertex, :func:`resettle`; a name of
small determinant, :func:`name_vertex`) try :func:`.vertexdd3d.vertex_dd_site` first: the
double-double stage in registers, which returns the exact stage's bits where it proves
them, before :func:`.predicates3d.vertex_offset` (its cache's lookup, two random reads in
7 MB, cost more than the solve: a helix's and three lines' cells solve most of their
vertices so).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..config import (
    CUT_EXACT_DET_RTOL,
    NJIT,
    VORONOI3D_DET_RTOL,
    VORONOI3D_EXACT_DET_RTOL,
    VORONOI3D_WALL_DET_RTOL,
    WALL_EXACT_SIN,
)
from ..config import CUT_ILL_MARGIN as _ILL_MARGIN
from .predicates3d import exact_point, vertex_offset, wall_lift
from .vertexdd3d import vertex_dd_site

#: nothing here allocates: compiled without reference counting (see kernels.cellcut3d)
_NO_NRT = {**NJIT, "_nrt": False}
#: inlined into the cell builder's naming (numba's inliner): every vertex of every cell is
#: named, and a call that passes arrays costs more than the rows' arithmetic
_INLINE = {**_NO_NRT, "inline": "always"}


@njit(**_INLINE)
def _row(key, p0, P, W, WP, ns, out, k):
    """Row ``k`` of the system for owner ``key`` into ``out[k] = (rx, ry, rz, t)``."""
    if key < ns:
        rx = P[key, 0] - P[p0, 0]
        ry = P[key, 1] - P[p0, 1]
        rz = P[key, 2] - P[p0, 2]
        out[k, 0] = rx
        out[k, 1] = ry
        out[k, 2] = rz
        out[k, 3] = 0.5 * ((rx * rx + ry * ry + rz * rz) + (W[p0] - W[key]))
    else:
        w = key - ns
        out[k, 0] = WP[w, 0]
        out[k, 1] = WP[w, 1]
        out[k, 2] = WP[w, 2]
        out[k, 3] = wall_lift(WP, w, P[p0, 0], P[p0, 1], P[p0, 2])


@njit(**_INLINE)
def solve_name(a, b, c, d, P, W, WP, ns, rows, out):
    """Coordinates of the vertex named ``(a, b, c, d)`` (``a`` a site).

    Writes ``y`` (relative to site ``a``) into ``out[0:3]`` and returns 1, or 2 when the name's
    walls meet at a small angle (:data:`WALL_EXACT_SIN`) or its determinant is small
    (:data:`VORONOI3D_EXACT_DET_RTOL`): the caller solves it exactly, or 0
    when the four planes are not independent (relative determinant below
    ``VORONOI3D_DET_RTOL``).
    """
    _row(b, a, P, W, WP, ns, rows, np.int64(0))  # not literals: one compile of _row
    _row(c, a, P, W, WP, ns, rows, np.int64(1))
    _row(d, a, P, W, WP, ns, rows, np.int64(2))
    # cofactors: c0 = r1 x r2, c1 = r2 x r0, c2 = r0 x r1
    c0x = rows[1, 1] * rows[2, 2] - rows[1, 2] * rows[2, 1]
    c0y = rows[1, 2] * rows[2, 0] - rows[1, 0] * rows[2, 2]
    c0z = rows[1, 0] * rows[2, 1] - rows[1, 1] * rows[2, 0]
    c1x = rows[2, 1] * rows[0, 2] - rows[2, 2] * rows[0, 1]
    c1y = rows[2, 2] * rows[0, 0] - rows[2, 0] * rows[0, 2]
    c1z = rows[2, 0] * rows[0, 1] - rows[2, 1] * rows[0, 0]
    c2x = rows[0, 1] * rows[1, 2] - rows[0, 2] * rows[1, 1]
    c2y = rows[0, 2] * rows[1, 0] - rows[0, 0] * rows[1, 2]
    c2z = rows[0, 0] * rows[1, 1] - rows[0, 1] * rows[1, 0]
    det = rows[0, 0] * c0x + rows[0, 1] * c0y + rows[0, 2] * c0z
    n0 = np.sqrt(rows[0, 0] ** 2 + rows[0, 1] ** 2 + rows[0, 2] ** 2)
    n1 = np.sqrt(rows[1, 0] ** 2 + rows[1, 1] ** 2 + rows[1, 2] ** 2)
    n2 = np.sqrt(rows[2, 0] ** 2 + rows[2, 1] ** 2 + rows[2, 2] ** 2)
    # three walls (``b``, hence ``c`` and ``d``, past the sites) are the container's own
    # corner: its unit normals' float determinant is good to a few ulps, so a wall triple
    # only slightly off coplanar (a roof of slope 1e-6: det 8e-12) still names its vertex
    rtol = VORONOI3D_DET_RTOL if b < ns else VORONOI3D_WALL_DET_RTOL
    if not abs(det) > rtol * n0 * n1 * n2:
        return 0
    t0 = rows[0, 3]
    t1 = rows[1, 3]
    t2 = rows[2, 3]
    out[0] = (t0 * c0x + t1 * c1x + t2 * c2x) / det
    out[1] = (t0 * c0y + t1 * c1y + t2 * c2y) / det
    out[2] = (t0 * c0z + t1 * c1z + t2 * c2z) / det
    if abs(det) < VORONOI3D_EXACT_DET_RTOL * n0 * n1 * n2:
        return 2  # ill-conditioned (flat owners): the caller solves it exactly
    if c >= ns:  # two walls (rows 1 and 2, c0 their cross product) or three
        if b >= ns:
            if abs(det) < WALL_EXACT_SIN * n0 * n1 * n2:
                return 2
        elif c0x * c0x + c0y * c0y + c0z * c0z < (WALL_EXACT_SIN * n1 * n2) ** 2:
            return 2
    return 1


#: ``p0 + y`` is solved again exactly when its largest coordinate is below this fraction of
#: the largest of ``p0`` and ``y`` (the float solve's error is a few ulps of those, so the
#: result kept fewer than ~20 bits of itself)
CANCEL = 2.0**-20


@njit(**_INLINE)
def place(name, P, W, WP, ns, y, x, buf):
    """Absolute coordinates ``x (3,)`` of the vertex ``name`` solved as ``y`` (:func:`solve_name`).

    ``x = p0 + y``, or, where that cancels below ``CANCEL`` of the terms, the exactly computed
    point (:func:`kernels.predicates3d.exact_point`; ``buf`` its scratch). Returns True when
    ``x`` is not ``p0 + y``.
    """
    a = name[0]
    big = 0.0
    small = 0.0
    for q in range(3):
        x[q] = P[a, q] + y[q]
        big = max(big, abs(P[a, q]), abs(y[q]))
        small = max(small, abs(x[q]))
    if not small < CANCEL * big:
        return False
    if exact_point(a, name[1], name[2], name[3], P, W, WP, ns, buf, x):
        return True
    for q in range(3):
        x[q] = P[a, q] + y[q]
    return False


@njit(**_INLINE)
def name_key(m, name):
    """The join's key of a vertex besides its coordinates: a hash of its name (22 bits, >= 1).

    Distinct exact vertices can round to the same doubles (float points on a sphere far from
    the origin, an FCC lattice at 1e8: vertices 1e-8 apart where an ulp is 1.5e-8); their
    names differ (two vertices named by the same independent quadruple are its one
    circumcentre), and every cell at a vertex collects the same owners and so the same
    name, so the name tells them apart where the coordinates cannot. ``m`` (the number of
    owners) is not used: a vertex of five owners or more is as distinct from its
    neighbours as one of four. A SplitMix-style mix of the four keys, plus one.
    """
    h = np.uint64(0x9E3779B97F4A7C15)
    for q in range(4):
        h ^= np.uint64(name[q])
        h *= np.uint64(0xBF58476D1CE4E5B9)
        h ^= h >> np.uint64(31)
    return np.int64(h >> np.uint64(42)) + 1


@njit(**_INLINE)
def axis_snap(keys, m, ns, WP, x):
    """Put ``x`` (absolute, 3,) exactly on every axis-aligned wall among ``keys[:m]``."""
    for t in range(m):
        k = keys[t]
        if k < ns:
            continue
        w = k - ns
        for a in range(3):
            b = (a + 1) % 3
            c = (a + 2) % 3
            if WP[w, b] == 0.0 and WP[w, c] == 0.0 and abs(WP[w, a]) == 1.0:
                if WP.shape[1] > 4:  # about the wall's origin (exact where the wall is a double)
                    x[a] = WP[w, 4 + a] + WP[w, 3] * WP[w, a]
                else:
                    x[a] = WP[w, 3] * WP[w, a]


@njit(**_INLINE)
def name_vertex(keys, m, P, W, WP, ns, rows, y, name, buf):
    """Name a vertex with sorted owner keys ``keys[:m]`` and solve its coordinates.

    ``name (4,)`` receives the quadruple, ``y (3,)`` the coordinates relative to
    ``name[0]``. Returns 1 (float solve), 2 (``y`` exactly rounded from exact determinants,
    :func:`kernels.predicates3d.vertex_offset`; ``buf`` its scratch) or 0 when no quadruple
    of the owners is independent.

    The name is the first quadruple whose float determinant passes (:func:`solve_name`);
    when none does, the first whose exact determinant is not zero (container walls that
    meet at slopes of 1e-7 and below: a hip roof's corner, its determinant 8 h^2; a
    bisector through a ridge of nearly parallel walls). Both depend on the owners alone, so
    every cell at the vertex picks the same name and the same bits.
    """
    for i0 in range(m):
        a = keys[i0]
        if a >= ns:
            break
        for i1 in range(i0 + 1, m):
            for i2 in range(i1 + 1, m):
                for i3 in range(i2 + 1, m):
                    r = solve_name(a, keys[i1], keys[i2], keys[i3], P, W, WP, ns, rows, y)
                    if r != 0:
                        name[0] = a
                        name[1] = keys[i1]
                        name[2] = keys[i2]
                        name[3] = keys[i3]
                        if r == 2:
                            return _exact_named(name, P, W, WP, ns, buf, y)
                        return 1
    for i0 in range(m):
        a = keys[i0]
        if a >= ns:
            break
        for i1 in range(i0 + 1, m):
            for i2 in range(i1 + 1, m):
                for i3 in range(i2 + 1, m):
                    name[0] = a
                    name[1] = keys[i1]
                    name[2] = keys[i2]
                    name[3] = keys[i3]
                    if _exact_named(name, P, W, WP, ns, buf, y) == 2:
                        return 2
    return 0


@njit(**_NO_NRT)
def _exact_named(name, P, W, WP, ns, buf, y):
    """``y``: the vertex ``name`` less site ``name[0]``, exactly rounded; 2, or 1 if ``y`` stands.

    Relative to the site, as the float solve: an absolute vertex far from the origin (a
    Convex roof at UTM offsets) would keep only ~5e-10 of a unit cell's coordinates.
    """
    a = name[0]
    ok, x0, x1, x2 = vertex_dd_site(a, name[1], name[2], name[3], P, W, WP, ns)
    if ok:  # (vertex_offset's bits, without its cache's lookup: see the module)
        y[0] = x0
        y[1] = x1
        y[2] = x2
        return 2
    if not vertex_offset(
        a, name[1], name[2], name[3], P, W, WP, ns, buf, P[a, 0], P[a, 1], P[a, 2], y
    ):
        return 1  # float determinant passed, so never; keep the float solve
    return 2


@njit(**_INLINE)
def _key(lab, ns):
    """The owner key of a face label (as ``kernels.cellcut3d.owner_key``)."""
    return lab if lab >= 0 else ns + (-1 - lab)


@njit(**_NO_NRT)
def resettle(i, j, V, CP, w, DEG, LB, S, P, W, WP, rows):
    """Solve again exactly the vertices the graph cut by ``j`` made on ill-conditioned edges.

    A new vertex (``S == 0``, three faces, the last ``j``'s) is interpolated along its edge
    from the ends' float values; where ``j``'s plane is nearly parallel to the edge (the
    bisectors of sites a few ulps apart) those values are mostly rounding and the point
    lands anywhere on the edge, far beyond the filter's band: later planes were then
    trusted on a wrong point (vertices outside the box, faces the exact cell lacks). Such a
    vertex is put at its owners' exact point, rounded (:func:`vertex_offset`).

    Called between :func:`kernels.graph3d.cut_open` and ``cut_close``: only the cap's points
    ``CP[:w, 2]`` can have ``j``'s face (a plane cuts a cell once), so they are the ones
    looked at. Returns the largest ``|v|^2`` of the vertices moved, before and after (0 when
    none): ``cut_close``'s radius sees only the moved points, the cell's radius takes both.
    Not inlined: inlined into the cut's loop it cost the 1e5 build ~3% more CPU.
    """
    r2 = 0.0
    ns = P.shape[0]
    for q in range(w):
        v = CP[q, 2]
        if S[v] != 0.0 or DEG[v] != 3 or LB[v, 2] != j:
            continue
        k0 = _key(LB[v, 0], ns)
        k1 = _key(LB[v, 1], ns)
        if _ill(i, k0, k1, j, P, WP, ns):
            r2 = max(r2, V[v, 0] * V[v, 0] + V[v, 1] * V[v, 1] + V[v, 2] * V[v, 2])
            ok, x0, x1, x2 = vertex_dd_site(i, k0, k1, j, P, W, WP, ns)
            if ok:  # (vertex_offset's bits, without its cache's lookup: see the module)
                V[v, 0] = x0
                V[v, 1] = x1
                V[v, 2] = x2
            else:
                vertex_offset(i, k0, k1, j, P, W, WP, ns, rows, P[i, 0], P[i, 1], P[i, 2], V[v])
            r2 = max(r2, V[v, 0] * V[v, 0] + V[v, 1] * V[v, 1] + V[v, 2] * V[v, 2])
    return r2


@njit(**_INLINE)
def _ill(i, a, b, c, P, WP, ns):
    """Whether owners ``a, b, c``'s relative determinant is below ``CUT_EXACT_DET_RTOL``.

    The same answer as ``|det| < CUT_EXACT_DET_RTOL * |n_a| |n_b| |n_c|`` of :func:`_rel_det`,
    from squares (no square roots): ``det^2`` against ``rtol^2 |n_a|^2 |n_b|^2 |n_c|^2``,
    which decides unless the two lie within :data:`_ILL_MARGIN` of each other or outside the
    range where neither under- nor overflows (then the test with roots decides).
    """
    ax, ay, az = _normal(i, a, P, WP, ns)
    bx, by, bz = _normal(i, b, P, WP, ns)
    cx, cy, cz = _normal(i, c, P, WP, ns)
    det = ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx)
    na = ax * ax + ay * ay + az * az
    nb = bx * bx + by * by + bz * bz
    nc = cx * cx + cy * cy + cz * cz
    lim = (CUT_EXACT_DET_RTOL * CUT_EXACT_DET_RTOL) * (na * nb * nc)
    d2 = det * det
    if 1e-250 < lim < 1e250:
        if d2 > lim * (1.0 + _ILL_MARGIN):
            return False
        if d2 < lim * (1.0 - _ILL_MARGIN):
            return True
    return abs(det) < CUT_EXACT_DET_RTOL * (np.sqrt(na * nb) * np.sqrt(nc))


@njit(**_NO_NRT)
def resettle_rings(i, j, V, F, R, labs, nf, P, W, WP, X):
    """:func:`resettle` for a cell held as face rings (the fallback): ``j``'s face's vertices.

    A vertex of three faces, ``j``'s one of them, is solved again exactly where the three
    planes meet at a small relative determinant (an on-plane vertex of old is one the
    exact point rounds to as well).
    """
    ns = P.shape[0]
    for g in range(nf):
        if F[g, 0] != j:
            continue
        for q in range(F[g, 2]):
            v = R[F[g, 1] + q]
            m = 0
            for f in range(nf):
                for k in range(F[f, 2]):
                    if R[F[f, 1] + k] == v:
                        if m < labs.shape[0] and F[f, 0] != j:
                            labs[m] = _key(F[f, 0], ns)
                            m += 1
                        break
            if m != 2:
                continue
            det, nrm = _rel_det(i, labs[0], labs[1], j, P, WP, ns)
            if abs(det) < CUT_EXACT_DET_RTOL * nrm:
                vertex_offset(
                    i, labs[0], labs[1], j, P, W, WP, ns, X[1], P[i, 0], P[i, 1], P[i, 2], V[v]
                )


@njit(**_INLINE)
def _normal(i, k, P, WP, ns):
    """The normal of owner ``k``'s plane in cell ``i``: ``p_k - p_i`` or the wall's."""
    if k < ns:
        return P[k, 0] - P[i, 0], P[k, 1] - P[i, 1], P[k, 2] - P[i, 2]
    w = k - ns
    return WP[w, 0], WP[w, 1], WP[w, 2]


@njit(**_INLINE)
def _rel_det(i, a, b, c, P, WP, ns):
    """The determinant of owners ``a, b, c``'s normals and the product of their lengths."""
    ax, ay, az = _normal(i, a, P, WP, ns)
    bx, by, bz = _normal(i, b, P, WP, ns)
    cx, cy, cz = _normal(i, c, P, WP, ns)
    det = ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx)
    nrm = np.sqrt((ax * ax + ay * ay + az * az) * (bx * bx + by * by + bz * bz))
    return det, nrm * np.sqrt(cx * cx + cy * cy + cz * cz)
