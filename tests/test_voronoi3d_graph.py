"""The vertex-graph cut (kernels/graph3d) against the face-ring cut (kernels/polyhedron).

Both cut the same box by the same planes, one after the other: random planes, planes through
a vertex, through an edge and along a face (the degenerate cases the cell builder meets on
lattices). After every cut the two polyhedra must be the same: status, vertex coordinates
(as sets), face labels (as multisets), volume; the graph's rings must be closed (every edge
twice, once each way) with Euler's V - E + F = 2. The graph may refuse a cut (the builder
then falls back to the face rings), but never on these inputs.
"""

from __future__ import annotations

import numpy as np

from voroforge.engine.containers import box_template
from voroforge.kernels import graph3d, polyhedron

CAP = 256


def _start():
    t = box_template(np.zeros(3), np.ones(3))
    V = np.zeros((CAP, 3))
    V[:8] = t.TV
    F = np.zeros((CAP, 3), np.int64)
    F[:6] = t.TF
    R = np.zeros(4 * CAP, np.int64)
    R[:24] = t.TR
    # the engine's dtypes (cellcut3d.graph_scratch): the kernels compiled once, as it runs them
    deg = np.zeros(CAP, np.int32)
    ed, bk, lb = (np.zeros((CAP, 24), np.int32) for _ in range(3))
    assert graph3d.from_rings(8, F, 6, R, deg, ed, bk, lb)
    ring = (V, 8, F, 6, R)
    graph = (V.copy(), 8, deg, ed, bk, lb)
    return ring, graph


def _rings_of_graph(graph):
    V, nv, deg, ed, bk, lb = graph
    F = np.zeros((CAP, 3), np.int64)
    R = np.zeros(4 * CAP, np.int64)
    seen = np.zeros((CAP, 24), np.bool_)
    nf = graph3d.to_rings(nv, deg, ed, bk, lb, F, R, seen)
    assert nf > 0
    return F, nf, R


def _polyhedron_summary(V, nv, F, nf, R):
    vol = polyhedron.moments(V, F, nf, R)[0]
    verts = np.unique(V[:nv], axis=0)
    labels = np.sort(F[:nf, 0])
    return vol, verts, labels


def _closed(nv, F, nf, R):
    edges = set()
    for f in range(nf):
        r = R[F[f, 1] : F[f, 1] + F[f, 2]].tolist()
        for a, b in zip(r, r[1:] + r[:1], strict=False):
            assert (a, b) not in edges
            edges.add((a, b))
    assert all((b, a) in edges for a, b in edges)
    used = {a for a, _ in edges}
    assert len(used) - len(edges) // 2 + nf == 2


def _plane(rng, V, nv, kind):
    n = rng.normal(size=3)
    if kind == "edge" and nv >= 2:  # through two vertices
        a, b = rng.choice(nv, 2, replace=False)
        n = np.cross(V[b] - V[a], rng.normal(size=3))
        return n, float(n[0] * V[a, 0] + n[1] * V[a, 1] + n[2] * V[a, 2])
    if kind == "vertex":
        v = rng.integers(nv)
        return n, float(n[0] * V[v, 0] + n[1] * V[v, 1] + n[2] * V[v, 2])
    if kind == "axis":  # axis-aligned through a vertex: along a face of the box
        n = np.zeros(3)
        n[rng.integers(3)] = rng.choice([-1.0, 1.0])
        v = rng.integers(nv)
        return n, float(n @ V[v])
    s = V[:nv] @ n
    return n, float(rng.uniform(s.min(), s.max()))


def test_graph_cut_matches_face_ring_cut():
    rng = np.random.default_rng(3)
    kinds = ("random", "vertex", "edge", "axis")
    checked = 0
    for seq in range(40):
        (V, nv, F, nf, R), (GV, gnv, deg, ed, bk, lb) = _start()
        R2 = np.zeros_like(R)
        work = np.zeros((4 * CAP, 4), np.int64)
        S = np.zeros(CAP)
        GS = np.zeros(CAP)
        CP = np.zeros((CAP, 3), np.int64)
        FL = np.zeros(CAP, np.bool_)
        for step in range(14):
            kind = kinds[(seq + step) % 4] if seq % 2 else "random"
            n, h = _plane(rng, V, nv, kind)
            scale = np.abs(V[:nv]).sum(axis=1).max()
            tol = 1e-12 * (np.linalg.norm(n) * scale + abs(h))
            polyhedron.plane_values(V, nv, n[0], n[1], n[2], h, tol, S)
            polyhedron.plane_values(GV, gnv, n[0], n[1], n[2], h, tol, GS)
            if (S[:nv] < 0).sum() < 4:
                continue  # would leave (nearly) nothing: not a cut the builder makes
            st, nv2, nf2 = polyhedron.cut(V, nv, F, nf, R, R2, S, work, 100 + step)
            gst, gnv2, _ = graph3d.cut(GV, gnv, deg, ed, bk, lb, FL, GS, CP, 100 + step)
            assert gst != graph3d.GCUT_BROKEN, (seq, step, kind)
            assert (st, gst) in {
                (polyhedron.CUT_NONE, graph3d.GCUT_NONE),
                (polyhedron.CUT_DONE, graph3d.GCUT_DONE),
            }, (seq, step, kind, st, gst)
            if st == polyhedron.CUT_NONE:
                continue
            nv, nf, gnv = nv2, nf2, gnv2
            GF, gnf, GR = _rings_of_graph((GV, gnv, deg, ed, bk, lb))
            _closed(gnv, GF, gnf, GR)
            a = _polyhedron_summary(V, nv, F, nf, R)
            b = _polyhedron_summary(GV, gnv, GF, gnf, GR)
            assert abs(a[0] - b[0]) <= 1e-12 * abs(a[0]), (seq, step, kind)
            assert a[1].shape == b[1].shape and np.allclose(a[1], b[1], rtol=0, atol=1e-12)
            assert (a[2] == b[2]).all(), (seq, step, kind)
            checked += 1
    assert checked > 200


def test_cells_that_fall_back_to_face_rings(monkeypatch):
    """With room for only 3 edges a vertex, lattice cells fall back to the face-ring cut.

    An FCC lattice's rhombic dodecahedra have vertices of degree 4 (every cell falls back),
    a BCC lattice's cells meet planes through their vertices while they are cut (most fall
    back). The cells must come out the same as with the graph: volumes, neighbours, vertices.
    """
    import voroforge as vf
    from catalogue3d import _bcc, _fcc
    from voroforge.engine import build3d

    cases = [(_fcc(3) + 0.25, (0, 0, 0, 3, 3, 3)), (_bcc(3) + 0.25, (0, 0, 0, 3, 3, 3))]
    for pts, box in cases:
        a = vf.voronoi3d(pts, box)
        monkeypatch.setattr(build3d, "CAPS", build3d.CAPS[:6] + (3,))
        b = vf.voronoi3d(pts, box)
        monkeypatch.undo()
        assert np.abs(a.volumes - b.volumes).max() <= 1e-12 * a.volumes.max()
        for x, y in zip(a.neighbors, b.neighbors, strict=True):
            assert (x == y).all()
        assert len(a.vertices) == len(b.vertices) and b.unmatched_vertices == 0


def test_cells_past_their_slots_are_built_again_in_place(monkeypatch):
    """Cells past their slots are built again alone and joined in their place.

    With slots for 28 vertices and 16 faces, 51 of these 300 cells overflow; the face table
    must stay in build order and the diagram be the same.
    """
    import voroforge as vf
    from voroforge.engine import build3d

    pts = np.random.default_rng(4).random((300, 3))
    a = vf.voronoi3d(pts, (0, 0, 0, 1, 1, 1))
    monkeypatch.setattr(build3d, "CAPS", (28, 16, 100) + build3d.CAPS[3:])
    b = vf.voronoi3d(pts, (0, 0, 0, 1, 1, 1))
    monkeypatch.undo()
    assert (a.volumes == b.volumes).all()
    assert (a.vertices == b.vertices).all()
    for x, y in zip(a.neighbors, b.neighbors, strict=True):
        assert (x == y).all()
    for k in (0, 57, 299):
        pa, pb = a.cell(k), b.cell(k)
        assert [r.tolist() for r in pa.faces] == [r.tolist() for r in pb.faces]
        assert (pa.neighbors == pb.neighbors).all()
