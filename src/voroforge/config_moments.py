"""Settings of the cells' moments (:mod:`voroforge.kernels.moments`: Lloyd, CVT, power_fit).

Re-exported by :mod:`voroforge.config`, so modules import them from ``config``.
"""

__all__ = ["MOMENTS_CANCEL", "MOMENTS_FAR_PART"]

#: kernels.moments (uniform and raster moments): where a cell's shoelace terms cover more than
#: this many times its area (parts of one cell far apart: MultiPolygon parts 1e12 apart gave
#: masses 6e-5 off), each of its polygons is summed about its own first vertex ...
MOMENTS_CANCEL = 16.0
#: ... where that polygon lies farther from the cell's origin than this many times its extent
MOMENTS_FAR_PART = 4.0
