"""Issue 12: integer points exactly on one sphere, without the centre (one Delaunay polytope).

All n sites are on one empty sphere: every cell is a cone from the one Voronoi vertex at
the centre, owned by all n sites. Above ~1,019 points that vertex's owners overflowed the
cells' owner table ("more than 98304 vertices"), and from 64 the cells were built again
with wide tables (1,008 points: 49 s). Now such a cell stops (``SLOW``), takes its
candidate list (the sites of the polytope's 2-faces at it) and names the centre from the
whole polytope. Checked here against independent references: samples in the nearest
site's cell, volumes tiling the box, voro++'s volumes, one centre vertex in every cell,
and the cells of the full search (no budget, wide owner tables) where that still runs.
"""

from __future__ import annotations

import numpy as np
import pytest

import voroforge as vf
from reference3d import voropp_cells
from test_issue12_exact3d import _check_cells
from test_issue12_sphere_global import _same
from voroforge.engine import lists3d
from voroforge.kernels.candidates3d import candidate_lists


def _int_sphere(r2):
    """Every integer point with x^2 + y^2 + z^2 = r2."""
    r = int(np.sqrt(r2))
    x, y = np.meshgrid(np.arange(-r, r + 1), np.arange(-r, r + 1), indexing="ij")
    z2 = r2 - x * x - y * y
    ok = z2 >= 0
    z = np.sqrt(np.where(ok, z2, 0)).round().astype(np.int64)
    ok &= z * z == z2
    p = np.column_stack([x[ok], y[ok], z[ok]])
    return np.unique(np.vstack([p, p * [1, 1, -1]]), axis=0).astype(np.float64)


def _case(r2, half=False, scale=1.0, off=0.0):
    """The points of ``r2``'s sphere (``half``: x >= 0, the box's wall x = 0 through the
    centre), scaled and moved exactly, in a box 1.5 radii about the centre."""
    p = _int_sphere(r2)
    R = 1.5 * np.sqrt(r2)
    box = np.array([-R, -R, -R, R, R, R])
    if half:
        p = p[p[:, 0] >= 0]
        box[0] = 0.0
    off = np.zeros(3) + off
    return p * scale + off, tuple(box * scale + np.r_[off, off]), off


def _centre_in_every_cell(d, c):
    V = np.asarray(d.vertices)
    at = np.flatnonzero((V == c).all(1))
    assert len(at) == 1  # one vertex, bit for bit
    for i in range(len(d)):
        assert (np.asarray(d.cell(i).vertices) == c).all(1).any(), i


@pytest.mark.parametrize(
    ("r2", "half", "scale", "off"),
    [
        (5045, False, 1.0, 0.0),  # 1,248 points: "more than 98304 vertices" before
        (5045, True, 1.0, 0.0),  # 632, the centre on a wall
        (693, False, 2.0**-9, (1000.5, -3.25, 7.0)),  # 288, scaled and moved (exact)
    ],
)
def test_one_sphere_cells_against_references(r2, half, scale, off):
    p, box, c = _case(r2, half, scale, np.asarray(off))
    d = vf.voronoi3d(p, box)
    _check_cells(d, box)
    _centre_in_every_cell(d, c)
    vol, nbs = voropp_cells(p, box)  # (voro++ prints 6 digits)
    np.testing.assert_allclose(d.volumes, vol, rtol=1e-5)
    # voro++ keeps faces of zero area (a diagonal of the hull's cocircular faces) that
    # its rounding leaves: ours are among its
    indptr, nbr = d.neighbors
    for i in range(len(p)):
        ours = {int(j) for j in nbr[indptr[i] : indptr[i + 1]] if j >= 0}
        assert ours <= set(nbs[i]), i


@pytest.mark.parametrize(
    ("r2", "half", "scale", "off"),
    [(65, False, 1.0, 0.0), (185, True, 1.0, 0.0), (230, False, 2.0**-9, 5.0)],
)
def test_one_sphere_cells_are_the_full_search_cells(monkeypatch, r2, half, scale, off):
    # 96 to 240 points: the full search (no budget: every owner found, wide tables) runs
    p, box, _ = _case(r2, half, scale, off)
    monkeypatch.setattr(lists3d.Lists, "budget", lambda self: self.g)
    full = vf.voronoi3d(p, box)
    monkeypatch.undo()
    _same(full, vf.voronoi3d(p, box))
    monkeypatch.setattr(lists3d, "FORCE", True)
    _same(full, vf.voronoi3d(p, box))


def test_big_polytope_lists_are_its_faces_sites():
    # 1,248 points of one sphere: one polytope; a site lists the sites of the hull's
    # faces at it (each face: the points on one plane), never all of them
    p = _int_sphere(5045)
    t = vf.delaunay3d(p)
    start, sites, listed, (bigof, bstart, bsite), _ = candidate_lists(
        p, t.simplices, t.neighbors, 64
    )
    assert listed.all() and (bigof == 0).all()
    assert bsite.tolist() == list(range(len(p)))
    from scipy.spatial import ConvexHull

    hull = ConvexHull(p)
    planes = np.unique(np.round(hull.equations, 9), axis=0)
    for i in range(0, len(p), 97):
        want = set()
        for e in planes:
            on = np.flatnonzero(np.abs(p @ e[:3] + e[3]) < 1e-6 * np.sqrt(5045))
            if i in on:
                want |= set(on.tolist())
        want.discard(i)
        assert set(sites[start[i] : start[i + 1]].tolist()) == want, i


# a cell of a long candidate list is read off its Delaunay star (kernels.star3d) where the
# container does not cut it: the centre of points on a sphere had n faces, cut one by one
_STAR = ["uniform", "uniform_default", "cubic_grid", "bcc", "fcc", "sphere_rounded_centre"]


@pytest.mark.parametrize("name", _STAR)
def test_star_cells_are_the_full_search_cells(monkeypatch, name):
    from test_issue12_sphere_global import _CASES

    p, box = _CASES[name]
    full = vf.voronoi3d(p, box)
    monkeypatch.setattr(lists3d, "FORCE", True)
    monkeypatch.setattr(lists3d, "STAR_LEAST", 0)  # every interior cell from its star
    _same(full, vf.voronoi3d(p, box))


def test_star_cells_are_built(monkeypatch):
    # the comparison above is not empty: stars with every tetrahedron turned inside out
    # give cells of negative volume
    from test_issue12_sphere_global import _CASES

    real = lists3d.Lists.get

    def flipped(self):
        made = real(self)
        if made and not getattr(self, "flipped", False):
            big, st = made[5]
            st = (st[0], st[1], st[2][:, [1, 0, 2, 3]].copy(), st[3][:, [1, 0, 2, 3]].copy())
            self.made = (*made[:5], (big, st + made[5][1][4:]), made[6])
            self.flipped = True
        return self.made

    monkeypatch.setattr(lists3d.Lists, "get", flipped)
    monkeypatch.setattr(lists3d, "FORCE", True)
    monkeypatch.setattr(lists3d, "STAR_LEAST", 0)
    p, box = _CASES["uniform"]
    assert (vf.voronoi3d(p, box).volumes < 0).sum() > 100


def test_sphere_centre_cell_from_its_star(monkeypatch):
    # 1,500 rounded sphere points and the centre, past a lowered budget: the centre's cell
    # (1,500 faces) from its star, the others cut; each sample in its nearest site's cell,
    # volumes tile the box and are voro++'s
    from catalogue3d import _sphere

    monkeypatch.setattr(lists3d, "SITE_BUDGET", 256.0)
    n = 1500
    S = np.r_[_sphere(n), [[0.0, 0.0, 0.0]]]
    box = (-2.0, -2.0, -2.0, 2.0, 2.0, 2.0)
    d = vf.voronoi3d(S, box)
    _check_cells(d, box)
    indptr, nbr = d.neighbors
    assert set(nbr[indptr[n] : indptr[n + 1]].tolist()) == set(range(n))
    vol, _ = voropp_cells(S, box)
    np.testing.assert_allclose(d.volumes, vol, rtol=1e-5)
