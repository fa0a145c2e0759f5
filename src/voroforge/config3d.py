"""Numerical settings of the 3D engine (voronoi3d, containers, 3D Lloyd).

Re-exported by :mod:`voroforge.config`, so every module still imports its constants from
``config``; they are kept here only to keep each module short.
"""

from __future__ import annotations

__all__ = [
    "BIN_SORT_FROM",
    "CELLCUT3D_RADIUS_PAD",
    "CONVEX_THIN_AXES",
    "CONVEX_THIN_MERGE",
    "MERGE3D_HASH_FROM",
    "CLIMB3D_FLOOD_BAND",
    "CLIMB3D_PLATEAU_BAND",
    "CLIMB3D_PLATEAU_MOST",
    "CLIMB3D_NOISE_BANDS",
    "CLIMB3D_SAMPLES",
    "CLIMB3D_LOCAL_FROM",
    "DOOMED_SIDE",
    "DOOMED_SPREAD",
    "TIES_RAY_RTOL",
    "GROW_BYTES",
    "GROW_LEAST",
    "GROW_MOST",
    "GROW_PAD",
    "GROW_SHARE",
    "GROW_PROBE_PAD",
    "GROW_CHUNK_LEAST",
    "BUILD3D_RESERVE_PAD",
    "CELLCUT3D_REFRESH_CUTS",
    "CELLCUT3D_PREFETCH_MOST",
    "VORONOI3D_CUT_RTOL",
    "VORONOI3D_STOP_RTOL",
    "VORONOI3D_DET_RTOL",
    "VORONOI3D_WALL_DET_RTOL",
    "VORONOI3D_EXACT_DET_RTOL",
    "HULL3D_BIG",
    "HULL3D_SLOTS",
    "HULL3D_CHUNK",
    "HULL3D_DOP_PAD",
    "HULL3D_REACH_RTOL",
    "JOIN_LOCAL_PROBES",
    "LISTS3D_SITE_BUDGET",
    "LISTS3D_AFTER",
    "LISTS3D_POLYTOPE_MOST",
    "LISTS3D_STAR_LEAST",
    "STAR3D_WALL_BANDS",
    "CELLCUT3D_OWN_ENTRIES",
    "CELLS3D_PLACE_CACHE",
    "REACH3D_BOX_RTOL",
    "REACH3D_ROUND_TRIES",
    "REACH3D_HEAVY_GAP",
    "REACH3D_HEAVY_MOST",
    "CONVEX_NEAR_PARALLEL_SIN",
    "CONVEX_VERTEX_OUT_ULPS",
    "OUTSIDE3D_RTOL",
    "OUTSIDE3D_BLOCK",
    "CONVEX_EXACT_ROWS",
    "CONVEX_EXACT_THIN",
    "VORONOI3D_INSIDE_BLOCK",
    "VORONOI3D_PAD",
    "VORONOI3D_MESH_SLACK_RTOL",
    "VORONOI3D_MESH_FACING",
    "VORONOI3D_MESH_RTOL",
    "VORONOI3D_MESH_VOLUME_RTOL",
    "LLOYD3D_INTO_MESH_PUSH",
    "LLOYD3D_INTO_MESH_FRACTIONS",
    "SUBDIVIDE_SLIVER",
    "IMPLICIT_SAG",
    "VORONOI3D_CHUNK",
    "SURFACE_EXPR_SAMPLES",
    "SOLID_FOAM_DRAWS",
    "SOLID_FOAM_CONVEX_RTOL",
    "CUT_EXACT_DET_RTOL",
    "CUT_ILL_MARGIN",
    "FAN_ERR",
    "FAN_D2_MIN",
    "FAN_D2_MAX",
    "CONVEX_FOLD_ULPS",
]

#: The 3D cut's float filter: a vertex's value against a bisector plane farther from 0 than
#: this (relative to |d| * cell radius + |offset|, the scale of the value) is trusted; one
#: within it is decided exactly (kernels/predicates3d) on the vertex's owners
VORONOI3D_CUT_RTOL = 1e-12
#: Relative slack of the 3D stop test and of the "plane beyond every vertex" skip (inclusive,
#: so a site whose plane only touches the cell is still visited and named as an owner)
VORONOI3D_STOP_RTOL = 1e-9
#: Four owners name a vertex only if their planes' determinant exceeds this fraction of the
#: product of the rows' lengths (co-spherical sites: the first independent quadruple names it)
VORONOI3D_DET_RTOL = 1e-10
#: The same for a site and three container walls: unit normals, whose float determinant is
#: good to ~10 ulps (a Convex roof of slope 2e-6 has walls with determinant 8e-12 at its
#: ridge; with the sites' 1e-10 no quadruple named that corner and the build failed)
VORONOI3D_WALL_DET_RTOL = 1e-13
#: A vertex whose name's determinant is below this fraction of the product of its rows'
#: lengths is solved exactly (kernels.vertex3d.solve_name): the float solve's error grows as
#: 1 / that ratio (a 1 x 1 x 1e-8 periodic box: volumes 2e-2 off); ~0.6% of uniform vertices
VORONOI3D_EXACT_DET_RTOL = 2.0**-6
#: engine.hull3d: a Convex template of more vertices than this takes the two-pass hull path
#: even when it fits the cell builder's scratch (hull3d.takes_hull_path)
HULL3D_BIG = 512
#: per-cell output slots of the second pass (vertices, faces, ring entries); a cell past
#: them runs again alone with its counts
HULL3D_SLOTS = (256, 128, 1024)
#: cells of the second pass a kernel call (slots reused)
HULL3D_CHUNK = 1024
#: the first pass's container (hull3d._around) is padded by this much of the hull's extent
HULL3D_DOP_PAD = 0.01
#: the reach test's margin, relative to the wall's offset and the cell's size
HULL3D_REACH_RTOL = 1e-9
#: engine.jointable3d: linear probes in a vertex's local run (slot) before its probe
#: sequence jumps to a slot hashed over the whole table (a float sphere's vertices all fall
#: in one bucket: linear probing made the join quadratic)
JOIN_LOCAL_PROBES = 32
#: engine.lists3d: the most sites a cell's grid search examines before it stops with SLOW
#: (uniform cells examine ~100, cells of 1e5 sites at a default container's padded walls at
#: most ~700; a cell of n points on a sphere examines all n)
LISTS3D_SITE_BUDGET = 2048.0
#: the lists are made (one Delaunay triangulation of all sites, ~100 us a site) once this
#: many cells ran past the budget, and this share of the cells built so far: fewer are
#: searched again without a budget (each cost at most a full scan: cheaper than the lists)
LISTS3D_AFTER = (64, 0.01)
#: the largest Delaunay polytope (sites on one empty sphere) listed whole: each of its sites'
#: lists holds all of it; a bigger one lists the sites of its 2-faces at each site
LISTS3D_POLYTOPE_MOST = 64
#: a cell with at least this many candidates is read off its Delaunay star
#: (kernels.star3d) where the container does not cut it: cut plane by plane, the centre of
#: n points on a sphere (n faces) cost O(n^2) (40,000 points: 68 s, now 6 s)
LISTS3D_STAR_LEAST = 256
#: kernels.star3d: every star vertex must be inside every wall by more than this many times
#: the cut's band (VORONOI3D_CUT_RTOL), else the cell is cut as before
STAR3D_WALL_BANDS = 4.0
#: kernels.cellcut3d: the most entries of a cell's owner table (vertices x owners a vertex,
#: int32: 64 MB); its width was vcap // 16, so a big cell's retry (scratch x256: 262,144
#: vertices) zeroed 17 GB (the centre site of 4,000 points on a sphere: 150 s for that cell)
CELLCUT3D_OWN_ENTRIES = 1 << 24
#: kernels.cells3d: entries of each thread's cache of exact vertex points by name (a power
#: of two): neighbouring cells on one thread reuse a vertex's exact point (points on a
#: sphere without centre, 40k: 18.2 -> 15.7 s one thread)
CELLS3D_PLACE_CACHE = 4096
#: kernels.reach3d (unequal weights' local stop): a max-weight pyramid node's box is widened
#: by this much of the grid's extent (bucket keys are rounded); tries to round a reach up
REACH3D_BOX_RTOL = 1e-15
REACH3D_ROUND_TRIES = 64
#: kernels.reach3d heavy sites (``heavy_sites``): weights above the lightest by more than
#: this many squared bucket sides (the light ones then reach about two buckets past the
#: unweighted stop), at most this many (more: none, the pyramid bounds them all); one site
#: of weight 1 among 80k of weight 0: 548 -> 16.6 s
REACH3D_HEAVY_GAP = 4.0
REACH3D_HEAVY_MOST = 256
#: engine.containers: sites within this much of a wall's scale of its outside may lie outside
#: (their cells built first, to learn which are empty); sites per block of that test
OUTSIDE3D_RTOL = 1e-12
OUTSIDE3D_BLOCK = 65536
#: Convex(points=) volume from the exact polytope of its rows at most this many walls, or
#: thin (volume below this of its extent cubed: a 1 x 1e-9 x 1e-9 box's float one 5e-10 off)
CONVEX_EXACT_ROWS = 256
CONVEX_EXACT_THIN = 1e-2
#: engine.voronoi3d: sites a block of the Convex container's any-site-inside test
VORONOI3D_INSIDE_BLOCK = 256
#: Default container: the sites' bounding box padded by this fraction of its size per side
VORONOI3D_PAD = 0.1
#: Mesh containers: the touch test's slack (cell planes moved out) and the tolerance of a
#: face lying in a container triangle's plane, relative to the mesh's largest coordinate
VORONOI3D_MESH_SLACK_RTOL = 1e-9
#: Mesh containers: a face and a container triangle face the same way when the cosine of
#: their normals is within this of 1
VORONOI3D_MESH_FACING = 1e-9
#: Mesh containers: a closed mesh's volume against the cells' sum (relative), for the checks
VORONOI3D_MESH_RTOL = 1e-9
#: Mesh containers: largest relative difference between the cells' total volume and the
#: mesh's signed volume before the mesh is refused as invalid (valid solids agree to ~1e-12;
#: two overlapping boxes given as one mesh differed by 2.4%)
VORONOI3D_MESH_VOLUME_RTOL = 1e-7

#: engine.lloyd3d._into_mesh pushes a projected site that rounding left outside the solid on
#: along the ray from the centroid through it (into the solid where the surface is smooth or
#: convex there) by ``2**-k`` of the mesh's largest coordinate, ``k`` from 50 (a few units
#: of rounding) to 30 by 4; the first step the exact inside test accepts is kept
LLOYD3D_INTO_MESH_PUSH = tuple(2.0**-k for k in range(50, 29, -4))
#: then (a sharp spike seen from the side) it steps back towards the site's previous,
#: inside, place by fractions ``2**-k`` of the way, ``k`` from 48 to 0 by 4
LLOYD3D_INTO_MESH_FRACTIONS = tuple(2.0**-k for k in range(48, -1, -4))
#: a float-cut hull whose walls include two within this sine of parallel (nearly coplanar
#: facets: corners coplanar only to rounding) has its cells' vertices checked against its
#: walls (engine.voronoi3d; checker14 F9)
CONVEX_NEAR_PARALLEL_SIN = 1e-3
#: ... and a vertex further outside a wall than this many ulps of the wall's scale (the
#: template's largest L1 coordinate plus the wall's offset) sends the cells to the exact
#: twin, whose cells lie inside to a few ulps. The float cut's cells may lie out by its
#: own tolerance (``VORONOI3D_CUT_RTOL``: a cube jittered by 1e-11 had cells 2.3e-11 out of
#: its rows, their volumes 7.6e-12 over the hull's); the wrong vertices were up to 0.94 out
CONVEX_VERTEX_OUT_ULPS = 64.0

#: solid.cells.subdivide: a leaf's hull triangle lower than this fraction of the leaf's size
#: (or 64 ulps of its coordinates) has a vertex that close to the other two's segment; that
#: vertex is left out, so trimesh's strict ``is_convex`` holds (``solid.cells._hull_mesh``)
SUBDIVIDE_SLIVER = 1e-9
#: solid.check.strut_widths: how deep marching cubes' chords cut into an implicit strut of
#: radius r at voxel h, as IMPLICIT_SAG * h**2 / r: measured 0.42-0.52 on sections for
#: h = 0.2 .. 1.0 r (10 Taubin steps); a bound above every measurement
IMPLICIT_SAG = 0.6
#: 3D cells per kernel call: n // 128 within these. Each call's two sets of output slots
#: (4.35 KB a cell each) stay resident for the call: 4,096 made the 1e5 peak 1.2 KB a cell
#: (0.9 KB at 1,024, outputs byte-equal); 1e6 keeps 4,096 (1,024 measured 5% more CPU)
VORONOI3D_CHUNK = (1024, 4096)
#: [surface] parametric: UV samples per side on which x/y/z expressions must be finite when
#: the design is checked (the builder's own grid is checked again when it is built)
SURFACE_EXPR_SAMPLES = 65
#: [solid] foam in a mesh container: draws of ``cells`` (at least 64) points in the mesh's
#: box to find sites inside it (a solid filling 1/20 of its box needs ~20)
SOLID_FOAM_DRAWS = 200
#: [solid] foam in a mesh container: a clipped cell is convex when its hull's volume exceeds
#: its own by at most this fraction (a float32 STL's convex solid dents its cells by its
#: rounding, ~1e-7 of a cell; 1e-9 refused convex STL containers)
SOLID_FOAM_CONVEX_RTOL = 1e-5
#: kernels.vertex3d._ill: the squared determinant test is trusted where it clears
#: CUT_EXACT_DET_RTOL by this margin (both sides carry a few roundings, ~1e-15); nearer,
#: the test with square roots decides (the same vertices re-solved)
CUT_ILL_MARGIN = 1e-12
#: engine.diagram3d._clearly_not_flat: a face's fan-sum component above FAN_ERR n^2 D^2
#: (n vertices, D the longest offset from the apex) is nonzero in every fan (the rounding
#: bound of two fans' difference is 5.6e-16 n^2 D^2); D^2 outside (FAN_D2_MIN, FAN_D2_MAX)
#: leaves it to the canonical fan (products clear of under- and overflow)
FAN_ERR = 2e-15
FAN_D2_MIN = 1e-260
FAN_D2_MAX = 1e260
#: kernels.vertex3d.resettle: a vertex a cut makes on an edge whose planes and the cut's meet
#: at a relative determinant below this is solved again exactly: the edge's interpolation
#: errs by ~ulp / determinant (sites a few ulps apart: 0.0047 off in a unit box, 1.6 in a
#: rotated cube) and the float filter's band (``VORONOI3D_CUT_RTOL``) assumes ulps
CUT_EXACT_DET_RTOL = 1e-3
#: engine.voronoi3d: a Convex container's float-built cell with a wall face is folded
#: (rebuilt from the exact twin) when one of its vertices is power-nearer a site across one
#: of its faces by more than this many roundings of the distances (a folded cell at 1000:
#: 0.64 against a bound of ~7e-7; the worst unfolded cell 3e-13, at 1e5 4e-11 vs ~3e-5)
CONVEX_FOLD_ULPS = 2.0**20
#: engine.slots3d.grown_caps: a chunk's slots grow when at least this share of its cells
#: overflowed them (uniform 1e5 sites: none do; a helix: all) ...
GROW_SHARE = 1 / 8
#: ... and at least this many (a few many-faced cells among many go to big_cell alone)
GROW_LEAST = 8
#: room over the most a chunk's overflowed cells needed (the next chunks' cells vary)
GROW_PAD = 1.25
#: slots grow to at most this many times the base caps (past it, cells are built alone)
GROW_MOST = 16
#: bytes of one set of slots at most (a chunk's cells times a cell's slots)
GROW_BYTES = 2**26
#: the cells of the first chunk (the lists' probe) get output slots as large as the kernel's
#: scratch (slots3d.probe_caps), so a helix's or three lines' many-faced cells there are not
#: all built a second time alone; the growth from what they needed is padded by this much
#: more than GROW_PAD (three lines of 1,500: the next chunk's cells needed up to 1.47x the
#: probe's most; 210 of its 512 cells overflowed slots padded by GROW_PAD alone)
GROW_PROBE_PAD = 1.6
#: a chunk holds at least this many cells where grown slots would pass GROW_BYTES (smaller
#: chunks instead of slots kept small: three lines' 455 repeated builds -> 0)
GROW_CHUNK_LEAST = 64
#: engine.build3d._Out.reserve pads its estimate of a chunk's new vertices by this much
BUILD3D_RESERVE_PAD = 1.25
#: kernels.ties3d: a face found on a touching plane is relabelled only when the two sites lie
#: on one ray from the cell's site to this relative precision (a guard: exact ties are
#: parallel)
TIES_RAY_RTOL = 1e-10
#: engine.voronoi3d._doomed: a periodic build try is skipped when a sample of cells (the
#: DOOMED_SIDE sites nearest each open side of the box and DOOMED_SPREAD spread over the
#: input) already reaches past its image margin (sites on one plane or line)
DOOMED_SIDE = 8
DOOMED_SPREAD = 16
#: kernels.walk3d: batches of at least this many candidates are first grouped by distance
#: into bins (bin_group, a stable counting sort), so the insertion sort after it moves few
BIN_SORT_FROM = 24
#: kernels.cellcut3d: after a graph cut a cell's squared radius is bounded by the one before
#: (and the moved points') times this: a crossing interpolated between two vertices is no
#: farther than they are but for its rounding (~1e-16 relative); only a bound that holds
#: lets the cut skip finding the radius (_cut_batch)
CELLCUT3D_RADIUS_PAD = 1.0 + 1e-12
#: kernels.merge3d: cells of at least this many named vertices are merged through hash
#: tables; smaller ones by a scan of the kept vertices (cheaper at a uniform cell's ~26)
MERGE3D_HASH_FROM = 48
#: engine.containers: a hull whose principal extents' ratio (thinnest over widest) is below
#: this is thin (_hull_planes): walls keep their exact planes (engine.hullnormals) and
#: merge only within CONVEX_THIN_MERGE of its thickness
CONVEX_THIN_AXES = 1e-2
#: ...a thin hull's nearly coplanar facets merge only when every corner lies within this
#: fraction of its thickness of the kept plane (the wedge a merge adds is about that times
#: the face's area: 1e-12 of the extent had made a 1e-9 disk 1.28e-5 too big)
CONVEX_THIN_MERGE = 1e-13
#: kernels.climb3d (a many-faced cell's plane values found near the plane): the flood
#: reaches every vertex within this many times the filter's band below the plane (rounding
#: moves a vertex's value by far less than one band, ``VORONOI3D_CUT_RTOL``)
CLIMB3D_FLOOD_BAND = 1024.0
#: the top vertex's plateau: the vertices within this many bands below it, connected to it
#: (a degenerate vertex rounded into a cluster), none of whose neighbours may lie higher
CLIMB3D_PLATEAU_BAND = 16.0
#: the most vertices a plateau may hold (else the cell's values are all evaluated)
CLIMB3D_PLATEAU_MOST = 64
#: a vertex's value is good to this many bands (the band assumes far less): a plateau top
#: lower than that below the band passes the plane over
CLIMB3D_NOISE_BANDS = 4.0
#: vertices sampled for the climb's start (voro++ tests about sqrt(n) / 4)
CLIMB3D_SAMPLES = 8
#: cells of fewer vertices are evaluated whole (a uniform cell's ~26: the pass is cheaper)
CLIMB3D_LOCAL_FROM = 64
#: kernels.cellcut3d: a small graph cell's radius is found again once this many cuts have
#: made its bound stale and a plane within the bound comes (a uniform cell: 68 -> 47.5 plane
#: passes; after every cut cost more scans than it saved)
CELLCUT3D_REFRESH_CUTS = 2
#: the nearest candidates of a batch whose site rows are asked of the cache before the cuts
#: (kernels.vertex3d.resettle reads them by index: a cache miss)
CELLCUT3D_PREFETCH_MOST = 24
#: arrays of at least this many bytes get 4 KB pages (engine.slots3d.small_pages; numpy asks
#: for transparent huge pages from 4 MB, whose first touch cost 4-6x more system time here)
SMALL_PAGES_FROM = 1 << 22
