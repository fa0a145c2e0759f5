"""checker7 (session s40): the tiled path on MultiPolygon domains, and its input errors.

R1: a site outside a MultiPolygon domain (in the gap between its parts), more than twice the
clipped cell's radius away, changed the last bit of that cell's crossing with the domain's
edge: the engine intersects the cell's convex ring (cut to the domain's bounding box) with
the polygon, and the crossing depends on the ring edge's outer vertex. The certificate now
uses the ring's radius on polygon domains. F8/F9: duplicate CSV columns, non-numeric CSV
columns and extents that overflow float64 are refused before any tile runs, by name, and
leave nothing behind.
"""

from __future__ import annotations

import numpy as np
import pyarrow.parquet as pq
import pytest
import shapely

from reference_scale import differences, single_process, tiled_table
from voroforge import scale
from voroforge.scale.tasks import compute_cells

distributed = pytest.importorskip("distributed")

# checker7 R1: site 0 lies in the gap (x in (1, 1.5)), 0.1976 from site 5 (2R = 0.1823)
R1 = np.array(
    [
        [1.1148739742965028, 0.04423379275840478],
        [0.8857461044927533, 0.1409380453474247],
        [0.8947799938493124, 0.04805149365544792],
        [0.8772400427597202, 0.07001518914446836],
        [1.0051664688553517, 0.13347135071952843],
        [0.9173274087331724, 0.03836005675494669],
        [1.0261747019238858, 0.1111590493508341],
        [0.9490296200538015, 0.17094362584893785],
    ]
)
SQUARE = [(0, 0), (1, 0), (1, 1), (0, 1)]
HOLE = [(0.3, 0.3), (0.7, 0.3), (0.7, 0.7), (0.3, 0.7)]
MULTI = shapely.MultiPolygon(
    [shapely.Polygon(SQUARE, [HOLE]), shapely.Polygon([(1.5, 0), (2, 0), (2, 1), (1.5, 1)])]
)


@pytest.fixture(scope="module")
def client(dask_client):
    return dask_client


def test_certified_cells_on_a_multipolygon_are_the_full_diagrams(tmp_path):
    """R1 without dask: the cells a tile certifies without the gap's site are the full ones.

    The loaded region holds sites 1..7 and reaches past site 5's disc of twice its clipped
    cell's radius, but not site 0; the old certificate kept site 5's cell, whose crossing
    with x = 1 differed from the full diagram's in the last bit.
    """
    ref = single_process(R1, MULTI, tmp_path / "r.pq")
    ref_wkb = dict(
        zip(ref.column("site_id").to_pylist(), ref.column("geometry").to_pylist(), strict=True)
    )
    ids = np.arange(1, 8)
    xy = np.ascontiguousarray(R1[1:])
    loaded = (-1.0, -1.0, 1.1, 2.0)  # site 0 is at x = 1.1149
    table, (bad, _, _) = compute_cells(ids, xy, MULTI, loaded, np.arange(7))
    kept = table.column("site_id").to_pylist()
    assert set(kept) | set(bad.tolist()) == set(ids.tolist())
    assert kept  # the certificate still keeps a cell away from the gap
    for i, wkb in zip(kept, table.column("geometry").to_pylist(), strict=True):
        assert wkb == ref_wkb[i], i


def _identical(tmp_path, client, points, boundary, **kw):
    res = scale.voronoi(points, boundary, out=tmp_path / "tiled", client=client, **kw)
    diff = differences(
        tiled_table(tmp_path / "tiled"), single_process(points, boundary, tmp_path / "r.pq")
    )
    return res, {k: v for k, v in diff.items() if v}


@pytest.mark.parametrize("tile_size", [1, 3])
def test_r1_tiled_identical(tmp_path, client, tile_size):
    res, diff = _identical(tmp_path, client, R1, MULTI, tile_size=tile_size)
    assert res.uncertified == 0 and not diff, diff


def test_multipolygon_holes_and_gap_sites_identical(tmp_path, client):
    """checker7's s1_scale multipoly_hole, smaller: sites in the hole and the gap."""
    pts = np.random.default_rng(7).random((400, 2)) * [2, 1]
    res, diff = _identical(tmp_path, client, pts, MULTI, tile_size=25)
    assert res.uncertified == 0 and not diff, diff


def _cli(tmp_path, client, csv_text, name):
    from voroforge.cli import main

    src = tmp_path / f"{name}.csv"
    src.write_text(csv_text)
    out = tmp_path / f"{name}.parquet"
    argv = ["scale", str(src), "-o", str(out), "--scheduler", client.scheduler.address]
    return main(argv), out, src


def test_cli_duplicate_column_refused_and_nothing_left(tmp_path, client, capsys):
    rc, out, src = _cli(tmp_path, client, "x,y,x\n0,0,1\n1,1,2\n0.5,0.2,3\n", "dupcol")
    err = capsys.readouterr().err
    assert rc == 2 and "voroforge: error:" in err and "'x' appears more than once" in err
    assert "Traceback" not in err and not out.exists()
    src.write_text("x,y,z\n0,0,1\n1,1,2\n0.5,0.2,3\n")  # corrected: the rerun is not refused
    from voroforge.cli import main

    argv = ["scale", str(src), "-o", str(out), "--scheduler", client.scheduler.address]
    assert main(argv) == 0
    assert pq.read_table(out).num_rows == 3


def test_cli_text_column_names_the_users_csv(tmp_path, client, capsys):
    rc, out, src = _cli(tmp_path, client, "x,y\n0,0\n1,abc\n", "text")
    err = capsys.readouterr().err
    assert rc == 2 and f"{src}: column 'y' is not numeric" in err
    assert "_points.tmp" not in err and not out.exists()


@pytest.mark.parametrize("boundary", [None, (-1.5e308, -1, 1.5e308, 1)])
def test_overflowing_extent_refused_before_any_tile(tmp_path, client, boundary):
    pts = np.array([[1e308, 0.0], [-1e308, 0.0], [0.0, 0.5]])
    with pytest.raises(ValueError, match="overflows float64"):
        scale.voronoi(pts, boundary, out=tmp_path / "huge", client=client)
    assert not (tmp_path / "huge").exists()


def test_huge_but_finite_extent_still_runs(tmp_path, client):
    pts = np.random.default_rng(3).random((60, 2)) * 1e307
    res, diff = _identical(tmp_path, client, pts, None, tile_size=20)
    assert res.uncertified == 0 and not diff, diff
