"""A named catalogue of degenerate and awkward inputs for the 2D engine.

``CATALOGUE[name] = (points, boundary)`` where ``points`` is an ``(n, 2) float64`` array
(n <= 500) and ``boundary`` is ``None``, an ``(xmin, ymin, xmax, ymax)`` tuple or a shapely
Polygon/MultiPolygon, exactly what ``vf.voronoi`` accepts. Everything is deterministic.
"""

from __future__ import annotations

import numpy as np
from shapely.geometry import MultiPolygon, Polygon, box


def _rng(k: int) -> np.random.Generator:
    return np.random.default_rng(20240 + k)


def _grid(nx: int, ny: int, step: float = 1.0, x0: float = 0.0, y0: float = 0.0) -> np.ndarray:
    x, y = np.meshgrid(np.arange(nx) * step + x0, np.arange(ny) * step + y0)
    return np.column_stack((x.ravel(), y.ravel()))


def _hex(nx: int, ny: int) -> np.ndarray:
    rows = []
    for j in range(ny):
        x = np.arange(nx) + (0.5 if j % 2 else 0.0)
        rows.append(np.column_stack((x, np.full(nx, j * np.sqrt(3) / 2))))
    return np.concatenate(rows)


def _integer_circle(r: int) -> np.ndarray:
    """Every integer point on the circle of radius ``r`` (exactly cocircular)."""
    out = []
    for x in range(-r, r + 1):
        y2 = r * r - x * x
        y = int(round(np.sqrt(y2)))
        if y * y == y2:
            out.append((x, y))
            if y:
                out.append((x, -y))
    return np.array(out, dtype=np.float64)


def _star(k: int = 7, r_out: float = 10.0, r_in: float = 4.0) -> Polygon:
    ang = np.arange(2 * k) * np.pi / k
    rad = np.where(np.arange(2 * k) % 2 == 0, r_out, r_in)
    return Polygon(np.column_stack((rad * np.cos(ang), rad * np.sin(ang))))


def comb_outline(k, top=1000.0):
    """``k`` teeth 0.6 wide and ``top`` high on a strip 1 high: one outline of 4k vertices."""
    teeth = []
    for i in range(k):
        teeth += [(i, top), (i + 0.6, top), (i + 0.6, 1.0), (i + 1, 1.0)]
    return Polygon([(0, 0), (k, 0), *teeth[::-1]])


def saw_outline(k):
    """A saw of ``k`` slanted teeth (no two vertices share a side of a random rectangle)."""
    up = [(i + 0.5, 3.0 + 0.37 * np.sin(i)) for i in range(k)]
    down = [(i + 1.0, 1.0 + 0.11 * np.cos(i)) for i in range(k)]
    top = [p for pair in zip(up, down, strict=True) for p in pair]
    return Polygon([(0, 0), (k, 0), *top[::-1], (0, 1.0)])


def zigzag_outline(n):
    """A unit strip whose top is a zigzag of ``n`` vertices 0.01 high (a long boundary)."""
    x = np.linspace(0.0, 1.0, n)
    y = 1.0 + 0.01 * (np.arange(n) % 2)
    return Polygon([(0, 0), (1, 0), *zip(x[::-1], y[::-1], strict=True)])


def holed_square(k):
    """A ``k`` x ``k`` square with ``k * k`` small square holes, each turned a little."""
    from shapely import affinity

    holes = []
    for i in range(k):
        for j in range(k):
            sq = box(i + 0.3, j + 0.3, i + 0.7, j + 0.7)
            holes.append(affinity.rotate(sq, 7 * i + 3 * j).exterior.coords)
    return Polygon(box(0, 0, k, k).exterior.coords, holes)


def _build() -> dict[str, tuple[np.ndarray, object]]:
    c: dict[str, tuple[np.ndarray, object]] = {}
    unit = (0.0, 0.0, 1.0, 1.0)

    # tiny inputs
    c["empty_with_box"] = (np.zeros((0, 2)), unit)
    c["one_point"] = (np.array([[0.3, 0.4]]), unit)
    c["two_points"] = (np.array([[0.2, 0.5], [0.8, 0.5]]), unit)
    c["two_points_none"] = (np.array([[0.0, 0.0], [1.0, 2.0]]), None)
    c["three_points"] = (np.array([[0.0, 0.0], [1.0, 0.0], [0.3, 0.9]]), None)
    c["three_collinear"] = (np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]), (-1.0, -1.0, 3.0, 1.0))

    # duplicates
    r = _rng(1).random((60, 2))
    c["duplicates"] = (np.concatenate((r, r[::3], r[5:9])), None)
    base = _rng(2).random((20, 2))
    trip = np.concatenate((base, base[:6], base[:6]))
    c["duplicate_triples"] = (trip[_rng(3).permutation(len(trip))], None)
    c["all_same"] = (np.tile([[0.5, 0.5]], (5, 1)), unit)
    c["signed_zero"] = (
        np.array([[0.0, 0.0], [-0.0, 0.0], [1.0, 0.0], [0.0, -0.0], [0.0, 1.0]]),
        None,
    )

    # collinear
    t = np.linspace(0.0, 10.0, 41)
    c["collinear_horizontal"] = (np.column_stack((t, np.zeros_like(t))), (-1.0, -2.0, 11.0, 2.0))
    c["collinear_vertical"] = (np.column_stack((np.full_like(t, 3.0), t)), (0.0, -1.0, 6.0, 11.0))
    k = np.arange(30, dtype=np.float64)
    c["collinear_diagonal"] = (np.column_stack((k, k))[_rng(4).permutation(30)], None)
    c["collinear_diagonal_boxed"] = (np.column_stack((k, 2 * k)), (-5.0, -5.0, 35.0, 65.0))
    s = _rng(5).random(40)
    c["nearly_collinear"] = (np.column_stack((0.1 * s, 0.3 * s)), (-0.1, -0.1, 0.2, 0.4))
    line = np.column_stack((np.linspace(0, 1, 120), np.zeros(120)))
    c["line_plus_few"] = (np.concatenate((line, [[0.5, 0.3], [0.2, -0.4], [0.9, 0.05]])), None)

    # cocircular structures
    c["grid_20x20"] = (_grid(20, 20), None)
    c["grid_shuffled"] = (_grid(12, 12)[_rng(6).permutation(144)], (-0.5, -0.5, 11.5, 11.5))
    c["hex_grid"] = (_hex(15, 15), None)
    ang = np.arange(64) * (2 * np.pi / 64)
    c["circle_plus_centre"] = (
        np.concatenate((np.column_stack((np.cos(ang), np.sin(ang))), [[0.0, 0.0]])),
        None,
    )
    th = 0.3
    rot = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
    c["grid_rotated"] = (_grid(15, 15) @ rot.T, None)  # cocircular up to rounding
    c["circle_integer"] = (np.concatenate((_integer_circle(65), [[0.0, 0.0]])), None)

    # distributions and scales
    g = _rng(7)
    blobs = [g.normal(ctr, 0.02, size=(100, 2)) for ctr in ((0.2, 0.2), (0.8, 0.3), (0.5, 0.8))]
    c["clustered"] = (np.concatenate(blobs), None)
    c["utm_grid"] = (_grid(14, 14, 1.0, 500000.0, 4000000.0), None)
    c["utm_random"] = (
        np.array([500000.0, 4000000.0]) + _rng(8).random((200, 2)) * 14.0,
        None,
    )
    far = _rng(17).normal(0, 1e-6, size=(120, 2))
    c["far_clusters"] = (np.concatenate((far[:60], far[60:] + [1000.0, 300.0])), None)
    c["tiny_scale"] = (_rng(9).random((150, 2)) * 1e-9, None)
    c["huge_scale"] = (_rng(10).random((150, 2)) * 1e9, None)
    # a near-duplicate 1e-60 from a site, so their bisectors coincide in floating point
    near = _rng(20).random((40, 2)) * 100.0
    c["near_duplicate_1e-60"] = (np.concatenate((near, near[:3] + [0.0, 1e-60])), None)

    # sites and the domain
    c["sites_outside"] = (_rng(11).random((60, 2)), (0.25, 0.25, 0.75, 0.75))
    edge = np.linspace(0, 1, 6)
    on_box = np.concatenate(
        (
            np.column_stack((edge, np.zeros(6))),
            np.column_stack((edge, np.ones(6))),
            np.column_stack((np.zeros(4), edge[1:-1])),
            np.column_stack((np.ones(4), edge[1:-1])),
            _rng(12).random((10, 2)) * 0.8 + 0.1,
        )
    )
    c["sites_on_boundary"] = (on_box, unit)
    ell = Polygon([(0, 0), (10, 0), (10, 4), (4, 4), (4, 10), (0, 10)])
    c["concave_L"] = (_rng(13).random((80, 2)) * 10.0, ell)
    star = _star()
    c["concave_star"] = (_rng(14).uniform(-10, 10, size=(60, 2)), star)
    hole_cell = box(0, 0, 4, 4).difference(box(1.2, 1.2, 1.6, 1.6))
    c["hole_inside_one_cell"] = (
        np.array([[1.0, 1.0], [3.0, 1.0], [1.0, 3.0], [3.0, 3.0]]),
        hole_cell,
    )
    holes = Polygon(
        [(0, 0), (10, 0), (10, 10), (0, 10)],
        [[(2, 2), (4, 2), (4, 4), (2, 4)], [(6, 5), (8, 5), (7, 8)]],
    )
    inside_hole = np.array([[3.0, 3.0], [2.5, 3.5], [7.0, 6.0]])
    c["holes_with_sites_inside"] = (
        np.concatenate((_rng(15).random((50, 2)) * 10.0, inside_hole)),
        holes,
    )
    on_hole = np.array([[2.0, 3.0], [3.0, 2.0], [4.0, 4.0], [7.0, 5.0], [6.5, 6.5], [1.0, 1.0]])
    c["sites_on_hole_boundary"] = (np.concatenate((on_hole, _rng(18).random((30, 2)) * 10)), holes)
    _exactness_families(c)
    two = MultiPolygon([box(0, 0, 1, 1), box(2, 0, 3, 1)])
    c["multipolygon"] = (_rng(16).random((40, 2)) * [3.0, 1.0], two)
    c["multipolygon_one_site"] = (np.array([[1.5, 0.5]]), two)
    return c


def _circle(n: int, r: float = 1.0, phase: float = 0.0) -> np.ndarray:
    """``n`` float sites on a circle at the origin: cocircular up to rounding only."""
    t = np.arange(n) * (2.0 * np.pi / n) + phase
    return np.column_stack((r * np.cos(t), r * np.sin(t)))


def _ulps(x: float, k: int) -> float:
    """``x`` moved ``k`` ulps up."""
    for _ in range(k):
        x = float(np.nextafter(x, np.inf))
    return x


def _exactness_families(c: dict[str, tuple[np.ndarray, object]]) -> None:
    """The classes of issue 15: one small family each (every algorithm runs on all of them).

    - huge offsets: exact lattices far from the origin, where every site, box corner and
      vertex is a float64 (tolerances relative to the magnitude merged whole cells);
    - nearly cocircular floats: sites on circles (no centre), where rounded vertices folded
      rings into self-intersecting cells;
    - many neighbours of one cell (n sites on a line and one off it);
    - nearly cocircular floats far from the origin (``*_far``), whose folds go across edges
      that are not neighbours.

    Mixed scales and sites a few ulps apart are :data:`FEW_ULPS`; bigger far circles are
    :data:`FAR_CIRCLES`.
    """
    for off in (5e13, 1e15):
        lat = _grid(4, 4, 1.0, off, off)
        c[f"lattice_offset_{off:.0e}"] = (lat, (off - 0.5, off - 0.5, off + 3.5, off + 3.5))
    lat = _grid(5, 3, 2.0, 2.5e14, -7.5e14)
    c["lattice_offset_none"] = (lat, None)
    # a step of 4 ulps of the offset (0.5 at 1e15): every vertex is representable, and the
    # centres' rounding bound is ~0 (the final addition exact), so none merge
    off = 1e15
    x, y = np.meshgrid(np.arange(4) * 0.5 + off, np.arange(5) * 0.5 - 0.7 * off)
    lat = np.column_stack((x.ravel(), y.ravel()))
    c["lattice_offset_4ulp"] = (lat, (off - 0.25, -0.7 * off - 0.25, off + 1.75, -0.7 * off + 2.25))
    c["float_circle_64"] = (_circle(64), None)
    c["float_circle_257"] = (_circle(257), None)
    # a count at which one hull cell's box cut folded (every site is on the hull and every
    # bisector passes within rounding of the centre; kernels/cells splices such a cell).
    # 196 folded too, but the float half-plane oracle (reference.brute_voronoi) cannot clip
    # its wedges: test_exactness checks it on every algorithm instead; 513 and larger
    # counts are there too (the exact Delaunay checks cost ~16 s a test at 513)
    c["float_circle_205"] = (_circle(205), None)
    c["float_circles_concentric"] = (np.concatenate((_circle(64), _circle(64, 0.5))), None)
    # small float circles off the origin: rounding swaps some centres (the fold merge runs;
    # at the origin the exact sliver centres keep their order and nothing folds any more)
    c["float_circle_64_small_off"] = (_circle(64, 1e-3) + [1.0, 1.0], None)
    c["float_circle_128_tiny_off"] = (_circle(128, 1e-4) + [0.7, 0.3], None)
    # float circles far from the origin: the exact vertices near the centre are spaced like
    # the ulps there, so rounding folded rings across edges that are not neighbours (the
    # cells' exact convexity test contracts the fold, kernels/folds.fold_pairs)
    c["float_circle_100_far"] = (_circle(100, 3.0) + [1e5, -2e5], None)
    c["float_circle_257_far"] = (_circle(257, 10.0) + [-3e6, 1e6], None)
    c["float_circle_500_far"] = (_circle(500, 2.0) + [1e4, 1e4], None)
    c["float_circle_100_milli_far"] = (_circle(100, 1e-3) + [7.0, 7.0], None)
    t = np.linspace(0.0, 1.0, 200)
    c["collinear_plus_one"] = (
        np.concatenate((np.column_stack((t, np.zeros_like(t))), [[0.5, 0.1]])),
        (-0.5, -0.5, 1.5, 1.5),  # tall enough for every line site to touch the off-line cell
    )


def _few_ulps_families() -> dict[str, tuple[np.ndarray, object]]:
    """Mixed scales and sites a few ulps apart (issue 15), right for every algorithm now.

    Kept out of :data:`NAMES`: the validator's nearest-site samples cannot order a 1e-12
    cluster seen from 1e5 away (the diagrams are valid, tile, and every distinct site owns
    its cell: ``test_exactness``, ``test_algorithms``). ``describe()`` counts them since it
    identifies vertices by their bits (``test_describe``), except the strip a few ulps wide,
    one of whose vertices rounds to points 1-4 ulps apart in its three cells.

    - mixed scales: a 1e-12 cluster beside a 1e6 one (hull cells of the tiny cluster are
      cut from a 1e6 box);
    - a distinct site a few ulps from others: its strip is narrower than the Delaunay
      centres' rounding bounds; the half-plane rings keep it (``planar._lost``);
    - near-duplicates a few ulps inside the box's sides at x = 500000.
    """
    c: dict[str, tuple[np.ndarray, object]] = {}
    g = _rng(30)
    c["mixed_scales"] = (np.concatenate((g.random((50, 2)) * 1e-12, g.random((50, 2)) * 1e6)), None)
    x = 0.3
    diag = [[_ulps(x, k), _ulps(x, k)] for k in (0, 1, 6)]
    c["ulp_diagonal"] = (np.concatenate((diag, _rng(31).random((20, 2)))), (0.0, 0.0, 1.0, 1.0))
    lo, hi = 500000.0, 500001.0
    side = np.array([[_ulps(lo, 2), 0.25], [_ulps(lo, 3), 0.25], [_ulps(lo, 1), 0.75]])
    side = np.concatenate((side, [[-_ulps(-hi, 2), 0.5], [-_ulps(-hi, 1), 0.5]]))
    inner = [lo, 0.0] + _rng(32).random((20, 2))
    c["near_duplicates_at_box_sides"] = (
        np.concatenate((side, inner, inner[:4] + [0.0, 2.0**-33])),
        (lo, 0.0, hi, 1.0),
    )
    return c


def _far_circle_families() -> dict[str, tuple[np.ndarray, object]]:
    """Float circles far from the origin, where rounding folded cells or the builders split.

    Every cell's vertices are within the ulps there of each other near the centre; each of
    these folded cells (``shapely.is_valid`` false) for every algorithm, or the sweep's and
    the default's cells differed, before the centres' rounding bound counted the final
    addition exactly and classes were named independently of the builder's numbering
    (docs/exactness.md). Not in NAMES: a few hundred to ~2,000 sites each.
    """
    out = {}
    for n, r, off in (
        (1904, 1e-3, (-5e4, 2e4)),
        (661, 1e-3, (-3e6, 1e6)),
        (473, 1e-3, (-3e6, 1e6)),
        (896, 1e-3, (1e5, -2e5)),
        (614, 2.0, (1e4, 1e4)),
        (900, 10.0, (1e4, 1e4)),
    ):
        out[f"far_circle_{n}_r{r:g}_at_{off[0]:g}"] = (_circle(n, r, 0.1) + off, None)
    return out


CATALOGUE = _build()
#: Families every NAMES-parametrized test runs on: all but the small float circles off the
#: origin, whose features were below describe()'s old vertex tolerance (1e-13 of the domain's
#: diagonal; describe() is scale-free since 8e4fa54, but the other NAMES tests' samples and
#: comparisons were not checked on them); test_exactness checks them on every algorithm,
#: test_perf_regressions folds them.
NAMES = [n for n in CATALOGUE if not n.endswith("_off")]
#: Issue 15's mixed scales and sites a few ulps apart (see :func:`_few_ulps_families`).
FEW_ULPS = _few_ulps_families()
#: Issue 15's far float circles (see :func:`_far_circle_families`); not in NAMES.
FAR_CIRCLES = _far_circle_families()


def as_domain(boundary):
    """The shapely domain for a catalogue boundary (``None`` stays ``None``)."""
    if isinstance(boundary, tuple):
        return box(*boundary)
    return boundary


def general_position(n: int, seed: int = 0) -> np.ndarray:
    """Uniform random points: no four cocircular, no three collinear (for all practical seeds)."""
    return np.random.default_rng(seed).random((n, 2))


def sites_ulps_apart(seed: int, offset: float = 0.3) -> np.ndarray:
    """2-5 sites 1-6 ulps apart along a random direction at ``(offset, offset)``, then 20
    random sites in a 10-wide square about it (the sweep's notch family, issue 15)."""
    g = np.random.default_rng(seed)
    k = g.integers(2, 6)
    d = g.normal(size=2)
    d /= np.abs(d).max()
    p = np.array([offset, offset])
    near = [p.copy()]
    for _ in range(k - 1):
        for _ in range(int(g.integers(1, 7))):
            p = np.nextafter(p, p + d)
        near.append(p.copy())
    return np.concatenate((near, offset + (g.random((20, 2)) - 0.5) * 10.0))
