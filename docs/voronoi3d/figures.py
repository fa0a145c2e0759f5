"""Render the pictures of docs/voronoi3d.md (no GPU, no display).

Usage: ``.venv/bin/python docs/voronoi3d/figures.py`` (writes the two PNGs next to it).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import trimesh

import voroforge as vf
from voroforge.io.render3d import diagram_edges, diagram_meshes, render

HERE = Path(__file__).parent


def torus_200():
    """200 cells of uniform sites in a torus (a genus-1 mesh container), slightly exploded."""
    torus = trimesh.creation.torus(
        major_radius=1.0, minor_radius=0.4, major_sections=96, minor_sections=32
    )
    rng = np.random.default_rng(2)
    lo, hi = torus.bounds
    pts = np.zeros((0, 3))
    while len(pts) < 200:
        q = rng.uniform(lo, hi, (400, 3))
        ring = np.hypot(q[:, 0], q[:, 1]) - 1.0
        pts = np.vstack([pts, q[ring**2 + q[:, 2] ** 2 < 0.38**2]])  # inside the tube
    d = vf.voronoi3d(pts[:200], torus)
    meshes = diagram_meshes(d, explode=0.08)
    render(meshes, HERE / "torus_200.png", size=(800, 560), view=(30, 35), edges=diagram_edges(d))
    return d


def bcc_truncated_octahedra():
    """A BCC lattice's cells away from the walls: truncated octahedra, exploded."""
    g = np.stack(np.meshgrid(*[np.arange(4.0)] * 3, indexing="ij"), -1).reshape(-1, 3)
    pts = np.vstack([g, g[(g < 3).all(axis=1)] + 0.5])
    d = vf.voronoi3d(pts, (-0.5, -0.5, -0.5, 3.5, 3.5, 3.5))
    cf, lab, _, _, _ = d.cell_face_table()
    # whole cells: no wall faces, and all 14 of them (cells next to a missing neighbour close
    # with fewer)
    inner = [
        i for i in range(len(d)) if cf[i + 1] - cf[i] == 14 and (lab[cf[i] : cf[i + 1]] >= 0).all()
    ]
    meshes = diagram_meshes(d, inner, explode=0.35)
    render(meshes, HERE / "bcc_truncated_octahedra.png", size=(700, 600), view=(25, 20))
    return d, inner


if __name__ == "__main__":
    torus_200()
    d, inner = bcc_truncated_octahedra()
    print(
        f"{len(inner)} whole truncated octahedra; faces per cell:",
        set(int(np.diff(d.cell_face_table()[0])[i]) for i in inner),
    )
