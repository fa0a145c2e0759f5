"""checker8's 3D findings: Lloyd in non-convex mesh containers, mesh files, lloyd3d's options.

- Lloyd in a torus's tube: cells that curve around the hole have centroids outside the
  solid; the next ``voronoi3d`` refused ("contains none of the sites"). Sites now move to the
  nearest point of the surface, stay inside the exact inside test, and the energy (taken
  exactly from the cells' faces) does not increase.
- ``voronoi3d(pts, "x.3mf")`` / ``--container x.3mf`` needed lxml (trimesh's 3MF reader);
  ``.3dm`` could not be read at all. Mesh files now load through ``io.mesh.read``.
- ``lloyd3d(iterations=2.5)`` raised a TypeError, ``tol=nan`` was accepted, and 0 points
  raised numpy's "zero-size array to reduction operation".
"""

from __future__ import annotations

import numpy as np
import pytest

import voroforge as vf
from voroforge.engine.lloyd3d import lloyd3d
from voroforge.engine.mesh3d import as_mesh_container, sites_inside


def torus(R=1.0, r=0.1, nu=64, nv=12):
    """A closed, outward triangulated torus (ring radius ``R``, tube radius ``r``)."""
    u = np.arange(nu) * 2 * np.pi / nu
    v = np.arange(nv) * 2 * np.pi / nv
    U, W = np.meshgrid(u, v, indexing="ij")
    rad = R + r * np.cos(W)
    V = np.c_[(rad * np.cos(U)).ravel(), (rad * np.sin(U)).ravel(), (r * np.sin(W)).ravel()]
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    a = (i * nv + j).ravel()
    b = (((i + 1) % nu) * nv + j).ravel()
    c = (((i + 1) % nu) * nv + (j + 1) % nv).ravel()
    d = (i * nv + (j + 1) % nv).ravel()
    F = np.concatenate([np.c_[a, b, c], np.c_[a, c, d]])
    return V, F


def energy(d, sites):
    """``sum_i int_{V_i} |x - z_i|^2``, exact per signed tetrahedron of each face fan."""
    cf, _, _, roff, ring = d.cell_face_table()
    V = np.asarray(d.vertices)
    lens = np.diff(roff)
    face = np.repeat(np.arange(len(lens)), np.maximum(lens - 2, 0))
    k = np.arange(len(face)) - np.repeat(np.cumsum(lens - 2) - (lens - 2), lens - 2)
    cell = np.repeat(np.arange(len(sites)), np.diff(cf))[face]
    z = np.asarray(sites)[cell]
    a = V[ring[roff[face]]] - z
    b = V[ring[roff[face] + k + 1]] - z
    c = V[ring[roff[face] + k + 2]] - z
    vol = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0
    s = a + b + c
    sq = (a * a + b * b + c * c + s * s).sum(axis=1)
    return float((vol / 20.0 * sq).sum())


def _ring(n, phase=0.1):
    ang = np.arange(n) * 2 * np.pi / n + phase
    return np.c_[np.cos(ang), np.sin(ang), np.zeros(n)]


@pytest.mark.parametrize(("n", "r"), [(1, 0.2), (2, 0.1), (3, 0.1)])
def test_lloyd3d_in_torus_stays_inside_and_lowers_energy(n, r):
    V, F = torus(r=r)
    mesh = as_mesh_container((V, F))[0]
    p = _ring(n)
    energies = [energy(vf.voronoi3d(p, (V, F)), p)]
    for _ in range(2 if n == 1 else 4):  # one site is on the surface after one step
        res = lloyd3d(p, (V, F), iterations=1, tol=None)
        p = res.points
        assert sites_inside(mesh, p).all()
        assert res.diagram.volumes.min() > 0
        energies.append(energy(res.diagram, p))
    e = np.array(energies)
    assert (np.diff(e) <= 1e-12 * e[0]).all(), e
    assert e[-1] < 0.99 * e[0]  # the sites did move (the tube's arcs' centroids are outside)
    # vf.lloyd on 3D sites takes the same path
    assert sites_inside(mesh, vf.lloyd(_ring(n), (V, F), iterations=3).points).all()


def test_lloyd3d_single_site_goes_to_the_nearest_point_of_the_surface():
    # one site's cell is the whole torus: its centroid is the centre of the hole, and the
    # nearest points of the surface are the inner edges' midpoints, at R - r times cos(pi/nu)
    V, F = torus(r=0.2, nu=28, nv=14)
    res = lloyd3d(_ring(1), (V, F), iterations=2, tol=None)
    rad = float(np.hypot(*res.points[0, :2]))
    assert abs(rad - 0.8 * np.cos(np.pi / 28)) < 1e-9
    assert abs(res.points[0, 2]) < 1e-9
    assert res.moves[-1] <= 1e-9


def test_lloyd3d_mesh_sites_inside_are_untouched():
    # centroids inside the solid: a site is its centroid, bit for bit
    V, F = torus(r=0.35, nu=28, nv=14)
    rng = np.random.default_rng(0)
    ang = rng.random(40) * 2 * np.pi
    rr = 1 + (rng.random(40) - 0.5) * 0.4
    p = np.c_[rr * np.cos(ang), rr * np.sin(ang), (rng.random(40) - 0.5) * 0.3]
    d = vf.voronoi3d(p, (V, F))
    assert sites_inside(as_mesh_container((V, F))[0], np.asarray(d.centroids)).all()
    res = lloyd3d(p, (V, F), iterations=1)
    assert np.array_equal(res.points, d.centroids)


@pytest.mark.parametrize("ext", [".3mf", ".3dm", ".ply", ".obj"])
def test_mesh_container_files_read_by_the_projects_reader(tmp_path, ext):
    if ext == ".3dm":
        pytest.importorskip("rhino3dm")
    from voroforge.io import mesh as mesh_io

    V, F = torus(r=0.3, nu=24, nv=10)
    path = tmp_path / f"torus{ext}"
    mesh_io.write(mesh_io.Arrays(V, F), path)
    p = _ring(12)
    want = vf.voronoi3d(p, (V, F))
    got = vf.voronoi3d(p, str(path))
    assert got.container == "mesh"
    # these formats reload the vertices bit for bit (the reader may reorder faces)
    np.testing.assert_allclose(got.volumes, want.volumes, rtol=1e-12, atol=0)
    assert abs(got.volumes.sum() - want.volumes.sum()) < 1e-12


def test_cli_container_3mf(tmp_path):
    from voroforge.cli import main
    from voroforge.io import mesh as mesh_io

    V, F = torus(r=0.3, nu=24, nv=10)
    mesh_io.write(mesh_io.Arrays(V, F), tmp_path / "t.3mf")
    np.savetxt(tmp_path / "p.csv", _ring(6), delimiter=",", header="x,y,z", comments="")
    out = tmp_path / "c.csv"
    argv = ["voronoi3d", str(tmp_path / "p.csv"), "-o", str(out)]
    assert main([*argv, "--container", str(tmp_path / "t.3mf")]) == 0
    assert out.stat().st_size > 0


@pytest.mark.parametrize(
    ("kw", "word"),
    [
        (dict(iterations=2.5), "iterations"),
        (dict(iterations=-1), "iterations"),
        (dict(iterations=True), "iterations"),
        (dict(tol=float("nan")), "tol"),
        (dict(tol=-1.0), "tol"),
        (dict(tol="x"), "tol"),
        (dict(density=3.0), "density"),
    ],
)
def test_lloyd3d_bad_options(kw, word):
    p = np.random.default_rng(0).random((10, 3))
    with pytest.raises(ValueError, match=word):
        lloyd3d(p, (0, 0, 0, 1, 1, 1), **kw)
    if word != "density":  # vf.lloyd checks these itself, with the same words
        with pytest.raises(ValueError, match=word):
            vf.lloyd(p, (0, 0, 0, 1, 1, 1), **kw)


@pytest.mark.parametrize("container", [(0, 0, 0, 1, 1, 1), None])
def test_lloyd3d_no_points(container):
    res = lloyd3d(np.zeros((0, 3)), container)
    assert res.points.shape == (0, 3)
    assert len(res.diagram) == 0
    assert (res.moves == 0).all()
    two = vf.lloyd(np.zeros((0, 3)), container, iterations=3)
    assert two.points.shape == (0, 3)
