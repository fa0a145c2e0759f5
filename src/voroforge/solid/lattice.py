"""Strut lattices on the edges of 3D cells: ``solid.lattice``."""

from __future__ import annotations

import numpy as np

from .fields import as_size
from .graph import strut_graph

__all__ = ["lattice"]

NODES = ("sphere", "hull", "smooth")


def local_origin(points) -> np.ndarray:
    """An origin near ``points`` that every point minus it is exact about.

    Their bounding box's centre rounded to a multiple of the power of two above its largest
    extent (as :func:`voroforge.engine.containers.far_origin`, but always, near or far):
    both the point and the origin are multiples of the point's ulp and the difference is
    below the extent. Zero for no points or a box about the origin.
    """
    p = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    if len(p) == 0:
        return np.zeros(3)
    lo, hi = p.min(axis=0), p.max(axis=0)
    size = float((hi - lo).max())
    if not (size > 0 and np.isfinite(size)):
        return np.zeros(3)
    step = np.ldexp(1.0, int(np.frexp(size)[1]))
    return np.round((0.5 * lo + 0.5 * hi) / step) * step + 0.0


def _finish(verts, faces, meta):
    import trimesh

    m = trimesh.Trimesh(verts, faces, process=False)  # every vertex used (hull_lattice)
    m.metadata.update(meta)
    return m


def lattice(
    cells,
    radius=0.8,
    *,
    nodes: str = "sphere",
    field=None,
    container=None,
    skin: float = 0.0,
    segments: int = 8,
    node_scale: float = 1.0,
    voxel: float | None = None,
    smoothing: int = 10,
    route: str = "auto",
    bare: bool = False,
):
    """Struts on the edges of 3D cells, joined at watertight nodes.

    Parameters
    ----------
    cells : Diagram3D, (nodes, edges), Trimesh or list of Trimesh
        The cells whose edges become struts (see :func:`voroforge.solid.graph.strut_graph`).
    radius : float, callable or (far, near)
        Strut radius in the design's units: a number, a field ``xyz -> radius``, or with
        ``field`` the pair of radii where the field is 0 and 1. Sampled at the nodes; a
        strut between two radii is a frustum.
    nodes : {"sphere", "hull", "smooth"}
        ``sphere``: each node the convex hull of its strut rings and a polygonal sphere of
        ``node_scale * radius`` (exact polyhedral construction, fast); nodes joined by struts
        too short for two rings share a joint (a manifold3d union of their hulls and the
        short struts), as random Voronoi cells need. ``hull``: the rings' hull alone (sharp,
        lightest). ``smooth``: an implicit surface (smooth minimum of capsules) meshed by
        marching cubes and Taubin-smoothed (organic nodes; slower, resolution ``voxel``).
        Skins always take the implicit route.
    field : callable, optional
        A 0..1 field (:mod:`voroforge.solid.fields`) grading ``radius=(far, near)``.
    container : Trimesh, optional
        A closed mesh the lattice is trimmed to (manifold3d intersection).
    skin : float
        With ``container``: also keep a skin of this thickness inside the container's surface.
    segments : int
        Sides of each strut's polygon (>= 3).
    node_scale : float
        Node sphere radius over the strut radius (``sphere`` nodes).
    voxel : float, optional
        Grid spacing of the implicit route (default half the smallest radius).
    smoothing : int
        Taubin iterations of the ``smooth`` route.
    route : {"auto", "hull", "implicit"}
        ``auto``: node hulls (exact, light meshes) unless ``nodes="smooth"`` or a skin needs
        the implicit route, which also takes over if the hulls give up. ``implicit``: the
        plain union of round struts and spherical nodes on a voxel grid even for spheres
        (on 1,000 random cells 1.4 times less CPU than the hull route, with ten times the
        triangles and the voxel's accuracy; out of memory at 10,000). ``hull``: node hulls
        or an error.
    bare : bool
        Where the implicit route builds the lattice, return it as a
        :class:`voroforge.solid.implicit.Bare` mesh (arrays and metadata, no trimesh import:
        what a design build needs); the hull route returns a Trimesh either way.

    Returns
    -------
    trimesh.Trimesh
        Watertight (``is_volume``). ``metadata["struts"]`` holds the strut segments and
        radii (for :func:`voroforge.solid.check`), ``metadata["parts"]`` the construction's
        bookkeeping.

    Examples
    --------
    >>> import trimesh
    >>> from voroforge import solid
    >>> m = solid.lattice(trimesh.creation.box((10, 10, 10)), radius=0.5)
    >>> bool(m.is_volume), len(m.metadata["struts"]["a"])
    (True, 12)
    """
    if route not in ("auto", "hull", "implicit"):
        raise ValueError(f"route must be 'auto', 'hull' or 'implicit', got {route!r}")
    if route == "hull" and (nodes == "smooth" or skin > 0):
        raise ValueError("route='hull' cannot make smooth nodes or skins (the implicit route does)")
    if nodes not in NODES:
        raise ValueError(f"nodes must be one of {NODES}, got {nodes!r}")
    if not (isinstance(segments, int | np.integer) and segments >= 3):
        raise ValueError(f"segments must be an integer >= 3, got {segments!r}")
    if not (np.isfinite(node_scale) and node_scale > 0):
        raise ValueError(f"node_scale must be a finite number > 0, got {node_scale!r}")
    if not (np.isfinite(skin) and skin >= 0):
        raise ValueError(f"skin must be a finite number >= 0, got {skin!r}")
    if skin > 0 and container is None:
        raise ValueError("skin needs a container (the skin lines its surface)")
    size = as_size(radius, field, "radius")
    g = strut_graph(cells)
    r = size(g.nodes)
    if not (np.isfinite(r).all() and (r > 0).all()):
        raise ValueError("radius: the field gave non-positive or non-finite radii")
    struts = {
        "a": g.nodes[g.edges[:, 0]],
        "b": g.nodes[g.edges[:, 1]],
        "ra": r[g.edges[:, 0]],
        "rb": r[g.edges[:, 1]],
    }
    meta = {"kind": "lattice", "struts": struts}
    if nodes != "smooth" and skin == 0 and route != "implicit":
        from .hulls import hull_lattice  # scipy.spatial and .sparse: the hull route's only

        # built about a local origin, then translated back: the node hulls (qhull), the
        # joints' unions (manifold3d, whose tolerance grows with the coordinates' magnitude)
        # and the pocket test then see the same numbers wherever the lattice lies
        o = local_origin(g.nodes)
        try:
            verts, faces, parts = hull_lattice(
                g.nodes - o,
                g.edges,
                r,
                segments=int(segments),
                sphere=1 if nodes == "sphere" else None,
                node_scale=float(node_scale),
            )
        except ValueError:
            if nodes == "hull" or route == "hull":
                raise
        else:
            verts += o
            parts["method"] = "hull"
            meta["segments"] = int(segments)  # struts are k-gon prisms of circumradius r
            m = _finish(verts, faces, {**meta, "parts": parts})
            if container is not None:
                from .booleans import trim

                m = trim(m, container, skin=skin)
                m.metadata.update({**meta, "parts": parts})
            return m
    # implicit route: smooth nodes and skins, or spheres (a plain union of capsules) where the
    # hull route gives up (rings that cannot be placed even with joints)
    from .implicit import capsules_mesh

    m = capsules_mesh(
        struts,
        voxel=voxel,
        smoothing=smoothing,
        container=container,
        skin=skin,
        smooth=None if nodes == "smooth" else 0.0,
        bare=bare,
    )
    # the grid marching cubes ran on (capsules_mesh's default): check's strut widths use it
    from .. import config

    h = config.SOLID_VOXEL * float(r.min()) if voxel is None else float(voxel)
    m, count, filled = _drop_pockets(m, 2.0 * float(r.min()), bare)
    parts = {"method": "implicit", "pockets": count, "pocket_volume": filled}
    meta = {**meta, "parts": parts, "skin": float(skin), "voxel": h}
    m.metadata.update(meta)
    return m


def _drop_pockets(m, size, bare):
    """``m`` without closed cavities smaller than ``size`` (as the hull route fills them).

    A union of capsules can enclose a real pocket far below a voxel (checker28 F2: 2.6e-10
    at a voxel of 0.02), which ``check`` would list as a trapped void no printer resolves.
    Returns ``(mesh, count, volume filled)``; ``m`` itself where there is none.
    """
    from ..engine.csr import used_only
    from .check import fill_pockets

    verts, faces = np.asarray(m.vertices), np.asarray(m.faces)
    kept, filled, count = fill_pockets(verts, faces, size)
    if count == 0:
        return m, 0, 0.0
    verts, kept = used_only(verts, kept)
    if bare:
        from .implicit import Bare

        return Bare(verts, kept, m.metadata), count, filled
    import trimesh

    out = trimesh.Trimesh(verts, kept, process=False)
    out.metadata.update(m.metadata)
    return out, count, filled
