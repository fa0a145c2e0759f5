"""Issue 12, mesh containers: checker6 R0 (cells around an edge in a mesh's hole)."""

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
