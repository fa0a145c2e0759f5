"""Weighted Voronoi stippling (design/stipple, voroforge stipple)."""

import xml.etree.ElementTree as ET

import numpy as np
import pytest
from scipy.spatial import cKDTree

from voroforge.cli import main
from voroforge.design.stipple import demo_image, grey_image, stipple, stipple_svg
from voroforge.io.plotter import travel

SVG = "{http://www.w3.org/2000/svg}"


def test_dots_follow_the_darkness():
    img = np.full((40, 40), 0.9)
    img[:, :20] = 0.0  # left half black: density 1 against 0.1
    pts = stipple(img, 400, width=40.0, iterations=6, seed=1)
    left = (pts[:, 0] < 20).mean()
    assert left == pytest.approx(1 / 1.1, abs=0.04)
    assert (pts >= 0).all() and (pts[:, 0] <= 40).all() and (pts[:, 1] <= 40).all()


def test_relaxation_spaces_the_dots_evenly():
    img = np.full((32, 32), 0.5)
    start = stipple(img, 300, width=32.0, iterations=0, seed=2)
    relaxed = stipple(img, 300, width=32.0, iterations=10, seed=2)
    d0 = cKDTree(start).query(start, k=2)[0][:, 1]
    d1 = cKDTree(relaxed).query(relaxed, k=2)[0][:, 1]
    assert d1.min() > 2.5 * d0.min()
    assert d1.std() / d1.mean() < 0.5 * d0.std() / d0.mean()  # blue noise, not white noise


def test_svg_has_every_dot_in_pen_up_order(tmp_path):
    pts = stipple(demo_image(48), 250, width=50.0, iterations=3)
    path = stipple_svg(pts, tmp_path / "s.svg", width=50, height=50, dot=0.3)
    root = ET.parse(path).getroot()
    circles = list(root.iter(SVG + "circle"))
    assert len(circles) == 250 and circles[0].get("r") == "0.3"
    xy = np.array([[float(c.get("cx")), -float(c.get("cy"))] for c in circles])
    d, j = cKDTree(pts).query(xy)
    assert d.max() < 1e-4 and sorted(j.tolist()) == list(range(250))  # every dot, once
    ordered = travel([p[None] for p in xy], start=(0, 50))[0]
    assert ordered < 0.25 * travel([p[None] for p in pts], start=(0, 50))[0]


def test_bad_input():
    with pytest.raises(ValueError, match="white everywhere"):
        stipple(np.ones((8, 8)), 10)
    with pytest.raises(ValueError, match="grey values"):
        grey_image(np.full((4, 4), 2.0))
    with pytest.raises(ValueError, match="at least 1"):
        stipple(demo_image(16), 0)
    with pytest.raises(ValueError, match="no such image"):
        grey_image("missing.png")
    # sizes refused up front (checker5 F7: 1e8 dots, or 100 dots x 1e7 steps, ran on)
    with pytest.raises(ValueError, match="at most 1,000,000 points"):
        stipple(demo_image(16), 100_000_000)
    with pytest.raises(ValueError, match="too much work"):
        stipple(demo_image(16), 100, iterations=10_000_000)


def test_cli_stipples_an_image_file(tmp_path, capsys):
    from PIL import Image

    Image.fromarray((demo_image(40) * 255).astype(np.uint8)).save(tmp_path / "g.png")
    out = tmp_path / "g.svg"
    rc = main(
        [
            "stipple",
            str(tmp_path / "g.png"),
            "-o",
            str(out),
            "--points",
            "150",
            "--iterations",
            "2",
            "--width",
            "80",
        ]
    )
    assert rc == 0 and out.exists()
    assert len(list(ET.parse(out).getroot().iter(SVG + "circle"))) == 150
    assert main(["stipple", "@nope", "-o", str(out)]) == 2
    assert main(["stipple", "@sphere", "-o", str(tmp_path / "x.png")]) == 2
    capsys.readouterr()


def test_design_seeds_follow_an_image(tmp_path):
    from PIL import Image

    from voroforge.design.compute import compute
    from voroforge.design.designfile import load

    img = np.full((20, 40), 230, dtype=np.uint8)
    img[:, :20] = 0  # the left half black
    Image.fromarray(img).save(tmp_path / "half.png")
    design, base = load(
        {
            "boundary": {"shape": "circle", "radius": 50},
            "seeds": {"method": "image", "file": str(tmp_path / "half.png"), "count": 300},
        }
    )
    r = compute(design, base)
    assert len(r.sites) == 300
    assert (r.sites[:, 0] < 0).mean() > 0.85  # darkness 1 against 0.1
    assert np.hypot(*r.sites.T).max() <= 50


def test_sixteen_bit_and_float_images_are_read_at_their_depth(tmp_path):
    # checker25 F9: Pillow's convert("L") clipped a 16-bit grey PNG above 255/65535 to white
    # (98% white on a black-to-white gradient), and float images read black everywhere
    from PIL import Image

    x = np.linspace(0, 1, 64)[None, :].repeat(8, 0)
    Image.fromarray(np.round(x * 255).astype(np.uint8)).save(tmp_path / "g8.png")
    Image.fromarray(np.round(x * 65535).astype(np.uint16)).save(tmp_path / "g16.png")
    Image.fromarray(x.astype(np.float32)).save(tmp_path / "gf.tif")
    g8, g16, gf = (grey_image(tmp_path / f) for f in ("g8.png", "g16.png", "gf.tif"))
    assert np.abs(g16 - x).max() <= 0.5 / 65535 + 1e-15
    assert np.abs(g8 - x).max() <= 0.5 / 255 + 1e-15
    assert np.abs(gf - x).max() <= 1e-7
    bad = x.astype(np.float32)
    bad[0, 0] = np.nan
    Image.fromarray(bad).save(tmp_path / "nan.tif")
    with pytest.raises(ValueError, match="NaN"):
        grey_image(tmp_path / "nan.tif")
    Image.fromarray((x * 255).astype(np.float32)).save(tmp_path / "big.tif")
    with pytest.raises(ValueError, match=r"must lie in \[0, 1\]"):
        grey_image(tmp_path / "big.tif")
