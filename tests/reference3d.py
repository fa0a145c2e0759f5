"""Slow, obvious references for 3D Voronoi / power cells (tests only).

``brute_cell`` intersects the container's half-spaces with the power bisector of the site
and *every* other site (scipy's HalfspaceIntersection, Qhull), so no search, stop test or
naming can hide an error; ``brute_volumes`` takes their hulls' volumes. ``voropp_cells``
runs the voro++ command-line tool and reads its volumes and neighbour lists.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile

import numpy as np

VOROPP = shutil.which("voro++")


def brute_cell(points, i, walls, weights=None):
    """Vertices of cell ``i`` (power cell with ``weights``) in the region ``walls (W, 4)``.

    Returns ``(k, 3)`` vertices, or ``None`` when the cell is empty.
    """
    from scipy.optimize import linprog
    from scipy.spatial import HalfspaceIntersection

    p = np.asarray(points, np.float64)
    w = np.zeros(len(p)) if weights is None else np.asarray(weights, np.float64)
    others = np.flatnonzero(~(p == p[i]).all(axis=1))  # every site but i and its duplicates
    rows = [np.column_stack([walls[:, :3], -walls[:, 3]])]  # A x + b <= 0
    if len(others):
        d = p[others] - p[i]
        h = 0.5 * ((p[others] ** 2).sum(1) - (p[i] ** 2).sum() - w[others] + w[i])
        rows.append(np.column_stack([d, -h]))
    hs = np.vstack(rows)
    norm = np.linalg.norm(hs[:, :3], axis=1)
    A = hs[:, :3] / norm[:, None]
    b = -hs[:, 3] / norm
    # Chebyshev centre: an interior point, or proof that the cell is empty
    res = linprog(
        [0, 0, 0, -1],
        A_ub=np.column_stack([A, np.ones(len(A))]),
        b_ub=b,
        bounds=[(None, None)] * 3 + [(0, None)],
        method="highs",
    )
    if res.status != 0 or res.x[3] <= 1e-12 * (np.abs(b).max() + 1):
        return None
    hi = HalfspaceIntersection(np.column_stack([A, -b]), res.x[:3])
    return hi.intersections


def brute_volumes(points, walls, weights=None, cells=None):
    """Volume of every cell (or of ``cells``) by :func:`brute_cell` (0 for empty cells).

    The input is moved to the origin and scaled to unit size first (Qhull's tolerances are
    absolute); volumes are scaled back.
    """
    from scipy.spatial import ConvexHull

    p = np.asarray(points, np.float64)
    c = p.mean(axis=0)
    s = float(np.abs(p - c).max()) or 1.0
    p = (p - c) / s
    walls = np.asarray(walls, np.float64).copy()
    walls[:, 3] = (walls[:, 3] - walls[:, :3] @ c) / s
    weights = None if weights is None else np.asarray(weights) / s**2
    cells = range(len(p)) if cells is None else cells
    out = np.zeros(len(cells))
    for k, i in enumerate(cells):
        v = brute_cell(p, i, walls, weights)
        if v is not None and len(v) >= 4:
            out[k] = ConvexHull(v).volume * s**3
    return out


def brute_periodic_volumes(points, L=1.0):
    """Cells of the 3-torus ``[0, L)^3`` from the sites and their 26 images (n small)."""
    p = np.asarray(points, np.float64)
    shifts = np.array([(a, b, c) for a in (-1, 0, 1) for b in (-1, 0, 1) for c in (-1, 0, 1)])
    shifts = shifts[np.argsort((shifts != 0).sum(1), kind="stable")]  # (0, 0, 0) first
    allp = np.vstack([p + L * s for s in shifts])
    walls = np.array(
        [
            [-1, 0, 0, L],
            [1, 0, 0, 2 * L],
            [0, -1, 0, L],
            [0, 1, 0, 2 * L],
            [0, 0, -1, L],
            [0, 0, 1, 2 * L],
        ],
        np.float64,
    )
    return brute_volumes(allp, walls, cells=range(len(p)))


def dyadic_ints(*arrays):
    """The doubles of each ``(m, k)`` array as nested lists of Python ints, all times one
    power of two ``2**K`` (the largest denominator among them): exact, and an integer
    polynomial's sign (orientations, in-sphere tests, distance comparisons of one degree) is
    the rationals' sign, at int speed instead of ``Fraction``'s."""
    ratios = [
        [[v.as_integer_ratio() for v in row] for row in np.asarray(a, np.float64).tolist()]
        for a in arrays
    ]
    K = max((q.bit_length() for r in ratios for row in r for _, q in row), default=1) - 1
    return [[[n << (K - q.bit_length() + 1) for n, q in row] for row in r] for r in ratios]


def _voropp(points, box, fmt, *, weights=None, walls=None, ordered=False):
    """voro++'s command line on ``points`` in ``box = (xmin, ymin, zmin, xmax, ymax, zmax)``.

    ``fmt``: its custom output (``-c``), one line a cell; ``weights``: the radical tessellation
    (``-r``, radius^2 = weight - min(weight), the same power cells); ``walls``: rows
    ``[a, b, c, d]`` as ``-wp a b c d`` (inside ``a x + b y + c z < d``). Returns the output's
    lines split into fields.
    """
    pts = np.asarray(points, np.float64)
    rad = None if weights is None else np.sqrt(np.asarray(weights, np.float64) - np.min(weights))
    opts = ["-c", fmt] + (["-o"] if ordered else []) + ([] if rad is None else ["-r"])
    for r in np.asarray([] if walls is None else walls, np.float64).reshape(-1, 4):
        opts += ["-wp", *(repr(float(x)) for x in r)]
    x0, y0, z0, x1, y1, z1 = box
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "pts")
        with open(path, "w") as fh:
            for k, (x, y, z) in enumerate(pts):
                extra = "" if rad is None else f" {float(rad[k])!r}"
                fh.write(f"{k} {float(x)!r} {float(y)!r} {float(z)!r}{extra}\n")
        bounds = [str(x0), str(x1), str(y0), str(y1), str(z0), str(z1)]
        subprocess.run([VOROPP, *opts, *bounds, path], check=True, capture_output=True)
        with open(path + ".vol") as fh:
            return [line.split() for line in fh]


def voropp_volumes(points, box, *, weights=None, walls=None):
    """voro++'s volumes of ``points`` in ``box`` (weights: radical; walls: ``-wp`` rows)."""
    vol = np.zeros(len(points))
    for k, v in _voropp(points, box, "%i %v", weights=weights, walls=walls):
        vol[int(k)] = float(v)
    return vol


def voropp_cells(points, box):
    """voro++ CLI on ``points`` in ``box = (xmin, ymin, zmin, xmax, ymax, zmax)``.

    Returns ``(volumes (n,), neighbours: list of sorted int lists, walls as -1..-6)``.
    """
    vol = np.zeros(len(points))
    nbs = [[] for _ in range(len(points))]
    for parts in _voropp(points, box, "%i %v %n", ordered=True):
        k = int(parts[0])
        vol[k] = float(parts[1])
        nbs[k] = sorted(int(v) for v in parts[2:])
    return vol, nbs
