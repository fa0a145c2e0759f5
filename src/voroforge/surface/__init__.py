"""Voronoi on curved surfaces: Surface Morph, restricted Voronoi/CVT on meshes, panels.

>>> from voroforge import surface
>>> S = surface.cylinder(1.0, 2.0)
>>> vd = surface.voronoi(S, 40, relax=5)
>>> len(vd.areas)
40

See ``docs/surface.md``.
"""

from __future__ import annotations

from .morph import morph
from .panels import Panels, Planarity, PlanarizeReport, PlanarizeWarning
from .shapes import (
    Surface,
    cylinder,
    heightfield,
    mesh,
    parametric,
    saddle,
    sphere,
    sphere_patch,
    torus,
)
from .unroll import CutSheets, unroll
from .voronoi import SurfaceVoronoi, voronoi

__all__ = [
    "CutSheets",
    "Panels",
    "Planarity",
    "PlanarizeReport",
    "PlanarizeWarning",
    "Surface",
    "SurfaceVoronoi",
    "cylinder",
    "heightfield",
    "mesh",
    "morph",
    "parametric",
    "saddle",
    "sphere",
    "sphere_patch",
    "torus",
    "unroll",
    "voronoi",
]
