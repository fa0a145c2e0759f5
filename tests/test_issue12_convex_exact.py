"""Issue 12: ``vf.Convex(halfspaces=)`` is the exact polytope of its rows.

The template (``engine.polytope3d``) keeps every vertex exactly and decides every side
exactly: its vertices are the correctly rounded intersections of three of the rows, its
volume the exact volume rounded (about an ulp), and rows that touch the solid in a point, an
edge or a face (duplicates, redundant or nearly parallel rows) make no face. Before, the
float cut merged nearly coplanar walls: the rounded rows of a 1e-3 slab at UTM offsets gave
``.volume`` 5.8e-11 off, at the origin 4.2e-11.

The reference below is slow and plain: every triple of rows solved in rationals, the feasible
points kept, each row's points ordered round its normal and the fans summed.
"""

import itertools
import sys
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

import voroforge as vf

sys.path.insert(0, str(Path(__file__).parent))
from test_voronoi3d import check3d  # noqa: E402

UTM = np.array([5e5, 4e6, 100.0])


def _det(a, b, c):
    return (
        a[0] * (b[1] * c[2] - b[2] * c[1])
        - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
    )


def _sub(a, b):
    return [a[k] - b[k] for k in range(3)]


def _ints(r):
    """The row ``r`` of doubles times the power of two that makes it integers."""
    fr = [Fraction(float(x)) for x in r]
    den = max(f.denominator for f in fr)
    return [int(f * den) for f in fr]


_REFERENCE = {}  # rows' bytes -> (vertices, volume): check_exact asks for the raw rows twice


def reference(rows):
    """``(vertices, volume)`` of the polytope of ``rows (k, 4)``: exact rationals.

    Computed once per distinct ``rows`` (a sorted list of points and a Fraction).
    """
    rows = np.asarray(rows, float)
    key = (rows.shape, rows.tobytes())
    if key not in _REFERENCE:
        _REFERENCE[key] = _reference(rows)
    pts, vol = _REFERENCE[key]
    return list(pts), vol


def _reference(rows):
    H = [_ints(r) for r in rows]
    mag = np.abs(rows)
    pts = set()
    for r1, r2, r3 in itertools.combinations(H, 3):
        D = _det(r1, r2, r3)
        if D == 0:
            continue
        x = [
            _det(*[[r[3] if q == k else r[q] for q in range(3)] for r in (r1, r2, r3)])
            for k in range(3)
        ]
        # rows the point clearly violates (by far more than its rounding) rule it out fast
        xf = np.array([x[k] / D for k in range(3)])
        if (rows[:, :3] @ xf - rows[:, 3] > 1e-9 * (mag[:, :3] @ np.abs(xf) + mag[:, 3])).any():
            continue
        if D < 0:
            x, D = [-q for q in x], -D
        if all(r[0] * x[0] + r[1] * x[1] + r[2] * x[2] <= r[3] * D for r in H):
            pts.add(tuple(Fraction(q, D) for q in x))
    H = [[Fraction(float(x)) for x in r] for r in rows]
    pts = sorted(pts)
    o = [sum(p[k] for p in pts) / len(pts) for k in range(3)]  # inside: no face passes it
    vol = Fraction(0)
    seen = set()
    for r in H:
        on = [p for p in pts if r[0] * p[0] + r[1] * p[1] + r[2] * p[2] == r[3]]
        if len(on) < 3 or frozenset(on) in seen:
            continue  # no face, or a face already counted (a duplicate row)
        seen.add(frozenset(on))
        a = on[0]  # the smallest: an extreme point, the others within a half-turn of it
        rest = on[1:]
        for i in range(len(rest)):  # order round the outward normal (selection sort)
            for j in range(i + 1, len(rest)):
                u, w = _sub(rest[i], a), _sub(rest[j], a)
                cross = [
                    u[1] * w[2] - u[2] * w[1],
                    u[2] * w[0] - u[0] * w[2],
                    u[0] * w[1] - u[1] * w[0],
                ]
                if sum(r[k] * cross[k] for k in range(3)) < 0:
                    rest[i], rest[j] = rest[j], rest[i]
        for b, c in itertools.pairwise(rest):
            vol += _det(_sub(a, o), _sub(b, o), _sub(c, o))
    return pts, vol / 6


def _template_rows(c):
    """The rows ``(k, 4)`` the cells use, in the template's frame (``TV`` is in it too)."""
    return c._template.WP[:, :4]


def _faced(rows, pts) -> np.ndarray:
    """Which of ``rows`` have a face (three or more of the polytope's ``pts`` on them)."""
    out = []
    for r in rows:
        f = [Fraction(float(x)) for x in r]
        out.append(sum(f[0] * p[0] + f[1] * p[1] + f[2] * p[2] == f[3] for p in pts) >= 3)
    return np.array(out)


def check_exact(c, raw=None, rtol_raw=1e-12):
    """The template is the reference's polytope: vertices to the bit, volume to ~an ulp.

    Of the rows as the cells use them (divided by their norms, rounded), those that make a
    face of the exact polytope of the rows as given (``raw``): a row that only touches it
    (``[1, 1, 1, 3]`` on the unit cube) passes an ulp inside once rounded, and must not cut.
    """
    t = c._template
    rows = _template_rows(c)
    if raw is not None:
        rows = rows[_faced(raw, reference(raw)[0])]
    pts, vol = reference(rows)
    want = sorted(tuple(float(x) for x in p) for p in pts)
    got = sorted(map(tuple, t.TV.tolist()))
    assert got == want  # distinct exact vertices may round to the same doubles
    assert abs(t.volume - float(vol)) <= 4e-16 * float(vol)
    labels = -1 - t.TF[:, 0]
    assert len(set(labels.tolist())) == len(labels)  # one face per row at most
    if raw is not None:  # the rows as given: the unit rows' rounding only
        _, vraw = reference(raw)
        assert abs(c.volume - float(vraw)) <= rtol_raw * float(vraw)
    return vol


def _sites(c, n, seed):
    """``n`` points strictly inside the container."""
    t = c._template
    w = np.random.default_rng(seed).dirichlet(np.ones(len(t.TV)), size=n)
    return t.origin + w @ t.TV  # convex combinations with positive weights


def check_cells(c, n=40, seed=0, samples=300):
    """Cells sum to ``.volume`` to 1e-12; every invariant and sample (``check3d``) holds.

    Rounded rows make distinct vertices ulps apart (``near``). Far out, the faces' normals
    from vertices rounded at 4e6 tilt by ~1e-8 on a face 0.02 wide, past ``check3d``'s
    1e-9 of the size: there the same walls and sites moved exactly to the origin are checked,
    and the far cells must have the near cells' volumes.
    """
    sites = _sites(c, n, seed)
    d = vf.voronoi3d(sites, c)
    assert abs(d.volumes.sum() - c.volume) <= 1e-12 * c.volume
    assert d.describe()["euler_ok"]
    t = c._template
    if t.WP.shape[1] == 4:
        check3d(d, volume=c.volume, samples=samples, near=True)
        return
    near = vf.Convex(halfspaces=t.WP[:, :4])  # about the origin o (sites - o is exact)
    dn = vf.voronoi3d(sites - t.origin, near)
    check3d(dn, volume=near.volume, samples=samples, near=True)
    assert np.abs(d.volumes - dn.volumes).max() <= 1e-12 * c.volume


def _hull_rows(P):
    return vf.Convex(points=P).halfspaces


def _slab(n=40, seed=5):
    s = np.random.default_rng(seed).random((n, 3))
    s[:, 2] *= 1e-3
    return s


def _cube():
    return np.array([[i, j, k] for i in (0, 1) for j in (0, 1) for k in (0, 1)], float)


def _prism():
    a = np.linspace(0, 2 * np.pi, 7)[:-1]
    ring = np.column_stack([np.cos(a), np.sin(a), np.zeros(6)])
    return np.vstack([ring, ring + [0.1, 0.05, 2.0]])


@pytest.mark.parametrize("shape", ["slab", "cube", "prism"])
@pytest.mark.parametrize("at", ["origin", "utm"])
def test_rounded_rows(shape, at):
    from scipy.spatial.transform import Rotation

    P = {"slab": _slab(), "cube": _cube(), "prism": _prism()}[shape]
    P = Rotation.from_euler("xyz", [0.3, -0.7, 1.1]).apply(P)  # no wall on an axis
    if at == "utm":
        P = P + UTM
    rows = _hull_rows(P)
    c = vf.Convex(halfspaces=rows)
    check_exact(c, raw=rows)
    check_cells(c)


@pytest.mark.parametrize("k", [4, 7, 12, 25, 60])
def test_random_rows(k):
    r = np.random.default_rng(k)
    n = r.normal(size=(k, 3))
    n /= np.linalg.norm(n, axis=1)[:, None]
    n[:4] = [[1, 1, 1], [-1, 0.1, 0], [0, -1, 0.2], [0.1, 0, -1]]  # these four close it
    # tangent planes of the unit sphere (and the four), pushed out at random
    rows = np.column_stack([n, 1.0 + r.random(k)])
    c = vf.Convex(halfspaces=rows)
    check_exact(c, raw=rows)
    check_cells(c, seed=k)


BASE = [[-1, 0, 0, 0], [1, 0, 0, 1], [0, -1, 0, 0], [0, 1, 0, 1], [0, 0, -1, 0], [0, 0, 1, 1]]


@pytest.mark.parametrize(
    "extra",
    [
        [[0, 0, 1, 1]],  # a duplicate
        [[0, 0, 4, 4], [0, 0, 0.5, 0.5]],  # the same plane scaled
        [[1, 1, 0, 2]],  # touches the cube in an edge
        [[1, 1, 1, 3]],  # in a corner
        [[1, 1, 1, 2.5], [1, 1, 1, 2.5]],  # cuts a corner (1/48), twice
        [[0, 0, 1, np.nextafter(1.0, 2.0)]],  # an ulp outside the top wall
        [[0, 0, 1, np.nextafter(1.0, 0.0)]],  # an ulp inside: a real (thin) cut
        [[2.0**-53, 0, 1, 1]],  # tilted by an ulp, through the top face's x = 0 edge
        [[-(2.0**-52), 0, 1, 1]],  # tilted the other way: cuts a wedge an ulp high
        [[1e-13, 1e-13, 1, 1 + 1e-13]],  # nearly parallel, through a corner
    ],
)
def test_redundant_duplicate_and_nearly_parallel_rows(extra):
    rows = np.array(BASE + extra, float)
    c = vf.Convex(halfspaces=rows)
    vol = check_exact(c, raw=rows, rtol_raw=1e-15)  # rows not of unit normals: rounded once
    assert float(vol) == pytest.approx(1.0 - (extra[0][3] == 2.5) / 48, rel=1e-12)
    # a row that cuts nothing makes no face: only the cube's six walls and real cuts
    assert len(c._template.TF) <= 7
    check_cells(c, seed=1)


@pytest.mark.parametrize("scale", [1e-9, 1e9])
@pytest.mark.parametrize("at", [(0.0, 0.0, 0.0), (3.0, -2.0, 7.0)])
def test_tiny_and_huge(scale, at):
    P = scale * (np.array(at) + np.random.default_rng(3).normal(size=(30, 3)))
    rows = _hull_rows(P)
    c = vf.Convex(halfspaces=rows)
    check_exact(c, raw=rows)
    check_cells(c, n=20, samples=200)


@pytest.mark.parametrize("off", [(0.0, 0.0, 0.0), tuple(UTM)])
def test_rows_one_ulp_apart(off):
    # pairs of walls whose offsets differ by an ulp and whose normals by an ulp: each pair
    # keeps its outer row as a face only where it cuts; cells and samples hold
    rows = []
    for r in BASE:
        r = np.array(r, float)
        r[3] += np.dot(r[:3], off)
        rows.append(r)
        s = r.copy()
        s[3] = np.nextafter(s[3], -np.inf)
        rows.append(s)
        s = r.copy()
        s[np.flatnonzero(s[:3] == 0)[0]] = 2.0**-52
        rows.append(s)
    rows = np.array(rows)
    c = vf.Convex(halfspaces=rows)
    check_exact(c, raw=rows, rtol_raw=1e-15)
    check_cells(c, seed=2)


def test_empty_and_unbounded_are_errors():
    with pytest.raises(ValueError, match="no common point|no volume"):
        vf.Convex(halfspaces=[*BASE, [0, 0, -1, -2]])  # above the top and below it
    with pytest.raises(ValueError, match="no volume|flat"):
        vf.Convex(halfspaces=[*BASE, [0, 0, -1, -1]])  # only the top face is left
    with pytest.raises(ValueError, match="no volume|flat"):
        vf.Convex(halfspaces=[*BASE, [0, 0, -1, -np.nextafter(1.0, 0.0)]])  # one ulp thick
    with pytest.raises(ValueError, match="unbounded|open"):
        vf.Convex(halfspaces=BASE[:5] + [[1, 1, 0, 3]])
