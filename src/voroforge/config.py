"""Numerical settings shared by every kernel: numba flags and tolerances live here only."""

from __future__ import annotations

import os

#: Flags for every ``@njit`` kernel. ``fastmath`` stays off everywhere: the robust
#: predicates rely on IEEE round-to-nearest and on no contraction into FMA.
NJIT = {"cache": True, "nogil": True, "fastmath": False, "error_model": "numpy"}

#: Same, with ``parallel=True`` for kernels that use ``prange``.
NJIT_PARALLEL = {**NJIT, "parallel": True}

#: Relative tolerance (of the domain's size) below which a clipped Voronoi edge counts as
#: a point contact rather than a shared edge. Exactly cocircular sites are detected with the
#: exact incircle predicate, so this only matters for nearly degenerate input.
EDGE_LENGTH_RTOL = 1e-12

#: Relative tolerance (of the domain's size) used to snap vertices produced by clipping
#: back onto the exact coordinates of a rectangular domain.
SNAP_RTOL = 4.0 * 2.0**-52

#: Below this many sites the engine does not bother with threads.
PARALLEL_MIN_SITES = int(os.environ.get("VOROFORGE_PARALLEL_MIN_SITES", "20000"))

# ---------------------------------------------------------------------------------------------
# Tolerances. Each literal tolerance of the package lives below, one line saying what it guards.
# ---------------------------------------------------------------------------------------------

# --- predicates, vertices, Delaunay-dual cells, power cells ----------------------------------

#: Relative size of a centre's float denominator (to the sum of its two products) below
#: which the adaptive orient2d replaces it (kernels/vertex.center)
VERTEX_DET_RTOL = 1e-8
#: Squared distance between two sites, relative to the squared radius of their circle,
#: below which a triple holding both is not a vertex's name (ill-conditioned centre)
VERTEX_PAIR_RTOL = 2.0**-40
#: A cocircular triple names a vertex only if its centre is this close to the vertex (L1,
#: relative to the vertex's magnitude and distance from its site; kernels/vertex)
VERTEX_SNAP_RTOL = 2.0**-40

# --- half-plane cells, bucket grid, raster ----------------------------------------------------

# --- engine (inputs, domains, periodic, describe, interpolation, Lloyd) ------------------------

# --- design layer and io ----------------------------------------------------------------------
