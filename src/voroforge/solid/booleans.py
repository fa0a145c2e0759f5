"""Thin manifold3d helpers: Trimesh <-> Manifold (float64), status, trims and differences."""

from __future__ import annotations

import numpy as np

__all__ = ["from_manifold", "manifold_status", "status_name", "to_manifold", "trim"]


def to_manifold(m):
    """A ``manifold3d.Manifold`` of a Trimesh (float64 vertices, ``Mesh64``)."""
    import manifold3d

    mesh = manifold3d.Mesh64(
        vert_properties=np.ascontiguousarray(m.vertices, dtype=np.float64),
        tri_verts=np.ascontiguousarray(m.faces, dtype=np.uint64),
    )
    return manifold3d.Manifold(mesh)


def status_name(man) -> str:
    """A ``manifold3d.Manifold``'s status as a name: ``"NoError"`` when it is valid."""
    return str(man.status()).split(".")[-1]


def manifold_status(m) -> str:
    """manifold3d's verdict on a mesh: ``"NoError"`` when it is a closed 2-manifold."""
    return status_name(to_manifold(m))


def from_manifold(man):
    """A Trimesh of a ``manifold3d.Manifold`` (float64)."""
    import trimesh

    mesh = man.to_mesh64()
    v = np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3]
    f = np.asarray(mesh.tri_verts, dtype=np.int64)
    return trimesh.Trimesh(v, f, process=False)


def _check(man, what: str):
    status = status_name(man)
    if status != "NoError":
        raise ValueError(f"{what}: manifold3d rejects the mesh ({status}); is it closed?")
    return man


def trim(m, container, *, skin: float = 0.0):
    """``m`` intersected with a closed ``container`` mesh (manifold3d).

    A skin needs an inset of the container, which only the implicit route makes; here it is
    refused with a clear message (``solid.lattice`` routes skins to the implicit route).
    """
    if skin > 0:
        raise ValueError("trim: skins go through the implicit route")
    a = _check(to_manifold(m), "lattice")
    c = _check(to_manifold(container), "container")
    return from_manifold(a ^ c)
