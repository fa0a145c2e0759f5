"""Watertight strut lattices without a boolean union: node hulls joined by prisms.

Each strut end gets a ring (a regular ``k``-gon of the node's radius, perpendicular to the
strut) far enough from its node that the ring is a face of the convex hull of everything at
the node: the other rings and the node's sphere points. The node is that hull with its ring
faces removed; a strut is the prism (a frustum when the two radii differ) between its two
rings, whose vertices it shares with the hulls. Every edge of the result then has exactly two
triangles, consistently oriented, by construction: no union, no vertex merging.

The ring distance follows from the angles at the node: a ring at distance ``d`` is
supporting when ``d > r cot(theta / 2)`` for the smallest angle ``theta`` to another strut
(equal radii), and ``d > R`` for a node sphere of radius ``R``. Struts too short to hold
both rings (short Voronoi edges) merge their two nodes into one hull. Every hull is
checked: each ring must come back as exactly ``k - 2`` hull triangles over its own
vertices; a failure pushes the ring out or merges the nodes, and tries again.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import ConvexHull, QhullError

from .. import config

__all__ = ["hull_lattice"]

_MAX_ROUNDS = 12


def _unit_sphere(level: int) -> np.ndarray:
    import trimesh

    return np.asarray(trimesh.creation.icosphere(subdivisions=level).vertices)


def _frames(u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unit ``p, q`` perpendicular to each ``u`` with ``p x q = u``."""
    ref = np.where(np.abs(u[:, :1]) < 0.9, [[1.0, 0.0, 0.0]], [[0.0, 1.0, 0.0]])
    p = np.cross(u, ref)
    p /= np.linalg.norm(p, axis=1, keepdims=True)
    q = np.cross(u, p)
    return p, q


def _ring_distance(end_node, end_dir, r_end, sphere_r, n_nodes) -> np.ndarray:
    """Closed-form ring distance per strut end from the smallest angle at its node."""
    order = np.argsort(end_node, kind="stable")
    counts = np.bincount(end_node, minlength=n_nodes)
    start = np.concatenate([[0], np.cumsum(counts)])
    deg = counts.max()
    slot = np.arange(len(end_node)) - start[end_node[order]]
    dirs = np.full((n_nodes, deg, 3), np.nan)
    dirs[end_node[order], slot] = end_dir[order]
    cos = np.einsum("vik,vjk->vij", dirs, dirs)
    idx = np.arange(deg)
    cos[:, idx, idx] = np.nan
    cmax = np.where(np.isnan(cos), -1.0, cos).max(axis=2)
    c = np.clip(cmax[end_node[order], slot], -1.0, 1.0 - 1e-12)
    cot_half = np.sqrt((1.0 + c) / (1.0 - c))
    d = np.zeros(len(end_node))
    d[order] = r_end[order] * np.maximum(config.SOLID_RING_MIN, config.SOLID_RING_SAFETY * cot_half)
    return np.maximum(d, config.SOLID_RING_MIN * sphere_r[end_node])


def _components(n_nodes: int, pairs: np.ndarray) -> np.ndarray:
    """Cluster label per node: connected components of the node ``pairs`` (m, 2)."""
    if len(pairs) == 0:
        return np.arange(n_nodes)
    g = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n_nodes, n_nodes))
    return connected_components(g, directed=False)[1]


class _Geo:
    """The lattice's fixed geometry (per edge, per end), shared by the build rounds."""

    def __init__(self, nodes, edges, r_node, k, sphere, node_scale):
        self.nodes, self.edges, self.r_node, self.k = nodes, edges, r_node, k
        self.V, self.E = len(nodes), len(edges)
        a, b = edges[:, 0], edges[:, 1]
        vec = nodes[b] - nodes[a]
        self.length = np.linalg.norm(vec, axis=1)
        self.u = vec / self.length[:, None]
        self.p, self.q = _frames(self.u)
        phi = 2.0 * np.pi * np.arange(k) / k
        self.cs, self.sn = np.cos(phi), np.sin(phi)
        self.has_sphere = sphere is not None
        self.unit = _unit_sphere(sphere) if sphere is not None else np.zeros((1, 3))
        # nodes inside joints take a coarser sphere (an icosahedron: a subset of the finer
        # sphere's points, so every ring placed for the finer one still clears it): the
        # union's cost is its triangles
        self.unit_joint = _unit_sphere(0) if sphere is not None else self.unit
        self.sphere_r = r_node * (node_scale if sphere is not None else 0.0)
        # strut ends: end j < E sits at a (direction u), end E + j at b (direction -u)
        self.end_node = np.concatenate([a, b])
        self.end_dir = np.concatenate([self.u, -self.u])
        self.end_edge = np.concatenate([np.arange(self.E), np.arange(self.E)])
        self.len_end = np.concatenate([self.length, self.length])
        self.d_end = _ring_distance(
            self.end_node, self.end_dir, r_node[self.end_node], self.sphere_r, self.V
        )
        self.d_push = np.zeros(2 * self.E)  # ends pushed out by conflicts in their joint
        self.cache: dict = {}
        self.clear: set = set()  # piece pairs already found apart (see _conflicts)


def hull_lattice(nodes, edges, r_node, *, segments=8, sphere=1, node_scale=1.0):
    """Vertices, faces and parts of the lattice (see the module docstring).

    Parameters
    ----------
    nodes : (V, 3) float64
    edges : (E, 2) int64
        Each edge once, no loops.
    r_node : (V,) float64
        Strut radius at each node (> 0).
    segments : int
        Sides of each strut's polygon (>= 3).
    sphere : int or None
        Icosphere subdivision level of the node spheres; None: no spheres (bare hulls of
        the rings and the node point).
    node_scale : float
        Node sphere radius over the strut radius.

    Returns
    -------
    vertices : (n, 3) float64
    faces : (f, 3) int64
        Outward-oriented triangles.
    parts : dict
        ``hull_volume`` (node hulls and joint unions, ring faces included), ``strut_volume``
        (analytic prisms between the rings), ``merged`` (nodes that joined another node's
        joint), ``joints`` (joints of several nodes, each a manifold3d union), ``rounds``.
    """
    g = _Geo(nodes, edges, r_node, int(segments), sphere, node_scale)
    E = g.E
    short = g.d_end[:E] + g.d_end[E:] > config.SOLID_RING_SPAN * g.length
    joins = edges[short]
    for rounds in range(1, _MAX_ROUNDS + 1):
        label = _components(g.V, joins)
        out = _assemble(g, label)
        if out[0] is None:  # node pairs that must share a joint: join them and retry
            joins = np.vstack([joins, out[1]])
            continue
        verts, faces, hull_vol, d, n_joints = out
        a, b = edges[:, 0], edges[:, 1]
        h = g.length - d[:E] - d[E:]
        ext = label[a] != label[b]
        area0 = ring_area(g.k)
        a1, a2 = area0 * r_node[a] ** 2, area0 * r_node[b] ** 2
        strut_vol = float(np.sum((h / 3.0 * (a1 + a2 + np.sqrt(a1 * a2)))[ext]))
        parts = {
            "hull_volume": hull_vol,
            "strut_volume": strut_vol,
            "merged": int(g.V - len(np.unique(label))),
            "joints": n_joints,
            "rounds": rounds,
        }
        return verts, faces, parts
    raise ValueError(
        "lattice: could not place strut rings (struts nearly parallel and short?); "
        "try a smaller radius"
    )


def _place_rings(g, vs, ces):
    """Ring distances at nodes ``vs`` (their external ends ``ces``), all nodes at once.

    Each end starts at its closed-form distance (or where a conflict pushed it), then the
    exact two-ring solution for every pair at its node, then grows until nothing else at the
    node (its sphere, the other rings) reaches the ring's plane. Returns ``(dd, ok)``: per
    node the distances, or where an end outgrew its strut, the ends that failed.
    """
    S = len(vs)
    M = max((len(c) for c in ces), default=0)
    out_dd: list = [None] * S
    if M == 0:
        return [np.zeros(0)] * S, [True] * S
    idx = np.zeros((S, M), dtype=np.int64)
    valid = np.zeros((S, M), dtype=bool)
    for s_, c in enumerate(ces):
        idx[s_, : len(c)] = c
        valid[s_, : len(c)] = True
    far = (idx + g.E) % (2 * g.E)
    vv = np.asarray(vs)
    dirs = g.end_dir[idx]  # (S, M, 3)
    ed = g.end_edge[idx]
    rr = np.broadcast_to(g.r_node[vv][:, None], (S, M))
    dd = np.maximum(g.d_end[idx], g.d_push[idx])
    cap = g.len_end[idx] - np.maximum(g.d_end[far], g.d_push[far]) - 0.02 * g.len_end[idx]
    cij = np.clip(np.einsum("smk,snk->smn", dirs, dirs), -1.0, 1.0)  # dir_i . dir_j
    pv = valid[:, :, None] & valid[:, None, :] & ~np.eye(M, dtype=bool)[None]
    # the exact two-ring solution for every pair: a start near the fixed point
    sin = np.sqrt(np.maximum(1.0 - cij * cij, 0.0))
    bij = rr[:, None, :] * sin + 0.05 * rr[:, :, None]
    cp = np.maximum(cij, 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        pair = (bij + cp * np.swapaxes(bij, 1, 2)) / (1.0 - cp * cp)
    pair = np.where(pv & np.isfinite(pair), pair, -np.inf)
    dd = np.where(valid, np.maximum(dd, np.minimum(pair.max(axis=2), cap)), 0.0)
    # reach along dir_i of ring j's offsets, and of the node's sphere
    off = rr[:, :, None, None] * (
        g.cs[None, None, :, None] * g.p[ed][:, :, None, :]
        + g.sn[None, None, :, None] * g.q[ed][:, :, None, :]
    )  # (S, M, k, 3)
    off_reach = np.einsum("sjtk,sik->sijt", off, dirs).max(axis=3)
    sph = g.sphere_r[vv][:, None] * (dirs @ g.unit.T).max(axis=2)  # (S, M)
    margin = 1e-3 * rr
    active = np.ones(S, dtype=bool)
    ok = np.zeros(S, dtype=bool)
    failed = np.zeros((S, M), dtype=bool)
    for _ in range(40):
        a_ = np.flatnonzero(active)
        if len(a_) == 0:
            break
        reach = dd[a_, None, :] * cij[a_] + off_reach[a_]  # ring j along dir_i
        reach = np.where(pv[a_], reach, -np.inf)
        need = np.maximum(reach.max(axis=2), sph[a_])
        bad = (need > dd[a_] - margin[a_]) & valid[a_]
        done = ~bad.any(axis=1)
        ok[a_[done]] = True
        active[a_[done]] = False
        a2, bad2, need2 = a_[~done], bad[~done], need[~done]
        dd[a2] = np.where(bad2, need2 * 1.02 + 0.02 * rr[a2] + margin[a2], dd[a2])
        over = (dd[a2] > cap[a2]) & valid[a2]
        stop = over.any(axis=1)
        failed[a2[stop]] = over[stop]
        active[a2[stop]] = False
    for s_, c in enumerate(ces):
        m = len(c)
        if ok[s_] or m == 0:
            out_dd[s_] = dd[s_, :m].copy()
        else:  # outgrown: those ends; out of iterations: all of them
            f = failed[s_, :m]
            out_dd[s_] = c[f] if f.any() else c
    return out_dd, [bool(ok[s_]) or len(c) == 0 for s_, c in enumerate(ces)]


def _node_piece(g, v, ce, dd, coarse=False):
    """Node ``v``'s convex hull: its sphere and its external ends' rings ``ce`` at ``dd``.

    Returns ``(pts, simp, on_ring, n_in, dd, eq, volume)`` or ``(None, failed_ends)``.
    """
    k = g.k
    inner = g.nodes[v] + g.sphere_r[v] * (g.unit_joint if coarse else g.unit)
    m = len(ce)
    if m == 0 and not g.has_sphere:
        return (np.zeros((0, 3)), np.zeros((0, 3), np.int64), None, 0, None, None, 0.0)
    pts = inner
    if m:
        ed = g.end_edge[ce]
        offs = g.r_node[v] * (
            g.cs[None, :, None] * g.p[ed][:, None, :] + g.sn[None, :, None] * g.q[ed][:, None, :]
        )
        rings = g.nodes[v] + dd[:, None, None] * g.end_dir[ce][:, None, :] + offs
        pts = np.vstack([inner, rings.reshape(-1, 3)])
    try:
        hull = ConvexHull(pts)
    except QhullError:
        return (None, ce)
    simp = _outward(hull, pts)
    n_in = len(inner)
    ring_of = np.full(len(pts), -1, dtype=np.int64)
    ring_of[n_in:] = np.repeat(np.arange(m), k)
    ro = ring_of[simp]
    on_ring = (ro[:, 0] >= 0) & (ro[:, 0] == ro[:, 1]) & (ro[:, 1] == ro[:, 2])
    if m:
        per_ring = np.bincount(ro[on_ring, 0], minlength=m)
        used = np.zeros(len(pts), dtype=bool)
        used[simp[~on_ring].ravel()] = True
        if (per_ring != k - 2).any() or not used[n_in:].all():
            return (None, ce)
    return (pts, simp, on_ring, n_in, dd, hull.equations, float(hull.volume))


def _assemble(g, label):
    """One build pass: ``(verts, faces, hull_volume, d, joints)``, or ``(None, pairs)``."""
    E, k = g.E, g.k
    edges = g.edges
    a, b = edges[:, 0], edges[:, 1]
    ext_edge = label[a] != label[b]
    external = np.concatenate([ext_edge, ext_edge])
    cnt = np.bincount(label)
    ext_ends = np.flatnonzero(external)
    eo = np.argsort(g.end_node[ext_ends], kind="stable")
    ext_sorted = ext_ends[eo]
    ext_start = np.concatenate([[0], np.cumsum(np.bincount(g.end_node[ext_ends], minlength=g.V))])
    d = g.d_end.copy()
    pieces = [None] * g.V
    fail: list[np.ndarray] = []
    # node hulls, cached by what they depend on: the external ends and their pushes
    keys, todo = [], []
    for v in range(g.V):
        ce = ext_sorted[ext_start[v] : ext_start[v + 1]]
        far = (ce + E) % (2 * E)
        coarse = bool(cnt[label[v]] > 1)
        key = (v, coarse, ce.tobytes(), g.d_push[ce].tobytes(), g.d_push[far].tobytes())
        keys.append((key, ce))
        if key not in g.cache:
            todo.append(v)
    if todo:
        dds, oks = _place_rings(g, todo, [keys[v][1] for v in todo])
        for v, dd, ok in zip(todo, dds, oks, strict=True):
            key, ce = keys[v]
            g.cache[key] = _node_piece(g, v, ce, dd, key[1]) if ok else (None, dd)
    for v in range(g.V):
        key, ce = keys[v]
        out = g.cache[key]
        if out[0] is None:
            fail.append(edges[g.end_edge[out[1]]])
            continue
        pieces[v] = out
        if len(ce):
            d[ce] = out[4]
    if fail:
        return None, np.vstack(fail)
    pairs, pushed = _conflicts(g, label, pieces, d)
    if len(pairs) or pushed:
        return None, pairs
    # joints of several nodes: manifold3d unions of their hulls and inner struts
    verts: list[np.ndarray] = []
    faces: list[np.ndarray] = []
    ring_idx = np.full((2 * E, k), -1, dtype=np.int64)
    base = 0
    hull_vol = 0.0
    ring_k = np.arange(k)
    for v in np.flatnonzero(cnt[label] == 1):
        pts, simp, on_ring, n_in, _, _, vol = pieces[v]
        ce = ext_sorted[ext_start[v] : ext_start[v + 1]]
        hull_vol += vol
        verts.append(pts)
        faces.append(simp[~on_ring] + base)
        ring_idx[ce] = base + n_in + np.arange(len(ce))[:, None] * k + ring_k[None, :]
        base += len(pts)
    multi = np.flatnonzero(cnt > 1)
    if len(multi):
        members = np.argsort(label, kind="stable")
        start = np.concatenate([[0], np.cumsum(cnt)])
        inner_e = np.flatnonzero(~ext_edge)
        ie_lab = label[a[inner_e]]
        io = np.argsort(ie_lab, kind="stable")
        ie_start = np.concatenate([[0], np.cumsum(np.bincount(ie_lab, minlength=len(cnt)))])
        fail = []
        for c in multi:
            cn = members[start[c] : start[c + 1]]
            ie = inner_e[io[ie_start[c] : ie_start[c + 1]]]
            ce = np.concatenate([ext_sorted[ext_start[v] : ext_start[v + 1]] for v in cn])
            out = _joint(g, cn, ie, ce, pieces)
            if out[0] is None:
                fail.append(edges[g.end_edge[out[1]]])
                continue
            jv, jf, jring, vol = out
            hull_vol += vol
            verts.append(jv)
            faces.append(jf + base)
            ring_idx[ce] = jring + base
            base += len(jv)
        if fail:
            return None, np.vstack(fail)
    # struts: prisms between the two rings of each external edge
    ext_e = np.flatnonzero(ext_edge)
    ra = ring_idx[ext_e]
    rb = ring_idx[ext_e + E]
    ra1 = np.roll(ra, -1, axis=1)
    rb1 = np.roll(rb, -1, axis=1)
    t1 = np.stack([ra, ra1, rb1], axis=-1).reshape(-1, 3)
    t2 = np.stack([ra, rb1, rb], axis=-1).reshape(-1, 3)
    all_v = np.vstack(verts) if verts else np.zeros((0, 3))
    all_f = np.vstack([*faces, t1, t2]) if faces else np.zeros((0, 3), np.int64)
    return all_v, all_f, hull_vol, d, len(multi)


def _joint(g, cn, ie, ce, pieces):
    """The union of a joint's node hulls and inner struts, ring faces removed.

    Returns ``(verts, faces, ring_index (len(ce), k), volume)``, or ``(None, bad_ends)``
    when a ring face did not come through the union intact.
    """
    import manifold3d as mf

    k = g.k
    parts = []
    rings = []
    for v in cn:
        pts, simp, _, n_in, _, _, _ = pieces[v]
        if len(simp) == 0:
            continue
        used = np.unique(simp)
        remap = np.full(len(pts), -1, dtype=np.int64)
        remap[used] = np.arange(len(used))
        mesh = mf.Mesh64(
            vert_properties=np.ascontiguousarray(pts[used]),
            tri_verts=np.ascontiguousarray(remap[simp], dtype=np.uint64),
        )
        parts.append(mf.Manifold(mesh))
        if len(pts) > n_in:
            rings.append(pts[n_in:].reshape(-1, k, 3))
    nodes = g.nodes
    for e in ie:
        ea, eb = g.edges[e]
        # an inner strut from inside one node's sphere to inside the other's (none where
        # the spheres already cover it: fewer coincident faces for the union)
        s0, s1 = 0.5 * g.sphere_r[ea], 0.5 * g.sphere_r[eb]
        if g.length[e] <= s0 + s1:
            continue
        off = g.cs[:, None] * g.p[e][None, :] + g.sn[:, None] * g.q[e][None, :]
        ring = np.vstack(
            [
                nodes[ea] + s0 * g.u[e] + g.r_node[ea] * off,
                nodes[eb] - s1 * g.u[e] + g.r_node[eb] * off,
            ]
        )
        parts.append(mf.Manifold.hull_points(ring))
    union = mf.Manifold.batch_boolean(parts, mf.OpType.Add)
    out = union.to_mesh64()
    verts = np.asarray(out.vert_properties, dtype=np.float64)[:, :3]
    tris = np.asarray(out.tri_verts, dtype=np.int64)
    vol = float(union.volume())
    # the rings' vertices must come back bit for bit, their faces as whole polygons
    ring_pts = np.vstack(rings).reshape(-1, 3)
    allv = np.vstack([verts, ring_pts])
    _, first, inv = np.unique(allv, axis=0, return_index=True, return_inverse=True)
    inv = inv.ravel()
    ridx = first[inv[len(verts) :]]
    ridx = np.where(ridx < len(verts), ridx, -1).reshape(-1, k)
    m = len(ce)
    bad = (ridx < 0).any(axis=1)
    owner = np.full(len(verts), -1, dtype=np.int64)
    good = np.flatnonzero(~bad)
    owner[ridx[good].ravel()] = np.repeat(good, k)
    to = owner[tris]
    cap = (to[:, 0] >= 0) & (to[:, 0] == to[:, 1]) & (to[:, 1] == to[:, 2])
    per = np.bincount(to[cap, 0], minlength=m)
    t = verts[tris[cap]]
    nrm = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
    area = np.bincount(to[cap, 0], 0.5 * np.einsum("ij,ij->i", nrm, g.end_dir[ce][to[cap, 0]]), m)
    want = ring_area(k) * g.r_node[g.end_node[ce]] ** 2
    bad |= (per != k - 2) | (np.abs(area - want) > 1e-9 * want)
    if bad.any():
        return None, ce[bad]
    return verts, tris[~cap], ridx, vol


def _seg_dist(p1, q1, p2, q2) -> np.ndarray:
    """Distances between segments ``p1 q1`` and ``p2 q2`` (rows; points allowed)."""
    d1, d2, r = q1 - p1, q2 - p2, p1 - p2
    a = np.einsum("ij,ij->i", d1, d1)
    e = np.einsum("ij,ij->i", d2, d2)
    f = np.einsum("ij,ij->i", d2, r)
    c = np.einsum("ij,ij->i", d1, r)
    bb = np.einsum("ij,ij->i", d1, d2)
    tiny = 1e-300
    den = a * e - bb * bb
    with np.errstate(divide="ignore", invalid="ignore"):
        s = np.where(
            den > 1e-14 * a * e, np.clip((bb * f - c * e) / np.maximum(den, tiny), 0, 1), 0.0
        )
        t = (bb * s + f) / np.maximum(e, tiny)
        s = np.where(t < 0, np.clip(-c / np.maximum(a, tiny), 0, 1), s)
        s = np.where(t > 1, np.clip((bb - c) / np.maximum(a, tiny), 0, 1), s)
        t = np.clip(t, 0, 1)
        # a point as the first segment: s = 0 and t the projection; as the second: t = 0
        pt1, pt2 = a <= tiny, e <= tiny
        s = np.where(pt1, 0.0, np.where(pt2, np.clip(-c / np.maximum(a, tiny), 0, 1), s))
        t = np.where(pt2, 0.0, np.where(pt1, np.clip(f / np.maximum(e, tiny), 0, 1), t))
    return np.linalg.norm(p1 + s[:, None] * d1 - p2 - t[:, None] * d2, axis=1)


def _box_pairs(lo, hi) -> np.ndarray:
    """Index pairs ``(i < j)`` of overlapping axis-aligned boxes (uniform-grid buckets)."""
    n = len(lo)
    ext = (hi - lo).max(axis=1)
    cell = max(2.0 * float(np.median(ext)), 1e-300)
    o = lo.min(axis=0)
    c0 = np.floor((lo - o) / cell).astype(np.int64)
    c1 = np.floor((hi - o) / cell).astype(np.int64)
    nx = c1 - c0 + 1
    cnt = nx.prod(axis=1)
    owner = np.repeat(np.arange(n), cnt)
    local = np.arange(int(cnt.sum())) - np.repeat(np.cumsum(cnt) - cnt, cnt)
    nxo = nx[owner]
    ix = c0[owner, 0] + local % nxo[:, 0]
    iy = c0[owner, 1] + (local // nxo[:, 0]) % nxo[:, 1]
    iz = c0[owner, 2] + local // (nxo[:, 0] * nxo[:, 1])
    dim = c1.max(axis=0) + 1
    key = (iz * dim[1] + iy) * dim[0] + ix
    order = np.argsort(key, kind="stable")
    key, owner = key[order], owner[order]
    new = np.concatenate([[True], key[1:] != key[:-1]])
    gid = np.cumsum(new) - 1
    gend = np.flatnonzero(np.concatenate([new[1:], [True]])) + 1
    m = gend[gid] - np.arange(len(key)) - 1
    i = np.repeat(np.arange(len(key)), m)
    j = i + 1 + (np.arange(int(m.sum())) - np.repeat(np.cumsum(m) - m, m))
    pi, pj = owner[i], owner[j]
    pi, pj = np.minimum(pi, pj), np.maximum(pi, pj)
    keep = pi != pj
    pk = np.unique(pi[keep] * n + pj[keep])
    pi, pj = pk // n, pk % n
    over = ((lo[pi] <= hi[pj]) & (lo[pj] <= hi[pi])).all(axis=1)
    return np.stack([pi[over], pj[over]], axis=1)


def _conflicts(g, label, pieces, d) -> np.ndarray:
    """Node pairs that must share a joint: pieces of different joints that may touch.

    The pieces are the node hulls, the strut prisms between the rings, and the inner struts
    of joints. Candidates come from box overlaps; a pair is clear when a cheap sufficient test
    separates it (capsule distances, bounding balls, a hull facet with the other piece
    wholly outside). Legitimate contacts are exempt: a prism with its own two hulls (it
    starts on their ring faces), prisms leaving one hull (extrusions of two faces of a convex
    body), and the pieces of one joint (their union is taken).
    """
    E = g.E
    a, b = g.edges[:, 0], g.edges[:, 1]
    ext = label[a] != label[b]
    r_min = float(g.r_node.min())
    margin = 1e-3 * r_min
    hv = np.array([v for v in range(g.V) if pieces[v] is not None and len(pieces[v][1])])
    pe = np.flatnonzero(ext)
    fe = np.flatnonzero(~ext)
    h = g.length[pe] - d[pe] - d[pe + E]
    too_short = h <= 0.01 * g.length[pe]
    if too_short.any():
        return g.edges[pe[too_short]], False
    nh, npr = len(hv), len(pe)
    kind = np.concatenate([np.zeros(nh, int), np.ones(npr, int), np.full(len(fe), 2)])
    A = np.vstack([g.nodes[hv], g.nodes[a[pe]] + d[pe, None] * g.u[pe], g.nodes[a[fe]]])
    B = np.vstack([g.nodes[hv], g.nodes[b[pe]] - d[pe + E, None] * g.u[pe], g.nodes[b[fe]]])
    ee = np.concatenate([pe, fe])
    rho_e = np.maximum(g.r_node[a[ee]], g.r_node[b[ee]])
    R = np.array([np.linalg.norm(pieces[v][0] - g.nodes[v], axis=1).max() for v in hv])
    rho = np.concatenate([R.reshape(-1), rho_e])
    n1 = np.concatenate([hv, a[ee]]).astype(np.int64)
    n2 = np.concatenate([hv, b[ee]]).astype(np.int64)
    lo = np.minimum(A, B) - rho[:, None] - margin
    hi = np.maximum(A, B) + rho[:, None] + margin
    if nh:
        hb = np.array([pieces[v][0].min(axis=0) for v in hv])
        ht = np.array([pieces[v][0].max(axis=0) for v in hv])
        lo[:nh], hi[:nh] = hb - margin, ht + margin
    pairs = _box_pairs(lo, hi)
    if len(pairs) == 0:
        return np.zeros((0, 2), np.int64), False
    i, j = pairs[:, 0], pairs[:, 1]  # i < j: kinds ordered hull < prism < inner strut
    ki, kj = kind[i], kind[j]
    share = (n1[i] == n1[j]) | (n1[i] == n2[j]) | (n2[i] == n1[j]) | (n2[i] == n2[j])
    same_joint = (ki != 1) & (kj != 1) & (label[n1[i]] == label[n1[j]])
    # a prism may touch what it shares a node with only when that is a hull or a prism leaving
    # it (an inner strut at the same node is tested)
    exempt = same_joint | (share & (ki != 2) & (kj != 2) & ((ki == 1) | (kj == 1)))
    i, j, ki, kj = i[~exempt], j[~exempt], ki[~exempt], kj[~exempt]
    dist = _seg_dist(A[i], B[i], A[j], B[j])
    clear = dist > rho[i] + rho[j] + margin
    # what the capsules do not clear: two convex polytopes, separated when a facet of one
    # has all the other's vertices outside (a sufficient test, tight for these shapes)
    memo: dict = {}

    def sig(t):  # what a piece's polytope depends on (pairs found clear stay clear)
        if t < nh:
            return id(pieces[hv[t]])
        if t < nh + npr:
            e = pe[t - nh]
            return (e, float(d[e]), float(d[e + E]))
        return (fe[t - nh - npr],)

    for t in np.flatnonzero(~clear):
        key = (sig(i[t]), sig(j[t]))
        if key in g.clear:
            clear[t] = True
            continue
        vi, qi = _polytope(g, pieces, hv, pe, fe, d, i[t], memo)
        vj, qj = _polytope(g, pieces, hv, pe, fe, d, j[t], memo)
        if ((vj @ qi[:, :3].T + qi[:, 3]) > margin).all(axis=0).any():
            clear[t] = True
        elif ((vi @ qj[:, :3].T + qj[:, 3]) > margin).all(axis=0).any():
            clear[t] = True
        if clear[t]:
            g.clear.add(key)
    i, j = i[~clear], j[~clear]
    # a prism that meets another piece of a joint it leaves: push its ring out past that
    # piece (a ring face beyond which the piece lies wholly behind) if the strut is long
    # enough; anything else joins the pieces' nodes into one joint
    join = []
    pushed = False
    for x, y in zip(i.tolist(), j.tolist(), strict=True):
        done = False
        for s_, o_ in ((x, y), (y, x)):
            if kind[s_] != 1:
                continue
            e = pe[s_ - nh]
            for end, node in ((e, a[e]), (e + E, b[e])):
                if label[node] not in (label[n1[o_]], label[n2[o_]]):
                    continue
                vo, _ = _polytope(g, pieces, hv, pe, fe, d, o_, memo)
                reach = float(((vo - g.nodes[node]) @ g.end_dir[end]).max())
                new = reach + 0.05 * g.r_node[node]
                far = (end + E) % (2 * E)
                if new <= g.length[e] - d[far] - 0.02 * g.length[e]:
                    g.d_push[end] = max(g.d_push[end], new)
                    pushed = done = True
                    break
            if done:
                break
        if not done:
            join.append((n1[x], n1[y]))
            join.append((n1[x], n2[x]))
            join.append((n1[y], n2[y]))
    return np.array(join, dtype=np.int64).reshape(-1, 2), pushed


def _polytope(g, pieces, hv, pe, fe, d, t, memo):
    """Vertices and facet planes ``(n, offset)``, outward unit ``n``, of conflict piece ``t``."""
    hit = memo.get(t)
    if hit is not None:
        return hit
    memo[t] = out = _polytope_of(g, pieces, hv, pe, fe, d, t)
    return out


def _polytope_of(g, pieces, hv, pe, fe, d, t):
    nh, npr = len(hv), len(pe)
    if t < nh:
        pc = pieces[hv[t]]
        return pc[0], pc[5]
    e = pe[t - nh] if t < nh + npr else fe[t - nh - npr]
    ea, eb = g.edges[e]
    u = g.u[e]
    if t < nh + npr:
        A, B = g.nodes[ea] + d[e] * u, g.nodes[eb] - d[e + g.E] * u
    else:
        A, B = g.nodes[ea], g.nodes[eb]
    off = g.cs[:, None] * g.p[e][None, :] + g.sn[:, None] * g.q[e][None, :]
    ra, rb = A + g.r_node[ea] * off, B + g.r_node[eb] * off
    n = np.cross(np.roll(ra, -1, axis=0) - ra, rb - ra)
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    n *= np.sign(np.einsum("ij,ij->i", n, ra - A))[:, None]
    eq = np.vstack(
        [
            np.column_stack([n, -np.einsum("ij,ij->i", n, ra)]),
            [[*(-u), u @ A], [*u, -(u @ B)]],
        ]
    )
    return np.vstack([ra, rb]), eq


def ring_area(k: int) -> float:
    """Area of the unit-circumradius regular ``k``-gon (a strut's cross-section / r**2)."""
    return 0.5 * k * math.sin(2.0 * math.pi / k)


def _outward(hull, pts) -> np.ndarray:
    """Qhull's triangles, each turned to face along its facet's outward normal."""
    simp = hull.simplices.astype(np.int64)
    tri = pts[simp]
    nrm = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    flip = np.einsum("ij,ij->i", nrm, hull.equations[:, :3]) < 0
    simp[flip] = simp[flip][:, ::-1]
    return simp


def convex_mesh(points):
    """The convex hull of ``points`` as an outward-oriented Trimesh (no repair passes)."""
    import trimesh

    pts = np.asarray(points, dtype=np.float64)
    m = trimesh.Trimesh(pts, _outward(ConvexHull(pts), pts), process=False)
    m.remove_unreferenced_vertices()
    return m
