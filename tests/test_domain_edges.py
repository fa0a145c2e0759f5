"""Shared edges and neighbours in polygon domains whose boundary runs along Voronoi edges.

A Voronoi edge lying on the domain's boundary (a hole or an outline along grid lines)
separates no two clipped cells: ``d.edges`` keeps only edge pieces of positive length in the
domain's interior, and ``d.neighbors`` lists the pairs whose clipped cells share a boundary of
positive length. References: for sites on a unit grid (cells = unit squares, edges on the
grid lines), the grid's 4-neighbour pairs whose shared unit side keeps a positive length in
the domain less its boundary (every coordinate a small integer or a half: exact); for random
domains, the pairs of clipped cells whose boundaries share a positive length (shapely on
``d.cells``).
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from shapely.geometry import MultiPolygon, Polygon, box

import voroforge as vf

N = 6
GRID = np.array([[i + 0.5, j + 0.5] for i in range(N) for j in range(N)], dtype=np.float64)
ALGORITHMS = ("delaunay", "fortune", "halfplane")


def _square(i, j):
    return box(i, j, i + 1, j + 1)


def _with_holes(*holes):
    return Polygon(box(0, 0, N, N).exterior.coords, [h.exterior.coords[::-1] for h in holes])


GRID_DOMAINS = {
    "hole one cell": _with_holes(box(1, 1, 2, 2)),
    "hole half a cell": _with_holes(box(1, 1, 2, 1.5)),
    "two holes meeting at a corner": _with_holes(box(1, 1, 2, 2), box(2, 2, 4, 3)),
    "L of grid squares": shapely.union_all(
        [_square(i, j) for i in range(N) for j in range(N) if not (i > 2 and j > 2)]
    ),
    "checkerboard": MultiPolygon(
        [_square(i, j) for i in range(N) for j in range(N) if (i + j) % 2 == 0]
    ),
    "two squares meeting at a corner": MultiPolygon([box(0, 0, 3, 3), box(3, 3, 6, 6)]),
    "outline on grid lines, sloped hole": Polygon(
        box(0, 0, 5, 6).exterior.coords, [[(3.2, 3.2), (3.8, 3.4), (3.4, 3.8)]]
    ),
}


def _grid_reference(domain):
    """4-neighbour pairs of GRID whose shared unit side meets the interior (positive length)."""
    out = set()
    rim = domain.boundary
    for i in range(N):
        for j in range(N):
            a = i * N + j
            for b, side in (
                (a + N, [(i + 1, j), (i + 1, j + 1)]),
                (a + 1, [(i, j + 1), (i + 1, j + 1)]),
            ):
                if (b == a + N and i + 1 < N) or (b == a + 1 and j + 1 < N):
                    inner = shapely.intersection(shapely.LineString(side), domain).difference(rim)
                    if inner.length > 0:
                        out.add((a, b))
    return out


def _cells_reference(cells, tol):
    """Pairs of cells whose boundaries share a length above ``tol``."""
    tree = shapely.STRtree(cells)
    left, right = tree.query(cells, predicate="intersects")
    out = set()
    for a, b in zip(left.tolist(), right.tolist(), strict=True):
        if a < b and not cells[a].is_empty and not cells[b].is_empty:
            if shapely.intersection(cells[a].boundary, cells[b].boundary).length > tol:
                out.add((a, b))
    return out


def _pairs(d):
    ip, nb = d.neighbors
    got = {(i, int(j)) for i in range(len(ip) - 1) for j in nb[ip[i] : ip[i + 1]] if i < j}
    return got


def _check_edges(d, domain, expected):
    """Edges' pairs and neighbours equal ``expected``; each edge is inside, on both cells."""
    coords, pairs = d.edges
    assert {tuple(p) for p in pairs.tolist()} == expected
    assert _pairs(d) == expected
    cells = np.asarray(list(d.cells), dtype=object)
    if len(coords):
        mid = 0.5 * (coords[:, 0] + coords[:, 1])
        assert shapely.contains_xy(domain, mid[:, 0], mid[:, 1]).all()
        lines = shapely.linestrings(coords)
        for side in (0, 1):
            dist = shapely.distance(shapely.boundary(cells[pairs[:, side]]), lines)
            assert (dist <= 1e-12 * np.abs(coords).max()).all()
        assert (np.hypot(*(coords[:, 1] - coords[:, 0]).T) > 0).all()


@pytest.mark.parametrize("name", sorted(GRID_DOMAINS))
@pytest.mark.parametrize("algorithm", ALGORITHMS)
def test_grid_edges_on_the_boundary_are_not_shared(name, algorithm):
    domain = GRID_DOMAINS[name]
    d = vf.voronoi(GRID, domain, algorithm=algorithm)
    _check_edges(d, domain, _grid_reference(domain))


@pytest.mark.parametrize("name", sorted(GRID_DOMAINS))
def test_grid_power_edges_on_the_boundary_are_not_shared(name):
    domain = GRID_DOMAINS[name]
    d = vf.power(GRID, np.full(len(GRID), 0.125), domain)
    _check_edges(d, domain, _grid_reference(domain))


@pytest.mark.parametrize("box_", [(0, 0, 5, 6), (0, 0.5, 6, 6), (1, 1, 5, 5)])
def test_box_sides_on_grid_lines(box_):
    """Sites outside a rectangle, mirrored across its side: their edges are not shared."""
    d = vf.voronoi(GRID, box_)
    _check_edges(d, box(*box_), _grid_reference(box(*box_)))


def _random_domain(rng):
    """A star-shaped outline with a few random holes, some on the sites' grid lines."""
    t = np.sort(rng.random(9)) * 2 * np.pi
    r = 2.2 + rng.random(9)
    shell = Polygon(np.c_[3 + r * np.cos(t), 3 + r * np.sin(t)])
    holes = []
    for _ in range(3):
        x, y = rng.integers(1, 5, 2)
        w, h = rng.integers(1, 3, 2) * rng.choice([0.5, 1.0])
        holes.append(box(x, y, x + w, y + h))
    hole = shapely.union_all(holes)
    return shapely.difference(shell, hole)


@pytest.mark.parametrize("seed", range(6))
def test_random_domains_edges_equal_the_cells_shared_sides(seed):
    rng = np.random.default_rng(seed)
    domain = _random_domain(rng)
    pts = np.r_[GRID, rng.random((20, 2)) * N] if seed % 2 else GRID
    for algorithm in ALGORITHMS:
        d = vf.voronoi(pts, domain, algorithm=algorithm)
        cells = np.asarray(list(d.cells), dtype=object)
        _check_edges(d, domain, _cells_reference(cells, 1e-9))
    d = vf.power(pts, rng.random(len(pts)) * 0.2, domain)
    cells = np.asarray(list(d.cells), dtype=object)
    _check_edges(d, domain, _cells_reference(cells, 1e-9))
