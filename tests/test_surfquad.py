"""Surface Voronoi on coarse meshes: many sites per triangle (checker21 F8).

A triangle holding more than ``SURFACE_LOCAL_CUT`` candidate sites cuts each piece by its own
site's neighbours (``kernels.surfcut.cut_local``) instead of by every candidate: the cells
must be the ones of the definition (2D Voronoi clipped to a flat square, a brute-force clip
of every piece by every site, the same surface finely triangulated), and the time linear.
"""

from __future__ import annotations

import time

import numpy as np
import pytest
import trimesh
from scipy.spatial import Voronoi

from reference_surface import clip_polygon, polygon_area
from voroforge import surface
from voroforge.config import SURFACE_LOCAL_CUT

SQUARE = trimesh.Trimesh(
    [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2], [0, 2, 3]], process=False
)


def _fine(m: trimesh.Trimesh, times: int) -> trimesh.Trimesh:
    for _ in range(times):
        m = m.subdivide()
    return m


def _square_reference(p: np.ndarray):
    """Cell areas and neighbour pairs of 2D points in the unit square (mirrored Voronoi)."""
    n = len(p)
    mirrors = [p]
    for axis in range(2):
        for side in (0.0, 1.0):
            q = p.copy()
            q[:, axis] = 2 * side - q[:, axis]
            mirrors.append(q)
    vor = Voronoi(np.concatenate(mirrors))
    areas = np.zeros(n)
    for i in range(n):
        ring = vor.vertices[vor.regions[vor.point_region[i]]]
        x, y = ring[:, 0], ring[:, 1]
        areas[i] = 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
    pairs = set()
    for (a, b), rv in zip(vor.ridge_points, vor.ridge_vertices, strict=True):
        if a < n and b < n and -1 not in rv:
            if np.linalg.norm(vor.vertices[rv[0]] - vor.vertices[rv[1]]) > 1e-9:
                pairs.add((min(a, b), max(a, b)))
    return areas, pairs


def _pairs(vd) -> set:
    indptr, idx = vd.neighbors
    i = np.repeat(np.arange(len(vd.sites)), np.diff(indptr))
    return {(int(a), int(b)) for a, b in zip(i, idx, strict=True) if a < b}


@pytest.mark.parametrize(("scale", "offset"), [(1.0, 0.0), (1e-6, 0.0), (1e6, 0.0), (1.0, 1e6)])
def test_flat_square_is_the_clipped_2d_voronoi(scale, offset):
    n = 600
    assert n / 2 > 4 * SURFACE_LOCAL_CUT  # the triangles take the neighbour path
    p = np.random.default_rng(1).random((n, 2))
    S = surface.mesh(trimesh.Trimesh(SQUARE.vertices * scale + offset, SQUARE.faces, process=False))
    sites = np.column_stack([p, np.zeros(n)]) * scale + offset
    vd = surface.voronoi(S, sites)
    ref, pairs = _square_reference((sites[:, :2] - offset) / scale)  # the rounded sites
    mean = 1.0 / n
    np.testing.assert_allclose(vd.areas / scale**2, ref, rtol=0, atol=1e-9 * mean)
    assert _pairs(vd) == pairs
    assert vd.sample_check(1500) == 1.0


def _brute_pieces(V, F, sites) -> dict:
    """(cell, triangle) -> area: each triangle clipped to each site's side of every other
    site's bisector (nearest sites first, stopping once nothing is left)."""
    out = {}
    for t, f in enumerate(F):
        tri = [np.asarray(V[w], float) for w in f]
        for i, s in enumerate(sites):
            order = np.argsort(np.linalg.norm(sites - s, axis=1))
            poly = tri
            for j in order:
                if j == i:
                    continue
                g, mid = sites[j] - s, 0.5 * (sites[j] + s)
                poly = clip_polygon(poly, lambda x, g=g, mid=mid: float(g @ (x - mid)))
                if len(poly) < 3:
                    break
            a = polygon_area(poly) if len(poly) >= 3 else 0.0
            if a > 0:
                out[(i, t)] = a
    return out


def test_tetrahedron_pieces_match_brute_force():
    T = trimesh.Trimesh(
        [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]],
        [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
        process=False,
    )
    S = surface.mesh(T)
    sites = S.sample(280, seed=4)
    vd = surface.voronoi(S, sites)
    ref = _brute_pieces(S.vertices, S.faces, sites)
    pieces = zip(vd.piece_cell, vd.piece_tri, vd.piece_area, strict=True)
    got = {(int(c), int(t)): a for c, t, a in pieces}
    tiny = 1e-12 * S.area
    assert {k for k, a in got.items() if a > tiny} == {k for k, a in ref.items() if a > tiny}
    worst = max(abs(got.get(k, 0.0) - ref.get(k, 0.0)) for k in set(got) | set(ref))
    assert worst < 1e-12 * S.area
    assert vd.sample_check(1500) == 1.0


def _wedge(deg: float) -> trimesh.Trimesh:
    a = np.radians(deg)
    V = [[0, 0, 0], [0, 1, 0], [1, 0.5, 0], [np.cos(a), 0.5, np.sin(a)]]
    return trimesh.Trimesh(V, [[0, 2, 1], [0, 1, 3]], process=False)


CASES = {
    "cube on the surface": (trimesh.creation.box(), "surface", 700),
    "cube, sites in space": (trimesh.creation.box(), "space", 400),
    "icosahedron": (trimesh.creation.icosahedron(), "surface", 1500),
    "wedge 0.001 deg": (_wedge(1e-3), "surface", 500),
    "wedge 90 deg": (_wedge(90.0), "surface", 500),
    "wedge 179 deg": (_wedge(179.0), "surface", 500),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_coarse_mesh_cells_equal_the_finely_split_meshs(name):
    """The same surface split into 64 times more triangles (the per-candidate path) gives
    the same cells: areas, neighbours, ownership."""
    m, where, n = CASES[name]
    coarse = surface.mesh(m)
    fine = surface.mesh(_fine(m, 3))
    if where == "surface":
        sites = coarse.sample(n, seed=2)
    else:
        sites = np.random.default_rng(2).random((n, 3)) * 1.6 - 0.8
    a = surface.voronoi(coarse, sites)
    b = surface.voronoi(fine, sites)
    mean = coarse.area / n
    np.testing.assert_allclose(a.areas, b.areas, rtol=0, atol=1e-10 * mean)
    assert abs(a.areas.sum() - coarse.area) < 1e-12 * coarse.area
    assert _pairs(a) == _pairs(b)
    assert a.sample_check(1500) == 1.0


def test_many_sites_on_two_triangles_take_linear_time():
    """20,000 sites on a 2-triangle square: about 0.1 s CPU (it was 16 s: every piece was
    cut by every site of its triangle); 4x the sites stays within ~6x the time."""
    S = surface.mesh(SQUARE)
    rng = np.random.default_rng(5)
    surface.voronoi(S, 50, seed=1)  # compiled
    times = []
    for n in (5000, 20000):
        sites = rng.random((n, 3)) * [1, 1, 0]
        best = np.inf
        for _ in range(2):
            t = time.process_time()
            vd = surface.voronoi(S, sites)
            best = min(best, time.process_time() - t)
        times.append(best)
        assert abs(vd.areas.sum() - 1.0) < 1e-12
        assert (vd.areas > 0).all()
    assert vd.sample_check(2000) == 1.0
    assert times[1] < 3.0
    assert times[1] < 6.0 * times[0] + 0.05


# --- unroll: openings keep their 3D edge lengths (checker21 F5) ---------------------------


def _ring_edges(ring) -> np.ndarray:
    r = np.asarray(ring, float)
    return np.linalg.norm(np.roll(r, -1, axis=0) - r, axis=1)


@pytest.fixture(scope="module")
def bent_panels():
    """Unplanarized panels with openings on three curved surfaces (4% .. 30% off plane)."""
    out = {}
    for name, S in [
        ("dome", surface.sphere_patch(5.0, polar=(0, 1.2))),
        ("cylinder", surface.cylinder(1, 2)),
        ("torus", surface.torus(1, 0.4)),
    ]:
        vd = surface.voronoi(S, 50, relax=10, seed=1)
        out[name] = vd.panels().openings(0.5)
    return out


@pytest.mark.parametrize("name", ["dome", "cylinder", "torus"])
def test_unrolled_openings_keep_their_3d_edge_lengths(bent_panels, name):
    P = bent_panels[name]
    assert P.planarity().relative.max() > 0.03  # bent: the best-fit plane alone would not do
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sheets = P.unroll()
    for k, part in enumerate(sheets.parts):
        rings3 = P.polygon(k)
        assert len(part.rings) == len(rings3) == 2
        for r3, r2 in zip(rings3, part.rings, strict=True):
            np.testing.assert_allclose(_ring_edges(r2), _ring_edges(r3), rtol=0, atol=1e-12)


def test_planar_panels_unroll_rigidly_with_their_openings():
    """Planarized panels: every distance between two vertices of a part (outline or
    opening) is its 3D distance, and each opening lies inside its outline."""
    S = surface.sphere_patch(5.0, polar=(0, 1.0))
    P = surface.voronoi(S, 40, relax=10, seed=2).panels().planarize(1e-8).openings(0.4)
    flatness = P.planarity().absolute.max()
    assert flatness < 1e-7
    sheets = P.unroll()
    for k, part in enumerate(sheets.parts):
        p3 = np.concatenate(P.polygon(k))
        p2 = np.concatenate(part.rings)
        d3 = np.linalg.norm(p3[:, None] - p3[None], axis=2)
        d2 = np.linalg.norm(p2[:, None] - p2[None], axis=2)
        assert np.abs(d3 - d2).max() < 8 * flatness + 1e-12
        assert part.polygon.is_valid
