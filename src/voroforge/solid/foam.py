"""Closed-cell foams: every cell shrunk into a bubble, walls between them (``solid.foam``)."""

from __future__ import annotations

import warnings

import numpy as np
from scipy.spatial import HalfspaceIntersection, QhullError

from .fields import as_size
from .graph import cell_meshes
from .hulls import convex_mesh

__all__ = ["bubbles", "foam"]


def _planes(cell) -> tuple[np.ndarray, np.ndarray]:
    """Unique outward face planes ``n . x <= c`` of a convex cell mesh."""
    n = np.asarray(cell.face_normals)
    c = np.einsum("ij,ij->i", n, cell.triangles_center)
    key = np.round(np.column_stack([n, c / max(cell.scale, 1e-300)]), 9)
    _, first = np.unique(key, axis=0, return_index=True)
    first = np.sort(first)
    cen = cell.vertices[cell.faces[first]].mean(axis=1)
    return np.column_stack([n[first], c[first]]), cen


def _chebyshev(a: np.ndarray, c: np.ndarray):
    """Centre and radius of the largest ball inside ``a x <= c`` (None when empty)."""
    from scipy.optimize import linprog  # only for cells whose centroid is not inside

    norm = np.linalg.norm(a, axis=1)
    res = linprog(
        [0, 0, 0, -1],
        A_ub=np.column_stack([a, norm]),
        b_ub=c,
        bounds=[(None, None)] * 3 + [(0, None)],
    )
    if not res.success:
        return None, 0.0
    return res.x[:3], float(res.x[3])


def bubbles(cells, wall, *, field=None):
    """Each cell shrunk by half the local wall thickness on every face (convex bubbles).

    Returns
    -------
    list of (Trimesh or None, centre (3,), inscribed radius)
        ``None`` where the wall swallows the cell (it stays solid).
    """
    size = as_size(wall, field, "wall")
    out = []
    for cell in cells:
        pl, cen = _planes(cell)
        w = size(cen)
        a, c = pl[:, :3], pl[:, 3] - 0.5 * w
        x0 = cell.center_mass
        slack = c - a @ x0
        if slack.min() > 1e-6 * cell.scale:  # the centroid is inside: its clearance
            centre, rad = x0, float(slack.min())  # (a lower bound of the inscribed radius)
        else:
            centre, rad = _chebyshev(a, c)
        if centre is None or rad <= 1e-6 * cell.scale:
            out.append((None, x0, 0.0))
            continue
        try:
            v = HalfspaceIntersection(np.column_stack([a, -c]), centre).intersections
            b = convex_mesh(v)
        except QhullError:
            out.append((None, x0, 0.0))
            continue
        out.append((b, centre, rad))
    return out


def foam(cells3d, wall=1.2, *, field=None, container=None):
    """A closed-cell foam: the container with every cell's bubble taken out.

    Parameters
    ----------
    cells3d : Diagram3D or list of convex Trimesh
        The cells (``vf.voronoi3d(...)`` or convex meshes).
    wall : float or (far, near)
        Wall thickness between neighbouring bubbles (each side gives half; the container's
        skin is half a wall too, as every cell is shrunk by half the wall on every face).
        With ``field``: the pair of thicknesses at field 0 and 1.
    field : callable, optional
        A 0..1 3D field (:mod:`voroforge.solid.fields`), sampled at each face's centre.
    container : Trimesh, optional
        The outer solid (default: the convex hull of the cells: exact for box and convex
        containers).

    Returns
    -------
    trimesh.Trimesh
        Watertight: the outer surface and one inward-facing surface per bubble (the bubbles
        are closed voids; :func:`voroforge.solid.check` lists them as trapped).
        ``metadata["pores"]`` holds each bubble's centre and inscribed diameter (0 for a
        cell the walls fill: a warning says how many, and ``check(min_pore=...)`` lists
        them).

    Examples
    --------
    >>> import trimesh
    >>> from voroforge import solid
    >>> m = solid.foam([trimesh.creation.box((10, 10, 10))], wall=2.0)
    >>> round(float(m.volume), 6)  # 10**3 - 8**3
    488.0
    """
    import trimesh

    cells = cell_meshes(cells3d)
    if container is None:
        container = convex_mesh(np.vstack([c.vertices for c in cells]))
    bs = bubbles(cells, wall, field=field)
    parts = [container]
    centres, sizes = [], []
    for b, centre, rad in bs:
        if b is None:  # the walls fill this cell: a pore of size 0, which check() lists
            centres.append(centre)
            sizes.append(0.0)
            continue
        inv = b.copy()
        inv.invert()
        parts.append(inv)
        centres.append(centre)
        sizes.append(2.0 * rad)
    closed = sum(b is None for b, _, _ in bs)
    if closed:
        warnings.warn(
            f"foam: walls of {wall!r} fill {closed} of {len(bs)} cells (no bubble left there; "
            f"{len(bs) - closed} remain)",
            stacklevel=2,
        )
    m = trimesh.util.concatenate(parts)
    m.metadata.update(
        {
            "kind": "foam",
            "pores": {"centre": np.array(centres).reshape(-1, 3), "size": np.array(sizes)},
        }
    )
    return m
