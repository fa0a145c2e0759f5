"""Issue 12: the exact solves about a site in registers (kernels/vertexdd3d.vertex_dd_site, s58).

A many-faced cell's vertices are mostly ill-conditioned (a helix's: 91% of its Delaunay
tetrahedra have a relative determinant below ``VORONOI3D_EXACT_DET_RTOL``, three lines'
98%), so the cut's re-solve and the naming solve them exactly about a site, through
:func:`.predicates3d.vertex_offset`, whose cache lookup cost more than the double-double
solve. :func:`vertex_dd_site` is that solve without scratch or cache; where it answers it
must give ``vertex_offset``'s bits (the determinants' nearest doubles), on sites of a
helix, of three lines, nearly coplanar ones, weighted ones and with container walls.
"""

from __future__ import annotations

import numpy as np

from catalogue3d import helix, three_lines
from voroforge.engine.containers import box_template
from voroforge.kernels import predicates3d
from voroforge.kernels.vertexdd3d import vertex_dd_site


def _queries(rng, n, count, ns, nwall):
    """Site ``a`` and three distinct owners: sites near ``a`` in index (near-parallel
    planes on a curve), random sites, and walls."""
    out = []
    for k in range(count):
        a = int(rng.integers(ns))
        if k % 3 == 0:
            ks = a + rng.choice([-3, -2, -1, 1, 2, 3, 40, -40], 3, replace=False)
        elif k % 3 == 1:
            ks = rng.integers(0, ns, 3)
        else:
            ks = np.r_[rng.integers(0, ns, 2), ns + rng.integers(0, nwall, 1)]
        ks = [int(x) for x in ks]
        if min(ks) < 0 or max(ks) >= ns + nwall:  # (an index past the sites: a wall)
            continue
        if a in ks or len(set(ks)) < 3:
            continue
        out.append((a, *ks))
    return out


def test_site_solve_is_vertex_offsets_bits():
    rng = np.random.default_rng(12)
    t = box_template(np.zeros(3), np.ones(3))
    WP = np.ascontiguousarray(t.WP, dtype=np.float64)
    buf = predicates3d.scratch()
    x = np.zeros(3)
    cases = [helix(600), three_lines(600), rng.random((300, 3))]
    flat = rng.random((200, 3))
    flat[:, 2] = 0.5 + 1e-9 * flat[:, 2]  # nearly coplanar
    cases.append(flat)
    answered = total = 0
    for k, pts in enumerate(cases):
        P = np.ascontiguousarray(pts, dtype=np.float64)
        W = np.zeros(len(P)) if k != 2 else 1e-3 * rng.random(len(P))
        ns = len(P)
        for a, k0, k1, k2 in _queries(rng, ns, 600, ns, WP.shape[0]):
            ok, x0, x1, x2 = vertex_dd_site(a, k0, k1, k2, P, W, WP, ns)
            x[:] = np.nan
            want = predicates3d.vertex_offset(
                a, k0, k1, k2, P, W, WP, ns, buf, P[a, 0], P[a, 1], P[a, 2], x
            )
            total += 1
            if ok:
                answered += 1
                assert want
                got = np.array([x0, x1, x2])
                assert got.tobytes() == x.tobytes(), (k, a, k0, k1, k2, got, x)
    assert total > 1500
    assert answered > 0.7 * total  # (helix, lines: most; random and near-flat: fewer)
