"""Generated point sets (hypothesis): the triangulation and diagram invariants always hold."""

from __future__ import annotations

import numpy as np
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from scipy.spatial import cKDTree
from shapely.geometry import Polygon, box

import voroforge as vf

from validate import validate_diagram, validate_triangulation


def _array(pairs) -> np.ndarray:
    return np.array(pairs, dtype=np.float64).reshape(-1, 2)


coord = st.floats(min_value=-100.0, max_value=100.0, allow_nan=False, allow_infinity=False)
# shapely's checks (validity, areas) underflow once squared coordinates leave the double
# range, so diagrams are checked on values of 0 or above 1e-100; the exact power-of-two
# tests in test_voronoi cover the extreme scales
moderate = coord.map(lambda v: v if abs(v) >= 1e-100 else 0.0)
floats_in_box = st.lists(st.tuples(coord, coord), min_size=0, max_size=60).map(_array)

# few distinct values: duplicates, collinear rows and columns, cocircular squares everywhere
small = st.integers(0, 6)
integer_grid = st.lists(st.tuples(small, small), min_size=0, max_size=50).map(_array)


@st.composite
def snapped(draw):
    """Floats snapped to a coarse lattice, then scaled and offset (still exact in binary)."""
    pts = draw(st.lists(st.tuples(coord, coord), min_size=1, max_size=50).map(_array))
    step = draw(st.sampled_from([0.25, 8.0, 32.0]))
    scale = draw(st.sampled_from([1.0, 2.0**-30, 2.0**30, 1e-6, 1e6]))
    offset = draw(st.sampled_from([0.0, 500000.0, -4000000.0]))
    return np.round(pts / step) * step * scale + offset


point_sets = st.one_of(floats_in_box, integer_grid, snapped())
moderate_sets = st.one_of(
    st.lists(st.tuples(moderate, moderate), min_size=0, max_size=60).map(_array),
    integer_grid,
    snapped(),
)


@given(point_sets)
def test_triangulation_invariants(pts):
    validate_triangulation(vf.delaunay(pts))


# the ``algorithm`` fixture is a constant per parametrisation, safe to share between examples
@settings(suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(
    pts=moderate_sets, kind=st.sampled_from(["none", "box", "holes"]), seed=st.sampled_from([0, 1])
)
def test_diagram_invariants(pts, kind, seed, algorithm):
    if kind == "none" and len(pts) == 0:
        return  # no extent: an error, tested in test_errors
    # Sites a few ulps apart (0.25 * 2**-30 at 500000) have Voronoi vertices that float64
    # cannot represent: the triangulation stays exact, but cells are only good to an ulp,
    # below what these 1e-9-relative checks can tell apart. Keep distinct sites 2**22 ulps
    # apart (known gap: at 2**17 ulps the area sum can be off by 1e-6 relative).
    uniq = np.unique(pts, axis=0)
    if len(uniq) > 1:
        gap = cKDTree(uniq).query(uniq, k=2)[0][:, 1].min()
        assume(gap >= 2.0**-30 * max(np.abs(uniq).max(), 1e-300))
    if len(pts):
        lo, hi = pts.min(0), pts.max(0)
    else:
        lo, hi = np.zeros(2), np.ones(2)
    size = np.maximum(hi - lo, np.maximum(np.abs(lo), 1.0) * 1e-3)
    x0, y0 = lo - 0.2 * size
    x1, y1 = hi + 0.2 * size
    if kind == "none":
        boundary, domain = None, None
    elif kind == "box":
        boundary = (float(x0), float(y0), float(x1), float(y1))
        domain = box(*boundary)
    else:
        cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
        w, h = (x1 - x0) / 8, (y1 - y0) / 8
        hole = [(cx - w, cy - h), (cx + w, cy - h), (cx, cy + h)]
        boundary = domain = Polygon([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], [hole])
    d = vf.voronoi(pts, boundary, algorithm=algorithm)
    validate_diagram(d, pts, domain, samples=300, seed=seed)
