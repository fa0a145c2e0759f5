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

from .engine.delaunay import Triangulation, delaunay
from .engine.describe import Description
from .engine.diagram import Diagram, Edges
from .engine.interpolate import locate, natural_neighbor
from .engine.lloyd import Relaxation, lloyd
from .engine.power import PowerDiagram, power, power_fit
from .engine.raster import RasterVoronoi, rasterize
from .engine.voronoi import voronoi

__all__ = [
    "Description",
    "Diagram",
    "Edges",
    "PowerDiagram",
    "RasterVoronoi",
    "Relaxation",
    "Triangulation",
    "delaunay",
    "lloyd",
    "locate",
    "natural_neighbor",
    "power",
    "power_fit",
    "rasterize",
    "voronoi",
]
__version__ = "0.1.0"
