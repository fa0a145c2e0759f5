"""Tiled Voronoi on dask.distributed: identical to one process, certified, resumable.

One in-process LocalCluster (two single-threaded workers) serves the module; the fault test
starts two worker processes of its own and kills one mid-run.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq
import pytest
import shapely

import voroforge as vf
from reference_scale import differences, single_process, tiled_table
from voroforge import config, scale
from voroforge.scale.tasks import certified_sites, open_sides, radii
from voroforge.scale.tiling import kd_tiling

distributed = pytest.importorskip("distributed")


@pytest.fixture(scope="module")
def client(dask_client):
    return dask_client


def _identical(tmp_path, client, points, boundary, **kw):
    res = scale.voronoi(points, boundary, out=tmp_path / "tiled", client=client, **kw)
    got = tiled_table(tmp_path / "tiled")
    ref = single_process(points, boundary, tmp_path / "ref.parquet")
    return res, got, ref, differences(got, ref)


def test_1e5_uniform_identical_with_1000_site_tiles(tmp_path, client):
    pts = np.random.default_rng(5).random((100_000, 2))
    res, got, ref, diff = _identical(tmp_path, client, pts, (0, 0, 1, 1), tile_size=1000)
    assert res.tiles >= 90 and res.cells == len(pts)
    assert res.uncertified == 0 and res.retried > 0  # halos were exercised
    assert all(not v for v in diff.values()), {k: len(v) for k, v in diff.items()}


CASES = {
    "clustered": lambda r: (
        r.random((20, 2))[r.integers(0, 20, 6000)] + r.normal(0, 0.01, (6000, 2))
    ),
    "grid": lambda r: (
        np.stack(np.meshgrid(np.arange(80), np.arange(80)), -1).reshape(-1, 2).astype(float)
    ),
    "duplicates": lambda r: np.vstack([(p := r.random((3000, 2))), p[:300], p[:10]]),
    "collinear": lambda r: np.column_stack((r.random(1500), np.zeros(1500))),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_catalogue_identical(tmp_path, client, name):
    pts = CASES[name](np.random.default_rng(1))
    res, got, ref, diff = _identical(tmp_path, client, pts, None, tile_size=1000)
    assert res.uncertified == 0
    assert all(not v for v in diff.values()), {k: len(v) for k, v in diff.items()}


@pytest.mark.parametrize("curved", [False, True], ids=["straight", "curved-holes"])
def test_polygon_with_holes(tmp_path, client, curved):
    rng = np.random.default_rng(2)
    pts = rng.random((8000, 2))
    outer = [(0, 0), (1, 0), (1, 1), (0.55, 0.62), (0, 1)]
    holes = [
        [(0.2, 0.2), (0.45, 0.2), (0.45, 0.4), (0.2, 0.4)],
        [(0.7, 0.1), (0.9, 0.1), (0.8, 0.3)],
    ]
    dom = shapely.Polygon(outer, holes)
    if curved:  # about 400 vertices: the engine cuts the domain into local pieces
        dom = dom.difference(shapely.Point(0.3, 0.75).buffer(0.12, quad_segs=48))
        dom = dom.difference(shapely.Point(0.75, 0.55).buffer(0.08, quad_segs=48))
    res, got, ref, diff = _identical(tmp_path, client, pts, dom, tile_size=1000)
    # cut cells too: the domain pieces they are intersected with follow from the domain alone
    assert res.uncertified == 0
    assert all(not v for v in diff.values()), {k: len(v) for k, v in diff.items()}


def test_no_halo_still_identical(tmp_path, client, monkeypatch):
    """With no first halo nearly every border cell fails and is recomputed: same output."""
    monkeypatch.setattr(config, "SCALE_HALO_SPACINGS", 0.0)
    pts = np.random.default_rng(3).random((4000, 2))
    res, got, ref, diff = _identical(tmp_path, client, pts, None, tiles=12)
    assert res.retried > 200 and res.uncertified == 0
    assert all(not v for v in diff.values())


def test_certificate_rejects_cells_a_missing_site_changes():
    """Cells the certificate accepts on a subset are the full diagram's; some it rejects are not."""
    rng = np.random.default_rng(4)
    pts = rng.random((3000, 2))
    box = (0, 0, 1, 1)
    full = vf.voronoi(pts, box)
    region = (0.2, 0.2, 0.6, 0.6)
    inside = (
        (pts[:, 0] >= region[0])
        & (pts[:, 0] <= region[2])
        & (pts[:, 1] >= region[1])
        & (pts[:, 1] <= region[3])
    )
    idx = np.flatnonzero(inside)
    sub = vf.voronoi(pts[idx], box)
    ok = certified_sites(pts[idx], radii(sub, pts[idx]), open_sides(region, pts.min(0), pts.max(0)))
    assert 0 < ok.sum() < len(idx)
    equal = shapely.equals_exact(sub.cells, full.cells[idx], 0.0)
    normal = shapely.normalize(sub.cells)
    same = shapely.equals_exact(normal, shapely.normalize(full.cells[idx]), 0.0)
    assert same[ok].all()
    assert not same[~ok].all()  # the test could fail: rejected cells include wrong ones
    assert equal.dtype == bool


def test_kd_tiling_balances_and_partitions():
    rng = np.random.default_rng(6)
    pts = np.concatenate([rng.random((9000, 2)), rng.normal(0.3, 0.02, (9000, 2))])
    til = kd_tiling(pts, 13)
    t = til.assign(pts)
    counts = np.bincount(t, minlength=13)
    assert len(til) == 13 and counts.min() > 0.7 * counts.mean()
    r = til.rects[t]
    assert ((pts >= r[:, :2]) & (pts <= r[:, 2:])).all()
    assert kd_tiling(pts, 1).assign(pts).max() == 0


def test_bucket_files_hold_each_tiles_loaded_sites(tmp_path):
    """Every tile reads back exactly its own sites and the others' sites in its loaded box."""
    from voroforge.scale.buckets import Store, bucket_chunk, halo_sources
    from voroforge.scale.job import _grown
    from voroforge.scale.sources import open_source

    rng = np.random.default_rng(16)
    pts = np.vstack([rng.random((3000, 2)), rng.normal(0.3, 0.02, (1000, 2))])
    pts[::97] = pts[5]  # duplicates
    names = np.array([f"s{i}" for i in range(len(pts))])
    pq.write_table(
        pa.table({"x": pts[:, 0], "y": pts[:, 1], "name": names}),
        tmp_path / "p.parquet",
        row_group_size=700,
    )
    src = open_source(tmp_path / "p.parquet", tmp_path, 1400)
    til = kd_tiling(pts[::3], 9)
    halos = rng.random(9) * 0.05
    loaded = np.array([_grown(r, h) for r, h in zip(til.rects, halos, strict=True)])
    (tmp_path / "b").mkdir()
    counts = sum(
        bucket_chunk(c, None, til, loaded, halo_sources(til, loaded), str(tmp_path / "b"), i)
        for i, c in enumerate(src.chunks)
    )
    store = Store(str(tmp_path / "b"), len(src.chunks), len(til), attrs=True)
    owner = til.assign(pts)
    for t in range(len(til)):
        (ids, xy), (hids, hxy) = store.loaded(t)
        x0, y0, x1, y1 = loaded[t]
        inside = (pts[:, 0] >= x0) & (pts[:, 0] <= x1) & (pts[:, 1] >= y0) & (pts[:, 1] <= y1)
        assert ids.tolist() == np.flatnonzero(owner == t).tolist()
        assert sorted(hids.tolist()) == np.flatnonzero(inside & (owner != t)).tolist()
        assert np.array_equal(xy, pts[ids]) and np.array_equal(hxy, pts[hids])
        assert counts[:, t].tolist() == [len(ids), len(hids)]
        assert store.owned([t])[t][0].tolist() == ids.tolist()
        assert store.attributes(t).column("name").to_pylist() == names[ids].tolist()


def test_sources_npy_csv_parquet_dask_and_attributes(tmp_path, client):
    rng = np.random.default_rng(7)
    pts = rng.random((2500, 2))
    ref = None
    np.save(tmp_path / "p.npy", pts)
    names = np.array([f"site{i}" for i in range(len(pts))])
    table = pa.table({"x": pts[:, 0], "y": pts[:, 1], "name": names, "w": np.arange(len(pts))})
    pq.write_table(table, tmp_path / "p.parquet", row_group_size=700)
    with open(tmp_path / "p.csv", "w") as fh:
        fh.write("name,x,y,w\n")
        for i, (x, y) in enumerate(pts):
            fh.write(f"site{i},{float(x)!r},{float(y)!r},{i}\n")
    import dask.array as da

    inputs = {
        "array": pts,
        "npy": tmp_path / "p.npy",
        "parquet": tmp_path / "p.parquet",
        "csv": tmp_path / "p.csv",
        "dask": da.from_array(pts, chunks=(1300, 2)),
    }
    for kind, src in inputs.items():
        out = tmp_path / kind
        res = scale.voronoi(src, (0, 0, 1, 1), out=out, client=client, tiles=6, chunk_rows=900)
        got = tiled_table(out)
        if ref is None:
            ref = got
        assert res.cells == len(pts)
        assert got.select(["site_id", "geometry", "area", "neighbors"]).equals(
            ref.select(["site_id", "geometry", "area", "neighbors"])
        ), kind
        if kind in ("parquet", "csv"):
            assert got.column("name").to_pylist() == names.tolist()
            assert got.column("w").to_pylist() == list(range(len(pts)))
    assert not list(tmp_path.glob("array/_points*"))  # the converted input is removed


def test_bad_input(tmp_path, client):
    pts = np.random.default_rng(8).random((500, 2))
    pts[[17, 250]] = np.nan
    with pytest.raises(ValueError, match=r"2 rows: 17, 250"):
        scale.voronoi(pts, None, out=tmp_path / "a", client=client)
    assert not (tmp_path / "a").exists()  # nothing left that a corrected rerun would refuse
    bowtie = shapely.Polygon([(0, 0), (1, 1), (1, 0), (0, 1)])
    with pytest.raises(ValueError, match="invalid"):
        scale.voronoi(pts[:10], bowtie, out=tmp_path / "b", client=client)
    with pytest.raises(ValueError, match="shape"):
        scale.voronoi(np.zeros((5, 3)), None, out=tmp_path / "c", client=client)
    good = np.random.default_rng(9).random((300, 2))
    scale.voronoi(good, None, out=tmp_path / "d", client=client, tiles=2)
    with pytest.raises(ValueError, match="exists"):
        scale.voronoi(good, None, out=tmp_path / "d", client=client)
    res = scale.voronoi(good, None, out=tmp_path / "d", client=client, tiles=3, overwrite=True)
    assert res.tiles == 3
    (tmp_path / "e").mkdir()
    (tmp_path / "e" / "notes.txt").write_text("mine")
    with pytest.raises(ValueError, match="other files"):
        scale.voronoi(good, None, out=tmp_path / "e", client=client, overwrite=True)
    assert (tmp_path / "e" / "notes.txt").exists()


@pytest.mark.parametrize("scale_", [1e-300, 1e-200, 1e160, 1e300])
def test_extreme_scales_identical(tmp_path, client, scale_):
    """Squared radii under/overflow past ~1e+-154: the certificate and halo are scale-free.

    Found by an independent check: at 1e-300 every radius squared to 0, so every cell
    passed the certificate and 290 of 1000 rows were written with wrong neighbours; at
    1e160 the halo's area overflowed and the job raised.
    """
    pts = np.random.default_rng(3).random((300, 2)) * scale_
    res, got, ref, diff = _identical(tmp_path, client, pts, None, tile_size=60)
    assert res.tiles == 5 and res.uncertified == 0
    assert all(not v for v in diff.values()), {k: len(v) for k, v in diff.items()}


@pytest.mark.parametrize(
    "kw",
    [
        {"tiles": 1.5},
        {"tiles": 0},
        {"tiles": True},
        {"tile_size": "100"},
        {"tiles": 4, "tile_size": 100},
        {"chunk_rows": 0},
        {"workers": 0},
    ],
)
def test_bad_counts_refused(tmp_path, client, kw):
    pts = np.random.default_rng(9).random((50, 2))
    with pytest.raises(ValueError, match="tiles|tile_size|chunk_rows|workers"):
        scale.voronoi(pts, None, out=tmp_path / "a", client=client, **kw)
    assert not (tmp_path / "a").exists()
    if "chunk_rows" not in kw:
        with pytest.raises(ValueError, match="tiles|tile_size|workers"):
            scale.lloyd(pts, (0, 0, 1, 1), iterations=1, client=client, **kw)


class _Stop(Exception):
    pass


def test_interrupted_run_resumes_to_the_same_files(tmp_path, client):
    pts = np.random.default_rng(10).random((5000, 2))
    whole = tmp_path / "whole"
    scale.voronoi(pts, None, out=whole, client=client, tiles=10)

    def stop(done, total):
        if done >= 3:
            raise _Stop

    out = tmp_path / "cut"
    with pytest.raises(_Stop):
        scale.voronoi(pts, None, out=out, client=client, tiles=10, progress=stop)
    client.run(lambda: None)  # let in-flight tiles settle
    assert not (out / "_metadata").exists()
    with pytest.raises(ValueError, match="other input"):
        scale.voronoi(pts[::-1], None, out=out, client=client, tiles=10)
    res = scale.voronoi(pts, None, out=out, client=client, tiles=10)
    assert res.resumed >= 3
    for part in sorted(whole.glob("part-*.parquet")):
        a = pq.read_table(part)
        b = pq.read_table(out / part.name)
        assert a.equals(b)


def test_read_bbox_and_spatial_partitions(tmp_path, client):
    pts = np.random.default_rng(11).random((6000, 2))
    out = tmp_path / "cells.parquet"
    res = scale.voronoi(pts, (0, 0, 1, 1), out=out, client=client, tiles=8, crs="EPSG:3857")
    g = scale.read(out)
    assert len(g) == len(pts) and g.crs.to_epsg() == 3857
    assert len(g.attrs["spatial_partitions"]) == res.tiles
    assert "bbox" in g.columns
    window = (0.3, 0.3, 0.45, 0.5)
    sub = scale.read(out, bbox=window)
    b = g.geometry.bounds
    expect = (
        (b.minx <= window[2])
        & (b.maxx >= window[0])
        & (b.miny <= window[3])
        & (b.maxy >= window[1])
    )
    assert sorted(sub.site_id) == sorted(g.site_id[expect])
    assert len(sub.attrs["spatial_partitions"]) < res.tiles
    import geopandas as gpd

    plain = gpd.read_parquet(out)  # generic readers see one GeoParquet dataset
    assert len(plain) == len(pts) and plain.crs.to_epsg() == 3857
    tab = scale.read(out, arrow=True)
    assert tab.num_rows == len(pts)


def test_cli(tmp_path, client, capsys):
    from voroforge.cli import main

    pts = np.random.default_rng(12).random((3000, 2))
    np.save(tmp_path / "p.npy", pts)
    out = tmp_path / "cells.parquet"
    addr = client.scheduler.address
    argv = ["scale", str(tmp_path / "p.npy"), "-o", str(out), "--scheduler", addr]
    assert main([*argv, "--tile-size", "500"]) == 0
    captured = capsys.readouterr()
    assert "uncertified" in captured.err and "0 uncertified" in captured.err
    assert "dashboard" in captured.err and "tiles" in captured.err
    assert tiled_table(out).num_rows == len(pts)
    assert main(argv) == 2
    assert "exists" in capsys.readouterr().err
    assert main([*argv, "--overwrite", "--workers", "2"]) == 2  # --workers needs no scheduler


def test_write_cells_geoparquet(tmp_path):
    import geopandas as gpd

    rng = np.random.default_rng(13)
    pts = np.vstack([rng.random((400, 2)), [[0.5, 0.5], [0.5, 0.5]]])
    dom = shapely.box(0, 0, 1, 1).difference(shapely.box(0.48, -1, 0.52, 2))  # splits cells
    d = vf.voronoi(pts, dom)
    path = tmp_path / "c.parquet"
    from voroforge.io.parquet import write_cells

    write_cells(d, path, crs="EPSG:2056", attributes={"k": np.arange(len(pts))})
    g = gpd.read_parquet(path)
    assert g.crs.to_epsg() == 2056 and (g.site_id.to_numpy() == np.arange(len(pts))).all()
    assert set(g.geom_type) >= {"Polygon", "MultiPolygon"}
    assert shapely.equals(
        g.geometry.values[~g.geometry.is_empty], d.cells[~g.geometry.is_empty]
    ).all()
    assert np.allclose(g.area.to_numpy(), d.areas, rtol=1e-12, atol=1e-15)
    assert g.geometry.is_empty.sum() == (d.areas == 0).sum()
    ip, ix = d.neighbors
    assert all(list(g.neighbors[i]) == ix[ip[i] : ip[i + 1]].tolist() for i in range(len(pts)))
    meta = pq.read_metadata(path).metadata[b"geo"]
    assert b'"covering"' in meta and b'"1.1.0"' in meta


def test_import_voroforge_does_not_import_dask():
    code = "import sys, voroforge; voroforge.voronoi; print(any('dask' in m for m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_killed_worker_still_identical(tmp_path):
    pts = np.random.default_rng(14).random((6000, 2))
    with (
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0"
        ) as cluster,
        distributed.Client(cluster) as c,
    ):
        pids = list(c.run(os.getpid).values())
        killed = []

        def kill(done, total):
            if done >= 2 and not killed:
                os.kill(pids[0], signal.SIGKILL)
                killed.append(pids[0])

        res = scale.voronoi(pts, None, out=tmp_path / "run", client=c, tiles=8, progress=kill)
        assert killed and res.uncertified == 0
    got = tiled_table(tmp_path / "run")
    diff = differences(got, single_process(pts, None, tmp_path / "ref.parquet"))
    assert all(not v for v in diff.values())


def test_cli_voronoi_writes_geoparquet(tmp_path, capsys):
    import geopandas as gpd

    from voroforge.cli import main

    pts = np.random.default_rng(15).random((200, 2))
    np.save(tmp_path / "p.npy", pts)
    out = tmp_path / "cells.parquet"
    assert (
        main(["voronoi", str(tmp_path / "p.npy"), "-o", str(out), "-o", str(tmp_path / "c.svg")])
        == 0
    )
    g = gpd.read_parquet(out)
    assert np.allclose(g.area.to_numpy(), vf.voronoi(pts).areas, rtol=1e-12)
    assert main(["voronoi", str(tmp_path / "p.npy"), "-o", str(out), "--edges"]) == 2
    assert "--edges" in capsys.readouterr().err
