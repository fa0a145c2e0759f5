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

_MAX_ROUNDS = 3


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


def _clusters(n_nodes, edges, short) -> np.ndarray:
    if not short.any():
        return np.arange(n_nodes)
    e = edges[short]
    g = coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(n_nodes, n_nodes))
    return connected_components(g, directed=False)[1]


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
        ``hull_volume`` (sum of node hull volumes), ``strut_volume`` (analytic prisms),
        ``merged`` (nodes merged into hulls of several nodes), ``rounds``.
    """
    k = int(segments)
    V, E = len(nodes), len(edges)
    a, b = edges[:, 0], edges[:, 1]
    vec = nodes[b] - nodes[a]
    length = np.linalg.norm(vec, axis=1)
    u = vec / length[:, None]
    p, q = _frames(u)
    phi = 2.0 * np.pi * np.arange(k) / k
    cs, sn = np.cos(phi), np.sin(phi)
    unit = _unit_sphere(sphere) if sphere is not None else np.zeros((1, 3))
    sphere_r = r_node * (node_scale if sphere is not None else 0.0)

    # strut ends: end j < E sits at a (direction u), end E + j at b (direction -u)
    end_node = np.concatenate([a, b])
    end_dir = np.concatenate([u, -u])
    end_edge = np.concatenate([np.arange(E), np.arange(E)])
    r_end = r_node[end_node]
    d_end = _ring_distance(end_node, end_dir, r_end, sphere_r, V)
    short = d_end[:E] + d_end[E:] > config.SOLID_RING_SPAN * length

    for rounds in range(1, _MAX_ROUNDS + 1):
        label = _clusters(V, edges, short)
        cnt = np.bincount(label)  # checked before the build: a percolating merge fails fast
        if cnt.max() > 1:  # merged hulls must stay local (else the short edges percolate)
            mean = np.stack([np.bincount(label, nodes[:, i]) / cnt for i in range(3)], axis=1)
            spread = np.linalg.norm(nodes - mean[label], axis=1).max()
            if spread > config.SOLID_HULL_SPREAD * r_node.max():
                raise ValueError(
                    f"lattice: short struts merge nodes up to {spread:.3g} apart "
                    f"({spread / r_node.max():.1f} radii); the hull route needs cleaner cells"
                )
        out = _assemble(
            nodes,
            edges,
            length,
            u,
            p,
            q,
            cs,
            sn,
            unit,
            sphere_r,
            r_node,
            label,
            end_node,
            end_dir,
            end_edge,
            d_end,
            k,
        )
        if isinstance(out, np.ndarray):  # failed edges: merge their nodes and retry
            short = short | out
            continue
        verts, faces, hull_vol, d = out
        h = length - d[:E] - d[E:]
        ext = label[a] != label[b]
        area0 = 0.5 * k * np.sin(2.0 * np.pi / k)
        a1, a2 = area0 * r_node[a] ** 2, area0 * r_node[b] ** 2
        strut_vol = float(np.sum((h / 3.0 * (a1 + a2 + np.sqrt(a1 * a2)))[ext]))
        parts = {
            "hull_volume": hull_vol,
            "strut_volume": strut_vol,
            "merged": int(V - len(np.unique(label))),
            "rounds": rounds,
        }
        return verts, faces, parts
    raise ValueError(
        "lattice: could not place strut rings (struts nearly parallel and short?); "
        "try a smaller radius"
    )


def _assemble(
    nodes, edges, length, u, p, q, cs, sn, unit, sphere_r, r_node, label,
    end_node, end_dir, end_edge, d_end, k,
):  # fmt: skip
    """One build pass; returns the mesh, or a bool mask of edges whose nodes must merge."""
    E = len(edges)
    a, b = edges[:, 0], edges[:, 1]
    external = np.concatenate([label[a] != label[b], label[a] != label[b]])
    d = d_end.copy()
    len_end = np.concatenate([length, length])
    # group nodes and external ends by cluster
    n_lab = label.max() + 1
    node_order = np.argsort(label, kind="stable")
    node_start = np.concatenate([[0], np.cumsum(np.bincount(label, minlength=n_lab))])
    ext_ends = np.flatnonzero(external)
    ext_lab = label[end_node[ext_ends]]
    eo = np.argsort(ext_lab, kind="stable")
    ext_sorted = ext_ends[eo]
    ext_start = np.concatenate([[0], np.cumsum(np.bincount(ext_lab, minlength=n_lab))])

    verts: list[np.ndarray] = []
    faces: list[np.ndarray] = []
    ring_base = np.full(2 * E, -1, dtype=np.int64)
    failed = np.zeros(E, dtype=bool)
    base = 0
    hull_vol = 0.0
    ring_k = np.arange(k)
    for c in range(n_lab):
        cn = node_order[node_start[c] : node_start[c + 1]]
        ce = ext_sorted[ext_start[c] : ext_start[c + 1]]
        inner = (nodes[cn, None, :] + sphere_r[cn, None, None] * unit[None]).reshape(-1, 3)
        m = len(ce)
        ed = end_edge[ce]
        dirs = end_dir[ce]
        rr = r_node[end_node[ce]]
        origin = nodes[end_node[ce]]
        offs = rr[:, None, None] * (
            cs[None, :, None] * p[ed][:, None, :] + sn[None, :, None] * q[ed][:, None, :]
        )
        dd = d[ce]
        # an end may grow up to what the far end (final if built, else its minimum) leaves
        cap = len_end[ce] - d[(ce + E) % (2 * E)] - 0.02 * len_end[ce]
        ok = m == 0
        if m > 1:  # exact two-ring solution for every pair: a start near the fixed point
            c = np.clip(dirs @ dirs.T, -1.0, 1.0)
            sin = np.sqrt(np.maximum(1.0 - c * c, 0.0))
            # b[i, j]: reach of ring j (placed at its node) along u_i, from node i
            bij = (
                np.einsum("jk,ik->ij", origin, dirs) - np.einsum("ik,ik->i", origin, dirs)[:, None]
            )
            bij = bij + rr[None, :] * sin + 0.05 * rr[:, None]
            cp = np.maximum(c, 0.0)
            with np.errstate(divide="ignore", invalid="ignore"):
                pair = (bij + cp * bij.T) / (1.0 - cp * cp)
            np.fill_diagonal(pair, -np.inf)
            pair[~np.isfinite(pair)] = -np.inf
            dd = np.maximum(dd, np.minimum(pair.max(axis=1), cap))
        for _ in range(40):
            rings = origin[:, None, :] + dd[:, None, None] * dirs[:, None, :] + offs
            pts = np.vstack([inner, rings.reshape(-1, 3)])
            # reach of every point along every ring's direction, from that ring's node
            reach = pts @ dirs.T - np.einsum("ij,ij->i", origin, dirs)[None, :]
            own = np.arange(len(inner), len(pts))
            reach[own, np.repeat(np.arange(m), k)] = -np.inf
            need = reach.max(axis=0)
            margin = 1e-3 * rr
            bad = need > dd - margin
            if not bad.any():
                ok = True
                break
            dd = np.where(bad, need * 1.02 + 0.02 * rr + margin, dd)
            if (dd > cap).any():
                break
        if not ok:
            failed[ed[dd > cap] if (dd > cap).any() else ed] = True
            continue
        if m == 0:
            pts = inner
        try:
            hull = ConvexHull(pts)
        except QhullError:
            failed[ed] = True
            continue
        simp = _outward(hull, pts)
        n_in = len(inner)
        ring_of = np.full(len(pts), -1, dtype=np.int64)
        ring_of[n_in:] = np.repeat(np.arange(m), k)
        ro = ring_of[simp]
        on_ring = (ro[:, 0] >= 0) & (ro[:, 0] == ro[:, 1]) & (ro[:, 1] == ro[:, 2])
        per_ring = np.bincount(ro[on_ring, 0], minlength=m)
        used = np.zeros(len(pts), dtype=bool)
        used[simp[~on_ring].ravel()] = True
        if m and ((per_ring != k - 2).any() or not used[n_in:].all()):
            failed[ed] = True
            continue
        hull_vol += float(hull.volume)
        verts.append(pts)
        faces.append(simp[~on_ring] + base)
        ring_base[ce] = base + n_in + np.arange(m) * k
        d[ce] = dd
        base += len(pts)
    if failed.any():
        return failed
    # struts: prisms between the two rings of each external edge
    ext_e = np.flatnonzero(label[a] != label[b])
    ra = ring_base[ext_e][:, None] + ring_k[None, :]
    rb = ring_base[ext_e + E][:, None] + ring_k[None, :]
    ra1 = np.roll(ra, -1, axis=1)
    rb1 = np.roll(rb, -1, axis=1)
    t1 = np.stack([ra, ra1, rb1], axis=-1).reshape(-1, 3)
    t2 = np.stack([ra, rb1, rb], axis=-1).reshape(-1, 3)
    all_v = np.vstack(verts) if verts else np.zeros((0, 3))
    all_f = np.vstack([*faces, t1, t2]) if faces else np.zeros((0, 3), np.int64)
    return all_v, all_f, hull_vol, d


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
