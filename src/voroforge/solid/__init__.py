"""Printable 3D Voronoi: strut lattices, foams, perforated shells, extruded panels, checks.

Every builder returns a watertight ``trimesh.Trimesh`` (``is_volume``) in the design's units.

>>> from voroforge import solid  # doctest: +SKIP
>>> m = solid.lattice(vf.voronoi3d(points, box), radius=0.8)  # doctest: +SKIP
>>> solid.check(m, min_strut=1.0).violations  # doctest: +SKIP
"""

from __future__ import annotations

from . import cells, fields
from .check import Report, Violation, check
from .extrude import extrude
from .foam import foam
from .lattice import lattice
from .shell import shell

__all__ = ["Report", "Violation", "cells", "check", "extrude", "fields", "foam", "lattice", "shell"]
