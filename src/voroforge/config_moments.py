"""Settings of the cells' moments (:mod:`voroforge.kernels.moments`: Lloyd, CVT, power_fit).

Re-exported by :mod:`voroforge.config`, so modules import them from ``config``.
"""

__all__ = [
    "MOMENTS_CANCEL",
    "MOMENTS_FAR_PART",
    "POWER_FIT_PARTS_CANCELS",
    "POWER_FIT_PARTS_FAR",
    "POWER_FIT_PARTS_HOPELESS",
    "POWER_FIT_PARTS_REFUSE",
    "POWER_FIT_PARTS_SAMPLES",
    "POWER_FIT_PARTS_SHARE",
]

#: kernels.moments (uniform and raster moments): where a cell's shoelace terms cover more than
#: this many times its area (parts of one cell far apart: MultiPolygon parts 1e12 apart gave
#: masses 6e-5 off), each of its polygons is summed about its own first vertex ...
MOMENTS_CANCEL = 16.0
#: ... where that polygon lies farther from the cell's origin than this many times its extent
MOMENTS_FAR_PART = 4.0
#: engine.farparts: a MultiPolygon's parts are fitted apart (parts_start) when every two lie
#: farther apart than POWER_FIT_PARTS_FAR times the larger one's bounding-box diagonal
POWER_FIT_PARTS_FAR = 4.0
#: a site serves a part where the transport sends it more than this fraction of
#: its target (HiGHS's own rounding is ~1e-9 of the total)
POWER_FIT_PARTS_SHARE = 1e-9
#: the most negative cycles of the parts' transport (three or more parts) cancelled in exact
#: arithmetic after HiGHS's solve, whose tolerance can leave a nearly tied site on the wrong
#: side (each cancel lowers the exact cost)
POWER_FIT_PARTS_CANCELS = 1000
#: sample points per part (a grid in its bounds, plus its vertices) where a part
#: tied to no other is given its constant
POWER_FIT_PARTS_SAMPLES = 16
#: engine.capacity: power_fit refuses a domain's far parts at once where rounding the weights
#: they need limits the median cell's area to more than this many times tol
POWER_FIT_PARTS_REFUSE = 10.0
#: engine.capacity: the far parts' joined weights that miss tol are not polished where the
#: area error their rounding alone can cause (farparts.weights_limit, a worst case: 5-18x
#: the error the joined weights had) exceeds this many times tol. Two squares 200-2,000
#: apart, 200-2,000 sites in both, random targets: in 6 such runs the polish never reached
#: tol (5 left the error as it was, after ~100 diagrams); 500 sites (limit 2.7e-6) fit
POWER_FIT_PARTS_HOPELESS = 5.0
