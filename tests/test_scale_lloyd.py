"""Lloyd relaxation in tiles (scale.lloyd): the steps of vf.lloyd, halos exchanged per step."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

import voroforge as vf
from voroforge import scale

distributed = pytest.importorskip("distributed")


@pytest.fixture(scope="module")
def client(dask_client):
    return dask_client


def _close_to_single_process(pts, boundary, client, iterations, **kw):
    got = scale.lloyd(pts, boundary, iterations=iterations, client=client, **kw)
    ref = vf.lloyd(pts, boundary, iterations=iterations)
    size = np.ptp(np.asarray(ref.diagram.boundary.bounds).reshape(2, 2), axis=0).max()
    assert got.points.shape == pts.shape and got.iterations == iterations
    assert np.abs(got.points - ref.points).max() <= 1e-12 * size
    np.testing.assert_allclose(got.energy, ref.energy, rtol=1e-11)
    np.testing.assert_allclose(got.shift, ref.shift, rtol=1e-9, atol=1e-12 * size)
    assert got.uncertified == 0
    return got, ref


def test_uniform_small_tiles_follow_single_process(client):
    pts = np.random.default_rng(3).random((6000, 2))
    before = pts.copy()
    got, _ = _close_to_single_process(pts, (0, 0, 1, 1), client, 6, tile_size=400)
    assert got.tiles >= 12 and got.retried > 0  # halos were exercised
    assert np.array_equal(pts, before)  # the input is not touched
    assert np.all(np.diff(got.energy) <= 1e-15)  # Lloyd never raises the energy


def test_polygon_with_hole_and_clustered_sites(client):
    rng = np.random.default_rng(8)
    centres = rng.random((6, 2)) * 80 + 10
    pts = centres[rng.integers(0, 6, 3000)] + rng.normal(0, 3, (3000, 2))
    domain = shapely.box(0, 0, 100, 100).difference(shapely.Point(50, 50).buffer(15))
    pts[:5] = [50, 50]  # sites inside the hole (outside the domain) and duplicates
    _close_to_single_process(pts, domain, client, 4, tiles=9)


def test_huge_coordinates_are_scaled_exactly(client):
    pts = np.random.default_rng(4).random((800, 2)) * 1e70
    _close_to_single_process(pts, (0, 0, 1e70, 1e70), client, 3, tiles=4)


def test_bad_input(client):
    with pytest.raises(ValueError, match="iterations"):
        scale.lloyd(np.zeros((3, 2)), iterations=-1, client=client)
    bad = np.random.default_rng(0).random((10, 2))
    bad[7, 1] = np.nan
    with pytest.raises(ValueError, match="7"):
        scale.lloyd(bad, (0, 0, 1, 1), client=client)
    with pytest.raises(ValueError, match="no points"):
        scale.lloyd(np.zeros((0, 2)), (0, 0, 1, 1), client=client)
