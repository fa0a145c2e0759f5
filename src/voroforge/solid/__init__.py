"""Printable 3D Voronoi: strut lattices, foams, perforated shells, extruded panels, checks.

Every builder returns a watertight ``trimesh.Trimesh`` (``is_volume``) in the design's units.

>>> from voroforge import solid  # doctest: +SKIP
>>> m = solid.lattice(vf.voronoi3d(points, box), radius=0.8)  # doctest: +SKIP
>>> solid.check(m, min_strut=1.0).violations  # doctest: +SKIP
"""

from __future__ import annotations

import importlib
import sys
import types
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


class _Package(types.ModuleType):
    """The package's module type: its builder functions win over same-named submodules.

    Loading a submodule (``import voroforge.solid.shell``, or any ``from .shell import``)
    makes the import system set the package's attribute ``shell`` to the module, which
    would hide the function ``solid.shell`` (and break ``make_solid``). Such an assignment
    binds the submodule's function instead; the module stays in ``sys.modules``.
    """

    def __setattr__(self, name: str, value) -> None:
        if isinstance(value, types.ModuleType) and _LAZY.get(name) == f".{name}":
            value = getattr(value, name)
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Package
