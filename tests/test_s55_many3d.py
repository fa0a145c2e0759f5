"""Issue 12: many-faced 3D cells (a helix, three lines) built once.

``engine.build3d``: the first chunk (the lists' probe, 64 cells) gets output slots as large
as the kernel's scratch (``slots3d.probe_caps``), the growth from it is padded more
(``slots3d.probe_grown``), and where grown slots would pass ``GROW_BYTES`` the chunks are
made smaller (``slots3d.chunk_room``) instead of the slots not growing: three lines of
1,500 built 455 of their cells twice (the rest of a chunk's build thrown away, the cell
built again alone), none now. A cell's result does not depend on its slots, so the diagram
is the one whose cells were all built alone, bit for bit.
"""

from __future__ import annotations

import numpy as np
import pytest

import voroforge as vf
from catalogue3d import helix, three_lines
from test_issue12_helix4 import _counting, _same
from voroforge.engine import build3d, slots3d
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
