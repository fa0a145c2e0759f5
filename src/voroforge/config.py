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
#: Triples tried for a cocircular class's name before its reference centre is kept (the
#: same bound for every caller, so names agree; caps the cubic search on huge classes)
NAME_MAX_TRIES = 4096
#: A cocircular triple names a vertex only if its centre is this close to the vertex (L1,
#: relative to the vertex's magnitude and distance from its site; kernels/vertex)
VERTEX_SNAP_RTOL = 2.0**-40
#: A centre whose rounding bound exceeds this fraction of its own magnitude is computed from
#: exact expansions (a sliver's: sites on a circle, sites a few ulps apart; kernels/vertex)
VERTEX_REFINE_RTOL = 2.0**-30
#: Two computed vertices within their rounding bounds of each other and closer than this
#: (L1, relative to the circumradius, plus ulps of their magnitude) are one vertex: floats
#: cannot order a shorter Voronoi edge (kernels/vertex.same_vertex: adjacent Delaunay
#: centres, and a site joining a half-plane cell's vertex)
CC_MERGE_RTOL = 2.0**-46
#: Rounds of merging swapped Voronoi vertices (a backwards edge) before the cells are built;
#: each round merges, so this only bounds pathological input (kernels/centers._unfold)
FOLD_MAX_ROUNDS = 64
#: Only a Voronoi edge within this many times what rounding and naming move its ends (their
#: error bounds + VERTEX_SNAP_RTOL of the radius) can be a fold: a longer one that breaks a
#: turn test is a straight angle rounded (kernels/centers._unfold)
FOLD_SPAN_ERRS = 4.0
#: A cell's vertex that rounding left a right turn, on the line of its neighbours, joins the
#: nearer one when within this many times what rounding and naming moved the three (a nearly
#: cocircular cluster far out; kernels/folds._straight_fold)
FOLD_REACH_ERRS = 256.0
#: ... and never further than this of the vertex's distance from its site (a class's naming
#: move grows with every join: it must not carry vertices across the sites' spacing)
FOLD_REACH_RTOL = 2.0**-10
#: How many times a stalled fold test doubles its reach (FOLD_REACH_RTOL): 2**-10 -> 2**-4
#: of the vertex's distance from its site
FOLD_STALL_DOUBLINGS = 6
#: A folded ring's fan is sorted by its centres' bits for the stalled test
#: (kernels/folds._stalled_at) when it has more bad turns than this (fewer: read whole)
FOLD_SORT_TURNS = 8
#: Rings longer than this are not tested for simplicity (the test is quadratic): a folded one
#: counts as not simple, alike in every round (kernels/folds._ring_simple)
FOLD_SIMPLE_MAX = 512
#: ... while every join keeps its ends within this of the site's distance to its nearest
#: neighbour of their exact centres (0.5: half the spacing; 0.25 left 600 sites of radius
#: 1e-5 at (3e4, 1e4) non-convex, 2 folded more of the neighbouring circles)
FOLD_STALL_SPACING = 0.5
#: A point must be this far (relative to its distances to the two sites, plus 16 ulps of
#: its own coordinates for their rounding) off the bisector of two neighbours for a cut
#: cell's edge to be relabelled from one to the other (kernels/cellcut._nearest_label)
RELABEL_RTOL = 1e-9
#: ... plus this many unit roundoffs (2**-53) of the point's coordinates (its rounding)
RELABEL_ULPS = 16.0
#: A Voronoi vertex within 4 times its class's rounding bound plus this many ulps of its
#: larger coordinate of a box side is put on the side, in every cell at it, unless a site of
#: its triangles is within that reach of the side (kernels/cellsides.side_reach)
BOX_SIDE_REACH_ULPS = 1.0
#: A stalled fold's class with more triangles than this keeps its name (kernels/refit: each
#: candidate is scored on every site's ring; the largest class on issue 15's circles had 185)
FOLD_FIT_MAX_MEMBERS = 512
#: A fold round's class whose members' centres spread over more than this many ulps (L1) is
#: named from its middle member (kernels/refit.middle_member: a name at a class's edge folded
#: more rings, a 1000-site circle's class grew to 997 of 998 triangles, 22,189 ulps off)
CLASS_SPREAD_ULPS = 64.0
#: A cut cell's ring that rounding turns the wrong way only beside edges this many ulps (of
#: the vertex's coordinates) long, and is simple, is kept: the end of a strip an ulp wide
#: (kernels/cells._reflex_by_rounding)
REFLEX_SHORT_ULPS = 16.0
#: Two power-cell vertices are one point when within this times their L1 distance from the
#: cell's site (the local spacing), plus 16 ulps of their coordinates: the join of the rings'
#: tiny or one-sided edges across neighbours (kernels/power._close, _reconcile)
POWER_CROWDED_RTOL = 1e-9
#: ... that many unit roundoffs (2**-53) of the vertices' coordinates (their rounding far
#: from the origin)
POWER_CROWDED_ULPS = 16.0
#: Power lift: a lower facet resolves its sites' curvature when each side's squared length
#: (frame units) exceeds this many ulps of twice the largest lifted coordinate
POWER_LIFT_RESOLVE_ULPS = 1e4
#: Where not, each site's nearest this many in the lifted space are its first candidates;
#: then cells' vertices are checked against them, to POWER_CHECK_ULPS ulps, in at most
#: POWER_CHECK_ROUNDS rounds (engine/power_check.checked_cells)
POWER_LOST_NEAR = 12
POWER_CHECK_ULPS = 16.0
POWER_CHECK_ROUNDS = 64
#: Relative slack of the proof that no suspect reaches a power cell (engine/power_check
#: _unreached): far above its few roundings, far below any cell's margin that matters
POWER_REACH_RTOL = 2.0**-30
#: A power ring or edge at most this many ulps of its coordinates across is below what
#: float64 holds of a cell there and is merged to one point (engine/power_check.settle), in
#: at most POWER_SETTLE_ROUNDS rounds
POWER_SETTLE_ULPS = 64.0
POWER_SETTLE_ROUNDS = 8
#: power_fit runs Newton in a frame at the domain's corner when the domain lies farther than
#: this many of its sizes from the origin (a cell of area 2e-7 at 1e5 had stalled)
POWER_FIT_FAR = 4.0
#: Relative size of a seed candidate's float orientation below which the sweep's seed
#: search asks the exact orient2d (nearly collinear: never the smallest circle; delaunay)
SEED_DET_RTOL = 1e-10
#: engine.assemble._union_kept: a union of a cell's parts whose float area is below this
#: fraction of theirs is checked exactly for lost parts (GEOS gave POLYGON EMPTY for two
#: strip pieces an ulp wide)
UNION_KEPT_RATIO = 0.75

# --- half-plane cells, bucket grid, raster ----------------------------------------------------

#: Smallest side of a bucket grid's box relative to its larger one (collinear sites still
#: get a grid of positive area; kernels/grid.grid_shape)
GRID_DEGENERATE_RTOL = 1e-6
#: The bucket grid is this much (relative) wider than the sites, so every site's bucket
#: index is below the bucket count without clamping (kernels/grid.grid_shape)
GRID_WIDEN_RTOL = 1e-12
#: Margin on the half-plane cell's stop radius (2 r) against rounding in its radius r
HALFPLANE_REACH_RTOL = 1e-9
#: Half-plane settling: a site is watched where its plane value is below this times the
#: box's squared radius about the site (the float cut's vertex error, squared: 2**-40 of it)
HALFPLANE_SLACK2 = 2.0**-80
#: ... and an edge is sure (no exact test) only when its length times the sine at its ends,
#: squared, exceeds this times the box's squared radius about the site
HALFPLANE_SURE_FAR = 2.0**-72
#: Band around a vertex's circle (relative to its squared radius) inside which a candidate
#: site is watched and gets the exact incircle test in the half-plane cell's finishing
HALFPLANE_NEAR_RTOL = 1e-7
#: |d| (squared distance to a vertex's circle minus its radius squared) below which a site
#: counts as on the circle: 2 r times the default algorithm's 2**-46 vertex merge tolerance
HALFPLANE_MERGE_RTOL = 2.0**-45
#: Squared float edge length, relative to the squared cell radius, above which a half-plane
#: cell's edge is taken as it is (rounding moves vertices by ~1e-16 of the radius)
HALFPLANE_SURE_RTOL = 1e-12
#: Squared sine of the angle between adjacent float edges below which neither is taken as
#: it is (their crossing is ill-conditioned)
HALFPLANE_SURE_SIN2 = 1e-16
#: Squared distance of two sites, relative to a neighbour's squared distance, below which
#: the box crossing decides which of the two owns the edge at a box side (a few ulps apart)
HALFPLANE_SHADOW_RTOL = 2.0**-40
#: Half-plane cells certify themselves: convex rings (exact test) whose areas sum to the
#: box's within this fraction; otherwise the Delaunay dual builds the diagram (engine/planar)
HALFPLANE_TILING_RTOL = 1e-9
#: Half-plane k-d search: a node is cleared when its bound exceeds the cell's reach by this
#: times (the reach + the site's coordinates), absolute, not relative to |v|^2 (4x the cut's
#: vertex error; a relative margin kept ~45 sites each side of a 1e6-site line)
HALFPLANE_NODE_BAND = 4.0 * 2.0**-40
#: Relative widening of a raster tile's k-th nearest bound against rounding in it
RASTER_BOUND_RTOL = 1e-12
#: Absolute slack of that bound relative to the coordinates' magnitude (rounding in the
#: candidate distances), and its floor for all-zero coordinates
RASTER_SLACK_RTOL = 1e-12
RASTER_SLACK_FLOOR = 1e-300
#: Fraction of empty buckets (of a grid of two sites a bucket over image and sites) past which
#: the sites count as crowded and the raster finds nearest sites by a Delaunay walk (uniform
#: sites leave about e^-2 = 13.5% empty)
RASTER_CROWDED_EMPTY = 0.35

#: kernels.halfplane_settle: far out, the merge band past the near band decides a cell's
#: joins only while it is below this fraction of the circle's squared radius (sites ulps
#: apart: every site lies in it, and they keep the exact test)
HALFPLANE_MERGE_WIDE_MAX = 2.0**-4

# --- engine (inputs, domains, periodic, describe, interpolation, Lloyd) ------------------------

#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: an image's piece, or a part or hole of a united cell, at most this many
#: ulps of the box's magnitude wide (its area against its extent) is a rounding sliver: an
#: image site off by rounding moves its cell's edge by an ulp or two. A width, not an area:
#: a thin piece is kept however small (a corner that just reaches across the wrap)
PERIODIC_SLIVER_ULPS = 4.0
#: The largest periodic margin, in periods of its axis: past 1.5 every vertex passes the
#: bracket test of engine/periodic._proved; the rest is room for rounding
PERIODIC_CAP_PERIODS = 1.6
#: How far apart, in ulps of the box's coordinates, a vertex and its image may be computed
#: (a tie rounded to even both ways is 1 ulp): engine/periodic._tie_images
PERIODIC_TIE_ULPS = 2.0
#: engine.periodic: a margin whose proof fails grows each failing axis to this many times the
#: failing vertices' shortfall (``_shortfall``; sites on one line: 7.9 n copies -> 3 n)
PERIODIC_SHORTFALL_SLACK = 1.0625
#: engine/periodic_chord.chord_clear: a vertex whose chord holds more sites' coordinates than
#: this is left unproved by the chord test (the per-site check costs a pair per site)
PERIODIC_CHORD_SITES = 16
#: engine.periodic: the sites (a site off a line) whose copies a margin's proof may take out
#: to the caps when only they fail the chord test, instead of growing the whole margin
PERIODIC_EXTRA_SITES = 64
#: engine/periodic_chord.shortfall: at most this many cells cut off by the grown box on an
#: axis double its margin (instead of asking for their radius) where they ask for more than
#: PERIODIC_CUT_CELLS_ASK times it
PERIODIC_CUT_CELLS = 8
PERIODIC_CUT_CELLS_ASK = 4.0
#: engine.periodic_retry: a margin's first growth is at least this factor, a later one at
#: least PERIODIC_REGROW (sloped lines: 3-4 builds of ~2x each became smaller steps)...
PERIODIC_FIRST_GROW = 2.0
PERIODIC_REGROW = 1.25
#: ...and the margins of cells cut off on both axes double at once where that adds at most
#: this fraction of the next try's copies (unconditional: 18% more copies at 2,000 sites)
PERIODIC_WAIT_GROW_COST = 0.125
#: engine.periodic_lines: at least PERIODIC_LINE_MIN_SITES sites, all but a few in a band
#: across one axis at most PERIODIC_LINE_BAND of its period thin, start with the line's
#: margins (one build instead of two)
PERIODIC_LINE_BAND = 0.0625
PERIODIC_LINE_MIN_SITES = 64
#: ...an off site's cell is given room along the line this factor past its reach, plus this
#: many plain first margins
PERIODIC_LINE_OFF_REACH = 1.0
PERIODIC_LINE_OFF_SLACK = 0.25
#: engine.periodic_exact: a vertex rounded copies can move by more than this many ulps (a
#: first-order bound times the safety factor) is recomputed from the exact images
PERIODIC_EXACT_ULPS = 4.0
PERIODIC_EXACT_SAFETY = 2.0
#: describe(): on a torus, a vertex and another's image closer than this (of the box's
#: diagonal) are one vertex (images come from sites shifted by the box's size); a cell of a
#: non-convex domain within 100 times this of its own coordinates' magnitude from the
#: boundary may have been cut by it (its convexity is not checked)
VERTEX_RTOL = 1e-13
#: describe(): a ring vertex that at most two rings have, within this many ulps (of the
#: largest coordinate of it and its two ring neighbours) of the chord between them, is a
#: straight angle (a rounded T-junction); no turn that small makes a cell non-convex
VERTEX_STRAIGHT_ULPS = 8.0
#: describe(): a point only one ring has and turns at, not a domain corner (a boundary
#: crossing one cell rounded elsewhere), is one vertex with the points at most two rings have
#: within this many ulps of its largest coordinate; all others are one only when bit-equal
VERTEX_MERGE_ULPS = 2.0
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: 3D describe(): a cell is convex when no vertex is past another face's plane by more
#: than this of the cell's size, or CONVEX3D_ULPS ulps of its coordinates where coarser
#: (rounding at an offset: a third of an ulp at 7e13 was a dent)
CONVEX3D_RTOL = 1e-9
CONVEX3D_ULPS = 16.0
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate: float squared distances within this relative band of the nearest one may be
#: the nearest exactly (each is rounded by a few ulps): those sites are compared in rationals
LOCATE_ROUND_RTOL = 2.0**-48
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: locate(): queries farther than this from the sites' box centre (per axis) are settled by
#: |s|^2 - 2 q.s in a scaled frame, since their squared distances would overflow
LOCATE_FAR = 1e150
#: locate(): values of |s|^2 - 2 q.s (scaled) within this many eps of their terms' sizes of
#: the least are compared exactly (two rounded products and a sum: 8 is generous)
LOCATE_FAR_ULPS = 8.0
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: PowerDiagram.locate: power distances within this many eps of their terms (|x - p|^2 and
#: |w|) of the least are compared exactly (a rounded difference, square, sum: 8 is generous)
POWER_LOCATE_ULPS = 8.0
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: engine.integrate: a cell part's GEOS triangulation whose area differs from the part's by
#: more than this (relative) is not trusted and its signed fan is used (checker15 F6)
INTEGRATE_COVER_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

# --- design layer and io ----------------------------------------------------------------------

#: Largest picture the PNG writer, the 3D renderer and `explain` accept, in pixels (w x h,
#: with the PNG writer's supersampling): 2**30 px is about 3 GB of RGB; beyond it a typo
#: (--size 100000) would exhaust the machine's memory instead of failing with a clear error
#: (the rasteriser's own guard is on bytes: RASTER_MAX_BYTES)
MAX_PIXELS = 2**30
#: Largest `explode` of a 3D picture (a fraction of each cell centroid's offset from the
#: centre): the view fits every cell, so at 30 cells were specks and at 1e20 the PNG was blank
EXPLODE_MAX = 5.0
#: engine.raster: the most memory a raster may need (bytes); `rasterize` and `voroforge
#: raster` refuse a larger estimated peak up front (2**30 px had let ~108 GiB through)
RASTER_MAX_BYTES = 16 * 2**30
#: Peak bytes a pixel (without, with f2), exact/jfa/Delaunay walk: measured 12-25, 20-40
RASTER_BYTES = {False: 26, True: 42}
#: Bytes a pixel of the result: labels int32 and F1 float64 (and F2 float64)
RASTER_RESULT_BYTES = {False: 12, True: 20}
#: Peak bytes a site, on top: where the Delaunay walk decides labels (884 measured, sites
#: crowded on a circle), elsewhere (113-124 measured)
RASTER_SITE_BYTES = (1000, 160)
#: Peak bytes a pixel of drawing one field as a PNG, on top (measured 96, 25, 25, 33)
RASTER_WRITE_BYTES = {"labels": 100, "distance": 28, "f2": 28, "edge": 36}
#: And a site, for labels: the pairs of touching pixels that differ (372 measured)
RASTER_WRITE_SITE_BYTES = 400
#: design.stipple: largest page side (the pen-up ordering squares distances: inf past 1e154)
STIPPLE_MAX_PAGE = 1e150
#: Longest side of an `explain` GIF in pixels (its frames together hold at most MAX_PIXELS):
#: a typo such as --size 200000 fails at once instead of exhausting the memory
GIF_MAX_SIDE = 8192
#: Most points seeds.method = 'poisson' may place (about 0.67 area / radius^2 are expected;
#: it is checked before sampling, which takes about a millisecond per point)
POISSON_MAX_POINTS = 200_000
#: Most points any other seeding method may place (random, density, grids): 2e7 points are
#: 320 MB of coordinates before any cell is built; a typo such as count = 1e9 asked for 18 GiB
SEEDS_MAX_POINTS = 20_000_000
#: Most seeds a design may have (its cells are shapely polygons with openings, offsets and
#: fabrication checks, about 2 KB each and more; 1e7 was killed for memory on 24 GB)
DESIGN_MAX_CELLS = 2_000_000
#: The largest file a design may name (point tables, outlines, images, meshes, heights): a
#: link to /dev/zero or a 50 GB file was read whole until memory ran out.
DESIGN_FILE_MAX_BYTES = 4 * 2**30
#: The largest ``cells.scale``: a cell grown 100 times covers its neighbours many times
#: over; 1e200 had GEOS fail with a traceback and 1e307 ran for minutes.
DESIGN_MAX_CELL_SCALE = 100.0
#: design.boundary.circle / ``boundary.segments``: the most vertices of a circle boundary. At
#: 65,536 the chord error is 1.15e-9 of the radius, below any fabrication tolerance; 1e6
#: segments took 47 s and 1.9 GB to build a 10-seed panel (checker7 F7), 3e9 did not finish
BOUNDARY_MAX_SEGMENTS = 1 << 16
#: Most dots design.stipple places (each Lloyd step builds a diagram of them and integrates
#: the image's density over every cell: 3e6 dots on a 256 x 256 image ran past 60 s, 2.5 GB)
STIPPLE_MAX_POINTS = 1_000_000
#: Most dots x Lloyd steps of one stipple (3.4-6.5 us a dot-step here, 2e4-1e5 dots on a
#: 256 x 256 image): 5e7 is a few minutes; 100 dots x 1e7 steps ran on with no message
STIPPLE_MAX_WORK = 50_000_000
#: Most cells one recursion level may hold (design.recursive.subdivide): each costs ~0.2 ms
#: of shapely work, and depth 6 with count 6 on 60 seeds asked for 2.8M (over 8 minutes)
RECURSION_MAX_CELLS = 500_000

#: Surface tessellations (``vf.surface`` shapes): a default resolution is capped at this
#: many grid cells, with a warning (a cylinder of radius 1e-9 would need 114 GiB); an
#: explicit ``resolution`` beyond the second figure is refused (16M triangles: ~1 GB)
SURFACE_DEFAULT_MAX_CELLS = 1 << 18
SURFACE_MAX_CELLS = 1 << 23

#: mm: default SVG stroke width of a design build, a laser hairline (drivers cut only
#: hairlines, about 0.001 in or less, as vectors; 0.01 in would be engraved).
HAIRLINE_MM = 0.01

#: design.cellops.explode: vertices of neighbouring cells closer than this fraction of the
#: cells' bounding-box diagonal are one vertex (rounding-level differences double no edge).
EDGE_MERGE_RTOL = 1e-9

#: design.cellops: a single polygon is convex when its hull's area exceeds its own by at most
#: this fraction of the hull's (such cells are scaled and filleted on a fast path).
CONVEX_AREA_RTOL = 1e-12

#: design.convexops: a turn (radians) below this makes a vertex straight; it is dropped.
CONVEX_STRAIGHT_TURN = 1e-9
#: design.convexops: moved lines of two edges made neighbours by a dropped edge turning less
#: than this (radians) are too close to parallel to cross accurately (the cell goes to GEOS).
CONVEX_PARALLEL_TURN = 1e-7
#: design.convexops: an edge shorter than this fraction of its cell's size merges its ends.
CONVEX_SHORT_EDGE_RTOL = 1e-10
#: design.convexops: a corner sweeping less than this (radians) gets one point, as GEOS's
#: offset curve does (OFFSET_SEGMENT_SEPARATION_FACTOR).
CONVEX_ARC_SEPARATION = 1e-3
#: design.convexops: a ring whose turns add up to 2 pi within this (radians) is simple.
CONVEX_FULL_TURN_TOL = 1e-6

#: design.compute: a corner_radius of half the boundary's width (a stadium, a disc) leaves a
#: core GEOS drops; the radius is made this fraction smaller to keep a sliver of it.
CORNER_RADIUS_SHRINK = 1e-4

#: design.populate: a boundary filling less of its bounding box than this is sampled from
#: its triangles (rejection from the box would draw count / fill points).
POPULATE_REJECTION_MIN_FILL = 1e-3
#: design.populate / image seeds: rejection rounds keeping under this fraction of their
#: candidates draw the shortfall at the rate seen (at most POPULATE_MAX_BATCH a round, and a
#: uniform draw needing more is sampled from the triangles); POPULATE_MAX_DRAWS in all, or
#: POPULATE_EMPTY_DRAWS with none kept, before giving up.
POPULATE_LOW_ACCEPT = 0.05
POPULATE_MAX_BATCH = 10_000_000
POPULATE_MAX_DRAWS = 50_000_000
POPULATE_EMPTY_DRAWS = 1_000_000

#: design.compute: cells.min_size measures openings' inscribed circles to this fraction of
#: min_size.
MIN_SIZE_RTOL = 1e-3

#: design.recursive: cells tile their region when their areas sum to its area within this
#: fraction (else they are cut to the region again).
TILING_AREA_RTOL = 1e-9

#: design.fabrication.check: webs and openings within this fraction of their limit, plus
#: FAB_LIMIT_COORD_RTOL of the panel's largest coordinate, pass (a web inset to exactly
#: min_web is no violation because of rounding; relative, so a panel in metres or microns
#: is checked as closely as one in mm).
FAB_LIMIT_RTOL = 1e-6
FAB_LIMIT_COORD_RTOL = 1e-14

#: design.fabrication.check: uncut material thinner than this (drawing units) in a corner is
#: ignored (chord-vs-arc noise of fillets)
FAB_CORNER_TOLERANCE = 0.02
#: ...and a design file's default corner_tolerance, in millimetres (converted to design.units)
FAB_CORNER_TOLERANCE_MM = 0.02

#: design.fabrication: corner leftovers with area below (this x corner tolerance)^2 are noise.
FAB_CORNER_AREA_RTOL = 0.1

#: design.fabrication.inscribed_circles: default precision, this fraction of each polygon's
#: smaller box side...
INSCRIBED_RTOL = 1e-3

#: ...and never below this (drawing units), nor a drawing's extent for marker sizes.
INSCRIBED_FLOOR = 1e-9
#: A tolerance given to it is raised to at least this fraction of the polygon's smaller box
#: side (``cells.min_size = 1e-300`` asked GEOS for 1e-303 and never finished).
INSCRIBED_MIN_RTOL = 1e-12

#: design.fabrication: a frame part touches the outline when nearer than this fraction of the
#: outline's largest coordinate (at least 1); parts farther away are loose islands.
ISLAND_TOUCH_RTOL = 1e-9

#: mm: default largest distance between a curve (SVG Bézier/arc, DXF bulge/circle) and the
#: polyline a boundary reader flattens it to; well below laser and CNC resolution.
CURVE_TOLERANCE = 0.01
#: Largest coordinate or width a drawing (SVG, PNG, DXF, GIF) takes: its page size, padding
#: and pixel scale multiply the extent by up to ~1e3 (a box to 1e308 wrote width="inf").
DRAW_MAX_COORD = 1e300
#: Most points one flattened arc or circle may take (an SVG arc of radius 1e40 at 0.01 asked
#: for 1e21); past it the reader names the arc and asks for a coarser tolerance.
CURVE_MAX_POINTS = 4_000_000

#: Floor on an SVG element's transform scale, so its flattening tolerance never divides by 0.
SVG_MIN_SCALE = 1e-300

#: Radians: a DXF ELLIPSE whose parameter span is within this of a full turn is closed.
ELLIPSE_FULL_TURN_ATOL = 1e-9

#: Default largest distance (drawing units) of a vertex from the circular arc that replaces
#: its run of chords in DXF bulges and SVG ``A`` arcs.
ARC_TOLERANCE = 1e-6

#: Radians: a vertex turning less than this is straight, never inside an arc.
ARC_MIN_TURN = 1e-9

#: Relative slack on the largest turning per chord that still counts as part of an arc.
ARC_STEP_RTOL = 1e-9

#: Chords of one arc have equal length within this fraction of the longer one.
ARC_CHORD_RTOL = 1e-3

#: Neighbouring vertices of one arc turn equally within this fraction of the turn...
ARC_TURN_RTOL = 1e-3

#: ...or within this many radians for tiny turns (the floor of that fraction's scale).
ARC_TURN_FLOOR = 1e-3

#: Floor of the arc-fit tolerance relative to the ring's largest coordinate (float64 noise).
ARC_FIT_RTOL = 1e-11

#: Radians of slack (over half a step) between an arc's fitted sweep and its chords' turning.
ARC_SWEEP_ATOL = 1e-6

# --- explain (teaching tracers) -----------------------------------------------------------------

#: Fortune tracer: edges shorter than this (relative to the box's size) are the zero-length
#: edges between coinciding vertices of degenerate input, and are dropped.
EXPLAIN_EDGE_RTOL = 1e-9

#: Fortune tracer: arcs whose float heights are within this (relative) of the lowest are
#: compared exactly, so near-degenerate input cannot put a site under the wrong arc.
EXPLAIN_HEIGHT_RTOL = 1e-9

#: Fortune tracer: sites whose largest coordinate is past ``2**EXPLAIN_SCALE_EXP`` (or below
#: its inverse) are swept scaled by a power of two, every recorded coordinate scaled back
#: exactly (wrong edges past ~1e105 and an OverflowError from 1e154 before)
EXPLAIN_SCALE_EXP = 64

# --- voronoi3d (3D cells, containers): config3d.py; surfaces (Voronoi on curved surfaces,
# --- panels): config_surface.py; solid (printable lattices, foams, shells): config_solid.py;
# --- moments (Lloyd, CVT): config_moments.py; box sides and corners (2D crossings):
# --- config_sides.py; all re-exported here ---------------------------------------------------

from .config3d import *  # noqa: E402, F403
from .config_moments import *  # noqa: E402, F403
from .config_sides import *  # noqa: E402, F403
from .config_solid import *  # noqa: E402, F403
from .config_surface import *  # noqa: E402, F403

# --- fabrication / plotter (paths for machines: io/plotter, io/labels) --------------------

#: Path end points closer than this fraction of the drawing's size are one vertex when
#: layers are deduplicated and lines merged (rounding between products of one layer)
PLOTTER_MERGE_RTOL = 1e-9
#: ...and at least this many ulps of the largest coordinate (rounding far from the origin),
#: but below a quarter of the shortest drawn segment (io.plotter._tolerance)
PLOTTER_MERGE_ULPS = 64
#: Memory a GIF's frames may take while it is written (Pillow holds every frame, 1 byte a
#: pixel, before it writes the file): `voroforge animate` refuses frames x size^2 past it
GIF_MAX_BYTES = 2_000_000_000
#: 2-opt candidate list: this many nearest path ends of each end
PLOTTER_NEIGHBOURS = 10
#: 2-opt stops after this many passes even if a move still shortens the tour
PLOTTER_MAX_PASSES = 50
#: Or-opt moves a path at most this many positions along the tour (bounded shifts)
PLOTTER_OR_WINDOW = 64

# --- studio (the local editing page and the Jupyter widget) --------------------------------

#: The most sites one edit may ask for (count, or estimated from a spacing/radius): a clear
#: error on the page instead of a server busy for minutes
STUDIO_MAX_SEEDS = 50_000
#: Largest message the page may send (bytes); bigger ones are refused with an error
STUDIO_MAX_MESSAGE = 64 * 1024
#: Seconds ``voroforge studio`` waits after SIGTERM/Ctrl+C for open work (an edit's compute
#: in a worker thread cannot be interrupted) before it exits without it
STUDIO_SHUTDOWN_S = 5.0
#: Undo steps kept
STUDIO_UNDO_DEPTH = 200
#: Seconds without edits before the live fabrication check runs (dragging stays smooth)
STUDIO_CHECK_DELAY = 0.35

# --- scale (tiled Voronoi on dask.distributed): config_scale.py, re-exported here -----------

from .config_scale import *  # noqa: E402, F403

#: Bisection steps for a corner's inside radius in the fabrication check (radius / 2^steps)
FAB_CORNER_BISECTIONS = 10

# ---- exact power cells, half-plane side snap, the 3D range and memory

#: engine.power_exact.lost_sites: the sites nearest in power cut a lost site's box first
#: (enough for a tight cluster: 30 sites); those that beat its interior point are added, for
#: up to POWER_EXACT_ROUNDS rounds; then every site cuts it
POWER_EXACT_FIRST = 16
POWER_EXACT_ROUNDS = 8

#: engine.power_exact: the float filter's bound on a power difference, in units of eps
#: times its terms' sizes: the difference has five rounded operations and a rounded interior point
#: (relative eps); 32 is generous and only sends more sites to the exact test.
POWER_EXACT_FILTER_ULPS = 32.0

#: kernels.halfplane_settle: a vertex farther inside every box side than this times
#: |x| + |y| is put on none (_side_snap): above 4 VERTEX_REFINE_RTOL (its rounding bound's
#: largest, 2**-30 of that) and BOX_SIDE_REACH_ULPS ulps of its larger coordinate (at most
#: 2**-52 of it)
HALFPLANE_SNAP_PRE = 2.0**-27

#: the container volumes, in the caller's units, that 3D cells can be measured in (built in a
#: power-of-two working frame, reported in the caller's units): the volume a double with room
#: (a cube of side 1e100), cells' volumes normal doubles down to 1e-20 of the container's
VOLUME_RANGE = (1e-270, 1e300)

#: the largest face area of the container's bounding box (the product of its two largest
#: sides): face areas in the caller's units stay doubles (a flat box of sides 1e150, 1e150
#: and 1e-150 has a volume of 1e150 but faces of 1e300)
AREA_MAX = 1e300

#: engine.build3d: cells from which a build hands the memory it freed back to the system
#: (glibc malloc_trim; below, a few MB)
TRIM_CELLS = 100_000

#: kernels.natural: a query closer to a hull edge than this times the edge's length takes
#: Sibson's limit on the edge (linear along it). Its cell there is bounded but about
#: 1 / distance long, so its areas carry a relative error of about eps / distance, while the
#: limit is off by about the distance: 2**-26 (~sqrt(eps)) balances the two (~1.5e-8).
NATURAL_HULL_RTOL = 2.0**-26

#: engine.diagram: areas and centroids are computed on coordinates scaled below 2**this, so
#: the centroids' sums (cubes of coordinates, over many vertices) stay finite in float64
AREA_FRAME_EXP = 320

#: engine.voronoi3d: the working frame keeps the container's coordinates below 2**this:
#: volumes are cubes of them and first moments fourth powers (2**1024 overflows); ordinary
#: inputs have k = 0
FRAME3D_CAP_EXP = 240
#: engine.planar: the same for the 2D working frame (squares of the domain's coordinates stay
#: finite); sites closer than about 2**-684 (1e-206) of the domain are so one site
FRAME2D_CAP_EXP = 500

#: kernels.vertex3d: a name with two container walls whose angle's sine is below this (or
#: three whose determinant is) is solved exactly: the float solve's error grows as 1 / sine
#: (a roof of slope 1e-9: volumes 7e-10 off); box walls keep the float solve
WALL_EXACT_SIN = 1e-4

#: engine.containers: ``Convex(points=)`` thinner than this fraction of its extent is flat:
#: the template's cut decides "on a wall" within ``VORONOI3D_CUT_RTOL`` (1e-12) of the
#: container's size, so a solid must be some hundred times thicker to be cut reliably
FLAT_RTOL = 1e-10

#: engine.assemble: a ring whose mean width (area / diameter) is this many ulps of its
#: coordinates is a strip between sites a few ulps apart: its crossings with the domain's
#: boundary are ulps apart, which the overlay in the coordinates' own floats can snap together
ASSEMBLE_THIN_ULPS = 64.0
#: engine.assemble: ring vertices this many ulps apart on a shared edge are the same vertex
ASSEMBLE_ALIGN_ULPS = 4
#: engine.assemble._aligned: an edge is moved onto its neighbour's only where each end moves
#: by at most 1 / ASSEMBLE_ALIGN_MOVE_RATIO of the edge's length (in a polygon a few hundred
#: ulps wide, at 3e14, 4 ulps matched an edge with the next one and dropped a vertex)
ASSEMBLE_ALIGN_MOVE_RATIO = 4.0
#: engine.assemble: a clipped cell shifted back moves each vertex by under an ulp, its area by
#: under an ulp times its perimeter; a repair that changes it more lost part of the cell
ASSEMBLE_ROUNDING_ULPS = 4.0
#: engine.pieces: a domain with at most this many vertices is intersected whole, and tested
#: with predicates on the whole domain
PIECE_SMALL = 256
#: kernels.polyclip (cells meeting a long boundary, clipped by its nearby segments, every
#: sign exact): two crossings, or a crossing and a cell's vertex, closer than this fraction of
#: a cell's edge (or of a segment) are left to the overlay
POLYCLIP_PARAM_EPS = 1e-12
#: engine.pieces: consecutive segments of a ring in one chunk of the boundary index (a
#: geometry is tested against the chunks whose boxes it meets; a piece keeps those it meets)
PIECE_CHUNK = 32
#: engine.pieces: a point is located in the whole (prepared) domain when at most this many
#: boundary segments span its ordinate (GEOS's ray crosses those), else in a cut near it
PIECE_RAY_SPAN = 1024
#: engine.pieces: points located together in one cut of the domain, on average
PIECE_TILE = 32
#: engine.pieces: the boundary's chunks are used only when a ring has more vertices than
#: this (below, whole rings near a cell cost less than the chunks' bookkeeping: a comb of
#: 1,000 teeth 1.1x slower with chunks, 2,000 about even; 400 square holes 1.18x slower)
PIECE_BIG_RING = 8192

#: engine.restore: how far (ulps of the vertex's largest coordinate, per coordinate) a
#: rounded exact vertex may be moved to the gap's vertex: a merged class's vertex sits up to
#: 2 ulps from the exact points of a cluster 1-3 ulps wide (issue 15's cluster input: 2 ulps);
#: 4 leaves a margin and is still far below a cell's own size wherever a ring is no sliver
RESTORE_SNAP_ULPS = 4.0
#: engine.restore: nearest sites the exact cut starts with; sites that beat the cell's
#: vertices join it
RESTORE_FIRST = 12

#: engine.periodic: the widest a rounding sliver of a wrapped cell can be, as a fraction of
#: the box's shorter side: a piece a quarter of the box wide is no rounding noise, however far
#: out the box lies (a box 12 ulps tall at 2e12 lost its cells to 7 ulps of 4e12)
PERIODIC_SLIVER_MAX_SIDE = 0.25
#: engine.periodic_ties: how far the rings' area sum may move by rounding alone, in ulps of
#: the box's area per ring point (each term of the shoelace sums rounds by about one): a tie
#: that leaves it farther than that from the box's area joined distinct vertices and is undone
PERIODIC_AREA_NOISE_ULPS = 4.0

#: engine.periodic_ties: the relative room added to the farthest a named point lies from its
#: own site when choosing the sites near the box's sides whose cells may hold it (the
#: distances are rounded; a point a rounding farther than the farthest must not be missed)
PERIODIC_NAME_REACH_SLACK = 1e-6

#: engine.containers: a Convex whose centre lies farther from the origin than this many times
#: its largest extent keeps its walls about an origin near it (far_origin): at 4 the absolute
#: offsets are good to ~1e-15 of the solid's size, and nearer solids keep the bits they had
#: (the walls of a unit cube at 4e6 were placed to 2.3e-10 only)
CONVEX_FAR_ORIGIN = 4.0

#: engine.meshplanes3d: a face is thin (normal from its sites) when its area is at most this
#: many times the square of its largest extent (aspect 1e-6: far above the rounding of the
#: area vector of a face of any shape, and a genuine face that thin has the same plane
#: either way)
FACE_THIN_RTOL = 2.0**-20
#: ... or at most this many ulps of its vertices' largest coordinate times its extent (the
#: rounding of the vertices themselves, which a face's area vector cannot resolve)
FACE_NOISE_ULPS = 64.0
#: engine.mesh3d: coordinates (relative to the cut's origin) beyond this, or below its
#: inverse, reach manifold3d scaled by a power of two (cut_by_mesh)
MANIFOLD_SAFE = 2.0**200
#: kernels.meshcut3d: cell-local coordinates beyond this (or below its inverse) are scaled by
#: a power of two before their moments are taken (fourth powers: 2**200 keeps them below
#: 2**800, and its inverse above 2**-800, far from float64's limits; nearer 1 nothing is
#: scaled, so the bits of ordinary meshes do not depend on it)
MESH_MOMENT_SAFE = 2.0**200
#: kernels.meshcross3d: a float orientation counts as certain beyond this many times its
#: permanent (about six times the bound of Shewchuk's filter); an uncertain one counts as 0
#: (no proper crossing: a mesh is refused only where a crossing is certain; the exact test,
#: run on the ~25% of the bench torus's tests that are exactly coplanar, made the check 4x
#: slower)
MESH_CROSS_FILTER = 1e-14

#: engine.mesh3d: the rounding of a mesh's coordinates, with room, relative to their largest
#: magnitude: added to the cut's slack and tolerance (far from the origin it is what a
#: double can say about a position; 1e-14 is ~45 ulps)
MESH_COORD_RTOL = 1e-14

#: engine.meshplanes3d.local_vertices keeps a vertex recomputed about a far mesh's local
#: origin only within this many ulps of its absolute doubles (which the cell builder rounds
#: once, half an ulp): a larger move means ill-conditioned planes, not the absolute rounding
LOCAL_VERTEX_ULPS = 2.0

#: engine.raster: a raster whose sites or bounds are past 2**±this is computed at unit size
#: (a power-of-two scaling, exact) and its distances scaled back: squared distances
#: overflowed (inf distances at bounds 1e308; NaN from the width of (-1e308, 1e308))
RASTER_FRAME_EXP = 480

#: engine.domain: a polygon domain whose coordinates are past 2**±this is checked (validity)
#: and measured (area) by GEOS scaled near unit size by a power of two (exact): GEOS squares
#: coordinates, and at ~1e150 its validity check raised on a valid polygon, and at 1e154 its
#: area of a square with a hole overflowed
DOMAIN_GEOS_EXP = 255

#: engine.power: unequal-weight power diagrams are built scaled by a power of two (weights by
#: its square; exact) when the sites' or the domain's largest magnitude is beyond 2**±this:
#: squared distances reach float64's limits near 2**±511 (at 2**490 the cells' bits moved and
#: areas overflowed); up to 2**±300 the bits were already the scaled bits
POWER_FRAME_EXP = 256

#: engine.capacity: power_fit runs on the problem scaled by a power of two (exact) when its
#: domain's size is beyond 2**±this: at 1e-150 its Newton stalled after one step and the
#: polygon clip raised GEOSException; at 1e154 areas overflowed. Nearer 1 nothing is scaled
#: (the bits of ordinary fits do not depend on it)
POWER_FIT_SCALE_EXP = 64
#: engine.capacity: when both starts stall, targets moved from the shrunk sites' areas in
#: steps of this fraction (log areas, halved down to the least), each fitted to the rtol
POWER_FIT_CONTINUATION_STEP = 0.25
#: engine.capacity: sites that start with no area in a hole or notch of the domain get it
#: in damped Newton steps on the domain's convex hull (power.fit_breakout), each asking a
#: cell still outside POWER_FIT_BREAKOUT_GROW times its area there, for at most
#: POWER_FIT_BREAKOUT_ROUNDS steps (a 4,000-site ring: about 10), before Newton on the
#: domain; where that fails, the relaxed density's continuation follows
POWER_FIT_BREAKOUT_ROUNDS = 64
POWER_FIT_BREAKOUT_GROW = 4.0
POWER_FIT_CONTINUATION_MIN_STEP = 1.0 / 64.0
POWER_FIT_CONTINUATION_RTOL = 1e-3
#: engine.capacity._gap_continuation (a MultiPolygon's far parts; sites in a hole or a
#: notch): the relaxed density on the hull outside the domain starts at most at
#: POWER_FIT_GAP_FIRST_EPS (1: the plain fit on the convex hull) and falls by
#: POWER_FIT_GAP_FACTOR per stage, squared after a stage that fits in POWER_FIT_GAP_EASY_STEPS
#: Newton steps; each stage is fitted to POWER_FIT_GAP_STAGE_RTOL (a 1,000-site ring with
#: 28% of its sites in the hole: 234 power diagrams, 414 with the old 10x-a-stage schedule).
#: A later stage that does not fit in POWER_FIT_GAP_STAGE_STEPS Newton steps is retried
#: with the factor's square root, down to POWER_FIT_GAP_MIN_FACTOR; on a MultiPolygon plain
#: Newton first gets POWER_FIT_GAP_FIRST_STEPS steps
POWER_FIT_GAP_FIRST_EPS = 1.0
POWER_FIT_GAP_FACTOR = 2.0
POWER_FIT_GAP_STAGE_RTOL = 0.3
POWER_FIT_GAP_EASY_STEPS = 2
POWER_FIT_GAP_MIN_FACTOR = 1.1
POWER_FIT_GAP_STAGE_STEPS = 40
POWER_FIT_GAP_FIRST_STEPS = 20
#: engine.capacity: where at most POWER_FIT_HOLE_SEED_FRACTION of the cells start empty
#: (sites in a small hole), plain Newton from slivers seeded for them gets
#: POWER_FIT_HOLE_SEED_STEPS steps before the relaxed density's continuation
POWER_FIT_HOLE_SEED_FRACTION = 0.05
POWER_FIT_HOLE_SEED_STEPS = 20
#: engine.power: the first fraction of a Newton step tried is this times the last one taken
POWER_FIT_ALPHA_GROWTH = 2.0

#: engine.power (power_fit's bridge across a gap): a group's area gain counts only above this
#: fraction of the domain's area. Summed cell areas carry rounding of a few ulps each; a
#: "gain" of 1e-16 had been taken as a crossing, wasting Newton steps on raises that cross
#: nothing
POWER_BRIDGE_GAIN_RTOL = 2.0**-30
#: engine.powerfit (damped Newton on the transport dual after a breakout that pushed cells
#: back out): the hull Hessian's Levenberg-Marquardt weight at the start, its fall after a
#: full step and rise after a halved one (U notch 4,000: 8 / 4 took 32 diagrams, 2 / 2 36,
#: 8 / 8 49), the weight below which it is dropped once every cell has area, and Armijo's
#: fraction of the slope the objective must rise by
POWER_DUAL_MU_START = 1.0
POWER_DUAL_MU_DOWN = 8.0
POWER_DUAL_MU_UP = 4.0
POWER_DUAL_MU_OFF = 1e-4
POWER_DUAL_ARMIJO = 1e-4

#: engine.agree: joins reach this many ulps of the larger coordinate: sites 1-4 ulps apart
#: have exact vertices a few ulps apart, each cell rounding its own (measured: 1-3 ulps)
AGREE_JOIN_ULPS = 16.0
#: ... plus this much of the vertex's L1 distance from the cell's site (the local spacing),
#: as ``POWER_CROWDED_RTOL`` for the power cells' joins
AGREE_JOIN_RTOL = 1e-9
#: engine.agree: only rings with an edge, or a vertex's distance from their site, shorter
#: than this fraction of the vertex's L1 magnitude (64 ulps of its larger coordinate or more)
#: are checked: the cells of sites ulps apart are that narrow; uniform sites' are not (their
#: check is one pass over the vertices)
AGREE_SHORT = 64 * 2.0**-52
#: engine.agree: how many choices of the joined classes' points are tried: where the
#: first (the smallest bits) leaves a ring reflex by rounding or without its site, another
#: slot's point of the same class often keeps every ring convex (groups of 4-5 sites ulps
#: apart, each cell rounding its own centres). A bound on a rare path: on 816 clusters of 4-8
#: sites 1-3 ulps apart, 234 reached the placing, at most 12 choices tried in all (median 1)
AGREE_POINT_TRIES = 256
#: engine.assemble: the most rings one clip at a domain vertex takes (the rings meeting a
#: thin ring, and the rings meeting those of them that are thin too: _held, _group)
ASSEMBLE_GROUP_MAX = 64
