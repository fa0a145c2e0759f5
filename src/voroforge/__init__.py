"""voroforge: robust Voronoi diagrams and parametric design with them.

The core results are flat index arrays (Delaunator layout): ``triangles (t, 3)``
counter-clockwise, ``halfedges (3 t,)`` with -1 on the hull, and ``hull``. Halfedge ``e``
runs from ``triangles.flat[e]`` to ``triangles.flat[3 * (e // 3) + (e + 1) % 3]``; walk to
the neighbouring triangle with ``halfedges[e] // 3``::

    tri = vf.delaunay(points)
    e = 4                        # edge 1 of triangle 1
    twin = tri.halfedges[e]      # same edge seen from the other triangle, or -1
    other = twin // 3 if twin >= 0 else None
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

__version__ = "0.1.0"

# Public name -> the module that defines it. Nothing is imported until a name is used, so
# ``import voroforge`` (and the command line's --help/--version) does not load numpy or numba.
# Add a line here for a new public name; subsystems (solid, surface, scale, studio) are
# submodules, imported as ``from voroforge import solid``.
_EXPORTS = {
    "Description": ".engine.describe",
    "Diagram": ".engine.diagram",
    "Edges": ".engine.diagram",
    "PowerDiagram": ".engine.power",
    "RasterVoronoi": ".engine.raster",
    "Relaxation": ".engine.lloyd",
    "Triangulation": ".engine.delaunay",
    "delaunay": ".engine.delaunay",
    "Tetrahedralization": ".engine.delaunay3d",
    "delaunay3d": ".engine.delaunay3d",
    "lloyd": ".engine.lloyd",
    "locate": ".engine.interpolate",
    "natural_neighbor": ".engine.interpolate",
    "power": ".engine.power",
    "power_fit": ".engine.capacity",
    "rasterize": ".engine.raster",
    "voronoi": ".engine.voronoi",
    "voronoi3d": ".engine.voronoi3d",
    "Convex": ".engine.containers",
    "Diagram3D": ".engine.diagram3d",
    "lloyd3d": ".engine.lloyd3d",
    "Relaxation3D": ".engine.lloyd3d",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'voroforge' has no attribute {name!r}")
    value = getattr(importlib.import_module(module, __name__), name)
    globals()[name] = value  # later look-ups skip this function
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_EXPORTS))


if TYPE_CHECKING:  # for type checkers and editors: the same names, imported eagerly
    from .engine.capacity import power_fit  # noqa: F401
    from .engine.containers import Convex  # noqa: F401
    from .engine.delaunay import Triangulation, delaunay  # noqa: F401
    from .engine.delaunay3d import Tetrahedralization, delaunay3d  # noqa: F401
    from .engine.describe import Description  # noqa: F401
    from .engine.diagram import Diagram, Edges  # noqa: F401
    from .engine.diagram3d import Diagram3D  # noqa: F401
    from .engine.interpolate import locate, natural_neighbor  # noqa: F401
    from .engine.lloyd import Relaxation, lloyd  # noqa: F401
    from .engine.lloyd3d import Relaxation3D, lloyd3d  # noqa: F401
    from .engine.power import PowerDiagram, power  # noqa: F401
    from .engine.raster import RasterVoronoi, rasterize  # noqa: F401
    from .engine.voronoi import voronoi  # noqa: F401
    from .engine.voronoi3d import voronoi3d  # noqa: F401
