"""Printable 3D Voronoi: strut lattices, foams, perforated shells, extruded panels, checks.

Every builder returns a watertight ``trimesh.Trimesh`` (``is_volume``) in the design's units.

>>> from voroforge import solid  # doctest: +SKIP
>>> m = solid.lattice(vf.voronoi3d(points, box), radius=0.8)  # doctest: +SKIP
>>> solid.check(m, min_strut=1.0).violations  # doctest: +SKIP
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

__all__ = ["Report", "Violation", "cells", "check", "extrude", "fields", "foam", "lattice", "shell"]

# resolved on first use, so that ``voroforge.solid.schema`` (which every design file
# validation imports) does not load trimesh, manifold3d and scipy.optimize
_LAZY = {
    "Report": ".check",
    "Violation": ".check",
    "check": ".check",
    "extrude": ".extrude",
    "foam": ".foam",
    "lattice": ".lattice",
    "shell": ".shell",
}

if TYPE_CHECKING:
    from . import cells, fields
    from .check import Report, Violation, check
    from .extrude import extrude
    from .foam import foam
    from .lattice import lattice
    from .shell import shell


def __getattr__(name: str):
    if name in ("cells", "fields"):
        value = importlib.import_module(f".{name}", __name__)
    elif name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name], __name__), name)
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
