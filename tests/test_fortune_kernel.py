"""Fortune's sweep kernel: Delaunay dual, degenerate inputs, structure built by the sweep."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
from scipy.spatial import Delaunay

from voroforge.kernels.fortune import fortune_debug, fortune_triangles

from catalogue import CATALOGUE, NAMES, sites_ulps_apart
from reference import brute_delaunay_ok, first_occurrence
from validate import validate_triangulation


def _triples(triangles) -> set[tuple[int, ...]]:
    return {tuple(sorted(t)) for t in np.asarray(triangles).tolist()}


def _boundary_cycle(triangles: np.ndarray, halfedges: np.ndarray) -> np.ndarray:
    """Hull as the cycle of unpaired halfedges (so the validator checks it is convex)."""
    flat = triangles.ravel()
    nxt = triangles[:, [1, 2, 0]].ravel()
    bnd = np.flatnonzero(halfedges < 0)
    succ = {}
    for e in bnd.tolist():
        assert int(flat[e]) not in succ, "two hull halfedges start at one point"
        succ[int(flat[e])] = int(nxt[e])
    if not succ:
        return np.zeros(0, dtype=np.int64)
    start = next(iter(succ))
    hull = [start]
    v = succ[start]
    while v != start:
        hull.append(v)
        assert len(hull) <= len(succ), "boundary halfedges do not form one cycle"
        v = succ[v]
    assert len(hull) == len(succ), "boundary halfedges form several cycles"
    return np.array(hull, dtype=np.int64)


def check(points: np.ndarray, *, brute: bool = False) -> dict:
    """Run the kernel and assert it returned a Delaunay triangulation of every point."""
    pts = np.asarray(points, dtype=np.float64)
    d = fortune_debug(pts)
    tri = d["triangles"]
    assert tri.dtype == np.int32 and tri.ndim == 2 and tri.shape[1] == 3
    assert d["bad"] == 0, "the sweep gave one edge to three triangles"
    assert d["sweep_triangles"] == len(tri)
    assert np.array_equal(fortune_triangles(pts), tri)
    if len(tri):
        hull = _boundary_cycle(tri, d["halfedges"])
    else:
        hull = np.arange(len(pts)) if len(pts) < 3 else _collinear_order(pts)
    ns = SimpleNamespace(
        points=pts,
        triangles=tri,
        halfedges=d["halfedges"],
        hull=hull,
        duplicate_of=np.full(len(pts), -1),
    )
    validate_triangulation(ns)  # CCW, every point once, halfedges, convex hull, counts, empty
    if brute:
        assert brute_delaunay_ok(pts, tri)
    return d


def _collinear_order(pts: np.ndarray) -> np.ndarray:
    d = pts[np.argmax(((pts - pts[0]) ** 2).sum(1))] - pts[0]
    return np.argsort((pts - pts[0]) @ d, kind="stable")


def _grid(nx: int, ny: int, step: float = 1.0, x0: float = 0.0, y0: float = 0.0) -> np.ndarray:
    x, y = np.meshgrid(np.arange(nx) * step + x0, np.arange(ny) * step + y0)
    return np.column_stack((x.ravel(), y.ravel()))


def _hex(nx: int, ny: int) -> np.ndarray:
    j, i = np.meshgrid(np.arange(ny), np.arange(nx), indexing="ij")
    return np.column_stack(((i + 0.5 * (j % 2)).ravel(), (j * np.sqrt(3) / 2).ravel()))


def _circle(k: int) -> np.ndarray:
    ang = np.arange(k) * (2 * np.pi / k)
    return np.concatenate((np.column_stack((np.cos(ang), np.sin(ang))), [[0.0, 0.0]]))


def _line_plus(seed: int = 0) -> np.ndarray:
    line = np.column_stack((np.arange(50.0), np.zeros(50)))
    off = np.random.default_rng(seed).uniform([-5, -20], [55, 20], size=(5, 2))
    return np.concatenate((line, off))


def _blobs(seed: int = 3) -> np.ndarray:
    g = np.random.default_rng(seed)
    ctr = ((0.2, 0.2), (0.8, 0.3), (0.5, 0.8), (0.5, 0.5))
    return np.concatenate([g.normal(c, 0.01, size=(80, 2)) for c in ctr])


DEGENERATE = {
    "grid_15x15": _grid(15, 15),
    "grid_shuffled": _grid(9, 11)[np.random.default_rng(1).permutation(99)],
    "hex_grid": _hex(12, 12),
    "circle_plus_centre": _circle(48),
    "circle_only": _circle(40)[:-1],
    "line_50_plus_5": _line_plus(),
    "line_50_plus_5_above": np.concatenate((_line_plus()[:50], [[3, 1], [7, 2], [9, 9], [30, 4]])),
    "line_50_plus_5_below": np.concatenate((_line_plus()[:50], [[3, -1], [7, -2], [30, -4]])),
    "utm_grid": _grid(12, 12, 1.0, 500000.0, 4000000.0),
    "utm_random": np.array([500000.0, 4000000.0]) + np.random.default_rng(2).random((200, 2)) * 9,
    "scale_1e-9": np.random.default_rng(4).random((200, 2)) * 1e-9,
    "scale_1e9": np.random.default_rng(5).random((200, 2)) * 1e9,
    "grid_1e-9": _grid(10, 10, 1e-9),
    "grid_1e9": _grid(10, 10, 1e9),
    "blobs": _blobs(),
    "two_rows": np.concatenate((_grid(20, 1), _grid(20, 1, y0=3.0) + [0.5, 0])),
    "diamond_grid": _grid(12, 12) @ np.array([[1.0, 1.0], [-1.0, 1.0]]),
    "columns": np.concatenate((_grid(1, 30), _grid(1, 30, x0=5.0), [[2.5, 14.5]])),
    "site_on_breakpoint": np.array([[0.0, 0.0], [2.0, 0.0], [1.0, 1.0], [1.0, 3.0], [3.0, 1.0]]),
    "integer_circle": np.array(
        [(x, y) for x in range(-25, 26) for y in range(-25, 26) if x * x + y * y == 625]
    ),
}


@pytest.mark.parametrize("n", [10, 100, 2000])
def test_uniform_matches_scipy(n):
    pts = np.random.default_rng(n).random((n, 2))
    d = check(pts)
    assert _triples(d["triangles"]) == _triples(Delaunay(pts).simplices)
    assert d["flips"] == 0


@pytest.mark.parametrize("name", list(DEGENERATE), ids=list(DEGENERATE))
def test_degenerate(name):
    pts = np.asarray(DEGENERATE[name], dtype=np.float64)
    check(pts, brute=len(pts) <= 60)


@pytest.mark.parametrize("name", NAMES, ids=NAMES)
def test_catalogue(name):
    pts, _ = CATALOGUE[name]
    pts = np.asarray(pts, dtype=np.float64)
    check(pts[first_occurrence(pts) < 0])


def test_brute_small_degenerate():
    for pts in (_grid(5, 5), _hex(5, 5), _circle(12), _line_plus()[45:]):
        check(pts, brute=True)


@pytest.mark.parametrize(
    "pts",
    [
        np.zeros((0, 2)),
        np.array([[0.5, 0.5]]),
        np.array([[0.0, 0.0], [1.0, 1.0]]),
        np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]),
        np.array([[0.0, 0.0], [0.0, 1.0], [0.0, 3.0], [0.0, -2.0]]),
        np.column_stack((np.arange(30.0), 2 * np.arange(30.0) + 1))[::-1],
        np.column_stack((np.arange(20.0), np.zeros(20))),
    ],
    ids=["n0", "n1", "n2", "n3_collinear", "vertical", "diagonal", "horizontal"],
)
def test_few_or_collinear_points(pts):
    tri = fortune_triangles(pts)
    assert tri.shape == (0, 3) and tri.dtype == np.int32


def test_three_points_ccw():
    pts = np.array([[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]])
    tri = fortune_triangles(pts)
    assert tri.shape == (1, 3)
    check(pts, brute=True)


def test_input_not_mutated_and_order_independent():
    pts = np.random.default_rng(7).random((300, 2))
    keep = pts.copy()
    t1 = fortune_triangles(pts)
    assert np.array_equal(pts, keep)
    perm = np.random.default_rng(8).permutation(300)
    t2 = fortune_triangles(pts[perm])
    assert _triples(perm[t2]) == _triples(t1)


@pytest.mark.parametrize("angle", [0.0, np.pi / 2, np.pi, 0.3])
def test_rotations_of_a_grid(angle):
    """Rotated grids: horizontal rows and columns become every other direction."""
    c, s = np.cos(angle), np.sin(angle)
    pts = _grid(10, 10) @ np.array([[c, s], [-s, c]])
    if angle in (np.pi / 2, np.pi):
        pts = np.round(pts)  # exact rotations stay exactly cocircular
    check(pts)


def test_perturbed_grids():
    rng = np.random.default_rng(12)
    for eps in (1e-15, 1e-12, 1e-8):
        check(_grid(12, 12) + rng.uniform(-eps, eps, size=(144, 2)))


def test_engine_entry_point_sweep_order():
    """``fortune_delaunay`` (what vf.voronoi calls): sites in (y, x) order, triangles on them."""
    from voroforge.kernels.fortune import fortune_delaunay

    pts = np.concatenate((_grid(6, 6), np.random.default_rng(7).random((40, 2)) * 5))
    xs, ys = pts[:, 0].copy(), pts[:, 1].copy()
    order, sx, sy, tri, he, ok = fortune_delaunay(xs, ys)
    assert ok
    assert sorted(order.tolist()) == list(range(len(pts)))
    key = list(zip(ys[order].tolist(), xs[order].tolist(), strict=True))
    assert key == sorted(key)
    assert np.array_equal(sx, xs[order]) and np.array_equal(sy, ys[order])
    assert np.array_equal(xs, pts[:, 0]) and np.array_equal(ys, pts[:, 1])  # inputs untouched
    mapped = order[tri.reshape(-1, 3)]
    assert _triples(mapped) == _triples(fortune_triangles(pts))
    assert brute_delaunay_ok(pts, mapped)
    for few in (pts[:2], np.array([[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]])):
        assert not fortune_delaunay(few[:, 0].copy(), few[:, 1].copy())[-1]


def _right_of_exact(sx, px, py, qx, qy, sweep):
    """``sx`` right of the breakpoint of the arcs of ``p`` (left) and ``q``, to 100 digits.

    The breakpoint's offset from ``px`` is the root ``(hp dx - sqrt(hp hq |q - p|^2)) / a``
    of the two parabolas' intersection (``hp``, ``hq`` the sites' distances below the sweep
    line, ``a = qy - py``), evaluated in decimal arithmetic; ``None`` when it ties ``sx``.
    """
    from decimal import Decimal, localcontext

    with localcontext() as ctx:
        ctx.prec = 100
        sx, px, py, qx, qy, sweep = (Decimal(float(v)) for v in (sx, px, py, qx, qy, sweep))
        if py == qy:
            x = (px + qx) / 2
        elif sweep <= py:
            x = px
        elif sweep <= qy:
            x = qx
        else:
            hp, hq, dx, a = sweep - py, sweep - qy, qx - px, qy - py
            x = px + (hp * dx - (hp * hq * (dx * dx + a * a)).sqrt()) / a
        if abs(sx - x) <= abs(x) * Decimal(10) ** -90:
            return None
        return sx > x


def test_breakpoint_side_is_exact():
    """The arc search's breakpoint test against rationals on sites a few ulps apart.

    Sites 1-6 ulps apart put a new site into the wrong arc when the test was evaluated in
    floats (the sweep then left part of the hull uncovered on ~1% of such inputs).
    """
    from voroforge.kernels.fortune import _right_of

    g = np.random.default_rng(5)
    wrong = 0
    for _ in range(3000):
        base = g.random(2) * 2.0 - 1.0
        pts = [base]
        for _ in range(3):
            step = g.integers(-6, 7, size=2)
            q = pts[-1].copy()
            for k in range(2):
                for _ in range(abs(int(step[k]))):
                    q[k] = np.nextafter(q[k], q[k] + np.sign(step[k]))
            pts.append(q)
        (px, py), (qx, qy), (sx, sweep) = pts[0], pts[1], pts[2]
        sweep = max(sweep, py, qy)
        if g.random() < 0.3:
            sweep = max(py, qy) + abs(float(g.normal())) * 1e-15
        got = _right_of(float(sx), float(px), float(py), float(qx), float(qy), float(sweep))
        want = _right_of_exact(sx, px, py, qx, qy, sweep)
        wrong += want is not None and got != want
    assert wrong == 0


def test_sweep_fills_hull_of_sites_ulps_apart():
    """2-5 sites 1-6 ulps apart on a line among 20 random ones: the sweep's triangles cover
    the hull (Euler count ``2n - 2 - h``), for the seeds where floats left a notch."""
    from voroforge.engine.planar import _fills_hull
    from voroforge.kernels.fortune import fortune_delaunay

    for seed in (94, 127, 164, 627, 652, 801):
        pts = sites_ulps_apart(seed)
        assert _fills_hull(*fortune_delaunay(pts[:, 0].copy(), pts[:, 1].copy())[1:5]), seed
        check(pts, brute=True)
