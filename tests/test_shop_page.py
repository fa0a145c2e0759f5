"""output.page = "source": the SVG written lies exactly over the designer's drawing."""

import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from voroforge.design.build import build
from voroforge.design.designfile import DesignError

SVG = "{http://www.w3.org/2000/svg}"


@pytest.mark.parametrize("width", ["300mm", "30cm", None])
def test_source_page_keeps_size_and_origin(tmp_path, width):
    w = (
        f' width="{width}" height="{width.replace("300", "200").replace("30c", "20c")}"'
        if width
        else ""
    )
    (tmp_path / "src.svg").write_text(
        f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="-20 -10 300 200"{w}>'
        '<rect id="panel" x="10" y="20" width="100" height="60"/></svg>'
    )
    design = {
        "boundary": {"shape": "file", "file": str(tmp_path / "src.svg")},
        "seeds": {"method": "random", "count": 4},
        "output": {"formats": ["svg"], "layers": {"CUT": "boundary"}, "page": "source"},
    }
    (svg,) = build(design, tmp_path / "o")
    root = ET.parse(svg).getroot()
    vx, vy, vw, vh = (float(v) for v in root.get("viewBox").split())
    scale = {"300mm": 1.0, "30cm": 1.0, None: 1.0}[width]
    assert (vw, vh) == pytest.approx((300 * scale, 200 * scale))
    (path,) = [p for p in root.iter(SVG + "path")]
    pts = np.array(
        [[float(a), float(b)] for a, b in re.findall(r"(-?[\d.]+),(-?[\d.]+)", path.get("d"))]
    )
    rel = pts - (vx, vy)  # position on the page, from its top-left corner
    corners = {(30.0, 30.0), (130.0, 30.0), (130.0, 90.0), (30.0, 90.0)}  # rect - viewBox origin
    assert {tuple(np.round(r, 6)) for r in rel} == corners


def test_source_page_needs_an_svg_boundary(tmp_path):
    design = {
        "boundary": {"shape": "rectangle", "width": 10, "height": 10},
        "seeds": {"method": "random", "count": 4},
        "output": {"formats": ["svg"], "layers": {"CUT": "boundary"}, "page": "source"},
    }
    with pytest.raises(DesignError, match="output.page"):
        build(design, tmp_path)
