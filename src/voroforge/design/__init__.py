"""Parametric design with Voronoi diagrams: the Grasshopper-style workflow in Python.

boundary -> seeds (:mod:`populate`) -> optional relaxation (:mod:`relax`) -> ``vf.voronoi``
-> attractor fields (:mod:`attractors`) -> cell operations (:mod:`cellops`) -> recursive
subdivision (:mod:`recursive`). Units are millimetres by default; every function is pure
and takes its randomness from an explicit ``seed``.

Design files: :mod:`schema` (the models), :mod:`designfile` (reading TOML, overrides, errors
with file and line), :mod:`compute` (a design to geometry, in memory), :mod:`build` (the
files a design names, check reports, the starter design), :mod:`fabrication` (checks, kerf).
"""

from . import attractors, boundary, cellops, populate, recursive, relax  # noqa: F401

# isort: split
from . import build, compute, designfile, fabrication, schema  # noqa: F401  (design files)
