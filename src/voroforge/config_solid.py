"""Tolerances and limits of the solid layer (printable lattices, foams, shells).

Re-exported by :mod:`voroforge.config`, so modules import them from ``config``.
"""

__all__ = [
    "FOAM_LP_CELLS",
    "FOAM_FACE_AREA_RTOL",
    "SOLID_MERGE_TOL",
    "SOLID_FEATURE_ANGLE",
    "SOLID_RING_MIN",
    "SOLID_RING_SAFETY",
    "SOLID_RING_SPAN",
    "SOLID_HULL_SPREAD",
    "SOLID_VOXEL",
    "SOLID_MAX_OPENINGS",
    "SOLID_MAX_VOXELS",
]

#: solid.foam: the bubbles' inscribed balls are found as one LP of this many cells'
#: independent blocks at a time (one solver call, not one a cell)
FOAM_LP_CELLS = 256
#: solid.foam: a cell mesh's triangle below this fraction of its scale squared gives no
#: face plane (three collinear ring vertices fan into one: zero normal, or one rounding
#: turns; its plane read as a wall swallowed a roomy cell's bubble)
FOAM_FACE_AREA_RTOL = 1e-10

#: Strut graph: nodes closer than this fraction of the bounding-box diagonal are one node
SOLID_MERGE_TOL = 1e-9
#: Mesh cells given as triangles: faces meeting at more than this angle (radians) keep their
#: shared edge as a strut; flatter ones are one polygon and the edge is a diagonal
SOLID_FEATURE_ANGLE = 1e-6
#: Strut end rings sit at least this many radii from their node, and this factor beyond the
#: distance at which another ring (or the node's sphere) could reach their plane
SOLID_RING_MIN = 1.1
SOLID_RING_SAFETY = 1.15
#: A strut whose two end rings would need more than this fraction of its length joins its
#: two nodes into one hull (short Voronoi edges: the node blob covers them)
SOLID_RING_SPAN = 0.8
#: The hull route gives up (and ``nodes="sphere"`` falls back to the implicit route) when nodes
#: merged into one hull lie more than this many radii from their mean
SOLID_HULL_SPREAD = 4.0
#: Marching cubes: grid spacing as a fraction of the smallest radius/wall/thickness
SOLID_VOXEL = 0.5
#: The most openings a perforated shell takes (``solid.shell(openings=k)``, ``[solid]
#: openings``): sampling the surface for 1e8 seeds asked for 6.7 GiB after two minutes.
SOLID_MAX_OPENINGS = 200_000
#: The most samples a marching-cubes voxel grid may have (``solid.lattice`` / ``shell`` with
#: ``voxel``, ``[solid] voxel``): checked from the bounds before any work
SOLID_MAX_VOXELS = 2e9
