"""The face-ring cut of a convex polyhedron (kernels/polyhedron) and the Convex container.

Small exact cases: a unit cube cut through edges, through vertices, touched, emptied, and
chains of random cuts checked against scipy's half-space intersection. Cheap with the JIT
off too, so `make coverage` measures every branch of the cut.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import ConvexHull, HalfspaceIntersection

import voroforge as vf
from voroforge.engine.containers import as_container, box_template
from voroforge.kernels import polyhedron as ph

CAP = 64


def _cube(lo=(0.0, 0.0, 0.0), hi=(1.0, 1.0, 1.0), cap=CAP):
    """Work arrays holding a box: ``(V, nv, F, nf, R, R2, S, work)``."""
    t = box_template(np.asarray(lo, float), np.asarray(hi, float))
    V = np.zeros((cap, 3))
    F = np.zeros((cap, 3), np.int64)
    R = np.zeros(4 * cap, np.int64)
    V[:8] = t.TV
    F[:6] = t.TF
    R[:24] = t.TR
    return (
        V,
        8,
        F,
        6,
        R,
        np.zeros(4 * cap, np.int64),
        np.zeros(cap),
        np.zeros((4 * cap, 4), np.int64),
    )


def _cut(P, n, h, label, tol=0.0):
    V, nv, F, nf, R, R2, S, work = P
    ph.plane_values(V, nv, n[0], n[1], n[2], h, tol, S)
    st, nv2, nf2 = ph.cut(V, nv, F, nf, R, R2, S, work, label)
    if st == ph.CUT_DONE:
        P = (V, nv2, F, nf2, R, R2, S, work)
    return st, P


def _check_closed(P):
    """Euler's formula, every edge used once each way, area vectors summing to zero."""
    V, nv, F, nf, R, *_ = P
    assert ph.ring_count(F, nf) == F[:nf, 2].sum()
    edges = set()
    used = set()
    for f in range(nf):
        st, ln = F[f, 1], F[f, 2]
        ring = R[st : st + ln].tolist()
        assert ln >= 3 and len(set(ring)) == ln
        used.update(ring)
        for k in range(ln):
            e = (ring[k], ring[(k + 1) % ln])
            assert e not in edges
            edges.add(e)
    assert all((q, p) in edges for p, q in edges), "an edge without its twin"
    assert used == set(range(nv)), "compact left an unused vertex"
    assert nv - len(edges) // 2 + nf == 2
    total = np.sum([ph.face_vector(V, R, F[f, 1], F[f, 2]) for f in range(nf)], axis=0)
    assert np.abs(total).max() <= 1e-15 * nf


def test_cube_cut_through_edges_keeps_half():
    st, P = _cut(_cube(), (1.0, 0.0, 0.0), 0.5, 7)  # x <= 0.5
    assert st == ph.CUT_DONE
    _check_closed(P)
    V, nv, F, nf, R, *_ = P
    assert (nv, nf) == (8, 6)
    vol, mx, my, mz = ph.moments(V, F, nf, R)
    assert vol == 0.5 and (mx / vol, my / vol, mz / vol) == (0.25, 0.5, 0.5)
    cap = [f for f in range(nf) if F[f, 0] == 7]
    assert len(cap) == 1 and F[cap[0], 2] == 4
    ax, ay, az = ph.face_vector(V, R, F[cap[0], 1], 4)
    assert (ax, ay, az) == (1.0, 0.0, 0.0)  # outward +x, area 1
    # the old vertices come first (their numbers are kept), the crossings after them
    assert (V[:4, 0] == 0.0).all() and (V[4:nv, 0] == 0.5).all()


def test_cut_through_vertices_reuses_them():
    # x + y <= 1 passes through four corners: no new vertex, the cap is the diagonal square
    st, P = _cut(_cube(), (1.0, 1.0, 0.0), 1.0, 9)
    assert st == ph.CUT_DONE
    _check_closed(P)
    V, nv, F, nf, R, *_ = P
    assert (nv, nf) == (6, 5)  # a triangular prism
    assert ph.moments(V, F, nf, R)[0] == 0.5
    cap = [f for f in range(nf) if F[f, 0] == 9]
    assert len(cap) == 1 and F[cap[0], 2] == 4
    # the faces the plane leaves a single edge of (two of the six) are gone
    assert sorted(F[:nf, 0].tolist()) == sorted([-1, -3, -5, -6, 9])


def test_corner_tetrahedron_and_values_snapped_to_the_plane():
    # x + y + z <= 0.5 leaves the corner tetrahedron of volume 0.5**3 / 6
    st, P = _cut(_cube(), (1.0, 1.0, 1.0), 0.5, 3)
    assert st == ph.CUT_DONE
    _check_closed(P)
    V, nv, F, nf, R, *_ = P
    assert (nv, nf) == (4, 4)
    assert ph.moments(V, F, nf, R)[0] == pytest.approx(0.5**3 / 6, rel=1e-15)
    # a plane within tol of three corners snaps them onto it: no sliver, no new vertex
    st, P2 = _cut(_cube(), (1.0, 1.0, 1.0), 1.0 + 2.0**-50, 4, tol=1e-12)
    assert st == ph.CUT_DONE
    _check_closed(P2)
    assert (P2[1], P2[3]) == (4, 4)
    assert (P2[0][:4] == [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]).all()
    assert ph.moments(P2[0], P2[2], P2[3], P2[4])[0] == pytest.approx(1 / 6, rel=1e-15)
    # without the snap the same plane makes three crossings a rounding from the corners
    st, P3 = _cut(_cube(), (1.0, 1.0, 1.0), 1.0 + 2.0**-50, 4)
    assert st == ph.CUT_DONE
    _check_closed(P3)
    assert P3[1] > 4


def test_touching_and_missing_planes():
    P = _cube()
    st, _ = _cut(P, (1.0, 0.0, 0.0), 1.0, 5)  # the face x = 1: touches, nothing above
    assert st == ph.CUT_NONE
    st, _ = _cut(P, (1.0, 0.0, 0.0), 2.0, 5)  # misses
    assert st == ph.CUT_NONE
    st, _ = _cut(P, (1.0, 0.0, 0.0), 0.0, 5)  # keeps only the face x = 0: empty
    assert st == ph.CUT_EMPTY
    st, _ = _cut(P, (1.0, 1.0, 1.0), 0.0, 5)  # touches the corner at the origin only
    assert st == ph.CUT_EMPTY
    st, _ = _cut(P, (-1.0, 0.0, 0.0), -2.0, 5)  # everything above
    assert st == ph.CUT_EMPTY
    # the box itself is untouched by all of these
    _check_closed(P)
    assert ph.moments(P[0], P[2], P[3], P[4])[0] == 1.0


@pytest.mark.parametrize("what", ["vertices", "faces", "rings", "work"])
def test_scratch_too_small_is_reported(what):
    V, nv, F, nf, R, R2, S, work = _cube()
    if what == "vertices":
        V, S = V[:9], S[:9]  # room for one crossing, the cut needs three
    elif what == "faces":
        F = F[:6]  # no room for the seventh face
    elif what == "rings":
        R, R2 = R[:24], R2[:24]
    else:
        work = work[:2]
    # cutting off the corner (1, 1, 1) adds a face, three vertices and five ring entries
    st, _ = _cut((V, nv, F, nf, R, R2, S, work), (1.0, 1.0, 1.0), 2.5, 1)
    assert st == ph.CUT_OVERFLOW


def _halfspace_volume(planes):
    """Volume of the unit cube cut by ``n . x <= h`` rows (scipy, independent of the kernel)."""
    hs = [[-1, 0, 0, 0], [1, 0, 0, -1], [0, -1, 0, 0], [0, 1, 0, -1], [0, 0, -1, 0], [0, 0, 1, -1]]
    hs += [[n[0], n[1], n[2], -h] for n, h in planes]
    inter = HalfspaceIntersection(np.array(hs, float), np.array([0.5, 0.5, 0.5]))
    return ConvexHull(inter.intersections).volume


@pytest.mark.parametrize("seed", [0, 1])
def test_random_cut_chains_match_halfspace_intersection(seed):
    rng = np.random.default_rng(seed)
    P = _cube()
    planes = []
    for step in range(12):
        n = rng.normal(size=3)
        n /= np.linalg.norm(n)
        # planes at distance 0.2..0.45 from the centre: the centre always stays inside
        h = float(n @ [0.5, 0.5, 0.5]) + rng.uniform(0.2, 0.45)
        st, P = _cut(P, n, h, 10 + step)
        assert st in (ph.CUT_DONE, ph.CUT_NONE)
        if st == ph.CUT_DONE:
            planes.append((n, h))
            labels = P[2][: P[3], 0]
            assert 10 + step in labels.tolist()
        _check_closed(P)
        vol = ph.moments(P[0], P[2], P[3], P[4])[0]
        assert vol == pytest.approx(_halfspace_volume(planes), rel=1e-12)


def test_convex_container_from_halfspaces_and_points():
    # the unit tetrahedron, twice: by half-spaces and as a hull of its corners
    tet = vf.Convex([[1, 1, 1, 1], [-1, 0, 0, 0], [0, -1, 0, 0], [0, 0, -1, 0]])
    assert tet.volume == pytest.approx(1 / 6, rel=1e-14)
    assert "4 half-spaces" in repr(tet)
    hull = vf.Convex(points=[[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [0.1, 0.1, 0.1]])
    assert len(hull.halfspaces) == 4 and hull.volume == pytest.approx(1 / 6, rel=1e-14)
    # a redundant half-space is accepted; its wall is simply never reached
    red = vf.Convex([[1, 1, 1, 1], [1, 1, 1, 5], [-1, 0, 0, 0], [0, -1, 0, 0], [0, 0, -1, 0]])
    assert red.volume == pytest.approx(1 / 6, rel=1e-14)
    t = as_container(tet, np.zeros((0, 3)))
    assert t.kind == "convex" and len(t.WP) == 4
    # scaled by 2**k exactly
    s = t.scaled(3)
    assert (
        s.volume == t.volume * 512
        and (s.TV == t.TV * 8).all()
        and np.array_equal(s.WP[:, 3], t.WP[:, 3] * 8)
    )
    assert t.scaled(0) is t
    # a few sites inside: the cells tile the tetrahedron and only its walls bound them
    pts = np.array([[0.1, 0.1, 0.1], [0.5, 0.1, 0.1], [0.1, 0.5, 0.1], [0.1, 0.1, 0.5]])
    d = vf.voronoi3d(pts, tet)
    assert d.volumes.sum() == pytest.approx(1 / 6, rel=1e-12)
    assert (d.volumes > 0).all()
    walls = d.faces.cells[d.faces.cells[:, 1] < 0, 1]
    assert set((-1 - walls).tolist()) <= {0, 1, 2, 3}


@pytest.mark.parametrize(
    ("args", "kwargs", "match"),
    [
        ((), {}, "exactly one"),
        (([[1, 0, 0, 1]] * 4,), {"points": np.eye(3)}, "exactly one"),
        (([[1, 0, 0, 1]] * 3,), {}, "shape"),
        (([[1, 0, 0]] * 4,), {}, "shape"),
        ((["a"],), {}, "real array"),
        (([[1, 0, 0, np.nan]] * 4,), {}, "NaN"),
        (([[0, 0, 0, 1]] * 4,), {}, "zero normal"),
        (([[1, 0, 0, 1], [-1, 0, 0, 1], [0, 1, 0, 1], [0, -1, 0, 1]],), {}, "unbounded"),
        (
            ([[1, 0, 0, -1], [-1, 0, 0, -1], [0, 1, 0, 1], [0, -1, 0, 1], [0, 0, 1, 1]],),
            {},
            "no common point",
        ),
        (
            (
                [
                    [1, 0, 0, 0],
                    [-1, 0, 0, 0],
                    [0, 1, 0, 1],
                    [0, -1, 0, 1],
                    [0, 0, 1, 1],
                    [0, 0, -1, 1],
                ],
            ),
            {},
            "no volume",
        ),
        ((), {"points": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]]}, "span no volume"),
    ],
)
def test_convex_container_errors(args, kwargs, match):
    with pytest.raises(ValueError, match=match):
        vf.Convex(*args, **kwargs)


def test_box_container_errors():
    pts = np.zeros((1, 3))
    with pytest.raises(ValueError, match="numbers"):
        as_container(("a", 0, 0, 1, 1, 1), pts)
    with pytest.raises(ValueError, match="non-finite"):
        as_container((0, 0, 0, np.inf, 1, 1), pts)
    with pytest.raises(ValueError, match="xmin < xmax"):
        as_container((0, 0, 0, 0, 1, 1), pts)
    with pytest.raises(TypeError, match="not a box"):
        as_container("box", pts)
    # the default box of no points, of one point and of flat input
    assert (as_container(None, np.zeros((0, 3))).bounds == [[0, 0, 0], [1, 1, 1]]).all()
    one = as_container(None, np.array([[2.0, 3.0, 4.0]])).bounds
    assert (one[0] < [2, 3, 4]).all() and (one[1] > [2, 3, 4]).all()
    flat = as_container(None, np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])).bounds
    pad = -flat[0]  # every axis padded as the longest one, on both sides
    assert pad.min() == pad.max() > 0 and (flat[1] - [1, 0, 0] == pad).all()
