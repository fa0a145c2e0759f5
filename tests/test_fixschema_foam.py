"""``[solid] kind = "foam"`` with a mesh container: the foam of the cells cut by the mesh.

It filled the mesh's bounding box (checker17 F8). The foam must lie in the mesh (checked
against the mesh's own planes: an icosphere is convex), its outer surface be the mesh
(trimesh's volume), and the bubbles be closed voids inside it; an open mesh is refused
naming its open edges, as ``voronoi3d`` does.
"""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from voroforge.design.designfile import DesignError, load
from voroforge.solid.build import make_solid

TOML = """[design]
name = "s"
units = "mm"
seed = 7

[solid]
kind = "foam"
container = "{name}"
cells = {cells}
relax = {relax}
wall = 1.0
formats = ["stl"]
"""


def _design(tmp_path, mesh, cells=8, relax=0):
    mesh.export(tmp_path / "c.stl")
    path = tmp_path / "f.toml"
    path.write_text(TOML.format(name="c.stl", cells=cells, relax=relax))
    return load(path)


@pytest.mark.parametrize("relax", [0, 1])
def test_foam_lies_in_its_convex_mesh_container(tmp_path, relax):
    ball = trimesh.creation.icosphere(subdivisions=2, radius=10.0)
    ball.apply_translation((10.0, 10.0, 10.0))
    design, base = _design(tmp_path, ball, relax=relax)
    m = make_solid(design, base)
    ball = trimesh.load(tmp_path / "c.stl")  # the float32 file, as the design reads it
    assert m.is_watertight
    # every vertex on the inner side of every facet plane of the (convex) container, to
    # the float32 file's rounding (its facets are convex to that)
    side = (m.vertices[:, None, :] - ball.triangles[None, :, 0, :]) @ ball.face_normals.T
    side = np.einsum(
        "vfk,fk->vf", m.vertices[:, None, :] - ball.triangles[None, :, 0, :], ball.face_normals
    )
    assert side.max() <= 20 * 2.0**-20, side.max()
    # the outer surface is the container, the bubbles voids inside it
    parts = m.split(only_watertight=False)
    outer = max(parts, key=lambda p: abs(p.volume))
    assert outer.volume == pytest.approx(ball.volume, rel=1e-9)
    bubbles = [p for p in parts if p is not outer]
    assert len(bubbles) == len(m.metadata["pores"]["size"][m.metadata["pores"]["size"] > 0])
    assert all(b.volume < 0 for b in bubbles)  # inward-facing
    void = -sum(b.volume for b in bubbles)
    assert 0 < void < ball.volume
    assert m.volume == pytest.approx(ball.volume - void, rel=1e-9)
    # a half wall of skin: no bubble vertex within 0.5 of the container's planes
    for b in bubbles:
        d = np.einsum(
            "vfk,fk->vf", b.vertices[:, None, :] - ball.triangles[None, :, 0, :], ball.face_normals
        )
        assert d.max() <= -0.5 + 20 * 2.0**-20


def test_foam_refuses_an_open_mesh_container(tmp_path):
    cube = trimesh.creation.box((10, 10, 10))
    opened = trimesh.Trimesh(cube.vertices, cube.faces[1:], process=False)
    design, base = _design(tmp_path, opened)
    with pytest.raises(DesignError) as info:
        make_solid(design, base)
    issue = info.value.issues[0]
    assert issue.key == "solid.container"
    assert "open" in issue.message and "edges" in issue.message


def test_foam_refuses_a_concave_cut(tmp_path):
    # an L-shaped solid: cells reaching its inner corner are cut into non-convex pieces
    a = trimesh.creation.box((20, 10, 10))
    b = trimesh.creation.box((10, 20, 10))
    b.apply_translation((-5, 5, 0))
    ell = a.union(b)
    assert not ell.is_convex
    design, base = _design(tmp_path, ell, cells=3)
    with pytest.raises(DesignError, match="non-convex"):
        make_solid(design, base)
