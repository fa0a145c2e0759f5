"""Voronoi on curved surfaces: Surface Morph, restricted Voronoi/CVT on meshes, panels.

>>> from voroforge import surface
>>> S = surface.cylinder(1.0, 2.0)
>>> vd = surface.voronoi(S, 40, relax=5)
>>> len(vd.areas)
40

See ``docs/surface.md``.
"""

from __future__ import annotations

import importlib
import sys
import types
from typing import TYPE_CHECKING

__all__ = [
    "CutSheets",
    "Panels",
    "Planarity",
    "PlanarizeReport",
    "MissingPanelWarning",
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
    "UnrollWarning",
    "voronoi",
]

# Resolved on first use, so that ``voroforge.surface.schema`` (which every design file's
# validation imports, solid and 2D builds included) does not load the surface modules.
_LAZY = {
    "CutSheets": ".unroll",
    "Panels": ".panels",
    "Planarity": ".panels",
    "PlanarizeReport": ".panels",
    "MissingPanelWarning": ".panels",
    "PlanarizeWarning": ".panels",
    "Surface": ".shapes",
    "SurfaceVoronoi": ".voronoi",
    "cylinder": ".shapes",
    "heightfield": ".shapes",
    "mesh": ".shapes",
    "morph": ".morph",
    "parametric": ".shapes",
    "saddle": ".shapes",
    "sphere": ".shapes",
    "sphere_patch": ".shapes",
    "torus": ".shapes",
    "unroll": ".unroll",
    "UnrollWarning": ".unroll",
    "voronoi": ".voronoi",
}

if TYPE_CHECKING:
    from .morph import morph
    from .panels import MissingPanelWarning, Panels, Planarity, PlanarizeReport, PlanarizeWarning
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
    from .unroll import CutSheets, UnrollWarning, unroll
    from .voronoi import SurfaceVoronoi, voronoi


def __getattr__(name: str):
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(module, __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))


class _Package(types.ModuleType):
    """The package's module type: its functions win over same-named submodules.

    Importing a submodule sets the package's attribute of that name to the module, which
    would hide the functions ``surface.morph``, ``surface.unroll`` and ``surface.voronoi``;
    such an assignment binds the submodule's function instead (the module stays in
    ``sys.modules``).
    """

    def __setattr__(self, name: str, value) -> None:
        if isinstance(value, types.ModuleType) and _LAZY.get(name) == f".{name}":
            value = getattr(value, name)
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Package
