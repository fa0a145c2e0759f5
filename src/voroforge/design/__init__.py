"""Parametric design with Voronoi diagrams: the Grasshopper-style workflow in Python.

boundary -> seeds (:mod:`populate`) -> optional relaxation (:mod:`relax`) -> ``vf.voronoi``
-> attractor fields (:mod:`attractors`) -> cell operations (:mod:`cellops`) -> recursive
subdivision (:mod:`recursive`). Units are millimetres by default; every function is pure
and takes its randomness from an explicit ``seed``.
"""

from . import attractors, boundary, cellops, populate, recursive, relax  # noqa: F401

# isort: split
from . import fabrication, pipeline, schema  # noqa: F401  (design files and fabrication)
