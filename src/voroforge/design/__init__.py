"""Parametric design with Voronoi diagrams: the Grasshopper-style workflow in Python.

boundary -> seeds (:mod:`populate`) -> optional relaxation (:mod:`relax`) -> ``vf.voronoi``
-> attractor fields (:mod:`attractors`) -> cell operations (:mod:`cellops`) -> recursive
subdivision (:mod:`recursive`). Units are millimetres by default; every function is pure
and takes its randomness from an explicit ``seed``.

Design files: :mod:`schema` (the models), :mod:`designfile` (reading TOML, overrides, errors
with file and line), :mod:`compute` (a design to geometry, in memory), :mod:`build` (the
files a design names, check reports, the starter design), :mod:`fabrication` (checks, kerf).

The submodules are imported on first use (``voroforge.design.populate`` or ``from
voroforge.design import populate``), so a build loads only what its design needs.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

_SUBMODULES = (
    "attractors",
    "boundary",
    "build",
    "cellops",
    "compute",
    "designfile",
    "fabrication",
    "features",
    "populate",
    "recursive",
    "relax",
    "schema",
    "stipple",
)

__all__ = list(_SUBMODULES)


def __getattr__(name: str) -> Any:
    if name not in _SUBMODULES:
        raise AttributeError(f"module 'voroforge.design' has no attribute {name!r}")
    return importlib.import_module(f".{name}", __name__)  # binds itself in this namespace


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_SUBMODULES))


if TYPE_CHECKING:  # for type checkers and editors: the same names, imported eagerly
    from . import (  # noqa: F401
        attractors,
        boundary,
        build,
        cellops,
        compute,
        designfile,
        fabrication,
        features,
        populate,
        recursive,
        relax,
        schema,
        stipple,
    )
