"""The hull route's conflict pass: pieces of different joints that could touch.

The pieces of a hull lattice are the node hulls (:class:`voroforge.solid.hulls._Piece`), the
strut prisms between rings, and the inner struts of joints. Two pieces of different joints
must not touch (they are glued by nothing), so every candidate pair is either proved apart or
resolved: a prism pushes its ring out past the other piece, or the two pieces' nodes join one
joint. Every test is vectorised over the pairs; the only loop is over the pairs left touching.
"""

from __future__ import annotations

import numpy as np

from .kernels import box_pairs, separated

__all__ = ["conflicts"]


def conflicts(g, label, pieces, d):
    """Node pairs that must share a joint, and whether a ring was pushed out instead.

    Candidates come from box overlaps; a pair is clear when a cheap sufficient test separates
    it (capsule distances, bounding balls, a facet of one polytope with the other wholly
    outside). Legitimate contacts are exempt: a prism with its own two hulls (it starts on
    their ring faces), prisms leaving one hull (extrusions of two faces of a convex body), and
    the pieces of one joint (their union is taken). Returns ``(pairs (m, 2), pushed)``.
    """
    E = g.E
    a, b = g.edges[:, 0], g.edges[:, 1]
    ext = label[a] != label[b]
    r_min = float(g.r_node.min())
    margin = 1e-3 * r_min
    hv = np.array([v for v in range(g.V) if pieces[v] is not None and len(pieces[v].simp)], int)
    pe = np.flatnonzero(ext)
    fe = np.flatnonzero(~ext)
    h = g.length[pe] - d[pe] - d[pe + E]
    too_short = h <= 0.01 * g.length[pe]
    if too_short.any():
        return g.edges[pe[too_short]], False
    nh, npr = len(hv), len(pe)
    kind = np.concatenate([np.zeros(nh, int), np.ones(npr, int), np.full(len(fe), 2)])
    ee = np.concatenate([pe, fe])
    # struts as segments A-B: a prism between its rings, an inner strut node to node
    dA = np.concatenate([d[pe], np.zeros(len(fe))])
    dB = np.concatenate([d[pe + E], np.zeros(len(fe))])
    SA = g.nodes[a[ee]] + dA[:, None] * g.u[ee]
    SB = g.nodes[b[ee]] - dB[:, None] * g.u[ee]
    A = np.vstack([g.nodes[hv], SA])
    B = np.vstack([g.nodes[hv], SB])
    rho_e = np.maximum(g.r_node[a[ee]], g.r_node[b[ee]])
    rho = np.concatenate([np.array([pieces[v].R for v in hv]), rho_e])
    n1 = np.concatenate([hv, a[ee]]).astype(np.int64)
    n2 = np.concatenate([hv, b[ee]]).astype(np.int64)
    lo = np.minimum(A, B) - rho[:, None] - margin
    hi = np.maximum(A, B) + rho[:, None] + margin
    if nh:
        lo[:nh] = np.array([pieces[v].lo for v in hv]) - margin
        hi[:nh] = np.array([pieces[v].hi for v in hv]) + margin
    pairs = box_pairs(lo, hi)
    if len(pairs) == 0:
        return np.zeros((0, 2), np.int64), False
    i, j = pairs[:, 0], pairs[:, 1]  # i < j: kinds ordered hull < prism < inner strut
    ki, kj = kind[i], kind[j]
    share = (n1[i] == n1[j]) | (n1[i] == n2[j]) | (n2[i] == n1[j]) | (n2[i] == n2[j])
    same_joint = (ki != 1) & (kj != 1) & (label[n1[i]] == label[n1[j]])
    # a prism may touch what it shares a node with only when that is a hull or a prism leaving
    # it (an inner strut at the same node is tested)
    exempt = same_joint | (share & (ki != 2) & (kj != 2) & ((ki == 1) | (kj == 1)))
    i, j = i[~exempt], j[~exempt]
    dist = seg_dist(A[i], B[i], A[j], B[j])
    keep = dist <= rho[i] + rho[j] + margin
    i, j = i[keep], j[keep]
    if len(i) == 0:
        return np.zeros((0, 2), np.int64), False
    # what the capsules do not clear: two convex polytopes, separated when a facet of one
    # has all the other's vertices outside (a sufficient test, tight for these shapes)
    used = np.unique(np.concatenate([i, j]))
    vp, V, qp, Q = _polytopes(g, pieces, hv, ee, SA, SB, used)
    slot = np.full(len(kind), -1, dtype=np.int64)
    slot[used] = np.arange(len(used))
    si, sj = slot[i], slot[j]
    apart = separated(vp, V, qp, Q, sj, si, margin)
    apart[~apart] = separated(vp, V, qp, Q, si[~apart], sj[~apart], margin)
    i, j = i[~apart], j[~apart]
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
                vo = V[vp[slot[o_]] : vp[slot[o_] + 1]]
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


def _polytopes(g, pieces, hv, ee, SA, SB, used):
    """Vertices and facet planes of pieces ``used`` (CSR: ``vp, V, qp, Q``).

    A hull piece's are its points and Qhull's planes; a strut's, the prism over its two ring
    polygons (outward unit normal, offset: ``n . v + offset > 0`` outside).
    """
    nh = len(hv)
    k = g.k
    hs = used[used < nh]
    st = used[used >= nh] - nh
    Vs = [pieces[hv[t]].pts for t in hs.tolist()]
    Qs = [pieces[hv[t]].eq for t in hs.tolist()]
    nv = [len(x) for x in Vs] + [2 * k] * len(st)
    nq = [len(x) for x in Qs] + [k + 2] * len(st)
    if len(st):
        e = ee[st]
        ea, eb = g.edges[e, 0], g.edges[e, 1]
        off = g.cs[None, :, None] * g.p[e][:, None, :] + g.sn[None, :, None] * g.q[e][:, None, :]
        Aq, Bq = SA[st], SB[st]
        ra = Aq[:, None, :] + g.r_node[ea][:, None, None] * off
        rb = Bq[:, None, :] + g.r_node[eb][:, None, None] * off
        n = np.cross(np.roll(ra, -1, axis=1) - ra, rb - ra)
        n /= np.linalg.norm(n, axis=2, keepdims=True)
        n *= np.sign(np.einsum("sij,sij->si", n, ra - Aq[:, None, :]))[:, :, None]
        u = g.u[e]
        eq = np.concatenate(
            [
                np.concatenate([n, -np.einsum("sij,sij->si", n, ra)[:, :, None]], axis=2),
                np.concatenate([-u, np.einsum("ij,ij->i", u, Aq)[:, None]], axis=1)[:, None],
                np.concatenate([u, -np.einsum("ij,ij->i", u, Bq)[:, None]], axis=1)[:, None],
            ],
            axis=1,
        )
        Vs.append(np.concatenate([ra, rb], axis=1).reshape(-1, 3))
        Qs.append(eq.reshape(-1, 4))
    vp = np.concatenate([[0], np.cumsum(nv)]).astype(np.int64)
    qp = np.concatenate([[0], np.cumsum(nq)]).astype(np.int64)
    return vp, np.vstack(Vs), qp, np.vstack(Qs)


def seg_dist(p1, q1, p2, q2) -> np.ndarray:
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
