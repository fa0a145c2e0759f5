"""``voroforge raster``: run in-process through ``cli.main`` and check the files it writes."""

import numpy as np
import pytest
from PIL import Image

import voroforge as vf
from voroforge.cli import main
from voroforge.cli.raster import parse_bounds, parse_size


@pytest.fixture
def points_csv(tmp_path):
    pts = np.random.default_rng(4).random((40, 2))
    src = tmp_path / "pts.csv"
    src.write_text("x,y\n" + "\n".join(f"{x!r},{y!r}" for x, y in pts.tolist()))
    return src, pts


def test_labels_png_colours_map_to_labels(tmp_path, points_csv, capsys):
    src, pts = points_csv
    png, npy = tmp_path / "cells.png", tmp_path / "labels.npy"
    argv = ["raster", str(src), "-o", str(png), "-o", str(npy), "--size", "64x48"]
    assert main([*argv, "--bounds", "0,0,1,1"]) == 0
    assert capsys.readouterr().out.split() == [str(png), str(npy)]
    img = Image.open(png)
    assert img.size == (64, 48) and img.mode == "RGB"
    rgb = np.asarray(img)
    labels = np.load(npy)
    want = vf.rasterize(pts, (48, 64), (0, 0, 1, 1))
    np.testing.assert_array_equal(labels, want.labels)
    # every label is drawn in exactly one colour ...
    codes = rgb.reshape(-1, 3).astype(np.int64) @ np.array([1 << 16, 1 << 8, 1])
    pairs = np.unique(np.stack([labels.ravel(), codes]), axis=1)
    assert len(np.unique(pairs[0])) == pairs.shape[1]
    # ... and horizontally or vertically touching cells in different colours
    for a, b in ((np.s_[:, :-1], np.s_[:, 1:]), (np.s_[:-1, :], np.s_[1:, :])):
        differ = labels[a] != labels[b]
        assert differ.any()
        assert np.all(np.any(rgb[a][differ] != rgb[b][differ], axis=-1))


@pytest.mark.parametrize("field", ["distance", "f2", "edge"])
def test_distance_fields_are_normalised_greyscale(tmp_path, points_csv, field):
    src, pts = points_csv
    png, npy = tmp_path / f"{field}.png", tmp_path / f"{field}.npy"
    argv = ["raster", str(src), "-o", str(png), "-o", str(npy), "--size", "50", "--field", field]
    assert main([*argv, "--method", "jfa"]) == 0
    img = Image.open(png)
    assert img.size == (50, 50) and img.mode == "L"
    grey = np.asarray(img).astype(float)
    values = np.load(npy)
    r = vf.rasterize(pts, (50, 50), method="jfa", f2=field != "distance")
    want = r.distance if field == "distance" else getattr(r, field)
    np.testing.assert_array_equal(values, want)
    assert grey.max() == 255
    np.testing.assert_allclose(grey, np.round(255 * values / values.max()), atol=0.5)


def test_metric_and_method_options(tmp_path, points_csv):
    src, pts = points_csv
    npy = tmp_path / "l.npy"
    base = ["raster", str(src), "-o", str(npy), "--size", "30x20", "--bounds=-0.5,-0.5,1.5,1.5"]
    assert main([*base, "--metric", "chebyshev"]) == 0
    want = vf.rasterize(pts, (20, 30), (-0.5, -0.5, 1.5, 1.5), metric="chebyshev")
    np.testing.assert_array_equal(np.load(npy), want.labels)
    assert main([*base, "--method", "jfa"]) == 0
    want = vf.rasterize(pts, (20, 30), (-0.5, -0.5, 1.5, 1.5), method="jfa")
    np.testing.assert_array_equal(np.load(npy), want.labels)


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (["-o", "out.svg"], ".png or .npy"),
        (["-o", "out.png", "--size", "64x0"], "size"),
        (["-o", "out.png", "--size", "big"], "size"),
        (["-o", "out.png", "--bounds", "0,0,1"], "bounds"),
        (["-o", "out.png", "--bounds", "1,0,0,1"], "xmin < xmax"),
        (["-o", "out.png", "--method", "jfa", "--metric", "manhattan"], "euclidean"),
    ],
)
def test_bad_arguments_exit_2_with_message(tmp_path, points_csv, capsys, extra, message):
    src, _ = points_csv
    extra = [str(tmp_path / e) if e.startswith("out.") else e for e in extra]
    assert main(["raster", str(src), *extra]) == 2
    err = capsys.readouterr().err
    assert "error" in err and message in err
    assert not list(tmp_path.glob("out.*"))


def test_parse_helpers():
    assert parse_size("64") == (64, 64) and parse_size("64x32") == (32, 64)
    assert parse_bounds(None) is None and parse_bounds("-1,0,2.5,3") == (-1.0, 0.0, 2.5, 3.0)


def test_help_lists_raster(capsys):
    assert main(["--help"]) == 0
    assert "raster" in capsys.readouterr().out
    assert main(["raster", "--help"]) == 0
    assert "--method" in capsys.readouterr().out
