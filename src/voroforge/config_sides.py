"""Settings of bisectors meeting the box's sides and corners (2D).

Used by kernels.sidecross, kernels.vertex.box_crossing and kernels.cornercut. Re-exported
by :mod:`voroforge.config`, so modules import them from ``config``.
"""

__all__ = [
    "CORNER_CROSSING_ULPS",
    "CORNER_CUT_RTOL",
    "SIDE_BOX_RTOL",
    "SIDE_NEAREST_MAX_STEPS",
    "SIDE_NEAREST_ULPS",
]

#: kernels.sidecross: sites at most this many ulps (of their largest coordinate) apart get
#: their bisector's box-side crossing as the nearest double (farther pairs keep the float
#: formula: every pair changed the bits of 114 of the 186 catalogue diagrams, 2**-26 of the
#: magnitude 15). Crossings of one side come within the formula's error (an ulp or two) of
#: each other where the bisectors, turning by |b - a| / R over a circumradius R, reach the
#: side h from their vertex with h |b - a| / R below it: for h ~ R (a float circle in its
#: box) sites a few ulps apart; a vertex much nearer the side is a side sliver
SIDE_NEAREST_ULPS = 16.0
#: ...found in at most this many ulp steps from the float estimate (within an ulp or two)
SIDE_NEAREST_MAX_STEPS = 8
#: ...and every pair does where the sites' ulp passes this fraction of the box's extent
#: (sites ~4096 box widths from the origin: a box 1e-16 wide between sites at +-1 had each
#: crossing on the sites' ulp grid; 27 far catalogue diagrams changed bits, all valid)
SIDE_BOX_RTOL = 2.0**-40
#: kernels.vertex.box_crossing: a box-side crossing within this many ulps of the sites'
#: magnitude of a box corner is the double nearest the exact one (the float formula's error
#: would move it past the corner, or past other crossings there: a float circle's centre on
#: a corner, issue 15)
CORNER_CROSSING_ULPS = 64.0
#: kernels.cornercut: a cut cell's centre within this of a box corner, relative to its L1
#: distance from the cell's site, has the box cut exactly (the float cut is off by ~16 u of
#: that distance: each cell decided alone which edges reach the corner's sides)
CORNER_CUT_RTOL = 2.0**-40
