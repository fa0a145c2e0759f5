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
from typing import NamedTuple

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import ConvexHull, QhullError

from .. import config
from ..engine.bitmix import splitmix64
from ..engine.csr import used_only
from .check import fill_pockets
from .conflicts import conflicts

__all__ = ["hull_lattice"]

_MAX_ROUNDS = 12
_BLOCK = 1 << 18  # triangles per block of the node hulls' checks


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
        self.piece: list = [None] * self.V  # each node's latest hull (see _assemble)
        self.built = None  # what the hulls were built from
        self.pockets = (0, 0.0)  # cavities of the joints' unions filled, their volume


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
        joint), ``joints`` (joints of several nodes, each a manifold3d union), ``rounds``,
        ``pockets`` and ``pocket_volume`` (cavities smaller than a strut's diameter that the
        joints' unions enclosed, filled).
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
            "pockets": g.pockets[0],
            "pocket_volume": g.pockets[1],
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


class _Piece(NamedTuple):
    """A node's convex hull: its sphere points, then its external ends' rings (``k`` each)."""

    pts: np.ndarray
    simp: np.ndarray  # outward triangles
    on_ring: np.ndarray  # triangles of ring faces (removed: the prisms start there)
    n_in: int  # sphere points
    dd: np.ndarray  # ring distances of the external ends
    eq: np.ndarray  # facet planes (outward unit normal, offset) per triangle
    volume: float
    R: float  # farthest point from the node
    lo: np.ndarray  # bounding box
    hi: np.ndarray


_EMPTY = _Piece(
    np.zeros((0, 3)), np.zeros((0, 3), np.int64), np.zeros(0, bool), 0, np.zeros(0),
    np.zeros((0, 4)), 0.0, 0.0, np.zeros(3), np.zeros(3),
)  # fmt: skip


def _node_pieces(g, vs, ces, dds, coarse):
    """Convex hulls of nodes ``vs``: each its sphere and its external ends' rings.

    ``ces``/``dds``: per node its external ends and their ring distances; ``coarse``: per
    node whether it takes the joint sphere. The points are made and the hulls checked for all
    nodes at once; only Qhull runs per node. Returns per node a :class:`_Piece`, or
    ``(None, failed_ends)`` when a ring did not come back as a face of the hull.
    """
    k = g.k
    vs = np.asarray(vs, dtype=np.int64)
    S = len(vs)
    m = np.array([len(c) for c in ces], dtype=np.int64)
    coarse = np.asarray(coarse, dtype=bool)
    n_in = np.where(coarse, len(g.unit_joint), len(g.unit))
    empty = (m == 0) & (not g.has_sphere)
    n_in[empty] = 0
    npts = n_in + m * k
    start = np.concatenate([[0], np.cumsum(npts)])
    pts = np.zeros((int(start[-1]), 3))
    # sphere points
    for unit, sel in ((g.unit_joint, coarse & ~empty), (g.unit, ~coarse & ~empty)):
        w = np.flatnonzero(sel)
        if len(w):
            blk = start[w][:, None] + np.arange(len(unit))[None, :]
            v = vs[w]
            pts[blk] = g.nodes[v][:, None, :] + g.sphere_r[v][:, None, None] * unit[None]
    # rings, in each node's end order
    ce = np.concatenate([np.asarray(c, dtype=np.int64) for c in ces]) if S else np.zeros(0, int)
    if len(ce):
        dd = np.concatenate(dds)
        owner = np.repeat(np.arange(S), m)
        ed = g.end_edge[ce]
        v = vs[owner]
        off = g.cs[None, :, None] * g.p[ed][:, None, :] + g.sn[None, :, None] * g.q[ed][:, None, :]
        ring = (
            g.nodes[v][:, None, :]
            + dd[:, None, None] * g.end_dir[ce][:, None, :]
            + g.r_node[v][:, None, None] * off
        )
        slot = np.arange(len(ce)) - np.repeat(np.cumsum(m) - m, m)  # end within its node
        first = start[owner] + n_in[owner] + slot * k
        rows = first[:, None] + np.arange(k)[None, :]
        pts[rows] = ring
    ring_of = np.full(len(pts), -1, dtype=np.int64)  # global end slot of each ring point
    if len(ce):
        ring_of[rows] = np.arange(len(ce))[:, None]
    # Qhull per node: the only loop
    simps, eqs, vols, tcount = [], [], np.zeros(S), np.zeros(S, dtype=np.int64)
    qfail = np.zeros(S, dtype=bool)
    for s_ in range(S):
        if empty[s_]:
            continue
        try:
            hull = ConvexHull(pts[start[s_] : start[s_ + 1]])
        except QhullError:
            qfail[s_] = True
            continue
        simps.append(hull.simplices + start[s_])
        eqs.append(hull.equations)
        vols[s_] = hull.volume
        tcount[s_] = len(hull.simplices)
    simp = np.vstack(simps).astype(np.int64) if simps else np.zeros((0, 3), np.int64)
    eq = np.vstack(eqs) if eqs else np.zeros((0, 4))
    tstart = np.concatenate([[0], np.cumsum(tcount)])
    # outward orientation (Qhull's triangles come in either order), and the ring faces: in
    # blocks of triangles (bounded temporaries)
    on_ring = np.zeros(len(simp), dtype=bool)
    per_ring = np.zeros(len(ce), dtype=np.int64)
    used = np.zeros(len(pts), dtype=bool)
    for b0 in range(0, len(simp), _BLOCK):
        sb = simp[b0 : b0 + _BLOCK]
        p0, p1, p2 = pts[sb[:, 0]], pts[sb[:, 1]], pts[sb[:, 2]]
        nrm = np.cross(p1 - p0, p2 - p0)
        flip = np.einsum("ij,ij->i", nrm, eq[b0 : b0 + _BLOCK, :3]) < 0
        sb[flip] = sb[flip][:, ::-1]
        # each ring a face: exactly k - 2 triangles over its own points, every ring point used
        ro = ring_of[sb]
        onr = (ro[:, 0] >= 0) & (ro[:, 0] == ro[:, 1]) & (ro[:, 1] == ro[:, 2])
        on_ring[b0 : b0 + _BLOCK] = onr
        per_ring += np.bincount(ro[onr, 0], minlength=len(ce))
        used[sb[~onr].ravel()] = True
    bad_end = per_ring != k - 2
    if len(ce):
        bad_end |= ~used[rows].all(axis=1)
    bad = qfail.copy()
    if len(ce):
        bad |= np.bincount(owner, bad_end, minlength=S) > 0
    # bounds per node (segments of pts; an empty node's segment borrows a neighbour's row)
    cut = np.minimum(start[:-1], max(len(pts) - 1, 0))
    if len(pts):
        lo = np.minimum.reduceat(pts, cut)
        hi = np.maximum.reduceat(pts, cut)
        rad = np.sqrt(np.maximum.reduceat(((pts - g.nodes[np.repeat(vs, npts)]) ** 2).sum(1), cut))
    simp -= np.repeat(start[:-1], tcount)[:, None]  # local to each node
    out: list = []
    e0 = 0
    for s_ in range(S):
        e1 = e0 + int(m[s_])
        if bad[s_]:
            out.append((None, ce[e0:e1]))
        elif empty[s_]:
            out.append(_EMPTY)
        else:
            t0, t1 = tstart[s_], tstart[s_ + 1]
            out.append(
                _Piece(
                    pts[start[s_] : start[s_ + 1]],
                    simp[t0:t1],
                    on_ring[t0:t1],
                    int(n_in[s_]),
                    dds[s_],
                    eq[t0:t1],
                    float(vols[s_]),
                    float(rad[s_]),
                    lo[s_],
                    hi[s_],
                )  # fmt: skip
            )
        e0 = e1
    return out


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
    # node hulls, rebuilt where what they depend on changed: their external ends, the pushes
    # of those ends (near and far) and the sphere (coarse in joints)
    far_all = (np.arange(2 * E) + E) % (2 * E)
    coarse = cnt[label] > 1
    push, push_far = g.d_push, g.d_push[far_all]
    if g.built is None:
        todo = np.arange(g.V)
    else:
        p_ext, p_push, p_far, p_coarse = g.built
        moved = (external != p_ext) | (
            (external | p_ext) & ((push != p_push) | (push_far != p_far))
        )
        todo = np.flatnonzero((coarse != p_coarse) | (np.bincount(g.end_node, moved, g.V) > 0))
    g.built = (external, push.copy(), push_far, coarse)
    if len(todo):
        ces = [ext_sorted[ext_start[v] : ext_start[v + 1]] for v in todo]
        dds, oks = _place_rings(g, todo, ces)
        hv = [i for i, ok in enumerate(oks) if ok]
        built = _node_pieces(
            g, todo[hv], [ces[i] for i in hv], [dds[i] for i in hv], coarse[todo[hv]]
        )
        for i, ok in enumerate(oks):
            if not ok:
                g.piece[todo[i]] = (None, dds[i])
        for i, pc in zip(hv, built, strict=True):
            g.piece[todo[i]] = pc
    for v in range(g.V):
        out = g.piece[v]
        if out[0] is None:
            fail.append(edges[g.end_edge[out[1]]])
            continue
        pieces[v] = out
        if len(out.dd):
            d[ext_sorted[ext_start[v] : ext_start[v + 1]]] = out.dd
    if fail:
        return None, np.vstack(fail)
    pairs, pushed = conflicts(g, label, pieces, d)
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
        pc = pieces[v]
        pts, simp, on_ring, n_in, vol = pc.pts, pc.simp, pc.on_ring, pc.n_in, pc.volume
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
        groups = [
            (members[start[c] : start[c + 1]], inner_e[io[ie_start[c] : ie_start[c + 1]]])
            for c in multi
        ]
        cn_all = np.concatenate([cn for cn, _ in groups])
        ce = np.concatenate([ext_sorted[ext_start[v] : ext_start[v + 1]] for v in cn_all])
        out = _joints(g, groups, ce, pieces)
        if out[0] is None:
            return None, edges[g.end_edge[out[1]]]
        jv, jf, jring, vol = out
        hull_vol += vol
        verts.append(jv)
        faces.append(jf + base)
        ring_idx[ce] = jring + base
        base += len(jv)
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
    all_v, all_f = used_only(all_v, all_f)  # drop the sphere points no hull triangle uses
    return all_v, all_f, hull_vol, d, len(multi)


def _joints(g, groups, ce, pieces):
    """The union of each joint's node hulls and inner struts, ring faces removed.

    ``groups``: per joint its nodes and inner edges; ``ce``: the joints' external ends in the
    order of their nodes. Each joint is one manifold3d batch union (one union of all joints
    costs twice as much: it unions large composed meshes); pieces of different joints never
    touch (the conflict pass), so their meshes are concatenated (manifold3d's ``compose``
    costs a third of the unions) and checked at once.
    Returns ``(verts, faces, ring_index (len(ce), k), volume)``, or ``(None, bad_ends)``
    when a ring face did not come through its union intact.
    """
    import manifold3d as mf

    k = g.k
    # every joint node's hull as a compact mesh (its unused inner sphere points dropped), made
    # for all nodes at once
    cn_all = np.concatenate([cn for cn, _ in groups])
    pcs = [pieces[v] for v in cn_all]
    npts = np.array([len(pc.pts) for pc in pcs])
    ntri = np.array([len(pc.simp) for pc in pcs])
    p0 = np.concatenate([[0], np.cumsum(npts)])
    P = np.vstack([pc.pts for pc in pcs])
    T = np.vstack([pc.simp for pc in pcs]) + np.repeat(p0[:-1], ntri)[:, None]
    used = np.zeros(len(P), dtype=bool)
    used[T.ravel()] = True
    newid = np.cumsum(used) - 1
    c0 = np.concatenate([[0], np.cumsum(used)])[p0]  # compact start of each node
    T = (newid[T] - np.repeat(c0[:-1], ntri)[:, None]).astype(np.uint64)
    P = P[used]
    t0 = np.concatenate([[0], np.cumsum(ntri)])
    rings = np.vstack([pc.pts[pc.n_in :] for pc in pcs])
    struts = _inner_struts(g, np.concatenate([ie for _, ie in groups]))
    unions = []
    vol = 0.0
    at = st = 0
    for cn, ie in groups:
        parts = []
        for x in range(at, at + len(cn)):
            if ntri[x]:
                mesh = mf.Mesh64(P[c0[x] : c0[x + 1]], T[t0[x] : t0[x + 1]])
                parts.append(mf.Manifold(mesh))
        at += len(cn)
        parts.extend(x for x in struts[st : st + len(ie)] if x is not None)
        st += len(ie)
        union = mf.Manifold.batch_boolean(parts, mf.OpType.Add)
        out = union.to_mesh64()
        # copies: the manifold and its mesh (several arrays per triangle) go at once
        v = np.array(np.asarray(out.vert_properties)[:, :3], dtype=np.float64)
        unions.append((v, np.array(out.tri_verts, dtype=np.int64)))
        vol += union.volume()
        del union, out
    nv = np.cumsum([0] + [len(v) for v, _ in unions])
    verts = np.vstack([v for v, _ in unions])
    tris = np.vstack([t + o for (_, t), o in zip(unions, nv, strict=False)])
    del unions
    tris, filled, count = fill_pockets(verts, tris, 2.0 * float(g.r_node.min()))
    vol += filled
    g.pockets = (count, filled)
    # the rings' vertices must come back bit for bit, their faces as whole polygons
    ridx = _find_rows(verts, rings).reshape(-1, k)
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


def _inner_struts(g, ie):
    """Manifolds of the inner struts ``ie`` of joints (None where a strut is left out).

    Prisms from inside one node's sphere to inside the other's; none where the spheres
    already cover the strut (fewer coincident faces for the union).
    """
    import manifold3d as mf

    ea, eb = g.edges[ie, 0], g.edges[ie, 1]
    s0, s1 = 0.5 * g.sphere_r[ea], 0.5 * g.sphere_r[eb]
    off = g.cs[None, :, None] * g.p[ie][:, None, :] + g.sn[None, :, None] * g.q[ie][:, None, :]
    u = g.u[ie][:, None, :]
    r0 = g.nodes[ea][:, None, :] + s0[:, None, None] * u + g.r_node[ea][:, None, None] * off
    r1 = g.nodes[eb][:, None, :] - s1[:, None, None] * u + g.r_node[eb][:, None, None] * off
    pts = np.concatenate([r0, r1], axis=1)
    keep = (g.length[ie] > s0 + s1).tolist()
    return [mf.Manifold.hull_points(x) if ok else None for x, ok in zip(pts, keep, strict=True)]


def _row_hash(a) -> np.ndarray:
    """A 64-bit hash of each row's three float64 bit patterns."""
    u = np.ascontiguousarray(a, dtype=np.float64).view(np.uint64).reshape(-1, 3)
    h = splitmix64(u[:, 0].copy())
    h = splitmix64(h ^ u[:, 1])
    return splitmix64(h ^ u[:, 2])


def _find_rows(table, rows) -> np.ndarray:
    """Index in ``table`` of each of ``rows`` found bit for bit (first match), else -1.

    Rows are looked up by a 64-bit hash (sorted stably: equal hashes keep the table's
    order) and compared exactly; the rare run of equal hashes is searched in full.
    """
    out = np.full(len(rows), -1, dtype=np.int64)
    if len(table) == 0 or len(rows) == 0:
        return out
    ht = _row_hash(table)
    order = np.argsort(ht, kind="stable")
    hs = ht[order]
    hr = _row_hash(rows)
    lo = np.searchsorted(hs, hr, side="left")
    hi = np.searchsorted(hs, hr, side="right")
    one = hi - lo == 1
    cand = order[np.minimum(lo, len(hs) - 1)]
    ok = one & (table[cand] == rows).all(axis=1)
    out[ok] = cand[ok]
    for q in np.flatnonzero(hi - lo > 1):  # equal hashes: the first exact match
        for c in order[lo[q] : hi[q]]:
            if (table[c] == rows[q]).all():
                out[q] = c
                break
    return out


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
