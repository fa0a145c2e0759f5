"""Issue 12, mesh containers: checker6 R0 (cells around an edge in a mesh's hole), R4 (meshes
that cross themselves)."""

from __future__ import annotations

import numpy as np
import pytest

import voroforge as vf
from voroforge.engine.mesh3d import as_mesh_container, sites_inside

trimesh = pytest.importorskip("trimesh")


def _ring(k, rho=1.0, phase=0.0, z=0.0):
    a = 2 * np.pi * np.arange(k) / k + phase
    return np.c_[rho * np.cos(a), rho * np.sin(a), np.full(k, z)]


def _check(d, mesh, pts, nsamp=300):
    """Volumes sum to the mesh's; samples inside lie in their nearest site's cell."""
    mc, _ = as_mesh_container(mesh)
    assert abs(d.volumes.sum() - mc.volume) <= 1e-9 * mc.volume
    rng = np.random.default_rng(0)
    lo, hi = mc.vertices.min(axis=0), mc.vertices.max(axis=0)
    q = rng.uniform(lo, hi, (nsamp, 3))
    q = q[sites_inside(mc, q)]
    d2 = ((q[:, None] - pts[None]) ** 2).sum(-1)
    near = d2.argmin(1)
    srt = np.sort(d2, axis=1)
    q, near = q[srt[:, 1] - srt[:, 0] > 1e-6], near[srt[:, 1] - srt[:, 0] > 1e-6]  # clear
    assert len(q) > 20
    for i in np.unique(near):
        cell, _ = as_mesh_container(d.to_trimesh(int(i)))
        assert sites_inside(cell, q[near == i]).all()


@pytest.mark.parametrize("k", [5, 6, 12])
def test_sites_around_the_edge_through_a_torus_hole(k):
    # >= 5 cells share the z axis, which lies in the torus's hole: faces between sites that
    # are not neighbours are slivers along the axis whose area vectors are rounding; their
    # planes cut the torus away from the cells (cells filled 2.75 of a 1.68 torus)
    tor = trimesh.creation.torus(1.0, 0.3, major_sections=24, minor_sections=12)
    P = _ring(k)
    d = vf.voronoi3d(P, tor)
    _check(d, tor, P)
    assert (d.pieces == 1).all()


def test_rings_in_an_annulus_and_mesh_vertices_as_sites():
    ann = trimesh.creation.annulus(0.7, 1.3, 0.6)
    P = _ring(6, phase=0.1)
    _check(vf.voronoi3d(P, ann), ann, P)
    tor = trimesh.creation.torus(1.0, 0.3, major_sections=24, minor_sections=12)
    V = tor.vertices
    rad = np.hypot(V[:, 0], V[:, 1])
    inner = np.flatnonzero((np.abs(rad - 0.7) < 1e-9) & (np.abs(V[:, 2]) < 1e-9))
    P = V[inner]
    d = vf.voronoi3d(P, tor)
    assert abs(d.volumes.sum() - tor.volume) <= 1e-9 * tor.volume


def _cat(*ms):
    return trimesh.util.concatenate(list(ms))


def _moved(m, t, s=1.0):
    m = m.copy()
    m.apply_scale(s)
    m.apply_translation(t)
    return m


def _inverted(m):
    m = m.copy()
    m.invert()
    return m


BOX = trimesh.creation.box((1, 1, 1))
P3 = np.array([[0.1, 0.1, 0.1], [-0.2, 0.1, 0.3], [0.3, -0.3, 0.0]])


@pytest.mark.parametrize(
    "mesh, what",
    [
        # edges meet the other box's faces on their diagonals: no proper crossing
        (_cat(BOX, _moved(BOX, (0.5, 0.5, 0.5))), "shells 0 and 1 overlap or nest"),
        (_cat(BOX, _moved(BOX, (0.3, 0.41, 0.27))), r"shells 0 and 1 overlap \(faces"),
        (_cat(BOX, _moved(BOX, (0.999, 0, 0))), "shells 0 and 1 overlap or nest"),
        (_cat(BOX, _moved(BOX, (0, 0, 0), 0.5)), "nest facing the same way"),
        (_cat(trimesh.creation.box((3, 1, 1)), trimesh.creation.box((1, 3, 1))), "cross"),
    ],
    ids=["offset_half", "offset_generic", "sliver", "nested_same_way", "plus"],
)
def test_meshes_that_cross_themselves_are_refused(mesh, what):
    with pytest.raises(ValueError, match="intersects itself: .*" + what):
        vf.voronoi3d(P3, (mesh.vertices, mesh.faces))
    with pytest.raises(ValueError, match="intersects itself"):
        vf.voronoi3d(P3[:1], (mesh.vertices, mesh.faces))  # not "contains none of the sites"


def test_a_shell_through_itself_and_a_lone_inward_shell_are_refused():
    t = trimesh.creation.torus(1, 0.3, major_sections=24, minor_sections=12)
    V = t.vertices.copy()
    V[np.flatnonzero(np.abs(V[:, 2] - 0.3) < 1e-9)[0], 2] = -0.5  # pushed through the tube
    with pytest.raises(ValueError, match=r"intersects itself: faces \d+ and \d+ of shell 0"):
        vf.voronoi3d(_ring(4), (V, t.faces))
    m = _cat(BOX, _inverted(_moved(BOX, (2, 0, 0), 0.5)))
    with pytest.raises(ValueError, match="faces inwards but lies inside no other shell"):
        vf.voronoi3d(P3, (m.vertices, m.faces))


def test_cavities_separate_and_touching_shells_stay_valid():
    hole = _cat(BOX, _inverted(_moved(BOX, (0, 0, 0), 0.5)))
    P = P3 + [0, 0, 0.3]
    d = vf.voronoi3d(P, (hole.vertices, hole.faces))
    assert abs(d.volumes.sum() - 0.875) <= 1e-9
    island = _cat(BOX, _inverted(_moved(BOX, (0, 0, 0), 0.6)), _moved(BOX, (0, 0, 0), 0.3))
    assert abs(as_mesh_container((island.vertices, island.faces))[0].volume - 0.811) < 1e-12
    for m in (_cat(BOX, _moved(BOX, (2, 0, 0))), _cat(BOX, _moved(BOX, (1, 0.3, 0.2)))):
        assert as_mesh_container((m.vertices, m.faces))[0].volume == pytest.approx(2.0)


@pytest.mark.parametrize("text", ["", "solid x\n facet nonsense\nendsolid\n"])
def test_an_empty_or_garbage_mesh_file_is_named(tmp_path, text):
    path = tmp_path / "bad.stl"
    path.write_text(text)
    with pytest.raises(ValueError, match=r"mesh file .*bad\.stl holds 0 triangles"):
        vf.voronoi3d([[0.0, 0.0, 0.0]], str(path))
