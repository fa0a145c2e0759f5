"""Issue 12: many-faced cells (a helix, three orthogonal lines) built once, not twice.

A chunk whose cells mostly overflow their output slots gives the next chunks slots for the
counts it saw (``engine.slots3d.grown_caps``); before, every such cell was built in its
chunk, thrown away, and built again alone. These check that the cells come out the same bit
for bit as built alone (growth off), that most of them are no longer built alone, and the
diagram against voro++ and its own invariants.
"""

from __future__ import annotations

import numpy as np
import pytest

import voroforge as vf
from catalogue3d import helix, three_lines
from reference3d import VOROPP, voropp_volumes
from voroforge.engine import build3d, slots3d
from voroforge.engine.slots3d import grown_caps
from voroforge.kernels.cells3d import OK, OVERFLOW

BOX = (0.0, 0.0, 0.0, 1.0, 1.0, 1.0)


def _counting(monkeypatch):
    """Count the cells built alone (``slots3d.big_cell``)."""
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
    assert a.centroids.tobytes() == b.centroids.tobytes()
    for x, y in zip(a.neighbors, b.neighbors, strict=True):
        assert (x == y).all()
    for k in range(0, len(a.volumes), 37):
        pa, pb = a.cell(k), b.cell(k)
        assert [r.tolist() for r in pa.faces] == [r.tolist() for r in pb.faces]


@pytest.mark.parametrize(("name", "pts"), [("helix", helix(400)), ("lines3", three_lines(300))])
def test_grown_slots_give_the_cells_built_alone(monkeypatch, name, pts):
    """With growth the diagram is bit for bit the one whose cells were all built alone."""
    seen = _counting(monkeypatch)
    a = vf.voronoi3d(pts, BOX)
    grown_alone = len(seen)
    monkeypatch.setattr(slots3d, "GROW_LEAST", 10**9)
    monkeypatch.setattr(build3d, "probe_caps", lambda caps: caps)  # (the probe's big slots)
    seen.clear()
    b = vf.voronoi3d(pts, BOX)
    alone = len(seen)
    _same(a, b)
    # without growth nearly every cell overflowed and was built twice; with it only the
    # few past the grown slots (the first chunk, the lists' probe, has big slots)
    assert alone > 0.8 * len(pts)
    assert grown_alone < 0.35 * alone


def test_grown_helix_invariants_and_voropp():
    pts = helix(500)
    d = vf.voronoi3d(pts, BOX)
    assert d.unmatched_vertices == 0
    assert abs(d.volumes.sum() - 1.0) < 1e-12
    assert (d.volumes > 0).all()
    off, nb = d.neighbors
    pairs = {(i, int(j)) for i in range(len(pts)) for j in nb[off[i] : off[i + 1]] if j >= 0}
    assert all((j, i) in pairs for i, j in pairs)
    assert np.diff(off).mean() > 80  # the many-faced cells this is about
    if VOROPP:
        v = voropp_volumes(pts, BOX)
        assert np.abs(v - d.volumes).max() < 1e-5 * d.volumes.max()  # voro++'s 6 digits


def test_grown_caps_rule():
    base = build3d.CAPS
    n = 64
    status = np.full(n, OK)
    counts = np.tile([40, 20, 150], (n, 1))
    assert grown_caps(status, counts, base, base, n) is None  # nothing overflowed
    status[:7] = OVERFLOW
    counts[:7] = [300, 150, 900]
    assert grown_caps(status, counts, base, base, n) is None  # fewer than GROW_LEAST
    status[:16] = OVERFLOW
    counts[:16] = [300, 150, 900]
    counts[3] = [0, 0, 0]  # its scratch overflowed: no counts
    g = grown_caps(status, counts, base, base, n)
    assert g[:3] == (375, 188, 1125) and g[6:] == base[6:]
    assert all(g[3 + q] * base[q] >= base[3 + q] * g[q] for q in range(3))  # scratch in step
    assert grown_caps(status, counts, g, base, n) is None  # already fits
    counts[:16] = [10**5, 10**4, 10**6]
    g = grown_caps(status, counts, base, base, n)
    assert g[:3] == tuple(16 * c for c in base[:3])  # at most GROW_MOST times the base
    assert grown_caps(status, counts, base, base, 10**5) is None  # slots past GROW_BYTES
