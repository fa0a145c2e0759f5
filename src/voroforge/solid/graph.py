"""The strut graph of a cell complex: nodes (Voronoi vertices) and edges (cell edges).

:func:`strut_graph` accepts what the solids are built from: a 3D Voronoi diagram
(``vf.voronoi3d``: its shared ``vertices`` and face rings), a ``(nodes, edges)`` pair, one
closed mesh or a list of them (convex cells as meshes: the feature edges between
non-coplanar faces become struts, triangulation diagonals do not), and returns clean
arrays: nodes closer than ``tol`` merged, each edge once, no loops.
"""

from __future__ import annotations

import sys

import numpy as np

from .. import config
from .kernels import near_classes

__all__ = ["Graph", "feature_edges", "strut_graph"]


class Graph:
    """Nodes ``(V, 3)`` float64 and edges ``(E, 2)`` int64 (``a < b``, each once)."""

    def __init__(self, nodes: np.ndarray, edges: np.ndarray):
        self.nodes = nodes
        self.edges = edges

    @property
    def lengths(self) -> np.ndarray:
        """Edge lengths ``(E,)``."""
        return np.linalg.norm(self.nodes[self.edges[:, 1]] - self.nodes[self.edges[:, 0]], axis=1)

    def degree(self) -> np.ndarray:
        """Edges per node ``(V,)``."""
        return np.bincount(self.edges.ravel(), minlength=len(self.nodes))

    def __repr__(self) -> str:
        return f"Graph({len(self.nodes)} nodes, {len(self.edges)} edges)"


def feature_edges(mesh, *, angle: float = config.SOLID_FEATURE_ANGLE) -> np.ndarray:
    """Edges of a triangle mesh between faces that meet at more than ``angle`` radians.

    Parameters
    ----------
    mesh : trimesh.Trimesh
        A closed mesh (convex cells triangulated, for example).
    angle : float
        Faces closer to coplanar than this are one polygon; their shared edge is a diagonal.

    Returns
    -------
    (k, 2) int64
        Vertex index pairs, sorted within each pair.
    """
    adj = mesh.face_adjacency_edges
    sharp = mesh.face_adjacency_angles > angle
    edges = np.sort(np.asarray(adj[sharp], dtype=np.int64), axis=1)
    # boundary edges of an open mesh are features too
    e = np.sort(mesh.edges, axis=1)
    uniq, counts = np.unique(e, axis=0, return_counts=True)
    edges = np.vstack([edges, uniq[counts == 1]])
    return np.unique(edges, axis=0) if len(edges) else np.zeros((0, 2), np.int64)


def _from_diagram(c):
    """(nodes, edges) of a 3D diagram from its face rings (CSR into ``c.vertices``)."""
    faces = c.faces
    indptr = getattr(faces, "indptr", None)
    indices = getattr(faces, "indices", None)
    if indptr is None and isinstance(faces, tuple) and len(faces) >= 2:
        indptr, indices = faces[0], faces[1]
    if indptr is None:
        raise ValueError("cells: a 3D diagram's faces need CSR indptr/indices")
    indptr = np.asarray(indptr, dtype=np.int64)
    indices = np.asarray(indices, dtype=np.int64)
    nxt = np.arange(1, len(indices) + 1, dtype=np.int64)
    lens = np.diff(indptr)
    last = indptr[1:] - 1
    nxt[last[lens > 0]] = indptr[:-1][lens > 0]
    edges = np.stack([indices, indices[nxt]], axis=1)
    return np.asarray(c.vertices, dtype=np.float64), edges


def _is_trimesh(m) -> bool:
    """Whether ``m`` is a Trimesh (none exists before trimesh's import, which this avoids)."""
    tm = sys.modules.get("trimesh")
    return tm is not None and isinstance(m, tm.Trimesh)


def strut_graph(cells, *, tol: float | None = None) -> Graph:
    """The clean strut graph of ``cells``.

    Parameters
    ----------
    cells : Diagram3D, (nodes, edges), Graph, trimesh.Trimesh or sequence of Trimesh
        What to take the edges of (see the module docstring).
    tol : float, optional
        Nodes closer than this merge (default: ``config.SOLID_MERGE_TOL`` times the
        bounding-box diagonal).

    Returns
    -------
    Graph
    """
    if isinstance(cells, Graph):
        nodes, edges = cells.nodes, cells.edges
    elif hasattr(cells, "vertices") and hasattr(cells, "faces") and hasattr(cells, "volumes"):
        nodes, edges = _from_diagram(cells)
    elif _is_trimesh(cells):
        nodes, edges = np.asarray(cells.vertices), feature_edges(cells)
    elif isinstance(cells, tuple) and len(cells) == 2 and not _is_trimesh(cells[0]):
        nodes, edges = cells
    elif isinstance(cells, list | tuple) and all(_is_trimesh(m) for m in cells):
        if not cells:
            raise ValueError("cells: an empty list")
        parts, n = [], 0
        for m in cells:
            parts.append(feature_edges(m) + n)
            n += len(m.vertices)
        nodes = np.vstack([np.asarray(m.vertices) for m in cells])
        edges = np.vstack(parts)
    else:
        raise ValueError(
            "cells: expected a 3D diagram, (nodes, edges), a Trimesh or a list of Trimesh, "
            f"got {type(cells).__name__}"
        )
    nodes = np.array(nodes, dtype=np.float64)  # a copy: never the caller's array
    edges = np.array(edges, dtype=np.int64).reshape(-1, 2)
    if nodes.ndim != 2 or nodes.shape[1] != 3:
        raise ValueError(f"nodes must be (V, 3), got shape {nodes.shape}")
    if not np.isfinite(nodes).all():
        raise ValueError("nodes contain NaN or infinite coordinates")
    if len(edges) == 0:
        raise ValueError("cells: no edges to build struts on")
    if edges.min() < 0 or edges.max() >= len(nodes):
        raise ValueError(f"edges index nodes outside 0..{len(nodes) - 1}")
    span = float(np.linalg.norm(nodes.max(0) - nodes.min(0))) or 1.0
    tol = config.SOLID_MERGE_TOL * span if tol is None else float(tol)
    # merge near-coincident nodes (connected components of the <= tol graph, numbered by
    # their lowest node: scipy's labels, without importing scipy.spatial and scipy.sparse)
    label = near_classes(nodes, tol)
    used = np.unique(label[edges.ravel()])
    remap = np.full(label.max() + 1, -1, dtype=np.int64)
    remap[used] = np.arange(len(used))
    first = np.full(label.max() + 1, -1, dtype=np.int64)
    order = np.arange(len(nodes))[::-1]
    first[label[order]] = order  # lowest original index per class
    new_nodes = nodes[first[used]]
    e = remap[label[edges]]
    e = np.sort(e, axis=1)
    e = e[e[:, 0] != e[:, 1]]
    e = np.unique(e, axis=0)
    return Graph(new_nodes, e)


def convex_cell_meshes(cells, what: str, why: str) -> list:
    """:func:`cell_meshes`, each checked convex; ``ValueError`` naming a cell that is not.

    A cell a concave mesh container cut (a torus's inner side, an L's inner corner) is not
    the intersection of its faces' half-spaces: foams shrink cells plane by plane and
    subdivision fills each cell's hull, so both refuse it. ``what`` starts the message,
    ``why`` ends it. Cells of a diagram the container did not cut are convex by
    construction and not tested.
    """
    ms = cell_meshes(cells)
    if hasattr(cells, "to_trimesh") and hasattr(cells, "volumes"):
        ids = np.flatnonzero(np.asarray(cells.volumes) > 0)
        cut = getattr(cells, "cut_cells", None)
        test = np.zeros(len(ids), bool) if cut is None else np.asarray(cut, bool)[ids]
    else:
        ids, test = np.arange(len(ms)), np.ones(len(ms), bool)
    for k in np.flatnonzero(test):
        m = ms[k]
        hull = m.convex_hull.volume
        if hull - m.volume > config.SOLID_FOAM_CONVEX_RTOL * hull:
            raise ValueError(
                f"{what}: cell {int(ids[k])} is not convex (its volume {m.volume:.6g}, its "
                f"hull's {hull:.6g}; a concave mesh container cut it): {why}"
            )
    return ms


def cell_meshes(cells) -> list:
    """Closed convex cell meshes from a 3D diagram (``to_trimesh(i)``) or a list of meshes."""
    import trimesh

    if isinstance(cells, trimesh.Trimesh):
        return [cells]
    if hasattr(cells, "to_trimesh") and hasattr(cells, "volumes"):
        vol = np.asarray(cells.volumes)
        return [cells.to_trimesh(i) for i in range(len(vol)) if vol[i] > 0]
    if (
        isinstance(cells, list | tuple)
        and cells
        and all(isinstance(m, trimesh.Trimesh) for m in cells)
    ):
        return list(cells)
    raise ValueError(
        f"cells: expected a 3D diagram or a list of closed Trimesh, got {type(cells).__name__}"
    )
