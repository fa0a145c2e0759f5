"""Issue 12: many-faced 3D cells (a helix, three lines) built once, and planes beyond the box.

``engine.build3d``: the first chunk (the lists' probe, 64 cells) gets output slots as large
as the kernel's scratch (``slots3d.probe_caps``), the growth from it is padded more
(``slots3d.probe_grown``), and where grown slots would pass ``GROW_BYTES`` the chunks are
made smaller (``slots3d.chunk_room``) instead of the slots not growing: three lines of
1,500 built 455 of their cells twice (the rest of a chunk's build thrown away, the cell
built again alone), none now. A cell's result does not depend on its slots, so the diagram
is the one whose cells were all built alone, bit for bit.

``kernels.climb3d.box_misses``: a plane beyond the cell's bounding box (found once, kept
through cuts) by more than a few bands has every vertex's float value below the band: the
full pass's decision, without a climb.
"""

from __future__ import annotations

import numpy as np
import pytest

import voroforge as vf
from catalogue3d import helix, three_lines
from voroforge.engine import build3d, slots3d
from voroforge.engine.containers import box_template
from voroforge.kernels import climb3d, graph3d
from voroforge.kernels.cells3d import OK, OVERFLOW

BOX = (0.0, 0.0, 0.0, 1.0, 1.0, 1.0)
CAP = 4096


def test_probe_caps_and_chunk_room():
    base = build3d.CAPS
    probe = slots3d.probe_caps(base)
    assert probe[:3] == base[3:6] and probe[3:] == base[3:]  # the scratch unchanged
    # the slots of a chunk of chunk_room cells (nsl sets) stay within GROW_BYTES
    for caps in (base, slots3d.probe_caps(base), tuple(16 * c for c in base[:3]) + base[3:]):
        for nsl in (1, 2):
            k = slots3d.chunk_room(caps, nsl, 4096)
            assert k <= 4096 and k >= slots3d.GROW_CHUNK_LEAST
            assert k == slots3d.GROW_CHUNK_LEAST or nsl * slots3d.slot_bytes(k, caps) <= (
                slots3d.GROW_BYTES
            )
    assert slots3d.chunk_room(base, 1, 1024) == 1024  # small slots: the chunk as asked


def test_probe_grown_rule():
    base = build3d.CAPS
    n = 64
    status = np.full(n, OK)
    counts = np.tile([40, 20, 150], (n, 1))
    assert slots3d.probe_grown(status, counts, base, 1) is None  # every cell fits base
    counts[:16] = [300, 150, 900]  # fit the probe's slots, not base's: they would overflow
    g = slots3d.probe_grown(status, counts, base, 2)
    pad = slots3d.GROW_PAD * slots3d.GROW_PROBE_PAD
    assert g[:3] == tuple(int(np.ceil(c * pad)) for c in (300, 150, 900))
    assert g[6:] == base[6:]
    status[20] = OVERFLOW  # past the scratch: no counts, not counted
    counts[20] = [0, 0, 0]
    assert slots3d.probe_grown(status, counts, base, 2) == g


def _counting(monkeypatch):
    seen = []
    real = slots3d.big_cell

    def counted(*a):
        seen.append(int(a[0]))
        return real(*a)

    monkeypatch.setattr(build3d, "big_cell", counted)
    return seen


def _same(a, b):
    assert a.vertices.tobytes() == b.vertices.tobytes()
    assert a.volumes.tobytes() == b.volumes.tobytes()
    for x, y in zip(a.neighbors, b.neighbors, strict=True):
        assert (x == y).all()
    assert a.face_areas.tobytes() == b.face_areas.tobytes()
    for k in range(0, len(a.volumes), 29):
        pa, pb = a.cell(k), b.cell(k)
        assert [r.tolist() for r in pa.faces] == [r.tolist() for r in pb.faces]


@pytest.mark.parametrize(("name", "pts"), [("helix", helix(400)), ("lines3", three_lines(450))])
def test_many_faced_cells_built_once(monkeypatch, name, pts):
    """No cell is built alone, and the diagram is the one of cells all built alone."""
    seen = _counting(monkeypatch)
    a = vf.voronoi3d(pts, BOX)
    assert seen == []
    # growth and the probe's big slots off: the cells past CAPS' slots are built alone
    monkeypatch.setattr(slots3d, "GROW_LEAST", 10**9)
    monkeypatch.setattr(build3d, "probe_caps", lambda caps: caps)
    b = vf.voronoi3d(pts, BOX)
    assert len(seen) > 0.8 * len(pts)
    _same(a, b)
    assert a.unmatched_vertices == 0 and abs(a.volumes.sum() - 1.0) <= 1e-12


def test_small_chunks_where_slots_are_big(monkeypatch):
    """Grown slots past GROW_BYTES make the chunks smaller, not the cells built twice."""
    pts = three_lines(900)
    monkeypatch.setattr(slots3d, "GROW_BYTES", 2**22)  # ~60 cells of three lines' slots
    seen = _counting(monkeypatch)
    rooms = []
    real = build3d.chunk_room

    def room(*a):
        rooms.append(real(*a))
        return rooms[-1]

    monkeypatch.setattr(build3d, "chunk_room", room)
    a = vf.voronoi3d(pts, BOX)
    assert rooms and min(rooms) < 256  # the chunks shrank
    assert len(seen) < 0.05 * len(pts)
    monkeypatch.undo()
    _same(a, vf.voronoi3d(pts, BOX))


def _tangent_cell(n, seed):
    """The box [-1, 1]^3 cut as a graph by the bisectors of ``n`` sites at distance ~1.6."""
    rng = np.random.default_rng(seed)
    u = rng.normal(size=(n, 3))
    u /= np.linalg.norm(u, axis=1)[:, None]
    u *= rng.uniform(1.5, 1.7, (n, 1))
    t = box_template(-np.ones(3), np.ones(3))
    V = np.zeros((CAP, 3))
    V[:8] = t.TV
    F = np.zeros((CAP, 3), np.int64)
    F[:6] = t.TF
    R = np.zeros(4 * CAP, np.int64)
    R[:24] = t.TR
    G = [np.zeros(CAP, np.int32)] + [np.zeros((CAP, 24), np.int32) for _ in range(3)]
    assert graph3d.from_rings(8, F, 6, R, *G)
    FL = np.zeros(CAP, np.bool_)
    CP = np.zeros((CAP, 3), np.int64)
    S = np.zeros(CAP)
    nv = 8
    boxes = []
    for k in range(n):
        a = u[k]
        h = 0.5 * float(a @ a)
        S[:nv] = V[:nv] @ a - h
        st, nv2, _ = graph3d.cut(V, nv, *G, FL, S, CP, k)
        assert st in (graph3d.GCUT_DONE, graph3d.GCUT_NONE)
        nv = nv2 if st == graph3d.GCUT_DONE else nv
        if k % 50 == 0:
            boxes.append(climb3d.cell_box(V, nv))  # boxes of the cell before later cuts
    return V, nv, boxes


@pytest.mark.parametrize("seed", [1, 2])
def test_box_misses_only_below_the_band(seed):
    V, nv, boxes = _tangent_cell(300, seed)
    assert nv > 150
    boxes.append(climb3d.cell_box(V, nv))
    lo, hi = V[:nv].min(axis=0), V[:nv].max(axis=0)
    assert boxes[-1] == (lo[0], hi[0], lo[1], hi[1], lo[2], hi[2])
    rng = np.random.default_rng(seed)
    r2 = float((V[:nv] ** 2).sum(axis=1).max())
    said = 0
    for k in range(3000):
        u = rng.normal(size=3)
        u /= np.linalg.norm(u)
        top = float((V[:nv] @ u).max())
        # beyond the top by a few bands or by much; through the cell; just inside the top
        f = (1e-12 * rng.uniform(0, 12), rng.uniform(0, 1), -1e-12 * rng.uniform(0, 8))[k % 3]
        d = top * (1.0 + f) if k % 3 != 1 else top * (0.5 + 2 * f)
        if d <= 0:
            continue
        q = 2.0 * d * u
        d2 = float(q @ q)
        h = 0.5 * d2
        tol = 1e-12 * (np.sqrt(d2 * r2) + abs(h))
        full = q[0] * V[:nv, 0] + q[1] * V[:nv, 1] + q[2] * V[:nv, 2] - h
        for box in boxes:
            if climb3d.box_misses(box, q[0], q[1], q[2], h, tol):
                said += 1
                assert full.max() < -tol  # the full pass passes the plane over
    assert said > 500
