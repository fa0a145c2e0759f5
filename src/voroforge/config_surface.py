"""Numerical settings of Voronoi on surfaces (restricted Voronoi, surface Lloyd, panels).

Re-exported by :mod:`voroforge.config`, so every module still imports its constants from
``config``; they are kept here only to keep each module short.
"""

from __future__ import annotations

__all__ = [
    "SURFACE_FAR_SITES",
    "SURFACE_BUCKETS_PER_SITE",
    "SURFACE_EDGE_RTOL",
    "SURFACE_COORD_RANGE",
    "SURFACE_SAMPLE_ULPS",
    "SURFACE_COARSE_SHARE",
    "SURFACE_LBFGS_MEMORY",
    "SURFACE_LBFGS_BACKTRACK",
    "SURFACE_MORPH_MERGE_RTOL",
    "SURFACE_DEGENERATE_NORMAL",
    "SURFACE_NORMAL_NUDGE",
    "SURFACE_KNN",
    "SURFACE_STRAIGHT_DEG",
    "SURFACE_LOCAL_CUT",
]

#: surface.voronoi: sites farther than this many times the surface's size from its box centre
#: are refused: the cuts are exact to ~1e-16 there, but each mesh vertex's nearest site comes
#: from squared distances, which tie past ~1e13 (D = 1e16: cells 94% off, silently)
SURFACE_FAR_SITES = 1e12

#: Restricted Voronoi: at most this many grid buckets per site (the bucket side grows to fit;
#: sites on a surface leave most buckets of the box empty).
SURFACE_BUCKETS_PER_SITE = 8

#: A cell boundary shorter than this (relative to the mesh's size) makes no neighbour.
SURFACE_EDGE_RTOL = 1e-9

#: A Surface's extent and the magnitude of its vertices and sites must lie in this range:
#: the restricted Voronoi kernels square areas (fourth powers of lengths: 0 or inf past
#: ~1e+-77); out of it a ValueError says so
SURFACE_COORD_RANGE = (1e-60, 1e60)
#: surface.SurfaceVoronoi.sample_check's slack in unit roundoffs of the surface's largest
#: coordinate: piece vertices are rounded where they lie, so far from the origin a correct
#: diagram's sample lands up to ~1.4 of them past a tie (unit sphere at offsets 1e6..1e15)
SURFACE_SAMPLE_ULPS = 8

#: Surface CVT from a site count: the share of the relaxation steps spent on the coarse level
#: (a quarter of the sites) before the midpoints of its neighbour pairs are added (0.4: 94.9%
#: hexagons over three seeds on the 1,000-cell sphere benchmark; 0.2: 92.7%, 0.3: 94.1%).
SURFACE_COARSE_SHARE = 0.4

#: Surface CVT by L-BFGS: steps kept in the two-loop recursion, and halvings of a step tried
#: before a Lloyd step is taken instead.
SURFACE_LBFGS_MEMORY = 10
SURFACE_LBFGS_BACKTRACK = 8
#: surface.morph: mapped ring vertices this close (relative to the mapped design's extent)
#: to the previous kept one are one point: a UV edge collapsed by the map (a sphere's pole,
#: a cone's apex)
SURFACE_MORPH_MERGE_RTOL = 1e-12
#: surface.panels: a morphed vertex's normal f_u x f_v is degenerate where |f_u x f_v| <=
#: this x |f_u| |f_v| (a pole of the map); it is then taken a step SURFACE_NORMAL_NUDGE
#: (fractions of the way to the panel's UV centre) into the panel, the first that gives one
SURFACE_DEGENERATE_NORMAL = 1e-12
SURFACE_NORMAL_NUDGE = (1e-9, 1e-6, 1e-3)

#: Restricted Voronoi: each site's list of nearest sites, from which a triangle's candidate
#: sites are taken when the list provably holds them all (else a grid query).
SURFACE_KNN = 8

#: Planarize: a vertex of one panel only (a mesh border's facets) where the outline turns by
#: less than this many degrees is left out of the outline before planarising.
SURFACE_STRAIGHT_DEG = 10.0
#: kernels.surface: a triangle with more candidate sites than this cuts each piece by its
#: site's neighbours (kernels.surfcut.cut_local) instead of by every candidate (8,000 sites
#: on a 2-triangle square 2.6 s -> 0.05 s; below this the two cost about the same)
SURFACE_LOCAL_CUT = 32
