"""Each kernel sees one array type per argument on every engine path (one compile, not two).

numba types an array's writeable flag: a kernel handed a frozen diagram's array on one path
and a fresh one on another compiled a second specialisation with its whole call tree (a
cold test suite compiled ~30 kernels twice so). The engine hands such inputs through
``engine.readonly.readonly`` (read-only views, no copy), or writeable where the kernels they
share with another path get writeable ones (the power weights). Each test spies on the
kernel where the engine calls it and feeds the public path a writeable and a read-only input.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from numba import typeof, types

import voroforge as vf
from voroforge.engine.readonly import readonly


def _spy(monkeypatch, module, name):
    """The numba types of each call of ``module.name`` (called through, unchanged)."""
    seen = []
    kernel = getattr(module, name)

    def spy(*args):
        seen.append(tuple(typeof(a) for a in args))
        return kernel(*args)

    monkeypatch.setattr(module, name, spy)
    return seen


def _flagless(sig):
    return tuple(t.copy(readonly=False) if isinstance(t, types.Array) else t for t in sig)


def _no_flag_twins(seen):
    """No two signatures that differ only in arrays' writeable flags."""
    assert seen
    sigs = set(seen)
    assert len({_flagless(s) for s in sigs}) == len(sigs), sigs


def _frozen(a):
    a = np.array(a)
    a.setflags(write=False)
    return a


def test_readonly_is_a_view_and_leaves_the_callers_flag():
    a = np.arange(6.0).reshape(3, 2)
    r = readonly(a)
    assert not r.flags.writeable and a.flags.writeable
    assert np.shares_memory(a, r) and r.flags.c_contiguous
    col = readonly(a[:, 0], np.float64)  # strided: the contiguous copy, read-only
    assert not col.flags.writeable and (col == a[:, 0]).all()


def test_farthest_one_type_for_fresh_and_frozen_sites(monkeypatch):
    import voroforge.engine.planar as planar
    import voroforge.engine.power as power

    seen = _spy(monkeypatch, planar, "farthest")
    L = shapely.Polygon([(0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2)])
    pts = np.random.default_rng(0).random((40, 2)) * 0.9 + 0.05
    d = vf.voronoi(pts, L)  # a copy of the points: writeable
    # equal weights: the Voronoi cells of the sites as given (a diagram's: read-only)
    d2 = power.power_diagram(d.sites, np.zeros(len(pts)), power.make_domain(L, pts))
    assert not d.sites.flags.writeable and len(seen) == 2
    assert len(set(seen)) == 1, set(seen)
    assert np.array_equal(d.areas, d2.areas)


def test_uniform_moments_one_type_for_fresh_and_frozen_origins(monkeypatch):
    import voroforge.engine.integrate as integrate
    from voroforge.engine.diagram import buffers

    seen = _spy(monkeypatch, integrate, "uniform_moments")
    d = vf.voronoi(np.random.default_rng(1).random((30, 2)), (0, 0, 1, 1))
    ro = integrate.Integrator(None, len(d.sites)).scaled(buffers(d), d.sites)
    rw = integrate.Integrator(None, len(d.sites)).scaled(buffers(d), np.array(d.sites))
    assert len(seen) == 2 and len(set(seen)) == 1, set(seen)
    assert all(np.array_equal(a, b) for a, b in zip(ro, rw, strict=True))


def test_pairs_csr_one_type_for_any_pairs(monkeypatch):
    import voroforge.io.parquet as parquet

    seen = _spy(monkeypatch, parquet, "_pairs_csr")
    d = vf.voronoi(np.random.default_rng(2).random((20, 2)), (0, 0, 1, 1))
    pairs = d.edges.pairs
    assert not pairs.flags.writeable
    got = [parquet.neighbor_lists(p, 20) for p in (pairs, np.array(pairs), _frozen(pairs[:1]))]
    assert len(seen) == 3 and len(set(seen)) == 1, set(seen)
    assert all(np.array_equal(a, b) for a, b in zip(got[0], got[1], strict=True))


def test_power_weights_fresh_or_frozen_reach_the_kernels_as_the_voronoi_cells_pass_them(
    monkeypatch,
):
    import voroforge.engine.power as power

    seen = _spy(monkeypatch, power, "power_cells")
    pts = np.random.default_rng(3).random((40, 2))
    w = np.linspace(0.0, 0.01, len(pts))
    d = vf.power(pts, w)
    # a diagram's weights (read-only), as the fits pass them again
    d2 = power.power_diagram(pts, d.weights, power.make_domain(None, pts))
    assert not d.weights.flags.writeable and len(seen) == 2
    assert len(set(seen)) == 1, set(seen)
    # the Voronoi cells cut their hull cells with power.box_cell and writeable zero weights
    # (kernels/cells.py); the power cells share that cut, so theirs are writeable too
    assert seen[0][2] == typeof(np.zeros(3))
    assert np.array_equal(d.areas, d2.areas)


def test_project_pieces_one_type_for_surfaces_and_container_meshes(monkeypatch):
    import voroforge.kernels.surface as ks
    from voroforge.engine.lloyd3d import _nearest_on_mesh
    from voroforge.surface.shapes import sphere_patch

    seen = _spy(monkeypatch, ks, "project_pieces")
    s = sphere_patch(1.0, resolution=(12, 8))
    q = np.random.default_rng(4).normal(size=(10, 3))
    a = s.project(q)
    b = s.project(_frozen(q))
    mesh = type("Mesh", (), {"vertices": np.array(s.vertices), "faces": np.array(s.faces)})()
    c = _nearest_on_mesh(mesh, np.array(q))  # a container's writeable arrays
    assert len(seen) == 3 and len(set(seen)) == 1, set(seen)
    assert np.array_equal(a, b) and np.allclose(a, c, rtol=0, atol=1e-12)


def test_mesh_cut_run_kernels_one_type(monkeypatch):
    trimesh = pytest.importorskip("trimesh")
    import voroforge.engine.diagram3d as d3
    import voroforge.kernels.meshclip3d as mc

    seen = _spy(monkeypatch, mc, "map_runs")
    faces = _spy(monkeypatch, d3, "_face_vectors")
    ball = trimesh.creation.icosphere(subdivisions=1)
    d = vf.voronoi3d(np.random.default_rng(7).random((40, 3)) - 0.5, ball)
    assert d.volumes.sum() > 0
    assert len(seen) == 2  # the kept cells' rings and the cut cells' rings
    assert len(set(seen)) == 1, set(seen)
    # the cut diagram's face table and face areas (its int64 rings): no flag twins
    del faces[:]
    d.cell_face_table()
    d.face_areas  # noqa: B018
    assert len(faces) == 2
    _no_flag_twins(faces)
