"""scale.lloyd's recomputed cells see every site their box reaches (checker19 F3).

A cell whose certificate failed was recomputed in its grown box from the sites of the tiles
around the tile's first halo only, and certified against the box although sites of farther
tiles inside it were never loaded: wrong centroids with ``uncertified == 0``. The reference
is vf.lloyd (itself checked against a brute-force half-plane step below).
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely

import voroforge as vf
from voroforge import scale
from voroforge.scale.lloyd import lloyd_tile
from voroforge.scale.tasks import Piece
from voroforge.scale.tiling import kd_tiling

distributed = pytest.importorskip("distributed")

BOX = (0.0, 0.0, 1.0, 1.0)
# checker19 f3.py: 6 sites, 4 tiles, one step moved site 2 by 0.05 too far
F3 = np.array(
    [
        [0.623587806772324, 0.48469158663361445],
        [0.3728182167091746, 0.5203642467277935],
        [0.6103469641155855, 0.9894907288193786],
        [0.39716416770199603, 0.6496706489773141],
        [0.5947142708199009, 0.1970786851114794],
        [0.2852058174646287, 0.022613142713757584],
    ]
)


@pytest.fixture(scope="module")
def client(dask_client):
    return dask_client


def _brute_step(p):
    """One Lloyd step from half-plane intersections (shapely), independent of voroforge."""
    new = p.copy()
    for i in range(len(p)):
        cell = shapely.box(*BOX)
        for j in range(len(p)):
            if j != i:
                m = (p[i] + p[j]) / 2
                n = (p[j] - p[i]) / np.hypot(*(p[j] - p[i]))
                t = np.array([-n[1], n[0]])
                half = shapely.Polygon([m - 9 * t, m + 9 * t, m + 9 * t - 9 * n, m - 9 * t - 9 * n])
                cell = cell.intersection(half)
        new[i] = np.asarray(cell.centroid.coords[0])
    return new


def _same_as_vf(pts, client, iterations, tiles):
    got = scale.lloyd(pts, BOX, iterations=iterations, tiles=tiles, client=client)
    ref = vf.lloyd(pts, BOX, iterations=iterations)
    err = np.abs(got.points - ref.points).max(axis=1)
    assert err.max() <= 1e-12, (tiles, np.flatnonzero(err > 1e-12), err.max())
    np.testing.assert_allclose(got.energy, ref.energy, rtol=1e-11)
    assert got.uncertified == 0
    return got


@pytest.mark.parametrize("tiles", [4, 8, 16])
def test_checker_minimal_case(client, tiles):
    np.testing.assert_allclose(vf.lloyd(F3, BOX, iterations=1).points, _brute_step(F3), atol=1e-14)
    _same_as_vf(F3, client, 1, tiles)


@pytest.mark.parametrize("tiles", [4, 8, 16])
def test_cluster_with_scattered_sites(client, tiles):
    rng = np.random.default_rng(1)
    pts = np.vstack([0.3 + rng.random((700, 2)) * 0.02, rng.random((25, 2))])
    got = _same_as_vf(pts, client, 2, tiles)
    assert got.retried > 0  # the big scattered cells were recomputed


def test_cluster_straddling_a_tile_corner(client):
    rng = np.random.default_rng(2)
    # a symmetric scatter puts the kd cuts near 0.5: the cluster sits on the tiles' corner
    base = rng.random((60, 2))
    base = np.vstack([base, 1 - base])
    pts = np.vstack([base, 0.5 + (rng.random((500, 2)) - 0.5) * 0.01])
    _same_as_vf(pts, client, 2, 8)


def test_sites_exactly_on_tile_edges(client):
    g = (np.arange(8) + 0.5) / 8
    grid = np.column_stack([np.repeat(g, 8), np.tile(g, 8)])
    rng = np.random.default_rng(3)
    # kd cuts are site coordinates: on a lattice whole rows lie on the tile edges
    pts = np.vstack([grid, 0.7 + rng.random((300, 2)) * 0.01])
    _same_as_vf(pts, client, 2, 8)


def _spec(rect, halo, lo, hi, held):
    from voroforge.engine.domain import make_domain
    from voroforge.engine.lloyd import cell_domain

    return {
        "loaded": (rect[0] - halo, rect[1] - halo, rect[2] + halo, rect[3] + halo),
        "lo": list(lo),
        "hi": list(hi),
        "domain": cell_domain(make_domain(BOX, None)),
        "max_rounds": 4,
        "held": held,
    }


def test_tile_escalates_what_it_never_loaded():
    """In process: a tile holding only itself keeps no cell whose box reaches other tiles."""
    rng = np.random.default_rng(4)
    pts = np.vstack([0.3 + rng.random((300, 2)) * 0.02, rng.random((20, 2))])
    tiling = kd_tiling(pts, 16)
    owner = tiling.assign(pts)
    ids = np.arange(len(pts))
    ref = vf.lloyd(pts, BOX, iterations=1).points
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    total = 0
    for t in range(len(tiling)):
        own = Piece(ids[owner == t], pts[owner == t])
        summary, piece, esc = lloyd_tile(t, _spec(tiling.rects[t], 0.0, lo, hi, [t]), tiling, own)
        assert np.array_equal(np.sort(np.concatenate([piece.ids, esc[0]])), own.ids)
        assert summary["escalated"] == len(esc[0])
        # every cell it kept is the single-process one
        np.testing.assert_allclose(piece.xy, ref[piece.ids], atol=1e-12, rtol=0)
        total += len(esc[0])
    assert total > 0  # the scattered sites' cells reach past their tiles


def test_empty_tile():
    """In process: a tile that owns no site returns an empty piece, not an error."""
    pts = np.random.default_rng(5).random((50, 2))
    tiling = kd_tiling(pts, 4)
    owner = tiling.assign(pts)
    empty = Piece(np.zeros(0, np.int64), np.zeros((0, 2)))
    others = [Piece(np.flatnonzero(owner == u), pts[owner == u]) for u in range(1, len(tiling))]
    spec = _spec(tiling.rects[0], 0.1, pts.min(axis=0), pts.max(axis=0), list(range(len(tiling))))
    summary, piece, esc = lloyd_tile(0, spec, tiling, empty, *others)
    assert len(piece.ids) == 0 and len(esc[0]) == 0 and summary["energy"] == 0.0
